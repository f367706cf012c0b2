// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The DDA time step. A Stepper advances a WorldState by one step and owns
// everything the step needs besides the model itself: resolved controls, the
// contact list's search state, the system, the linear solver and the scratch
// reused from step to step (so that the step loop does not allocate).
// stepper.cpp opens with the step as its table of contents.
#include <tbb/task_arena.h>

#include <memory>
#include <string>
#include <vector>

#include "assembly/block_terms.hpp"
#include "assembly/contact_operator.hpp"
#include "assembly/mesh_reduction.hpp"
#include "block/motion.hpp"
#include "block/time_scheme.hpp"
#include "contact/contact_detection.hpp"
#include "contact/contact_model.hpp"
#include "solver/linear_solver.hpp"
#include "world/energy.hpp"
#include "world/solve_regime.hpp"
#include "world/step_control.hpp"
#include "world/world_state.hpp"

namespace dda {

class Stepper {
 public:
  StepStats step(WorldState& w);

  // The system of the last open-close iteration (A·D = F).
  const ContactOperator& system() const { return system_; }
  const VecX& rhs() const { return rhs_; }
  // The contact law of the last step (nullptr before the first).
  const ContactModel* current_contact_model() const { return contact_model_.get(); }

  // What a checkpoint holds of the Stepper (core/archive.hpp): what one step
  // leaves for the next besides the WorldState, the contact law's own state
  // included (ContactModel::save). The rest is set up anew by every step
  // (resolved controls, material constants, the solve regime, the contacts'
  // linearisation) or is scratch; the system's rows follow the restored
  // contact list.
  template <class Archive>
  void fields(Archive& ar, const WorldState& w) {
    ar.section("contact detection"), ar(detection_);
    if constexpr (Archive::reading) detection_.check_loaded(LoadCheck(ar.what()), w.blocks);
    ar.section("linear solver");
    bool has_solver = solver_ != nullptr;
    ar(has_solver);
    if constexpr (Archive::reading) {
      solver_ = has_solver ? make_linear_solver(w.controls.solver) : nullptr;
      if (solver_) use_meshed_solver(solver_, w.blocks), solver_->load_state(ar);
      system_.set_contacts(static_cast<int>(w.blocks.count()), w.contacts);
    } else if (solver_) {
      solver_->save_state(ar);
    }
    ar.section("contact law");
    if constexpr (Archive::reading) {
      contact_model_ = nullptr;  // the restored contacts' history is the file's
      contact_model(w).load(ar);
    } else {
      contact_model(w).save(ar);
    }
  }

 private:
  // The stages, in the order step() runs them.
  void check_new_model(WorldState& w);
  void begin_step(WorldState& w);
  void derive_automatic_controls(WorldState& w);
  void set_up_threads(const Controls& c);
  void derive_material_constants(const WorldState& w);
  void set_up_contact_model(const WorldState& w);
  void start_time_scheme(WorldState& w);
  void set_up_solver(const WorldState& w);
  void detect_contacts(WorldState& w);
  Rejection attempt(WorldState& w);
  void assemble_own_terms(WorldState& w);
  void predict(WorldState& w);
  Rejection open_close(WorldState& w);
  Rejection check_motion(const WorldState& w);
  void control_step(WorldState& w, Rejection r);
  void update(WorldState& w);
  struct ImpactWork {
    Boundaries::Work solved, landed;  // the boundaries' work over the solve, over the step after impacts
  };
  ImpactWork resolve_impacts(WorldState& w);
  void finish_step(WorldState& w);
  std::string divergence_message(const WorldState& w) const;  // names the block
  ContactModel& contact_model(const WorldState& w);           // the model of w.controls.contact_law

  // Set once per step by begin_step.
  double g0_ = 0, g1_ = 0;  // resolved (automatic values filled in)
  std::unique_ptr<tbb::task_arena> arena_;
  int arena_threads_ = -1;
  SolveRegime regime_;
  std::vector<Mat3> elastic_;         // per rock material
  std::vector<double> tan_friction_;  // tan φ per joint material
  TimeScheme scheme_;                 // Δt set by each attempt

  // Kept from step to step.
  ContactDetection detection_;
  ContactLinearisation linearisation_;  // per contact
  std::vector<int> previous_contact_;   // per contact: its index before the last search (-1: new)
  // The contact law (contact/contact_model.hpp): its per-contact state, what
  // a redo restores, what the contacts add to the system, its impacts.
  std::unique_ptr<ContactModel> contact_model_;
  ContactOperator system_;  // the matrix of the step, matrix-free off the diagonal
  std::unique_ptr<LinearSolver> solver_;
  BlockTerms own_;  // per block
  VecX rhs_, solution_;
  VecX solved_;                        // the accepted solve, before the contact law's impacts changed it
  std::vector<char> row_reassembled_;  // per block row: rewritten by the last assembly
  std::vector<char> block_inverted_;   // per block (check_block_motion's scratch)
  std::vector<Vec2> vertex_motion_;    // per vertex: the last checked solve's motion
  StepEnergy step_energy_;             // the accepted step's energy terms, booked in Update
  MotionCheck motion_;                 // of the last attempt that got to its motion checks

  StepStats stats_;  // of the step under way
};

}  // namespace dda
