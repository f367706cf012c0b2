#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# ntdda side by side: the benchmark's staggered walls in ntdda (the open-source
# Shi/Doolin DDA in C: direct block LDL^T, one thread) and in this engine, CPU
# milliseconds and open-close iterations per step, quasi-static and dynamic.
#
#   bench/ntdda_side_by_side.sh /path/to/ntdda            # walls 10 20 40, 3 runs each
#   WALLS="10 20" RUNS=5 bench/ntdda_side_by_side.sh /path/to/ntdda
#   THREADS="1 2" SOLVERS="auto pcg cholmod" bench/ntdda_side_by_side.sh /path/to/ntdda
#   OURS="holding:default" bench/ntdda_side_by_side.sh /path/to/ntdda   # our defaults alone
#
# ntdda is not part of the build. Its checkout is read, never written: the
# sources are copied into $WORK (default /tmp/ntdda-side-by-side; ntdda's own
# output files make it about 450 MB with wall(40): remove it after) and patched
# there, then compiled with -O2 and a console driver written by this script:
#   - -fcommon: its headers define globals (GCC 10 and later default to -fno-common);
#   - its ray casting in blocks.c (crr, rlt) takes rand()/2048 and rand()/2^21
#     as the sine of a ray's angle after srand(2), written for the Windows C
#     library (RAND_MAX 32767): on glibc (2^31 - 1) the sine is far above 1, the
#     block cutting never ends and points fall outside every block. The driver
#     supplies the Windows C library's generator (its linear congruence, values
#     0..32767) through the linker's --wrap;
#   - FORTY (analysis.h) sizes its sparse-storage scratch arrays at 40 entries per
#     block, too few for wall(40) (3,241 blocks: a heap overflow): raised to 400.
# (The checkout's console/ holds only Windows project files, and its
# tests/unit/pipeline_test.c runs one fixed example, so the driver is written here.)
# The driver runs ddacut and ddanalysis on the XML input this script writes and
# times the steps after WARMUP (2) untimed ones through ntdda's display() hook
# (linked with --wrap), which the step loop calls after every step.
#
# The walls are scripts/bench/scenes.lua's wall(N): N columns of 1 m x 0.5 m
# bricks, 2N rows in running bond on a 1 m base held by three fixed points;
# rho = 2600, E = 5 GPa, nu = 0.25, plane stress, friction 30 deg, no cohesion or
# tension, gravity 9.81, dt = 1e-3 s (no automatic step), maximum displacement
# ratio 0.001, penalty 50 E (fixed), open-close limit 8 (ntdda's is hard-wired to
# 8). Quasi-static: ntdda's "static" analysis and gg = 0 here; dynamic: ntdda's
# "dynamic" and gg = 1. ntdda's open-close tolerances (Openclose s0 and
# Opencriteria f0, fractions of w0 = half the model's larger side) are both set
# to 2e-7: with its default s0 = 2e-4 a contact that opened only closes again
# after penetrating 2e-4 w0 (4 mm on wall(40)), and the quasi-static wall falls
# freely. This engine runs each LAW:TOL of OURS (default "holding:default
# shi:default shi:ntdda"): its default contact law ("holding", whose bands are
# its own) at its defaults, and Shi's law (ntdda's) with contact_tolerance at
# its default (1e-9 of half the model height) and at ntdda's 2e-7 w0 ("ntdda").
#
# Runs alternate (ntdda, ours, ntdda, ours, ...) so that a slow spell of the
# shared machine hits both; the table gives medians. Per simulated millisecond:
# CPU ms per step divided by the simulated ms a step advanced (Δt cuts shorten it).
set -euo pipefail
ntdda=${1:?usage: bench/ntdda_side_by_side.sh NTDDA_CHECKOUT (see the comment at the top)}
[[ -f $ntdda/src/analysisdriver.c && -f $ntdda/include/analysis.h ]] ||
  { echo "ntdda_side_by_side.sh: '$ntdda' is not an ntdda checkout (no src/analysisdriver.c)" >&2; exit 2; }
root=$(cd "$(dirname "$0")/.." && pwd)
dda=${DDA:-$root/build/dda}
[[ -x $dda ]] || { echo "ntdda_side_by_side.sh: $dda not built (cmake --build build)" >&2; exit 2; }
command -v xml2-config > /dev/null ||
  { echo "ntdda_side_by_side.sh: ntdda reads its input with libxml2: install libxml2-dev (xml2-config not found)" >&2; exit 2; }
work=${WORK:-/tmp/ntdda-side-by-side}
walls=${WALLS:-10 20 40}
runs=${RUNS:-3}
steps=${STEPS:-10}
warmup=${WARMUP:-2}
threads_list=${THREADS:-1}
solvers=${SOLVERS:-auto}
ours_runs=${OURS:-holding:default shi:default shi:ntdda}
mkdir -p "$work"

