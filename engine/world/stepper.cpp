// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The DDA time step as its table of contents (as Box2D v3's b2World_Step):
//
//   step
//   ├─ check_new_model       once per set of blocks: no overlaps, the g2 length
//   ├─ begin_step            validate controls; derive automatic g0, g1;
//   │                        threads; material constants; the contact law
//   │                        (checks the controls it cannot work with); the
//   │                        time scheme (and the state of new blocks); the
//   │                        linear solver's backend, then the solve regime
//   │                        (solve_regime.hpp) from that backend's last step
//   ├─ DetectContacts        contact/contact_detection: search or reuse the list
//   │                        (the contact law's history follows a search)
//   ├─ attempt, until one is accepted:
//   │  ├─ Assemble           assembly/block_terms, loading/, boundary/ at t + Δt
//   │  ├─ PredictStates      warm start; the contact law's first guess
//   │  ├─ open-close loop, until the contact law asks for no other solve:
//   │  │  ├─ Assemble        the contact law's terms (springs, forces) into
//   │  │  │                  assembly/contact_terms: rows of the changed contacts
//   │  │  ├─ Solve           solver/: the LinearSolver (PCG or CHOLMOD; with
//   │  │  │                  meshed blocks assembly/mesh_reduction, for the nodes)
//   │  │  └─ CheckContacts   the contact law: open, sliding, locked
//   │  └─ ControlStep        block/motion: g2 bound, contact range, inverted
//   │                        blocks, penetration → accept, or cut Δt (or widen
//   │                        the contact range) and redo (step_control.hpp)
//   ├─ the linear solver's end of step (its choice for the next step)
//   └─ Update                the energy budget (world/energy.cpp); the contact
//                            law's impacts (the landing law, opt-in);
//                            block/motion, loading/, boundary/; what the
//                            contacts keep; Δt grows back after a clean step
//
// Each stage is timed into StepStats::profile (step_profile.hpp). Where the
// next changes land:
//   * the time integrator (Shi, Newmark, generalized-α): block/time_scheme.hpp,
//     the one place that says how inertia, dashpots, the warm start and the
//     velocity update follow from the step displacement; its state
//     (Blocks::velocity, acceleration, out_of_balance) is written in Update
//     only, so a redone attempt finds it untouched;
//   * the energy budget: world/energy.cpp, at the start of Update (each
//     kind's work from its own folder: Loads/Boundaries::step_work);
//   * contact transfer: contact/contact_detection (carries states over by
//     identity);
//   * a contact law: contact/ behind ContactModel (contact_model.hpp), one
//     file each (shi_law, holding_law); the open-close iteration's
//     questions, what a redo restores (save_step/restore_step) and what the
//     contacts keep (commit) are the model's;
//   * another solver backend: solver/ only (linear_solver.hpp says how).
#include "world/stepper.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_invoke.h>

#include "assembly/contact_terms.hpp"
#include "assembly/mesh_reduction.hpp"
#include "contact/broad_phase.hpp"
#include "contact/contact_report.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/parallel.hpp"
#include "geometry/polygon.hpp"
#include "world/energy.hpp"
#include "world/inert_controls.hpp"
#include "world/time_step_rule.hpp"

