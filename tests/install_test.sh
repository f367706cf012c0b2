#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# cmake --install into a scratch prefix, then, from a folder of its own, the
# installed dda: its version, two installed scenes (free_fall.lua, and
# earthquake_slope.lua, which reads its record from the installed data/), the
# docs, and the man page when help2man made one.
#   install_test.sh SCRATCH BUILD_DIR CMAKE VERSION [HELP2MAN]
set -euo pipefail
scratch=$1 build=$2 cmake=$3 version=$4 help2man=${5:-}
rm -rf "$scratch"
"$cmake" --install "$build" --prefix "$scratch/prefix" >/dev/null
dda=$scratch/prefix/bin/dda
fail() { echo "install test: $*" >&2; exit 1; }
mkdir -p "$scratch/work" && cd "$scratch/work"
"$dda" --version | grep -q "^dda $version, commit " || fail "dda --version does not give $version: $("$dda" --version)"
"$dda" run free_fall.lua --quiet --set t_end=0.05 --out out >log.txt || fail "free_fall.lua failed: $(tail -3 log.txt)"
grep -q 'largest relative error' log.txt && test -s out/free_fall.csv || fail "free_fall.lua wrote no results"
"$dda" run earthquake_slope.lua --quiet --set t_end=0.005 --set settle=0.001 --set frames=0 --out quake >quake.txt 2>&1 \
  || fail "earthquake_slope.lua failed: $(tail -3 quake.txt)"
grep -q "^record: .* PGA" quake.txt || fail "earthquake_slope.lua did not read its record: $(head -3 quake.txt)"
for doc in README.md LICENSE docs/scripting.md docs/lua_api.md docs/seismic.md; do
  test -s "$scratch/prefix/share/doc/dda/$doc" || fail "$doc is not installed"
done
if [ -n "$help2man" ]; then
  grep -q "dda run" "$scratch/prefix/share/man/man1/dda.1" || fail "the man page is not installed"
fi
echo "install test: ok"