# --- build ntdda out of its tree ------------------------------------------------
build_ntdda() {
  local tree=$work/tree
  rm -rf "$tree" && mkdir -p "$tree"
  cp -r "$ntdda/src" "$ntdda/include" "$tree/"
  sed -i 's/^#define FORTY 40$/#define FORTY 400/' "$tree/include/analysis.h"
  grep -q '^#define FORTY 400$' "$tree/include/analysis.h" ||
    { echo "ntdda_side_by_side.sh: FORTY not found in include/analysis.h" >&2; exit 1; }
  cat > "$work/driver.c" <<'EOF'
/* Console driver: cut the geometry, read the analysis, run it; time the steps
 * after `warmup` through the display() hook that ddanalysis calls after each. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "dda.h"
#include "ddafile.h"
#include "geometrydata.h"
#include "analysisdata.h"

Filepaths filepath;
static int warmup;
static clock_t t0, t1;
static int oc0, oc1;
static double time0, time1;

/* The Windows C library's rand(): ntdda's ray casting expects its 0..32767. */
static unsigned int rand_state = 1;
void __wrap_srand(unsigned int seed) { rand_state = seed; }
int __wrap_rand(void) {
  rand_state = rand_state * 214013u + 2531011u;
  return (int)((rand_state >> 16) & 0x7fff);
}

/* Mean centroid height of the bricks (blocks above y = 0): the wall's settlement
 * is its change over the run. */
static double brick_centroid_mean_y(Geometrydata *gd) {
  double sum = 0;
  int count = 0;
  for (int b = 1; b <= gd->nBlocks; ++b) {
    int j0 = gd->vindex[b][1], j1 = gd->vindex[b][2];
    double a = 0, cy = 0;
    for (int j = j0; j <= j1; ++j) {
      int k = j < j1 ? j + 1 : j0;
      double x1 = gd->vertices[j][1], y1 = gd->vertices[j][2];
      double x2 = gd->vertices[k][1], y2 = gd->vertices[k][2];
      double c = x1 * y2 - x2 * y1;
      a += c;
      cy += (y1 + y2) * c;
    }
    cy /= 3 * a;
    if (cy > 0) { sum += cy; ++count; }
  }
  return count ? sum / count : 0;
}

void __real_display(Geometrydata *, Analysisdata *);
void __wrap_display(Geometrydata *gd, Analysisdata *ad) {
  __real_display(gd, ad);
  if (ad->cts == warmup) { t0 = clock(); oc0 = ad->n9; time0 = ad->elapsedTime; }
  if (ad->cts == ad->nTimeSteps) { t1 = clock(); oc1 = ad->n9; time1 = ad->elapsedTime; }
}

int main(int argc, char **argv) {
  if (argc != 4) { fprintf(stderr, "usage: driver GEO ANA WARMUP\n"); return 2; }
  warmup = atoi(argv[3]);
  DDA *dda = dda_new();
  Geometrydata *gd = gdata_new();
  gd->display_error = dda_display_error;
  gd->display_warning = dda_display_warning;
  gdata_read_input_file(gd, argv[1]);
  dda_set_geometrydata(dda, gd);
  ddacut(gd);
  Analysisdata *ad = adata_new();
  ad->display_error = dda_display_error;
  ad->display_warning = dda_display_warning;
  adata_read_input_file(ad, argv[2], gd->nFPoints, gd->pointCount, gd->nLPoints);
  dda_set_analysisdata(dda, ad);
  memset(&filepath, 0, sizeof filepath);
  strncpy(filepath.gfile, argv[1], FNAME_BUFSIZE - 1);
  strncpy(filepath.afile, argv[2], FNAME_BUFSIZE - 1);
  strncpy(filepath.rootname, "wall", FNAME_BUFSIZE - 1);
  int blocks = gd->nBlocks;
  double y_start = brick_centroid_mean_y(gd);
  if (ddanalysis(dda, &filepath) != 1 || t1 == 0) { fprintf(stderr, "ntdda: the analysis failed\n"); return 1; }
  int timed = ad->nTimeSteps - warmup;
  printf("NTDDA blocks %d cpu_ms_per_step %.3f oc_per_step %.3f sim_ms_per_step %.6f settlement_um %.4f\n",
         blocks, 1e3 * (double)(t1 - t0) / CLOCKS_PER_SEC / timed, (double)(oc1 - oc0) / timed,
         1e3 * (time1 - time0) / timed, 1e6 * (y_start - brick_centroid_mean_y(gd)));
  return 0;
}
EOF
  local srcs
  srcs=$(sed -n '/set(LIBDDA_SRCS/,/)/p' "$ntdda/src/CMakeLists.txt" | grep -E '^\s+[a-z_]+\.c' | sed "s|^ *|$tree/src/|")
  # shellcheck disable=SC2086
  gcc -O2 -std=gnu99 -fcommon -w -I"$tree/include" -I"$tree/src/platform/stubs" $(xml2-config --cflags) \
    -o "$work/ntdda_wall" "$work/driver.c" $srcs "$tree/src/platform/stubs/stubs.c" \
    -Wl,--wrap=display,--wrap=rand,--wrap=srand $(xml2-config --libs) -lm
}

