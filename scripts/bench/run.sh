#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# The engine benchmark table: every scene with 1 and 2 threads, one dda
# process per row (so each row's peak memory is its own), as CSV with the
# machine's description on its first line.
#   scripts/bench/run.sh            # the default table (about 35 minutes), written to
#                                   # bench/results/<machine>.csv, overwriting it
#   SCENES="wall:10 bar" scripts/bench/run.sh    # chosen scenes: the table on stdout
#   SCENES="wall:200:3" scripts/bench/run.sh     # a third field: timed steps (default 10)
#   SCENES="blast_meshed:0.25/12" scripts/bench/run.sh  # 2 m joints, meshed at 0.25 m within 12 m
#   SCENES="blast:0.5:50:2500" scripts/bench/run.sh   # a fourth: untimed steps first (default 2);
#                                                     # the row's scene is then blast(0.5)@2500
#   SCENES="wall:40:10:2:cholmod:1" scripts/bench/run.sh  # a fifth: the solver (pcg or cholmod;
#                                                     # default auto), a sixth: gg; the row's
#                                                     # scene is then wall(40)gg1[cholmod]
#   REPEAT=3 SCENES="blast:0.5" scripts/bench/run.sh
#   OUT=/tmp/table.csv scripts/bench/run.sh      # the table to that file instead
#
# <machine> is the CPU model from /proc/cpuinfo and the core count, e.g.
# amd-epyc-2c: one file per machine for the default scene set, overwritten,
# so git holds its history. Chosen scenes never overwrite it. Progress
# goes to stderr.
#
# REPEAT=N runs each row N times and keeps the run with the median ms per
# step; the last columns give the number of runs and the fastest and slowest
# ms per step. A shared VM's speed can swing by 1.5x within minutes, so the
# 1- and 2-thread runs of a scene alternate (1, 2, 1, 2, ...): a slow spell
# then hits both thread counts alike.
set -euo pipefail
cd "$(dirname "$0")/../.."
dda=${DDA:-build/dda}
repeat=${REPEAT:-1}
[[ $repeat =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: REPEAT must be a positive integer (got '$repeat')" >&2; exit 2; }
# blast:2:5000 times the paper's whole 0.05 s (5000 steps of 1e-5 s after 2
# untimed ones). blast:2:50:2500 and blast:0.5:50:2500 time steps 2501-2550,
# late in the run where most joints slide: the early-step rows alone would
# hide what a whole run costs.
# The solver rows: the walls with each solver side by side, quasi-static
# and dynamic (gg = 1).
solver_rows="wall:20:10:2:pcg wall:20:10:2:cholmod wall:40:10:2:pcg wall:40:10:2:cholmod
  wall:20:10:2:pcg:1 wall:20:10:2:cholmod:1 wall:40:10:2:pcg:1 wall:40:10:2:cholmod:1"
# The meshed rows: the paper's 2 m blocks meshed at 0.25 m within 12 m (the
# Section 4 run) and every block meshed at 1 m (41,370 elements,
# beside blast(0.5)'s 40,518 blocks: an element-step against a block-step).
meshed_rows="blast_meshed:0.25/12 blast_meshed:1/0"
default_scenes="wall:10 wall:20 wall:40 wall:100:5 wall:200:3 $solver_rows blast:2:5000 blast:2:50:2500 blast:1 blast:0.5 blast:0.5:50:2500 blast:0.25:5 $meshed_rows bar"
scenes=${SCENES:-$default_scenes}
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')
machine=$(echo "$cpu" | sed -E 's/\((R|TM|tm)\)//g; s/ (CPU|Processor)\b//g; s/@.*//' | tr 'A-Z' 'a-z' | tr -cs 'a-z0-9' '-' | sed 's/^-*//; s/-*$//')-$(nproc)c
if [[ -n ${OUT:-} ]]; then
  out=$OUT
elif [[ $scenes == "$default_scenes" ]]; then
  out=bench/results/$machine.csv
else
  out=/dev/stdout
fi
[[ $out == /dev/stdout ]] || mkdir -p "$(dirname "$out")"
table=$(mktemp)
{
  echo "# machine: $machine ($(nproc) cores, $cpu, $(free -g | awk '/Mem:/{print $2}') GiB); commit $(git rev-parse --short HEAD 2>/dev/null || echo '?'); runs per row $repeat (median kept)"
  echo "scene,threads,blocks,contacts,steps,ms_per_step,block_steps_per_s,oc_per_step,cg_per_step,cuts,detect_share,assemble_share,solve_share,update_share,other_share,peak_rss_mb,patch_per_step,cpu_ms_per_step,runs,ms_min,ms_max"
} > "$table"
runs=$(mktemp -d)
trap 'rm -rf "$runs" "$table"' EXIT
for s in $scenes; do
  IFS=: read -r name arg steps skip solver gg <<< "$s"
  case $name in
    wall) args=(--set scene=wall --set n="$arg" --set steps="${steps:-10}") ;;
    blast) args=(--set scene=blast --set h="$arg" --set steps="${steps:-10}") ;;
    # blast_meshed:H/R: element size H, meshed within R m (scenes.lua)
    blast_meshed) args=(--set scene=blast_meshed --set mesh="${arg%/*}" --set steps="${steps:-10}")
      [[ $arg != */* ]] || args+=(--set radius="${arg#*/}") ;;
    bar) args=(--set scene=bar --set steps="${steps:-100}") ;;
    *) echo "run.sh: unknown scene '$name' (wall, blast, blast_meshed, bar)" >&2; exit 2 ;;
  esac
  [[ -z $skip ]] || args+=(--set warmup="$skip")
  [[ -z $solver ]] || args+=(--set solver="$solver")
  [[ -z $gg ]] || args+=(--set gg="$gg")
  rm -f "$runs"/*.csv
  for ((r = 1; r <= repeat; ++r)); do
    for t in 1 2; do
      "$dda" run scripts/bench/bench.lua --quiet --out /tmp "${args[@]}" --set threads=$t --set csv="$runs/$t.csv" >&2
    done
  done
  for t in 1 2; do
    # The median run by ms per step (column 6); with an even count the faster
    # of the middle two.
    sort -t, -k6,6g "$runs/$t.csv" | awk -F, -v n="$repeat" '
      { ms[NR] = $6; row[NR] = $0 }
      END { printf "%s,%d,%s,%s\n", row[int((n + 1) / 2)], n, ms[1], ms[n] }' >> "$table"
  done
done
# Written only once every row is done: an interrupted run keeps the last table.
if [[ $out == /dev/stdout ]]; then
  cat "$table"
else
  cp "$table" "$out"
  echo "table saved to $out" >&2
fi
