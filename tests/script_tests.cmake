# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
# Tests that run scripts with the dda executable (`dda run`, outputs under the
# build folder). Labels: `scripts` (the example scripts), `paper` (the paper's
# targets, quick cases), `long` (full sweeps and figure runs: ctest -L long).
# The gtest suite tests/scripting checks the example scripts' outputs against
# closed forms.
set(DDA_SCRIPT_TEST_OUT ${CMAKE_BINARY_DIR}/script-tests)

# dda_run_test(<test name> <label> <timeout s> <script under scripts/> [args...])
# A `paper` test runs on one thread: under `ctest -j2` two of them then share
# the two cores instead of each asking for both (results are the same for
# any thread count). A `long` test uses every core and runs alone.
function(dda_run_test name label timeout script)
  set(args ${ARGN})
  if(label STREQUAL "paper")
    list(APPEND args --threads 1)
  endif()
  add_test(NAME ${name}
           COMMAND $<TARGET_FILE:dda> run ${PROJECT_SOURCE_DIR}/scripts/${script} --quiet
                   --out ${DDA_SCRIPT_TEST_OUT}/${name} ${args}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(${name} PROPERTIES LABELS ${label} TIMEOUT ${timeout})
  if(label STREQUAL "long")
    set_tests_properties(${name} PROPERTIES RUN_SERIAL TRUE)
  endif()
endfunction()

dda_run_test(script.free_fall scripts 600 free_fall.lua --set t_end=0.2)
dda_run_test(script.incline scripts 600 incline.lua --set t_end=0.3)
dda_run_test(script.rock_bar scripts 600 rock_bar.lua --set t_end=2e-5)
# The README's job as it runs by default (docs/waves.md): no tensile lobe
# above 1 % of the amplitude ahead of the pulse at the centre and in the
# frames, the 1 % arrival at the centre within 2 % of the exact one (the 2-D
# bar's plate modes plus the joints' delay from the exact jointed 1-D bar).
dda_run_test(script.rock_bar_clean scripts 1200 rock_bar.lua --set check=true --set frame_every=0 --set movie=)
# A P wave across N parallel joints (scripts/waves/joint_set.lua, docs/waves.md):
# the engine's |T| at 1000 Hz (Fourier ratio of a broadband pulse's transmitted
# and incident records) within 2 % of the exact transfer-matrix answer
# (engine/reference/joint_set.hpp, Cai & Zhao 2000). Six cases (N = 1 to 10,
# spacing 0.05 to 1 wavelength, kn 0.5 to 20 x omega Z/2) in the default set
# (measured worst +0.58 %); the whole sweep as a long run, which redraws
# docs/figures/joint_set.png and leaves out the cases whose |T| moves by more
# than 2 % for 0.1 % of wave speed or where |T| < 1e-3 (listed in the docs).
dda_run_test(script.joint_set scripts 300 waves/joint_set.lua --set check=true
             --set cases=1:0.05:0.5,2:0.05:0.5,2:0.25:2,3:1:2,5:0.05:20,10:1:20 --set figure=)
dda_run_test(script.joint_set_sweep long 3600 waves/joint_set.lua --set check=true
             --set figure=${PROJECT_SOURCE_DIR}/docs/figures/joint_set.png)
# Model 1 under a 500 Hz pulse, its 0.2 m blocks within the element size the
# load needs, nothing pinned but the step: meshed all the same, no tension
# ahead of the pulse above 1 % of the amplitude and the peak within 1 % of
# the exact jointed 1-D bar's (nu = 0).
dda_run_test(script.small_blocks_meshed scripts 600 waves/small_blocks.lua --set check=true)
foreach(base rigid compliant)
  dda_run_test(script.earthquake_slope_${base} scripts 600 earthquake_slope.lua --set base=${base} --set settle=0.1
               --set t_end=0.1 --set frames=0.05)
endforeach()
# The 77-block jointed slope (contact transfer): stalled at
# t = 0.13 s before vertices transferred past the corners of edges; the test
# fails if any step cannot be completed. 0.5 s here, 5 s at both step sizes
# as long tests, under the default contact law ("holding"; the script takes
# --set law=shi for Shi's, which runs too: docs/contacts.md).
dda_run_test(script.jointed_slope scripts 600 jointed_slope.lua --set t_end=0.5)
foreach(dt 1e-3 1e-4)
  dda_run_test(script.jointed_slope_5s_dt${dt} long 3600 jointed_slope.lua --set t_end=5 --set dt=${dt})
endforeach()
dda_run_test(script.paper_geometry scripts 600 paper/geometry_models.lua)
dda_run_test(script.blast_geometry scripts 600 paper/blast_geometry.lua)

# The benchmark table's machinery on tiny scenes (a smoke test: the scripts
# run and the table has its rows and columns; no timing is checked). Two
# runs per row, the median kept: 4 scenes × 2 thread counts = 8 rows of 21
# columns; blast:4:2:3 is timed after 3 untimed steps, its row blast(4)@3; the
# meshed row's name holds no comma. Chosen scenes print the table on stdout.
add_test(NAME script.bench_table
         COMMAND bash -c "mkdir -p \"$(dirname \"$2\")\" && DDA=$1 REPEAT=2 SCENES='wall:3:2 blast:4:2 blast:4:2:3 blast_meshed:2/4:1' scripts/bench/run.sh > \"$2\" && test $(grep -c '^wall(3),' \"$2\") = 2 && test $(grep -c '^blast(4),' \"$2\") = 2 && test $(grep -c '^blast(4)@3,' \"$2\") = 2 && test $(grep -c '^blast_meshed(2/4),' \"$2\") = 2 && test $(awk -F, '!/^#/ && NF != 21' \"$2\" | wc -l) = 0" _
                 $<TARGET_FILE:dda> ${DDA_SCRIPT_TEST_OUT}/bench_table.csv
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(script.bench_table PROPERTIES LABELS scripts TIMEOUT 120)

# The thread-scaling table on a tiny scene (a smoke test: every stage's row has
# a time per thread count, a speed-up, a serial fraction and a bound).
add_test(NAME script.thread_scaling
         COMMAND bash -c "DDA=$1 THREADS='1 2' RUNS=1 SCENES='blast:4:2' scripts/bench/thread_scaling.sh > \"$2\" && grep -q '^== blast(4), [0-9]* blocks' \"$2\" && test $(grep -cE '^(detect|predict|assemble|solve|check|control|update|total) +([0-9.]+ +){4}[0-9.]+$' \"$2\") = 8" _
                 $<TARGET_FILE:dda> ${DDA_SCRIPT_TEST_OUT}/thread_scaling.txt
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(script.thread_scaling PROPERTIES LABELS scripts TIMEOUT 120)

# The solver-choice table on a tiny wall (a smoke test: the row has each
# solver's ms and CPU ms and auto's ratio to the better fixed solver).
add_test(NAME script.solver_choice
         COMMAND bash -c "DDA=$1 RUNS=1 WALLS='3:1' STEPS=2 scripts/bench/solver_choice.sh > \"$2\" && grep -qE '^wall\\(3\\) +dynamic( +[0-9.]+ +\\( *[0-9.]+\\)){4}$' \"$2\"" _
                 $<TARGET_FILE:dda> ${DDA_SCRIPT_TEST_OUT}/solver_choice.txt
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(script.solver_choice PROPERTIES LABELS scripts TIMEOUT 120)

# This engine's half of bench/ntdda_side_by_side.sh on a tiny dynamic wall,
# under the default law and under Shi's at ntdda's tolerance (a smoke test: the
# line the side-by-side reads has its 19 fields, and the wall settled, by more
# than 1 µm, over its 12 steps; no timing is checked).
add_test(NAME script.ntdda_wall
         COMMAND bash -c "{ $1 run bench/ntdda_wall.lua --quiet --out \"$2\" --set n=3 --set gg=1 --set law=holding && $1 run bench/ntdda_wall.lua --quiet --out \"$2\" --set n=3 --set gg=1 --set tol=ntdda; } | awk '/^OURS/ && NF == 19 && $13 > 1 { ++ok } END { exit ok != 2 }'" _
                 $<TARGET_FILE:dda> ${DDA_SCRIPT_TEST_OUT}
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(script.ntdda_wall PROPERTIES LABELS scripts TIMEOUT 60)

# The automatic solver choice keeps the factor on wall(200) (80,201 blocks)
# after its trial: there a step with the kept factor costs a fifth of a PCG
# step, and the trial's first factorisation (counted as spread over 50
# steps, solver_choice.hpp) must not send it back to PCG. The last of 8 steps
# must have run with the factor.
add_test(NAME script.auto_keeps_the_factor_on_wall200
         COMMAND bash -c "$1 run bench/ntdda_wall.lua --quiet --out \"$2\" --set n=200 --set warmup=2 --set steps=6 --set threads=2 | awk '/^OURS/ && $11 == \"cholmod\" { ok = 1 } END { exit !ok }'" _
                 $<TARGET_FILE:dda> ${DDA_SCRIPT_TEST_OUT}
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(script.auto_keeps_the_factor_on_wall200 PROPERTIES LABELS long TIMEOUT 1800 RUN_SERIAL TRUE)
# The automatic solver choice never leaves PCG on blast(2), a wave problem
# (a few CG iterations a solve, solver_choice.hpp): no factorisation in its
# first 30 steps, not even a trial's, and the last step on PCG.
add_test(NAME script.auto_keeps_pcg_on_blast
         COMMAND bash -c "$1 run scripts/bench/bench.lua --quiet --set scene=blast --set h=2 --set warmup=0 --set steps=30 --set threads=1 | grep -q ' pcg (0.00 factorisations/step)$'" _
                 $<TARGET_FILE:dda>
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(script.auto_keeps_pcg_on_blast PROPERTIES LABELS scripts TIMEOUT 120)

# The paper's Section 4 blast (scripts/paper/blast.lua). A 3 ms run of the 100 m
# DHI model checks the first arrival at MP1 against the P-wave travel time and
# that no contact penetrates beyond the g2 bound; the full figure runs
# (Figs. 14a, 14b, 15-18) carry the label long.
dda_run_test(paper.blast_check paper 120 paper/blast.lua --set check=true --set t_end=0.003)
foreach(fig 14a 14b 15)
  dda_run_test(paper.blast_fig${fig} long 3600 paper/blast.lua --set figure=${fig})
  dda_run_test(paper.blast_fig${fig}_h1 long 7200 paper/blast.lua --set figure=${fig} --set spacing=1)
endforeach()
# The field's PPV at MP1 (0.95 m/s, paper Fig. 14b) within 15 %, 100 m DHI
# model with 1 m joints (the 2 m joints of the paper give 1.82 m/s: see
# docs/validation.md, Section 4). 4 ms (the peak comes at 1.9 ms).
dda_run_test(paper.blast_ppv_h1 paper 600 paper/blast.lua --set spacing=1 --set t_end=0.004 --set expect_ppv=0.95
             --set ppv_tolerance=0.15)
# The blast with meshed 2 m blocks (docs/validation.md, Section 4 notes, "The
# paper's 2 m joints with meshed blocks"). A 3 ms run of a 40 m model meshed at 1 m within 12 m of the
# centre: the arrival and penetration checks above, the DHI's 2.03 m/s at the
# roof's middle at 0.5 ms within 2 % (the wall of meshed elements moves as the
# load prescribes), and MP1 reading the element under it (area at most 1 m^2,
# its block's is 4 m^2).
dda_run_test(paper.blast_meshed_check paper 300 paper/blast.lua --set check=true --set t_end=0.003 --set size=40
             --set mesh=1 --set mesh_radius=12)
# Why the chamber's four concave corner blocks are meshed too
# (scripts/paper/blast_corner_block.lua; 40 m model, 0.5 m elements within
# 12 m, 2.2 ms, corners first-order and meshed). References: the DHI's own
# motion (the corner point at 0.5 ms 0.5075 mm along each wall's normal) and
# causality (nothing moves before distance / C_P, C_P = 5570 m/s). Meshed: the
# corner point within 2 % of the DHI (measured 1.0 %), the corner block's far
# points no earlier than 0.9 x their travel time (0.95, 0.97). First-order: the
# block misses the DHI by over 10 % (25.8 %) and its far side moves before a
# third of its travel time (0.02 of 0.38 ms: a plug).
dda_run_test(paper.blast_corner_block paper 300 paper/blast_corner_block.lua --set check=true)
# The PPV at MP1 with meshed 2 m blocks, 1 m and 0.5 m elements within 12 m
# (5 ms; every block within 12 m meshed, the chamber's corner blocks too): the
# two coarse rows of the convergence table (docs/validation.md, Section 4
# notes) agree within 5 % (measured 1.267 and 1.298 m/s, +2.5 %).
dda_run_test(paper.blast_mesh_coarse long 1800 paper/blast.lua --set figure=mesh --set meshes=1,0.5
             --set mesh_radius=12 --set t_end=0.005 --set max_change=0.05)
# The target: the two finest meshes, 0.25 m and
# 0.125 m elements (113,721, the chamber's corner blocks meshed too), agree
# within 5 % at MP1 (reference: the finer mesh; measured 1.358 and 1.366 m/s,
# +0.6 %; about 7 minutes of CPU).
dda_run_test(paper.blast_mesh_converged long 3600 paper/blast.lua --set figure=mesh --set meshes=0.25,0.125
             --set mesh_radius=12 --set t_end=0.005 --set max_change=0.05)
# Figs. 15-18 with meshed 2 m blocks (docs/validation.md, Section 4 notes,
# "Figs. 15-18 with meshed 2 m blocks"): the cheapest of the report's 0.05 s
# runs, SBC with 0.5 m elements within 12 m (about a minute of CPU), rerun and summarised by
# blast_meshed_summary.lua, whose check compares it with the report's run (made
# on a 16-core machine; bit-identical for any thread count): PPV at MP1 and MP2
# and MP3's uy at 0.05 s within 1 %, the reflected energies at MP1 and MP2
# (integral of v^2 over t >= 15 ms) within 5 %, Fig. 18's count of line points
# within a factor 2 of Eq. 23 within one point (9 of 23).
add_test(NAME paper.blast_meshed_sbc
         COMMAND bash -c "$1 run scripts/paper/blast.lua --quiet --set boundary=sbc --set mesh=0.5 --set mesh_radius=12 --set t_end=0.05 --out \"$2/m05_sbc\" && $1 run scripts/paper/blast_meshed_summary.lua --quiet --set dirs=\"$2/m05_sbc\" --set check=true --out \"$2/m05_sbc_summary\"" _
                 $<TARGET_FILE:dda> ${DDA_SCRIPT_TEST_OUT}/paper.blast_meshed_sbc
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(paper.blast_meshed_sbc PROPERTIES LABELS long TIMEOUT 3600 RUN_SERIAL TRUE)
# Where the 2 m joint pattern lies decides the PPV at MP1 (0.81 to 1.82 m/s over
# one period of placements, scripts/paper/blast_joint_offset.lua). Four
# placements, DHI and SHI, 12 ms: mirrored placements (d and 2.83 m - d) must give
# the same PPV within 1 % (the model's mirror symmetry about x = 0).
dda_run_test(paper.blast_joint_offset paper 600 paper/blast_joint_offset.lua --set n=4 --set check=true)

# The paper's Section 2-3 targets (scripts/paper/fig*.lua with check=true: a
# target not met is an error). Quick cases, one of each target, are labelled
# `paper`; the full sweeps `long`.
function(dda_paper_test name label timeout script)
  dda_run_test(script.paper.${name} ${label} ${timeout} paper/${script} --set check=true ${ARGN})
endfunction()
dda_paper_test(fig3_g0_20E paper 600 fig3_joint_stiffness.lua --set cases=20 --set t_end=3.2e-3)
dda_paper_test(fig3_g0_E paper 600 fig3_joint_stiffness.lua --set cases=1 --set t_end=3.6e-3)
dda_paper_test(fig4_frequency paper 600 fig4_frequency.lua --set t_end=4.4e-3)
dda_paper_test(fig7_fixed_free paper 600 fig7_fixed_free.lua --set t_end=6.6e-3)
dda_paper_test(fig8_vbc_sbc_p0 paper 600 fig8_vbc_sbc.lua --set p0s=0.01,10,100 --set t_end=6.6e-3)
dda_paper_test(fig10_model4_eq22 paper 600 fig10_model4.lua --set eq21=false --set t_end=6.6e-3)
dda_paper_test(fig11_vbc_incidence paper 600 fig11_models5_6.lua --set models=5,6 --set sbc=false --set t_end=7.5e-3)
dda_paper_test(fig3_full long 1800 fig3_joint_stiffness.lua)
dda_paper_test(fig5_full long 1800 fig5_joint_strength.lua)
dda_paper_test(fig6_full long 1800 fig6_joint_direction.lua)
dda_paper_test(fig10_full long 1800 fig10_model4.lua)
dda_paper_test(fig11_full long 1800 fig11_models5_6.lua)

# cmake --install: the installed binary runs installed scenes from another
# folder, the earthquake slope reading its record from the installed data/;
# the docs and (with help2man) the man page are installed.
add_test(NAME install.run_installed
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/install_test.sh ${CMAKE_BINARY_DIR}/install-test ${CMAKE_BINARY_DIR}
                 ${CMAKE_COMMAND} ${PROJECT_VERSION} "${HELP2MAN}")
set_tests_properties(install.run_installed PROPERTIES LABELS scripts TIMEOUT 120)

# The exact jointed bar (scripts/paper/jointed_bar_exact.lua) against
# closed forms, and the paper's Model 1 with the second-order integrator at the
# paper's Δt against the step's limit (Richardson from Δt/2 and Δt/4), within
# 0.5 %: one frequency on a nearer receiver in the default set, the three
# frequencies at the centre as a long run.
dda_run_test(paper.jointed_bar_exact paper 300 paper/jointed_bar_exact_check.lua)
dda_run_test(paper.bar_time_step_1500Hz paper 600 paper/bar_time_step.lua --set freqs=1500 --set dts=2e-6,1e-6
             --set at=4.1 --set check=true)
dda_run_test(paper.bar_time_step long 7200 paper/bar_time_step.lua --set check=true)
# The blocks' own error on Model 1's joints (scripts/paper/bar_block_size.lua,
# newmark): the precursor ahead of the pulse at least halves with each halving
# of the blocks and lies under 2 % of the amplitude at the smallest, whose
# first peaks are within 1 % of the exact jointed bar: 0.2 and 0.1 m blocks in
# the default set, 0.2, 0.1 and 0.05 m as a long run.
dda_run_test(paper.bar_block_size paper 600 paper/bar_block_size.lua --set sizes=0.2,0.1 --set check=true)
dda_run_test(paper.bar_block_size_full long 3600 paper/bar_block_size.lua --set check=true)
# The precursor (a tensile lobe ahead of the compressive pulse at
# the centre, the exact jointed bar has none) with the 0.2 m blocks meshed, at
# g0 = 20E, where no first-order block size takes it under 2 % (16 % with 0.2 m
# blocks): meshed at 0.05 m it lies under 2 % of the amplitude
# (measured 1.3 %; long), and meshed at 0.2 m under 5 % (measured 4.2 %; default set).
dda_run_test(paper.meshed_precursor paper 600 paper/bar_block_size.lua --set sizes=0.2 --set mesh=0.2 --set g0=20
             --set max_precursor=5)
dda_run_test(paper.meshed_precursor_full long 3600 paper/bar_block_size.lua --set sizes=0.2 --set mesh=0.05
             --set g0=20 --set max_precursor=2)
# The same with the elements' mass lumped at their corners (mesh_mass =
# "lumped", docs/meshed_blocks.md) and nu = 0 (the 2-D bar is the 1-D one),
# where the consistent mass leaves 5.4 % at 0.1 m and 3.2 % at 0.05 m: the
# precursor under 2 % and both first peaks within 1 % of the exact
# jointed bar (-5.017 / 5.000 MPa), at 0.2 m elements in the default set
# (measured 0.00 %, +0.71 % and +0.16 %) and at 0.05 m as a long run.
dda_run_test(paper.meshed_precursor_lumped paper 600 paper/bar_block_size.lua --set sizes=0.2 --set mesh=0.2
             --set g0=20 --set nu=0 --set mesh_mass=lumped --set max_precursor=2 --set check=true)
dda_run_test(paper.meshed_precursor_lumped_full long 3600 paper/bar_block_size.lua --set sizes=0.2 --set mesh=0.05
             --set g0=20 --set nu=0 --set mesh_mass=lumped --set max_precursor=2 --set check=true)
# The paper's Model 1 with its blocks meshed (docs/meshed_blocks.md),
# nu = 0 (the 2-D bar is then the 1-D one), against the exact jointed bar: the
# first compressive peak at the centre within 3 % at 0.05 m (long); a smoke run
# of the script on a near receiver in the default set.
dda_run_test(paper.meshed_bar_smoke paper 600 paper/meshed_bar.lua --set sizes=0.2 --set at=1.1 --set nu=0
             --set first_order=false)
dda_run_test(paper.meshed_bar long 7200 paper/meshed_bar.lua --set sizes=0.05 --set nu=0 --set first_order=false
             --set check=true)
# The Fig. 8 bar's energy budget with the VBC closes under newmark (residual
# under 1 % of the load's work; scripts/paper/vbc_energy_check.lua).
dda_run_test(paper.vbc_energy paper 600 paper/vbc_energy_check.lua)
# The state hashes of the benchmark scenes (scripts/bench/state_hashes.lua)
# under each contact law equal bench/state_hashes.txt ("holding", the
# default) and bench/state_hashes_shi.txt ("shi": the engine's results before
# the holding law, bit for bit), comment lines aside.
foreach(law holding shi)
  if(law STREQUAL "holding")
    set(name script.state_hashes)
    set(expected bench/state_hashes.txt)
  else()
    set(name script.state_hashes_${law})
    set(expected bench/state_hashes_${law}.txt)
  endif()
  add_test(NAME ${name}
           COMMAND bash -c "diff <(grep -v '^#' \"$2\") <(\"$1\" run scripts/bench/state_hashes.lua --quiet --out \"$3\" --set contact_law=$4 | grep -v '^progress')"
                   _ $<TARGET_FILE:dda> ${expected} ${DDA_SCRIPT_TEST_OUT}/${name} ${law}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(${name} PROPERTIES LABELS scripts TIMEOUT 120)
endforeach()
# The same hashes whatever BLAS kernels the machine's OpenBLAS would pick
# (OPENBLAS_CORETYPE forces them, as another CPU would): the CHOLMOD factor
# of the walls calls the engine's own dense kernels (solver/portable_blas.hpp).
foreach(core Prescott Haswell SkylakeX Zen)
  set(name script.state_hashes_blas_${core})
  add_test(NAME ${name}
           COMMAND bash -c "diff <(grep -v '^#' \"$2\") <(\"$1\" run scripts/bench/state_hashes.lua --quiet --out \"$3\" | grep -v '^progress')"
                   _ $<TARGET_FILE:dda> bench/state_hashes.txt ${DDA_SCRIPT_TEST_OUT}/${name}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(${name} PROPERTIES LABELS scripts TIMEOUT 120 ENVIRONMENT OPENBLAS_CORETYPE=${core})
endforeach()