namespace dda {

StepStats Stepper::step(WorldState& w) {
  const auto t_start = std::chrono::steady_clock::now();
  if (!w.prepared) check_new_model(w);
  begin_step(w);
  arena_->execute([&] {
    detect_contacts(w);
    {
      StageTimer timer(stats_.profile, Stage::ControlStep);
      contact_model_->save_step(w.contacts);
    }
    for (;;) {
      const Rejection r = attempt(w);
      if (r == Rejection::None) break;
      control_step(w, r);
    }
    stats_.factorisations += solver_->end_step();
    update(w);
    finish_step(w);
  });
  stats_.profile.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  w.last_stats = stats_;
  return stats_;
}

// ---- Once per set of blocks ---------------------------------------------------

void Stepper::check_new_model(WorldState& w) {
  const Blocks& blocks = w.blocks;
  if (blocks.count() == 0) throw Error("the model has no blocks");

  // Blocks must not overlap at the start: a crossing of two edges, or a
  // vertex inside another block, is a modelling error.
  // Edges that merely touch, computed with round-off (cos/sin), are not
  // crossings: a crossing must go deeper than 1e-9 of the blocks' size.
  const BlockPolygons polys = blocks.polygons();
  for (const auto& [a, b] : find_candidate_pairs(polys, 0.0)) {
    const auto pa = polys.of(a), pb = polys.of(b);
    const double tol = 1e-9 * std::sqrt(std::min(blocks.area[a], blocks.area[b]));
    for (std::size_t i = 0; i < pa.size(); ++i)
      for (std::size_t j = 0; j < pb.size(); ++j)
        if (segments_cross_clearly(pa[i], pa[(i + 1) % pa.size()], pb[j], pb[(j + 1) % pb.size()], tol))
          throw Error(msg("blocks ", a, " and ", b, " overlap at the start (edge ", i + 1, " of block ", a,
                          " crosses edge ", j + 1, " of block ", b, ")"));
    auto vertex_inside = [&](std::span<const Vec2> p, std::span<const Vec2> q, int pb_id, int qb_id) {
      const double size = std::sqrt(std::abs(signed_area(q)));
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (point_in_polygon(q, p[i]) && distance_to_outline(q, p[i]) > 1e-9 * size)
          throw Error(msg("blocks ", pb_id, " and ", qb_id, " overlap at the start (vertex ", i + 1, " of block ",
                          pb_id, " lies inside block ", qb_id, ")"));
      }
    };
    vertex_inside(pa, pb, a, b);
    vertex_inside(pb, pa, b, a);
    // Shared area with no crossing and no vertex inside: coinciding blocks,
    // or blocks overlapping along collinear edges (they would run with no
    // contact between them).
    const double inset = 1e-6 * std::sqrt(std::min(blocks.area[a], blocks.area[b]));
    auto shared = shared_area_point(pa, pb, inset, tol);
    if (!shared) shared = shared_area_point(pb, pa, inset, tol);
    if (shared)
      throw Error(msg("blocks ", a, " and ", b, " overlap at the start: they share area near (", shared->x(), ", ",
                      shared->y(), "); coinciding blocks, or blocks overlapping along collinear edges"));
  }
  // Memory stated up front: a model the machine cannot hold is refused
  // here, with the estimate, not killed part way (docs/robustness.md has
  // the calibration: about 3.3 kB a block for squares, 3.9 kB for triangles).
  constexpr double kStepBytesPerBlock = 2500, kStepBytesPerVertex = 500;
  const double vertices = static_cast<double>(blocks.vertices.size());
  check_memory_need(kStepBytesPerBlock * static_cast<double>(blocks.count()) + kStepBytesPerVertex * vertices,
                    memory_headroom(), "the model's first step",
                    msg(blocks.count(), " blocks with ", vertices, " vertices"),
                    blocks.has_meshes() ? "use fewer blocks and elements (larger joint spacings, a larger mesh_size, "
                                          "or a smaller domain)"
                                        : "use fewer blocks (larger joint spacings or a smaller domain)");
  w.half_height = w.measured_half_height();
  if (!(w.half_height > 0)) throw Error("the model has no height (all vertices on one horizontal line)");
  detection_.start_automatic_range(blocks);
  w.prepared = true;
}

// ---- begin_step ---------------------------------------------------------------

void Stepper::begin_step(WorldState& w) {
  stats_ = StepStats{};
  validate_controls(w.controls);
  for (int r = 0; r < static_cast<int>(w.rocks.size()); ++r) validate(w.rocks[r], r);
  for (int j = 0; j < static_cast<int>(w.joints.size()); ++j) validate(w.joints[j], j);
  derive_automatic_controls(w);
  set_up_threads(w.controls);
  derive_material_constants(w);
  set_up_contact_model(w);
  refuse_inert_controls(
      {w.controls, effective_integrator(w), w.blocks.has_meshes(), contact_model_->ignored_controls()});
  start_time_scheme(w);
  set_up_solver(w);
}

// g0 = 50 × the largest E and g1 from the default time step rule
// (world/time_step_rule.hpp) where the controls say 0 (automatic); Δt starts
// at g1 and never exceeds it.
void Stepper::derive_automatic_controls(WorldState& w) {
  const Controls& c = w.controls;
  g0_ = w.contact_spring();
  g1_ = c.g1 > 0 ? c.g1 : default_time_step(w).dt;
  if (w.dt <= 0 || w.dt > g1_) w.dt = g1_;
}

void Stepper::set_up_threads(const Controls& c) {
  if (arena_threads_ != c.threads || !arena_) {
    arena_ = c.threads > 0 ? std::make_unique<tbb::task_arena>(c.threads) : std::make_unique<tbb::task_arena>();
    arena_threads_ = c.threads;
  }
}

