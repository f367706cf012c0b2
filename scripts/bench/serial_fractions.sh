#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# Each stage's serial fraction on this machine: the stage's time per step on 1
# and on 2 threads (scripts/bench/bench.lua --set stages=true), runs
# alternating 1, 2, 1, 2, ... and the median of each kept. With Amdahl's law,
# T2 = T1 (s + (1 - s) / 2), so s = 2 T2 / T1 - 1; the bound it implies on N
# threads is 1 / (s + (1 - s) / N). Two cores can only show what two threads
# gain: read s as an upper bound on the serial part (memory bandwidth and
# the second thread's own overheads count as serial here).
#
#   scripts/bench/serial_fractions.sh                      # blast(2), blast(0.5), wall(40)[pcg]
#   RUNS=5 SCENES="blast:2:1000" scripts/bench/serial_fractions.sh
#
# SCENES: scene:size:steps (wall:n, blast:h, blast_meshed:mesh, bar:0).
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
dda="${DDA:-$root/build/dda}"
runs="${RUNS:-3}"
scenes="${SCENES:-blast:2:500 blast:0.5:10 wall:40:10}"
stages="detect predict assemble solve check control update total"

one_run() {  # scene size steps threads -> "detect ... total" ms per step
  local scene=$1 size=$2 steps=$3 threads=$4 args=()
  case $scene in
    wall) args=(--set scene=wall --set n="$size" --set solver=pcg) ;;
    blast) args=(--set scene=blast --set h="$size") ;;
    blast_meshed) args=(--set scene=blast_meshed --set mesh="$size") ;;
    bar) args=(--set scene=bar) ;;
    *) echo "unknown scene $scene" >&2; exit 2 ;;
  esac
  "$dda" run "$root/scripts/bench/bench.lua" "${args[@]}" --set threads="$threads" --set steps="$steps" \
    --set stages=true 2>/dev/null | sed -n 's/^stages ms\/step: //p' | awk '{for (i = 2; i <= NF; i += 2) printf "%s ", $i; print ""}'
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

for spec in $scenes; do
  IFS=: read -r scene size steps <<<"$spec"
  tmp=$(mktemp -d)
  for ((r = 0; r < runs; r++)); do
    one_run "$scene" "$size" "$steps" 1 >>"$tmp/1"
    one_run "$scene" "$size" "$steps" 2 >>"$tmp/2"
  done
  echo "== $scene($size), $steps steps, $runs runs of each, medians; ms per step"
  printf "%-9s %9s %9s %8s %7s %9s\n" stage "1 thread" "2 threads" speed-up serial "16-bound"
  col=1
  for st in $stages; do
    t1=$(awk -v c=$col '{print $c}' "$tmp/1" | median)
    t2=$(awk -v c=$col '{print $c}' "$tmp/2" | median)
    awk -v st="$st" -v t1="$t1" -v t2="$t2" 'BEGIN {
      s = (t1 > 0) ? 2 * t2 / t1 - 1 : 0; if (s < 0) s = 0; if (s > 1) s = 1
      printf "%-9s %9.4f %9.4f %8.2f %7.2f %9.1f\n", st, t1, t2, (t2 > 0 ? t1 / t2 : 0), s, 1 / (s + (1 - s) / 16) }'
    col=$((col + 1))
  done
  rm -rf "$tmp"
done
