#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# Thread scaling, stage by stage: each stage's time per step on each thread
# count (scripts/bench/bench.lua --set stages=true), one process per run, the
# thread counts alternating within each round (1, 2, 4, ..., then again) and
# the median of each kept.
#
# Per scene it prints the stages' ms per step on each thread count, the
# speed-up on the most threads, and Amdahl's serial fraction from the first
# two thread counts: with T(p) = T(1) (s + (1 - s) / p), s = (p T(p) / T(1) - 1)
# / (p - 1), and the bound that implies on 16 threads, 1 / (s + (1 - s) / 16).
# On two cores, read s as an upper bound on the serial part: memory bandwidth
# and the second thread's own overheads count as serial there, and a second
# core's cache can make a memory-bound stage more than 2x faster.
#
#   scripts/bench/thread_scaling.sh                       # 1 and 2 threads: blast(2), blast(0.5), wall(40)[pcg]
#   THREADS="1 2 4 8 16" RUNS=3 SCENES="blast:0.25:5" scripts/bench/thread_scaling.sh
#   DDA=path/to/dda RAW=dir scripts/bench/thread_scaling.sh   # RAW keeps each run's line
#
# SCENES: scene:size:steps (wall:n, blast:h, blast_meshed:mesh, bar:0). The
# walls run under PCG (solver = pcg), whose work is the engine's own.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
dda="${DDA:-$root/build/dda}"
runs="${RUNS:-3}"
threads="${THREADS:-1 2}"
scenes="${SCENES:-blast:2:500 blast:0.5:10 wall:40:10}"
stages="detect predict assemble solve check control update total"

one_run() {  # scene size steps threads -> "detect ... total" ms per step, then the blocks
  local scene=$1 size=$2 steps=$3 nthreads=$4 args=() out
  case $scene in
    wall) args=(--set scene=wall --set n="$size" --set solver=pcg) ;;
    blast) args=(--set scene=blast --set h="$size") ;;
    blast_meshed) args=(--set scene=blast_meshed --set mesh="$size") ;;
    bar) args=(--set scene=bar) ;;
    *) echo "unknown scene $scene" >&2; exit 2 ;;
  esac
  out=$("$dda" run "$root/scripts/bench/bench.lua" "${args[@]}" --set threads="$nthreads" --set steps="$steps" \
    --set stages=true 2>/dev/null)
  printf '%s\n' "$out" | sed -n 's/^stages ms\/step: //p' | awk '{for (i = 2; i <= NF; i += 2) printf "%s ", $i}'
  printf '%s\n' "$out" | sed -n 's/.* blocks *\([0-9]*\) .*/\1/p' | head -n 1
}

median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

read -ra counts <<<"$threads"
for spec in $scenes; do
  IFS=: read -r scene size steps <<<"$spec"
  tmp=$(mktemp -d)
  for ((r = 0; r < runs; r++)); do
    for t in "${counts[@]}"; do
      line=$(one_run "$scene" "$size" "$steps" "$t")
      printf '%s\n' "$line" >>"$tmp/$t"
      if [[ -n "${RAW:-}" ]]; then mkdir -p "$RAW" && printf '%s threads=%s %s\n' "$spec" "$t" "$line" >>"$RAW/runs.txt"; fi
    done
  done
  blocks=$(awk 'NR == 1 {print $9}' "$tmp/${counts[0]}")
  echo "== $scene($size), $blocks blocks, $steps steps, $runs runs of each, medians; ms per step"
  printf "%-9s" stage
  for t in "${counts[@]}"; do printf " %9s" "$t thr"; done
  printf " %8s %6s %9s\n" speed-up serial 16-bound
  col=1
  for st in $stages; do
    printf "%-9s" "$st"
    meds=()
    for t in "${counts[@]}"; do
      m=$(awk -v c=$col '{print $c}' "$tmp/$t" | median)
      meds+=("$m")
      printf " %9.4f" "$m"
    done
    awk -v t1="${meds[0]}" -v tp="${meds[1]:-${meds[0]}}" -v p="${counts[1]:-1}" -v tn="${meds[-1]}" 'BEGIN {
      s = (t1 > 0 && p > 1) ? (p * tp / t1 - 1) / (p - 1) : 0; if (s < 0) s = 0; if (s > 1) s = 1
      printf " %8.2f %6.2f %9.1f\n", (tn > 0 ? t1 / tn : 0), s, 1 / (s + (1 - s) / 16) }'
    col=$((col + 1))
  done
  rm -rf "$tmp"
done