# --- the walls in ntdda's XML ---------------------------------------------------
# Joints overshoot their ends by 0.01 m: ddacut drops the dangling pieces.
write_geometry() {
  local n=$1 file=$2
  awk -v n="$n" 'BEGIN {
    e = 0.01
    print "<?xml version=\"1.0\" standalone=\"no\"?>"
    print "<!DOCTYPE DDA SYSTEM \"geometry.dtd\">"
    print "<Berkeley:DDA xmlns:Berkeley=\"http://www.tsoft.com/~bdoolin/dda\">"
    print "<Berkeley:Geometry>"
    print "<Berkeley:Edgenodedist distance=\"0.001\"/>"
    print "<Jointlist>"
    # the base: (-1,-1) to (n+1,0); its top line is the wall'"'"'s bottom
    printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", -1 - e, -1, n + 1 + e, -1
    printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", n + 1, -1 - e, n + 1, 0 + e
    printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", n + 1 + e, 0, -1 - e, 0
    printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", -1, 0 + e, -1, -1 - e
    # the wall'"'"'s outline and bed joints: x = 0 and x = n, y = 0.5 k
    printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", 0, -e, 0, n + e
    printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", n, -e, n, n + e
    for (k = 1; k <= 2 * n; ++k)
      printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", -e, 0.5 * k, n + e, 0.5 * k
    # head joints: whole bricks in even rows, half bricks at the ends of odd rows
    for (r = 0; r < 2 * n; ++r) {
      y0 = 0.5 * r
      for (c = 0; c < n; ++c) {
        x = (r % 2 == 0) ? c : c + 0.5
        if (x <= 0 || x >= n) continue
        printf "<Joint type=\"1\"> %g %g %g %g </Joint>\n", x, y0 - e, x, y0 + 0.5 + e
      }
    }
    print "</Jointlist>"
    print "<Fixedpointlist>"
    printf "<Point> %g %g </Point>\n<Point> %g %g </Point>\n<Point> %g %g </Point>\n", 0, -0.5, n / 2, -0.5, n, -0.5
    print "</Fixedpointlist>"
    print "</Berkeley:Geometry>"
    print "</Berkeley:DDA>"
  }' > "$file"
}

write_analysis() {
  local type=$1 total=$2 file=$3
  cat > "$file" <<EOF
<?xml version="1.0" standalone="no"?>
<!DOCTYPE DDA SYSTEM "analysis.dtd">
<Berkeley:DDA xmlns:Berkeley="http://www.tsoft.com/~bdoolin/dda">
<Analysis>
  <Analysistype type="$type"/>
  <Rotation type="linear"/>
  <Gravity flag="no"/>
  <Gravaccel value="9.81"/>
  <Autotimestep flag="no"/>
  <Autopenalty flag="no" pfactor="50.0"/>
  <Planestrain flag="no"/>
  <Numtimesteps timesteps="$total"/>
  <Maxtimestep maxtimestep="0.001"/>
  <Opencloselimit maxopenclose="8"/>
  <Maxdisplacement maxdisplacement="0.001"/>
  <Saveinterval step="100000"/>
  <AConstants>
    <Openclose value="0.0000002"/>
    <Opencriteria value="0.0000002"/>
    <NormSpringPen value="0.0004"/>
    <AngleOverlap value="3.0"/>
    <ShearNormRatio value="2.5"/>
  </AConstants>
  <Blockmaterial type="1">
    <Unitmass> 2600 </Unitmass>
    <Unitweight> 25506 </Unitweight>
    <Youngsmod> 5e9 </Youngsmod>
    <Poissonratio> 0.25 </Poissonratio>
    <Damping> 0.0 </Damping>
    <Istress> 0 0 0 </Istress>
    <Ivelocity> 0 0 0 </Ivelocity>
    <Istrain> 0 0 0 </Istrain>
  </Blockmaterial>
  <Jointproperties type="1">
    <Friction> 30 </Friction>
    <Cohesion> 0 </Cohesion>
    <Tensile> 0 </Tensile>
  </Jointproperties>
</Analysis>
</Berkeley:DDA>
EOF
}