void Stepper::derive_material_constants(const WorldState& w) {
  const Controls& c = w.controls;
  elastic_.resize(w.rocks.size());
  for (std::size_t r = 0; r < w.rocks.size(); ++r) elastic_[r] = elastic_matrix(w.rocks[r], c.plane);
  tan_friction_.resize(w.joints.size());
  for (std::size_t j = 0; j < w.joints.size(); ++j) tan_friction_[j] = std::tan(deg_to_rad(w.joints[j].friction_deg));
  scheme_.gg = c.gg;
  scheme_.choose(effective_integrator(w), c.rho_inf);
  scheme_.mesh_mass = effective_mesh_mass(w);
}

// A model made for another law takes over the contacts' history where it
// means the same to it.
ContactModel& Stepper::contact_model(const WorldState& w) {
  if (!contact_model_ || contact_model_->law() != w.controls.contact_law) {
    std::unique_ptr<ContactModel> next = make_contact_model(w.controls.contact_law);
    next->take_over(contact_model_.get(), w.contacts.size());
    contact_model_ = std::move(next);
  }
  return *contact_model_;
}

// The model of the control contact_law, its parameters for the step, and its
// check of the controls (it refuses those it cannot work with).
void Stepper::set_up_contact_model(const WorldState& w) {
  const Controls& c = w.controls;
  ContactParameters p;
  p.g0 = g0_;
  p.shear_ratio = c.shear_ratio;
  p.tolerance = c.contact_tolerance * w.half_height;
  p.joints = w.joints;
  p.tan_friction = tan_friction_;
  p.friction_lag = c.friction_lag;
  p.restitution = c.restitution;
  p.integrator = effective_integrator(w);
  ContactModel& model = contact_model(w);
  model.check(p, w.blocks);
  model.set_parameters(p);
}

// The second-order schemes' state of blocks that have none yet (new blocks):
// their acceleration under the loads at the step's start.
void Stepper::start_time_scheme(WorldState& w) {
  Blocks& blocks = w.blocks;
  if (scheme_.is_shi() || std::none_of(blocks.acceleration.begin(), blocks.acceleration.end(),
                                       [](const Vec6& a) { return std::isnan(a[0]); }))
    return;
  BlockTerms loads;
  loads.f.assign(blocks.count(), Vec6::Zero());
  w.loads.add_terms(w.time, blocks, loads);
  start_time_scheme_state(blocks, w.controls.gravity, loads, scheme_.mesh_mass);
}

// The linear solver picks its backend, the step's solve regime follows from
// that backend's last step, and the solver is told what the solves are like.
void Stepper::set_up_solver(const WorldState& w) {
  const Controls& c = w.controls;
  if (!solver_) solver_ = make_linear_solver(c.solver);
  use_meshed_solver(solver_, w.blocks);  // meshed blocks: solved for their nodes
  StepSolveInfo info;
  info.blocks = static_cast<int>(w.blocks.count());
  info.block_centroids = w.blocks.centroid;
  info.last_step_solves = w.last_stats.open_close_iterations;
  info.last_step_iterations = w.last_stats.cg_iterations;
  info = solver_->choose_backend(c.solver, info);
  regime_ = SolveRegime::choose(c, info);
  info.local_resolves = regime_.local_resolves;
  solver_->begin_step(c.solver, info);
  stats_.solver = solver_->name();
  stats_.solve_regime = regime_.name();
  solver_->max_iterations =
      c.cg_max_iterations > 0 ? c.cg_max_iterations : static_cast<int>(60 * w.blocks.count() + 100);
  system_.store_products(regime_.stored_products);
}

// ---- DetectContacts -----------------------------------------------------------

void Stepper::detect_contacts(WorldState& w) {
  StageTimer timer(stats_.profile, Stage::DetectContacts);
  const Controls& c = w.controls;
  const double range = detection_.range(c.contact_range, 2.5 * c.g2 * w.half_height);
  if (detection_.detect(w.blocks, range, w.contacts, linearisation_, previous_contact_)) {
    stats_.contacts_searched = true;
    contact_model_->follow_search(previous_contact_);
    // The system's rows: which contacts couple which blocks.
    system_.set_contacts(static_cast<int>(w.blocks.count()), w.contacts);
  }
}

// ---- One attempt at the step --------------------------------------------------

