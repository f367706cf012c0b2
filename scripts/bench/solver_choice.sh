#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# The automatic solver choice against the fixed ones, by the clock: each wall
# with solver = auto, pcg and cholmod (scripts/bench/bench.lua, one thread,
# one process per run), the three alternating within each round, medians of
# the ms per step over the timed steps (and of the process's CPU ms), and
# auto's time over the better fixed solver's. The choice itself is made from
# counted work (engine/solver/solver_choice.hpp); this measures what it costs.
#
#   scripts/bench/solver_choice.sh                       # walls 10, 20, 40, quasi-static and dynamic
#   RUNS=5 WALLS="10:1 100:0" STEPS=5 scripts/bench/solver_choice.sh   # n:gg
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
dda="${DDA:-$root/build/dda}"
runs="${RUNS:-3}"
walls="${WALLS:-10:0 20:0 40:0 10:1 20:1 40:1}"
steps="${STEPS:-10}"
solvers="auto pcg cholmod"

one_run() {  # n gg solver -> "ms_per_step cpu_ms_per_step"
  "$dda" run "$root/scripts/bench/bench.lua" --set scene=wall --set n="$1" --set gg="$2" --set solver="$3" \
    --set threads=1 --set steps="$steps" 2>/dev/null |
    sed -n 's/.* \([0-9.]*\) ms\/step (CPU \([0-9.]*\)).*/\1 \2/p' | head -n 1
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

printf "%-10s %-12s %22s %22s %22s %14s\n" wall regime "auto ms (CPU)" "pcg ms (CPU)" "cholmod ms (CPU)" "auto/best"
for spec in $walls; do
  IFS=: read -r n gg <<<"$spec"
  tmp=$(mktemp -d)
  for ((r = 0; r < runs; r++)); do
    for s in $solvers; do one_run "$n" "$gg" "$s" >>"$tmp/$s"; done
  done
  declare -A ms cpu
  for s in $solvers; do
    ms[$s]=$(awk '{print $1}' "$tmp/$s" | median)
    cpu[$s]=$(awk '{print $2}' "$tmp/$s" | median)
  done
  rm -rf "$tmp"
  awk -v n="$n" -v gg="$gg" -v a="${ms[auto]}" -v ac="${cpu[auto]}" -v p="${ms[pcg]}" -v pc="${cpu[pcg]}" \
    -v c="${ms[cholmod]}" -v cc="${cpu[cholmod]}" 'BEGIN {
      best = (p < c) ? p : c; bestc = (pc < cc) ? pc : cc
      printf "%-10s %-12s %13.2f (%6.2f) %13.2f (%6.2f) %13.2f (%6.2f) %6.2f (%5.2f)\n", "wall(" n ")",
        (gg > 0 ? "dynamic" : "quasi-static"), a, ac, p, pc, c, cc, a / best, ac / bestc }'
done