# --- one run of each -----------------------------------------------------------
run_ntdda() {  # n type -> "cpu_ms oc sim_ms blocks settlement_um"
  local n=$1 type=$2 dir=$work/wall$1_$2
  mkdir -p "$dir/output"
  ( cd "$dir" && "$work/ntdda_wall" wall.geo wall.ana "$warmup" ) > "$dir/run.log" 2>&1 ||
    { echo "ntdda_side_by_side.sh: ntdda failed on wall($n) $type: see $dir/run.log" >&2; exit 1; }
  awk '/^NTDDA/ { print $5, $7, $9, $3, $11 }' "$dir/run.log"
}

run_ours() {  # n gg threads solver law:tol -> "cpu_ms oc sim_ms cuts solver settlement_um cg factorisations"
  "$dda" run "$root/bench/ntdda_wall.lua" --quiet --out "$work" --set n="$1" --set gg="$2" --set threads="$3" \
    --set solver="$4" --set law="${5%%:*}" --set tol="${5#*:}" --set steps="$steps" --set warmup="$warmup" |
    awk '/^OURS/ { print $3, $5, $7, $9, $11, $13, $17, $19 }'
}

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

echo "building ntdda from $ntdda in $work ..." >&2
build_ntdda
printf "| wall | blocks | regime | ntdda CPU ms/step | ntdda open-close/step | ntdda settlement µm |"
printf " ours: threads, solver (ran), law:tolerance | ours CPU ms/step | ours open-close/step | ours CG/step | ours factorisations/step | ours Δt cuts | ours settlement µm | ntdda/ours per simulated ms |\n"
printf "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n"
for n in $walls; do
  for regime in quasi-static dynamic; do
    if [[ $regime == quasi-static ]]; then type=static gg=0; else type=dynamic gg=1; fi
    dir=$work/wall${n}_$type
    mkdir -p "$dir"
    write_geometry "$n" "$dir/wall.geo"
    write_analysis "$type" $((warmup + steps)) "$dir/wall.ana"
    rm -f "$dir"/ntdda.txt "$dir"/ours_*.txt
    for ((r = 1; r <= runs; ++r)); do
      echo "wall($n) $regime: run $r of $runs" >&2
      run_ntdda "$n" "$type" >> "$dir/ntdda.txt"
      for t in $threads_list; do
        for s in $solvers; do
          for tol in $ours_runs; do
            run_ours "$n" "$gg" "$t" "$s" "$tol" >> "$dir/ours_${t}_${s}_${tol/:/_}.txt"
          done
        done
      done
    done
    nt_ms=$(cut -d' ' -f1 "$dir/ntdda.txt" | median)
    nt_oc=$(cut -d' ' -f2 "$dir/ntdda.txt" | median)
    nt_sim=$(cut -d' ' -f3 "$dir/ntdda.txt" | median)
    blocks=$(head -1 "$dir/ntdda.txt" | cut -d' ' -f4)
    nt_settle=$(cut -d' ' -f5 "$dir/ntdda.txt" | median)
    nt_per=$(awk -v a="$nt_ms" -v b="$nt_sim" 'BEGIN { printf "%.4f", a / b }')
    for t in $threads_list; do
      for s in $solvers; do
        for tol in $ours_runs; do
          f=$dir/ours_${t}_${s}_${tol/:/_}.txt
          ms=$(cut -d' ' -f1 "$f" | median)
          oc=$(cut -d' ' -f2 "$f" | median)
          sim=$(cut -d' ' -f3 "$f" | median)
          cuts=$(cut -d' ' -f4 "$f" | median)
          used=$(cut -d' ' -f5 "$f" | sort | uniq | paste -sd/)
          settle=$(cut -d' ' -f6 "$f" | median)
          cg=$(cut -d' ' -f7 "$f" | median)
          fact=$(cut -d' ' -f8 "$f" | median)
          per=$(awk -v a="$ms" -v b="$sim" 'BEGIN { printf "%.4f", a / b }')
          ratio=$(awk -v a="$nt_per" -v b="$per" 'BEGIN { printf "%.2f", a / b }')
          printf "| wall(%s) | %s | %s | %.1f | %.2f | %.3f | %s, %s (%s), %s | %.1f | %.2f | %.0f | %.2f | %s | %.3f | %s |\n" \
            "$n" "$blocks" "$regime" "$nt_ms" "$nt_oc" "$nt_settle" "$t" "$s" "$used" "$tol" "$ms" "$oc" "$cg" "$fact" "$cuts" \
            "$settle" "$ratio"
        done
      done
    done
  done
done