Rejection Stepper::attempt(WorldState& w) {
  scheme_.dt = w.dt;
  assemble_own_terms(w);
  predict(w);
  if (const Rejection r = open_close(w); r != Rejection::None) return r;
  return check_motion(w);
}

// The blocks' own terms, loads and boundaries: once per attempt (they do not
// depend on the contact states). Histories are evaluated at the end of the
// step, t + Δt (t while settling).
void Stepper::assemble_own_terms(WorldState& w) {
  StageTimer timer(stats_.profile, Stage::Assemble);
  const Controls& c = w.controls;
  const double t_end = w.step_end_time();
  assemble_block_terms(w.blocks, elastic_, c.gravity, c.strain_damping, scheme_, own_);
  w.loads.add_terms(t_end, w.blocks, own_);
  w.boundaries.add_terms(t_end, c.fixed_point_factor * g0_, w.blocks, scheme_, own_);
}

// The warm start and the open-close iteration's first guess (solve_regime.hpp).
void Stepper::predict(WorldState& w) {
  StageTimer timer(stats_.profile, Stage::PredictStates);
  const Blocks& blocks = w.blocks;
  // The Δt of the step the warm start extrapolates from: the last accepted
  // one's (after a cut or a growth of Δt it differs), as the contact law says
  // (Shi's keeps the engine's earlier results bit for bit, with this step's).
  const double dt_last = contact_model_->warm_start_dt(w.last_stats.dt, w.dt);
  solution_.resize(6 * static_cast<Eigen::Index>(blocks.count()));
  parallel_for_each(
      blocks.count(),
      [&](std::size_t b) {
        solution_.segment<6>(6 * b) =
            regime_.extrapolate_warm_start
                ? scheme_.extrapolated_displacement(blocks.scheme_state(b), blocks.last_displacement[b], dt_last)
                : blocks.last_displacement[b];
      },
      256);
  contact_model_->start_attempt(w.contacts, linearisation_, w.dt, regime_.predict_states ? &solution_ : nullptr);
}

// loop { Assemble → Solve → CheckContacts } until the contact law asks for
// no other solve.
// Solves while states change stop at the regime's open-close tolerance; once
// the states hold, a tightening pass (which does not count against the
// open-close limit) solves to the accepted tolerance and checks again.
// (Friction on sliding contacts uses the normal force of the solve before,
// as in Shi's iteration: after a tightening pass that is the loose solve with
// the same states, a smaller lag than after a solve whose states then
// changed.)
// Names the block a diverged solve comes from: the first with a non-finite
// load, stiffness or displacement; when every entry is finite yet the solve
// overflowed (a norm or product of huge entries), the block with the largest
// load or stiffness.
std::string Stepper::divergence_message(const WorldState& w) const {
  const std::string where = msg("step ", w.steps + 1, " at t = ", w.time, " s diverged: ");
  const char* cure = " (check material constants, loads, g0 and the time step)";
  const int n = static_cast<int>(w.blocks.count());
  for (int b = 0; b < n; ++b) {
    const bool load = rhs_.segment<6>(6 * b).allFinite(), stiffness = system_.diagonal_block(b).allFinite();
    if (!load || !stiffness || !solution_.segment<6>(6 * b).allFinite())
      return msg(where, "block ", b, " has a non-finite ",
                 !load        ? "load"
                 : !stiffness ? "stiffness"
                              : "displacement",
                 cure);
  }
  int worst = 0;
  double worst_size = -1;
  bool worst_is_load = true;
  for (int b = 0; b < n; ++b) {
    const double load = rhs_.segment<6>(6 * b).cwiseAbs().maxCoeff();
    const double stiffness = system_.diagonal_block(b).cwiseAbs().maxCoeff();
    if (std::max(load, stiffness) > worst_size)
      worst = b, worst_size = std::max(load, stiffness), worst_is_load = load >= stiffness;
  }
  return msg(where, "the linear solve overflowed; block ", worst, " has the largest ",
             worst_is_load ? "load" : "stiffness", " (", worst_size, ")", cure);
}

