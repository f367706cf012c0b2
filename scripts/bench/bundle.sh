#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# A self-contained build/dda for timing on another x86-64 Linux machine that
# lacks this one's Debian packages (a lent many-core machine): one tarball
# with dda, bench_triad, every shared library they load, and the loader.
#
#   scripts/bench/bundle.sh [OUT.tar.xz]          # default /tmp/dda-bundle.tar.xz
#   # there:  tar xJf dda-bundle.tar.xz -C /tmp && DDA=/tmp/dda-bundle/dda scripts/bench/thread_scaling.sh
#
# The renderer's OSMesa (with LLVM, 200 MB of libraries) is replaced by a
# library that makes no context: the bundle runs models and benchmarks, and
# refuses to render ("cannot create an off-screen OpenGL context"). The rest
# are this machine's own libraries, so results are this build's bits.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
out="${1:-/tmp/dda-bundle.tar.xz}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
dir=$work/dda-bundle
mkdir -p "$dir/lib" "$dir/bin"

# No context: every GL call a model run could reach is a no-op, and
# OSMesaCreateContextExt returns none, which the renderer reports.
gl_calls=$(nm -D --undefined-only "$root/build/dda" | awk '$2 ~ /^(gl|OSMesa)/ && $2 != "OSMesaCreateContextExt" {print $2}')
{
  echo 'void* OSMesaCreateContextExt(void) { return 0; }'
  for f in $gl_calls; do echo "int $f(void) { return 0; }"; done
} >"$work/no_osmesa.c"
cc -shared -fPIC -O1 -Wl,-soname,libOSMesa.so.8 -o "$dir/lib/libOSMesa.so.8" "$work/no_osmesa.c"

cp "$root/build/dda" "$root/build/bench/bench_triad" "$dir/bin/"
strip "$dir/bin/"*
for lib in $(LD_LIBRARY_PATH="$dir/lib" ldd "$root/build/dda" "$root/build/bench/bench_triad" |
  awk '/=> \// {print $3}' | sort -u); do
  [[ $(basename "$lib") == libOSMesa.so.8 ]] || cp -L "$lib" "$dir/lib/"
done
cp -L "$(ldd "$root/build/dda" | awk '/ld-linux/ {print $1}')" "$dir/lib/ld-linux-x86-64.so.2"
# Each program through the bundled loader, wherever the bundle is unpacked.
for p in dda bench_triad; do
  printf '#!/bin/sh\nd=$(dirname "$(readlink -f "$0")")\nexec "$d/lib/ld-linux-x86-64.so.2" --library-path "$d/lib" "$d/bin/%s" "$@"\n' \
    "$p" >"$dir/$p"
  chmod +x "$dir/$p"
done
tar -C "$work" -cJf "$out" dda-bundle
echo "$out: $(du -h "$out" | cut -f1)" >&2
