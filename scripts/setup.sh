#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# Setup on Debian 12: install the packages that are missing (apt-get, as root
# or through sudo), then configure and build into build/. The README's two
# commands:
#   scripts/setup.sh                  # what running needs; builds dda only
#   scripts/setup.sh --tests          # also what the tests need; builds dda and the tests
#                                     # (the README runs them: ctest --test-dir build -LE long)
#   WITH_FFMPEG=1 scripts/setup.sh    # also ffmpeg: runs then make movies from their frames
#   BUILD_DIR=b BUILD_TYPE=RelWithDebInfo scripts/setup.sh
set -euo pipefail
cd "$(dirname "$0")/.."

tests=0
case "${1:-}" in
  "") ;;
  --tests) tests=1 ;;
  -h | --help) sed -n '3,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "setup: unknown option '$1' (scripts/setup.sh [--tests])" >&2; exit 2 ;;
esac

# Build and run: compiler, CMake, the libraries linked (Eigen, oneTBB, Lua 5.4,
# OSMesa, stb, zlib for the PNG encoder, readline for the console).
packages=(g++ cmake make pkg-config libeigen3-dev libtbb-dev liblua5.4-dev
          libosmesa6-dev libstb-dev zlib1g-dev libreadline-dev
          # The sparse direct solver: CHOLMOD (SuiteSparse, with METIS) and an
          # optimised BLAS for its dense kernels.
          libsuitesparse-dev libopenblas-dev
          # The mesher of concave meshed blocks: CGAL (header-only; brings the
          # Boost, GMP and MPFR headers and libraries it uses).
          libcgal-dev
          # Run: the TrueType font frames and plots are labelled with (σ, τ);
          # without it a bitmap font spells Greek letters with Latin ones.
          fonts-dejavu-core
          # Run: the live view's HTTP server (dda run/console --live PORT).
          libcpp-httplib-dev)
# Tests: GoogleTest; VTK's own reader checks the ParaView (VTU/PVD) output
# (python3-vtk9 pulls Qt, MPI and more: about 260 packages, so only here);
# help2man makes the man page the install test installs.
test_packages=(libgtest-dev python3-vtk9 help2man
               # Tests: the live view in a real browser (headless Chromium via chromedriver).
               chromium chromium-driver
               # CI (.ci/run): the format check of every source.
               clang-format)
if [ $tests = 1 ]; then packages+=("${test_packages[@]}"); fi
if [ "${WITH_FFMPEG:-0}" = 1 ]; then packages+=(ffmpeg); fi
# Fuzzing (fuzz/, DDA_FUZZ; docs/robustness.md): clang, its libFuzzer and sanitizer runtime.
if [ "${WITH_FUZZ:-0}" = 1 ]; then packages+=(clang libclang-rt-dev); fi
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

# The live view's browser test: chromedriver reaches Chromium's DevTools at
# "localhost", which a minimal root (debootstrap, some containers) leaves
# unnamed without /etc/hosts. Named there only when no line names it.
if [ $tests = 1 ] && ! grep -qsE '^127\.0\.0\.1[[:space:]].*\blocalhost\b' /etc/hosts; then
  echo "setup: /etc/hosts names no 127.0.0.1 localhost (the browser test needs it): adding the line"
  line='127.0.0.1\tlocalhost\n'
  if [ "$(id -u)" -eq 0 ]; then printf "$line" >> /etc/hosts; else sudo sh -c "printf '$line' >> /etc/hosts"; fi ||
    echo "setup: could not add it; the browser test (workflow.live) cannot reach Chromium" >&2
fi

build_dir=${BUILD_DIR:-build}
jobs=$(nproc)
if [ $tests = 0 ]; then
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" >/dev/null
  cmake --build "$build_dir" -j "$jobs" --target dda
  echo "setup: built $build_dir/dda"
else
  # The tests and what they run; the benchmark programs are not tests.
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" -DDDA_BUILD_TESTS=ON \
        -DDDA_BUILD_BENCHMARKS=OFF >/dev/null
  cmake --build "$build_dir" -j "$jobs"
  echo "setup: built $build_dir/dda and the tests (ctest --test-dir $build_dir -LE long runs them)"
fi