Rejection Stepper::open_close(WorldState& w) {
  const Controls& c = w.controls;
  bool tightening = false;
  bool first_solve = true;
  for (int it = 0; it < c.open_close_limit; ++it) {
    ++stats_.open_close_iterations;
    solver_->tolerance = tightening ? regime_.accept_tolerance : regime_.open_close_tolerance;
    {
      StageTimer timer(stats_.profile, Stage::Assemble);
      contact_model_->contribute(w.contacts, linearisation_);
      assemble_contact_rows(w.contacts, linearisation_, contact_model_->terms(), contact_model_->changed(), own_,
                            /*all_rows=*/it == 0 && !tightening, system_, rhs_, row_reassembled_);
    }
    SolveReport report;
    {
      StageTimer timer(stats_.profile, Stage::Solve);
      solver_->set_operator(system_);
      // After the first solve only the reassembled rows changed: the solver
      // keeps the last residual elsewhere.
      report = first_solve ? solver_->solve(rhs_, solution_) : solver_->resolve(rhs_, solution_, row_reassembled_);
      first_solve = false;
    }
    stats_.cg_iterations += report.iterations;
    stats_.patch_iterations += report.patch_iterations;
    stats_.factorisations += report.factorisations;
    stats_.factor_iterations += report.factor_iterations;
    if (!report.finite || !parallel_all(static_cast<std::size_t>(solution_.size()),
                                        [&](std::size_t i) { return std::isfinite(solution_[i]); }))
      throw Error(divergence_message(w));
    if (!report.converged) return Rejection::SolverNotConverged;

    NextSolve next = NextSolve::None;
    {
      StageTimer timer(stats_.profile, Stage::CheckContacts);
      next = contact_model_->check_solve(w.contacts, linearisation_, solution_);
    }
    if (next != NextSolve::None) {
      tightening = false;
      if (next == NextSolve::Uncounted) --it;  // (friction that lagged grossly alone, under the holding law)
    } else if (solver_->tolerance == regime_.accept_tolerance) {
      return Rejection::None;  // settled
    } else {
      tightening = true;
      --it;  // the tightening pass is free
    }
  }
  return Rejection::OpenCloseUnsettled;
}

// ---- ControlStep --------------------------------------------------------------

// The settled solve's motion against the g2 bound and the contact range, and
// its blocks and contacts against inversion and deep penetration.
Rejection Stepper::check_motion(const WorldState& w) {
  StageTimer timer(stats_.profile, Stage::ControlStep);
  const Controls& c = w.controls;
  const double bound = c.g2 * w.half_height;
  motion_ = check_block_motion(w.blocks, solution_, block_inverted_, vertex_motion_);
  if (motion_.largest_displacement > bound) return Rejection::DisplacementTooLarge;
  const double range = detection_.range(c.contact_range, 2.5 * c.g2 * w.half_height);
  if (motion_.largest_displacement > range / 2.5) return Rejection::BeyondContactRange;
  if (motion_.inverted_block >= 0) return Rejection::BlockInverted;
  if (contact_model_->deepest_penetration() > bound) return Rejection::PenetrationTooDeep;
  return Rejection::None;
}

// A rejected attempt: widen the automatic contact range past the step's
// motion, search again and redo with the same Δt (the range only widens: this
// ends at Shi's range, which the g2 bound already guarantees); otherwise cut
// Δt and redo, up to max_step_cuts times.
void Stepper::control_step(WorldState& w, Rejection r) {
  const Controls& c = w.controls;
  if (r == Rejection::BeyondContactRange && c.contact_range == 0) {
    detection_.widen_automatic_range(motion_.largest_displacement);
    {
      StageTimer timer(stats_.profile, Stage::ControlStep);
      contact_model_->restore_step(w.contacts);
    }
    detect_contacts(w);
    StageTimer timer(stats_.profile, Stage::ControlStep);
    contact_model_->save_step(w.contacts);
    return;
  }
  StageTimer timer(stats_.profile, Stage::ControlStep);
  stats_.cut_reason =
      msg(describe(r), r == Rejection::BlockInverted ? msg(" (block ", motion_.inverted_block, ")") : std::string());
  if (stats_.step_cuts == c.max_step_cuts)
    throw Error(msg("step ", w.steps + 1, " at t = ", w.time, " s: ", stats_.cut_reason, " even after ",
                    stats_.step_cuts, " cuts of the time step (down to ", w.dt, " s). ",
                    r == Rejection::PenetrationTooDeep
                        ? describe_deepest_contact(w.blocks, w.contacts, linearisation_, contact_model_->parameters(),
                                                   c.g2 * w.half_height, w.half_height)
                        : "Check loads, g0 and g2."));
  ++stats_.step_cuts;
  contact_model_->restore_step(w.contacts);
  w.dt *= c.cut_factor;
}

// ---- Update -------------------------------------------------------------------

