#!/usr/bin/env bash
# Setup: install the Debian 12 packages the engine and its tests need (only
# those missing), then configure and build into build/. Both README commands
# start with this.
#   scripts/setup.sh                  # install what is missing, build (Release)
#   WITH_FFMPEG=1 scripts/setup.sh    # also ffmpeg: runs then make movies from their frames
#   BUILD_DIR=b scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."

# Build: compiler, CMake, the libraries linked (Eigen, oneTBB, Lua 5.4, OSMesa,
# stb, zlib for the PNG encoder, readline for the console) and GoogleTest.
packages=(g++ cmake make pkg-config libeigen3-dev libtbb-dev liblua5.4-dev
          libosmesa6-dev libstb-dev zlib1g-dev libgtest-dev libreadline-dev
          # The sparse direct solver: CHOLMOD (SuiteSparse, with METIS) and an
          # optimised BLAS for its dense kernels.
          libsuitesparse-dev libopenblas-dev
          # The mesher of concave meshed blocks: CGAL (header-only; brings the
          # Boost, GMP and MPFR headers and libraries it uses).
          libcgal-dev
          # Run: the TrueType font frames and plots are labelled with (σ, τ);
          # without it a bitmap font spells Greek letters with Latin ones.
          fonts-dejavu-core
          # Tests: VTK's own reader checks the ParaView (VTU/PVD) output.
          python3-vtk9
          # Run: the live view's HTTP server (dda run/console --live PORT).
          libcpp-httplib-dev
          # Tests: the live view in a real browser (headless Chromium via chromedriver).
          chromium chromium-driver)
if [ "${WITH_FFMPEG:-0}" = 1 ]; then packages+=(ffmpeg); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "setup: need root (or sudo) to apt-get install ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
