// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The stages of a step, and what a step reports: its counts and a profile of
// seconds per stage (Box2D v3's b2Profile). Adding a stage adds an entry to
// Stage and kStageKeys; Lua's m:stats() shows it as t_<key>.
#include <array>
#include <chrono>
#include <string>

#include "core/error.hpp"

namespace dda {

enum class Stage {
  DetectContacts,  // broad and narrow phase, or the reused list's linearisation
  PredictStates,   // warm start and the open-close iteration's first guess
  Assemble,        // block terms, loads and boundaries, contact rows
  Solve,           // the linear solver (its setup included)
  CheckContacts,   // the open-close decision
  ControlStep,     // motion checks, accept or cut Δt and redo
  Update,          // move blocks, points and contacts; advance time
};
inline constexpr int kStageCount = 7;
// Short names, in Stage order (m:stats() fields t_detect, t_predict, ...).
inline constexpr std::array<const char*, kStageCount> kStageKeys{"detect", "predict", "assemble", "solve",
                                                                 "check",  "control", "update"};

struct StepProfile {
  std::array<double, kStageCount> seconds{};  // per stage, redone attempts included
  double total = 0;                           // the whole step, wall clock
  double& operator[](Stage s) { return seconds[static_cast<int>(s)]; }
  double operator[](Stage s) const { return seconds[static_cast<int>(s)]; }
};

// Adds the seconds from its construction to its destruction to a stage.
class StageTimer {
 public:
  StageTimer(StepProfile& profile, Stage stage) : into_(profile[stage]), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() { into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  double& into_;
  std::chrono::steady_clock::time_point start_;
};

// One step, including redone attempts.
struct StepStats {
  double dt = 0;
  int open_close_iterations = 0;  // one solve each
  int cg_iterations = 0;          // over all rows
  int patch_iterations = 0;       // confined to the patch of a re-solve (PcgSettings::patch_hops)
  const char* solver = "";        // the backend that solved ("pcg", "cholmod": SolverSettings::kind)
  int factorisations = 0;         // numeric factorisations of the system (cholmod; LinearSolver::end_step's included)
  int factor_iterations = 0;      // of cg_iterations, those preconditioned with the factor (cholmod)
  const char* solve_regime = "";  // "short" or "long" solves (world/solve_regime.hpp)
  int step_cuts = 0;
  std::string cut_reason;  // why the last cut was made ("" when none), with the block when one is to blame
  int contacts = 0;
  int closed_contacts = 0;
  bool contacts_searched = false;     // a full contact search ran (else the list was reused)
  double max_displacement_ratio = 0;  // largest vertex displacement / (g2 bound)
  int landings = 0;                   // contacts the landing law (restitution) resolved in the step
  StepProfile profile;

  // What a checkpoint holds (core/archive.hpp): the counts, which choose the
  // next step's solve regime and preconditioner; not the timings.
  template <class Archive>
  void fields(Archive& ar) {
    ar(dt, open_close_iterations, cg_iterations, patch_iterations, step_cuts, cut_reason, contacts, closed_contacts,
       contacts_searched, max_displacement_ratio);
    if constexpr (Archive::reading) cut_reason = printable(cut_reason);  // (it reaches messages)
  }
};

}  // namespace dda