// The accepted step: its energy booked, the contact law's impacts, material
// points (they move with their block's old centroid), then the blocks (and
// the blocks' energy terms, in the same pass), then what the contacts keep;
// time advances (unless settling). The contacts' energy terms are read before
// an impact changes them, and what they keep written after the impacted
// blocks moved. Without impacts the contacts' energy and commit run beside
// the loads' and boundaries' work, the points (short serial loops) and the
// blocks' pass: neither touches what the other reads (each sum in its own
// fixed order, so the same bits).
void Stepper::update(WorldState& w) {
  StageTimer timer(stats_.profile, Stage::Update);
  const bool impacts = contact_model_->resolves_impacts();
  const auto book_contacts = [&] {
    step_energy_.book_contacts(contact_model_->energy(w.contacts, linearisation_, solution_));
  };
  const auto book_work = [&] {
    step_energy_.start(w, solution_, scheme_, elastic_, w.controls.fixed_point_factor * g0_);
  };
  const auto move_points = [&] {
    w.loads.move_points(w.blocks, solution_);
    w.boundaries.update(w.blocks, solution_, scheme_);
    move_material_points(w.tracked, w.blocks, solution_);
  };
  ImpactWork impact_work;
  if (impacts) {
    book_work();
    book_contacts();
    impact_work = resolve_impacts(w);
    move_points();
  } else {
    resolve_impacts(w);  // none (it forgets the last step's)
  }
  const VecX& solved = impacts ? solved_ : solution_;
  tbb::parallel_invoke(
      [&] {
        if (!impacts) {
          book_work();
          move_points();
        }
        move_blocks(w.blocks, solution_, vertex_motion_, elastic_, scheme_,
                    [&](std::size_t b, const IntegratedTt& mass) {
                      step_energy_.book_block(w.blocks, b, solved.segment<6>(6 * b), mass);
                      detection_.add_rotation(b, solution_[6 * b + 2]);
                    });
      },
      [&] {
        if (!impacts)
          step_energy_.book_contacts(
              contact_model_->energy_and_commit(w.blocks, w.contacts, linearisation_, solution_));
      });
  step_energy_.account(w);
  if (impacts) {
    if (stats_.landings > 0)
      account_impact_energy(w.energy, contact_model_->impact_energy(), impact_work.solved, impact_work.landed);
    contact_model_->commit(w.blocks, w.contacts, linearisation_);
  }
  w.time = w.step_end_time();
  ++w.steps;
}

// The contact law's impacts (the landing law, control restitution, off at
// -1): the contacts that land in the accepted step end it as a rigid-body
// impact would end them; the step's displacement and its blocks' motion
// change with it. Returns the boundaries' work over the solve and over the
// step the law made of it, for the energy budget to book what the impacts
// took (account_impact_energy, after the step's own terms).
Stepper::ImpactWork Stepper::resolve_impacts(WorldState& w) {
  const Controls& c = w.controls;
  const bool impacts = contact_model_->resolves_impacts();
  if (impacts) solved_ = solution_;
  const std::vector<char> held = impacts ? w.boundaries.held_blocks(w.blocks.count()) : std::vector<char>();
  stats_.landings = contact_model_->resolve_impacts(w.contacts, linearisation_,
                                                    {w.blocks, scheme_, own_.k, elastic_, held, c.gravity}, solution_);
  if (stats_.landings == 0) return {};
  const double spring = c.fixed_point_factor * g0_, t_end = w.step_end_time();
  ImpactWork work;
  work.solved = w.boundaries.step_work(w.time, t_end, spring, w.blocks, solved_, scheme_);
  work.landed = w.boundaries.step_work(w.time, t_end, spring, w.blocks, solution_, scheme_);
  check_block_motion(w.blocks, solution_, block_inverted_, vertex_motion_);
  return work;
}

// The step's figures; after a clean step Δt grows back towards g1.
void Stepper::finish_step(WorldState& w) {
  stats_.dt = w.dt;
  stats_.max_displacement_ratio = motion_.largest_displacement / (w.controls.g2 * w.half_height);
  if (stats_.step_cuts == 0) w.dt = std::min(g1_, w.dt * 1.5);
  stats_.contacts = static_cast<int>(w.contacts.size());
  // Counted in parallel: on one thread this memory-bound pass over every
  // contact would not shrink with the threads; a count is exact in any order.
  stats_.closed_contacts = static_cast<int>(
      parallel_count(w.contacts.size(), [&](std::size_t i) { return w.contacts[i].state != ContactState::Open; }));
}

}  // namespace dda
