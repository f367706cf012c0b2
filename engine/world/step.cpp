// The DDA time step: a table of contents first, then one function per stage.
#include <algorithm>
#include <cmath>

#include "block/displacement.hpp"
#include "contact/broad_phase.hpp"
#include "contact/narrow_phase.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/polygon.hpp"
#include "world/world_impl.hpp"

namespace dda {

StepStats World::step() {
  if (!prepared_) prepare_first_step();
  resolve_controls();
  Impl& m = *impl_;
  StepStats stats;
  const auto t_start = Clock::now();
  m.arena->execute([&] {
    auto t0 = Clock::now();
    const long searches_before = m.detections;
    detect_contacts();
    stats.contacts_searched = m.detections != searches_before;
    stats.t_detect = seconds_since(t0);

    // Solve; when the step is rejected, restore the contact states, cut Δt
    // and redo it (ControlStep).
    save_contact_states();
    m.open_close_iterations = m.cg_iterations = m.patch_iterations = 0;
    m.t_assemble = m.t_solve = m.t_check = 0;
    for (;;) {
      const Rejection r = static_cast<Rejection>(solve_step(dt_));
      if (r == Rejection::None) break;
      if (r == Rejection::BeyondContactRange && controls_.contact_range == 0) {
        // Widen the automatic range past this step's motion, search again and
        // redo the step with the same Δt (the range only widens: this ends
        // at Shi's range, which the g2 bound already guarantees).
        auto_range_ = std::max(2.0 * auto_range_, 2.5 * 1.5 * m.largest_displacement);
        restore_contact_states();
        const auto t1 = Clock::now();
        detect_contacts();
        stats.t_detect += seconds_since(t1);
        save_contact_states();
        continue;
      }
      stats.cut_reason =
          msg(describe(r), r == Rejection::BlockInverted ? msg(" (block ", m.inverted_block, ")") : std::string());
      if (stats.step_cuts == controls_.max_step_cuts)
        throw Error(msg(
            "step ", steps_ + 1, " at t = ", time_, " s: ", stats.cut_reason, " even after ", stats.step_cuts,
            " cuts of the time step (down to ", dt_, " s). ",
            r == Rejection::PenetrationTooDeep ? "Raise g0 (contact stiffness) or g2." : "Check loads, g0 and g2."));
      ++stats.step_cuts;
      restore_contact_states();
      dt_ *= controls_.cut_factor;
    }
    stats.open_close_iterations = m.open_close_iterations;
    stats.cg_iterations = m.cg_iterations;
    stats.patch_iterations = m.patch_iterations;
    stats.t_assemble = m.t_assemble;
    stats.t_solve = m.t_solve;
    stats.t_check = m.t_check;
    stats.dt = dt_;
    stats.max_displacement_ratio = m.largest_displacement / (controls_.g2 * half_height_);

    t0 = Clock::now();
    update(dt_);
    stats.t_update = seconds_since(t0);
  });
  // After a clean step, let Δt grow back towards g1.
  if (stats.step_cuts == 0) dt_ = std::min(m.g1, dt_ * 1.5);
  stats.contacts = static_cast<int>(contacts_.size());
  stats.closed_contacts = static_cast<int>(std::count_if(
      contacts_.begin(), contacts_.end(), [](const Contact& c) { return c.state != ContactState::Open; }));
  stats.t_total = seconds_since(t_start);
  last_stats_ = stats;
  return stats;
}

// The contacts' iteration state at the start of a step, for a redo.
void World::save_contact_states() {
  Impl& m = *impl_;
  m.saved_states.resize(contacts_.size());
  parallel_for_each(
      contacts_.size(), [&](std::size_t i) { m.saved_states[i] = iteration_state(contacts_[i]); }, 1024);
}

void World::restore_contact_states() {
  Impl& m = *impl_;
  parallel_for_each(
      contacts_.size(), [&](std::size_t i) { set_iteration_state(contacts_[i], m.saved_states[i]); }, 1024);
}

// ---- Stage: first-step checks ----------------------------------------------

void World::prepare_first_step() {
  if (block_count() == 0) throw Error("the model has no blocks");

  // Blocks must not overlap at the start: a crossing of two edges, or a
  // vertex inside another block, is a modelling error.
  // Edges that merely touch, computed with round-off (cos/sin), are not
  // crossings: a crossing must go deeper than 1e-9 of the blocks' size.
  const BlockPolygons polys{vertex_start_, vertices_};
  for (const auto& [a, b] : find_candidate_pairs(polys, 0.0)) {
    const auto pa = polys.of(a), pb = polys.of(b);
    const double tol = 1e-9 * std::sqrt(std::min(area_[a], area_[b]));
    for (std::size_t i = 0; i < pa.size(); ++i)
      for (std::size_t j = 0; j < pb.size(); ++j)
        if (segments_cross_clearly(pa[i], pa[(i + 1) % pa.size()], pb[j], pb[(j + 1) % pb.size()], tol))
          throw Error(msg("blocks ", a, " and ", b, " overlap at the start (edge ", i + 1, " of block ", a,
                          " crosses edge ", j + 1, " of block ", b, ")"));
    auto vertex_inside = [&](std::span<const Vec2> p, std::span<const Vec2> q, int pb_id, int qb_id) {
      const double size = std::sqrt(std::abs(signed_area(q)));
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!point_in_polygon(q, p[i])) continue;
        double depth = INFINITY;  // distance to q's boundary
        for (std::size_t j = 0; j < q.size(); ++j) {
          const Vec2 e = q[(j + 1) % q.size()] - q[j];
          const double t = std::clamp((p[i] - q[j]).dot(e) / e.squaredNorm(), 0.0, 1.0);
          depth = std::min(depth, (p[i] - (q[j] + t * e)).norm());
        }
        if (depth > 1e-9 * size)
          throw Error(msg("blocks ", pb_id, " and ", qb_id, " overlap at the start (vertex ", i + 1, " of block ",
                          pb_id, " lies inside block ", qb_id, ")"));
      }
    };
    vertex_inside(pa, pb, a, b);
    vertex_inside(pb, pa, b, a);
  }
  half_height_ = 0;
  half_height_ = half_height();
  if (!(half_height_ > 0)) throw Error("the model has no height (all vertices on one horizontal line)");
  std::vector<double> edges;
  edges.reserve(vertices_.size());
  for (std::size_t b = 0; b < block_count(); ++b)
    for (int v = vertex_start_[b]; v < vertex_start_[b + 1]; ++v) {
      const int next = v + 1 < vertex_start_[b + 1] ? v + 1 : vertex_start_[b];
      edges.push_back((vertices_[next] - vertices_[v]).norm());
    }
  std::nth_element(edges.begin(), edges.begin() + edges.size() / 2, edges.end());
  auto_range_ = 0.1 * edges[edges.size() / 2];
  prepared_ = true;
}

void World::resolve_controls() {
  const Controls& c = controls_;
  // Runs every step: a message is built only when its check fails.
  auto require = [](bool ok, const auto&... what) {
    if (!ok) throw Error(msg("controls: ", what...));
  };
  require(std::isfinite(c.g0) && c.g0 >= 0, "g0 must be positive (or 0 for automatic), got ", c.g0);
  require(std::isfinite(c.g1) && c.g1 >= 0, "g1 must be positive (or 0 for automatic), got ", c.g1);
  require(std::isfinite(c.g2) && c.g2 > 0, "g2 must be positive, got ", c.g2);
  require(std::isfinite(c.gg) && c.gg >= 0 && c.gg <= 1, "gg must lie in [0, 1], got ", c.gg);
  require(std::isfinite(c.shear_ratio) && c.shear_ratio >= 0, "shear ratio must be zero or positive, got ",
          c.shear_ratio);
  require(c.open_close_limit >= 1, "open-close limit must be at least 1, got ", c.open_close_limit);
  require(std::isfinite(c.contact_tolerance) && c.contact_tolerance >= 0,
          "contact tolerance must be zero or positive, got ", c.contact_tolerance);
  require(std::isfinite(c.contact_range) && c.contact_range >= 0,
          "contact range must be zero (automatic) or positive, got ", c.contact_range);
  require(std::isfinite(c.fixed_point_factor) && c.fixed_point_factor > 0, "fixed-point factor must be positive, got ",
          c.fixed_point_factor);
  require(c.gravity.allFinite(), "gravity is not finite");
  require(c.cut_factor > 0 && c.cut_factor < 1, "cut factor must lie in (0, 1), got ", c.cut_factor);
  require(c.max_step_cuts >= 0, "max step cuts must be zero or positive");
  require(std::isfinite(c.cg_tolerance) && c.cg_tolerance > 0, "CG tolerance must be positive, got ", c.cg_tolerance);
  require(c.solver.pcg.patch_hops >= 0, "patch hops must be zero (off) or positive, got ", c.solver.pcg.patch_hops);
  require(std::isfinite(c.cg_open_close_tolerance) && c.cg_open_close_tolerance > 0,
          "open-close CG tolerance must be positive, got ", c.cg_open_close_tolerance);
  require(std::isfinite(c.cg_static_tolerance) && c.cg_static_tolerance > 0,
          "static CG tolerance must be positive, got ", c.cg_static_tolerance);
  require(c.threads >= 0, "threads must be zero (all cores) or positive, got ", c.threads);

  for (int r = 0; r < rock_material_count(); ++r) validate(rocks_[r], r);
  for (int j = 0; j < joint_material_count(); ++j) validate(joints_[j], j);

  Impl& m = *impl_;
  double e_max = 0;
  for (const RockMaterial& r : rocks_) e_max = std::max(e_max, r.youngs);
  m.g0 = c.g0 > 0 ? c.g0 : 50 * e_max;
  m.g1 = c.g1 > 0 ? c.g1 : suggested_time_step();
  if (dt_ <= 0 || dt_ > m.g1) dt_ = m.g1;
  if (m.arena_threads != c.threads || !m.arena) {
    m.arena = c.threads > 0 ? std::make_unique<tbb::task_arena>(c.threads) : std::make_unique<tbb::task_arena>();
    m.arena_threads = c.threads;
  }
  m.elastic.resize(rocks_.size());
  for (std::size_t r = 0; r < rocks_.size(); ++r) m.elastic[r] = elastic_matrix(rocks_[r], c.plane);
  // The linear solver: told once per step what the step's solves are like.
  if (!m.solver) m.solver = make_linear_solver(c.solver);
  StepSolveInfo info;
  info.blocks = static_cast<int>(block_count());
  info.block_centroids = centroid_;
  info.local_resolves = !previous_step_had_long_solves();
  info.last_step_solves = last_stats_.open_close_iterations;
  info.last_step_iterations = last_stats_.cg_iterations;
  m.solver->begin_step(c.solver, info);
  m.tan_friction.resize(joints_.size());
  for (std::size_t j = 0; j < joints_.size(); ++j) m.tan_friction[j] = std::tan(deg_to_rad(joints_[j].friction_deg));
  m.solver->max_iterations = c.cg_max_iterations > 0 ? c.cg_max_iterations : static_cast<int>(60 * block_count() + 100);
}

// ---- Stage: DetectContacts --------------------------------------------------

// Contacts are searched for over twice the range a step can close, and the
// list is reused until a vertex has moved half the difference, or a block
// turned by kRedetectRotation, since the last search (a Verlet list): no
// contact that can close in the step is missed, and wave problems, whose
// blocks move micrometres, search once. The kinematics are refreshed every step.
namespace {
constexpr double kSearchFactor = 2.0;
constexpr double kRedetectRotation = 0.005;  // rad, well inside the facing-edge angle tolerance
}  // namespace

// Search range: 2.5 × the largest allowed step displacement (Shi's choice),
// so any contact that can close during the step is in the list.
double World::contact_range() const {
  if (controls_.contact_range > 0) return controls_.contact_range;
  return std::min(2.5 * controls_.g2 * half_height_, auto_range_);
}

bool World::contact_list_is_stale() const {
  const Impl& m = *impl_;
  if (m.detected_vertices.size() != vertices_.size()) return true;
  const double range = contact_range();
  const double allowed = 0.5 * (kSearchFactor - 1.0) * range;
  const double moved = parallel_max<double>(
      vertices_.size(), 0.0, [&](std::size_t v) { return (vertices_[v] - m.detected_vertices[v]).squaredNorm(); });
  const double turned =
      parallel_max<double>(block_count(), 0.0, [&](std::size_t b) { return std::abs(m.rotation_since_detection[b]); });
  return moved > allowed * allowed || turned > kRedetectRotation || m.detected_range != range;
}

void World::detect_contacts() {
  Impl& m = *impl_;
  const BlockPolygons polys{vertex_start_, vertices_};
  // Contact i's linearisation, into its two arrays (sized by the caller).
  auto linearise = [&](std::size_t i, const Contact& c) -> const ContactOffsets& {
    const ContactKinematics k = contact_kinematics(polys, centroid_, c);
    m.gradients[i] = k;
    return m.offsets[i] = k;
  };
  if (!contact_list_is_stale()) {
    // Same contacts: refresh their linearisation from the current geometry.
    m.gradients.resize(contacts_.size());
    m.offsets.resize(contacts_.size());
    parallel_for_each(
        contacts_.size(), [&](std::size_t i) { contacts_[i].penetration = linearise(i, contacts_[i]).d0; }, 256);
    return;
  }
  const double range = contact_range();
  NarrowPhaseSettings settings;
  settings.range = kSearchFactor * range;
  const auto pairs = find_candidate_pairs(polys, settings.range);
  std::vector<Contact> found = dda::detect_contacts(polys, edge_joint_, pairs, settings);
  m.detected_vertices = vertices_;
  m.rotation_since_detection.assign(block_count(), 0.0);
  m.detected_range = range;
  ++m.detections;

  // Carry each contact's state over from the previous step (same vertex and
  // edge); new contacts start locked when touching, open otherwise.
  std::vector<int> order(contacts_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return identity_less(contacts_[x], contacts_[y]); });
  m.gradients.resize(found.size());
  m.offsets.resize(found.size());
  parallel_for_each(found.size(), [&](std::size_t i) {
    Contact& c = found[i];
    const auto it = std::lower_bound(order.begin(), order.end(), c,
                                     [&](int x, const Contact& key) { return identity_less(contacts_[x], key); });
    const bool known = it != order.end() && same_identity(contacts_[*it], c);
    if (known) set_iteration_state(c, iteration_state(contacts_[*it]));  // (penetration: set below)
    const ContactOffsets& k = linearise(i, c);
    if (!known) {
      const bool touching = k.d0 >= -1e-9 * k.edge_length;
      c.state = touching ? ContactState::Locked : ContactState::Open;
      c.intact = touching && m.first_detection;
    }
    c.penetration = k.d0;
  });
  contacts_ = std::move(found);
  m.first_detection = false;

  // The system's rows: which contacts couple which blocks.
  m.system.set_contacts(static_cast<int>(block_count()), contacts_);
}

// ---- Stage: open-close loop { Assemble → Solve → CheckContacts } -------------

bool World::previous_step_had_long_solves() const {
  constexpr double kLooseAboveIterations = 30;  // CG iterations per solve in the last step
  return last_stats_.open_close_iterations > 0 &&
         last_stats_.cg_iterations > kLooseAboveIterations * last_stats_.open_close_iterations;
}

int World::solve_step(double dt) {
  Impl& m = *impl_;
  auto t0 = Clock::now();
  assemble_block_terms(dt);
  m.t_assemble += seconds_since(t0);

  m.iterate.resize(contacts_.size());
  parallel_for_each(
      contacts_.size(),
      [&](std::size_t i) {
        m.iterate[i] = {m.offsets[i].s0, contacts_[i].normal_force};
      },
      1024);
  const int n = static_cast<int>(block_count());
  m.solution.resize(6 * n);
  const bool long_solves = previous_step_had_long_solves();
  // Warm start. Short solves (wave problems): the displacement the last
  // step's acceleration would give, (1 + gg)·v·Δt − d_last (with
  // v = 2·d_last/Δt − gg·v_before, that is d = gg·v·Δt + a·Δt²/2 with the
  // last step's a): blast(2) takes 10 % fewer CG iterations than from d_last.
  // Long solves (quasi-static walls): the previous step's displacements (an
  // earlier trial found extrapolation raised their CG iterations).
  const double gg = controls_.gg;
  parallel_for_each(
      n,
      [&](std::size_t b) {
        m.solution.segment<6>(6 * b) =
            long_solves ? last_displacement_[b] : Vec6((1 + gg) * dt * velocity_[b] - last_displacement_[b]);
      },
      256);

  // Start the open-close iteration from the states the warm start predicts
  // (see predict_contact_states); only where it extrapolates motion.
  if (controls_.predict_states && !long_solves) predict_contact_states();

  // While contact states still change, a solve only has to be good enough to
  // decide them: solve to the looser tolerance, and once the states hold,
  // tighten (from where the loose solve got: to cg_tolerance, or in static
  // analysis cg_static_tolerance) and check again.
  // The tightening pass does not count against the open-close limit. Only
  // where solves are long (walls: hundreds of iterations). Wave problems solve
  // every iteration tightly: their relative residual is measured against a
  // right-hand side the blocks' inertia dominates, so 1e-4 of it is a large
  // error in the contact forces that decide states and friction. Measured
  // (2026-11-23): loose solves at 1e-4 cut blast(0.25)'s CG iterations from
  // 19.0 to 11.4 per step, but moved the Fig. 11 reflected amplitudes
  // (Models 5, 6) by 8 and 13 % from where the same scheme converges (loose
  // solves at 1e-13); solving tightly is within 0.02 % of its own limit (all
  // solves at 1e-14). At 1e-6 the loose scheme is within 0.05 % of its limit,
  // but blast(2) and the rock bar then run 5–11 % slower (an extra pass per
  // step) and blast(0.25) only 5 % faster. (The two schemes' limits differ,
  // by 3.5 and 0.4 %: friction lags the normal force of different solves.)
  // Static analysis after long solves accepts cg_static_tolerance (see
  // Controls): there the loose solves' friction lag is the larger error.
  const bool static_long_solves = long_solves && controls_.gg == 0;
  const double tight =
      static_long_solves ? std::max(controls_.cg_tolerance, controls_.cg_static_tolerance) : controls_.cg_tolerance;
  const double loose = long_solves ? std::max(tight, controls_.cg_open_close_tolerance) : tight;
  // Long solves are dominated by the mat-vec: multiply with stored blocks.
  m.system.store_products(long_solves);
  bool settled = false;
  bool tightening = false;
  bool first_solve = true;
  for (int it = 0; it < controls_.open_close_limit && !settled; ++it) {
    ++m.open_close_iterations;
    m.solver->tolerance = tightening ? tight : loose;
    t0 = Clock::now();
    assemble_contacts(/*all_rows=*/it == 0 && !tightening);
    m.t_assemble += seconds_since(t0);

    t0 = Clock::now();
    m.solver->set_operator(m.system);
    // After the first solve only the reassembled rows changed: the solver
    // keeps the last residual elsewhere.
    const SolveReport report =
        first_solve ? m.solver->solve(m.rhs, m.solution) : m.solver->resolve(m.rhs, m.solution, m.row_reassembled);
    first_solve = false;
    m.cg_iterations += report.iterations;
    m.patch_iterations += report.patch_iterations;
    m.t_solve += seconds_since(t0);
    if (!report.finite || !m.solution.allFinite()) {
      // Name the first block whose load or displacement is not finite.
      for (int b = 0; b < n; ++b)
        if (!m.rhs.segment<6>(6 * b).allFinite() || !m.solution.segment<6>(6 * b).allFinite())
          throw Error(msg("step ", steps_ + 1, " at t = ", time_, " s diverged: block ", b, " has a non-finite ",
                          m.rhs.segment<6>(6 * b).allFinite() ? "displacement" : "load",
                          " (check material constants, loads, g0 and the time step)"));
      throw Error(
          msg("step ", steps_ + 1, " at t = ", time_, " s diverged: the linear solve produced non-finite values"));
    }
    if (!report.converged) return static_cast<int>(Rejection::SolverNotConverged);

    t0 = Clock::now();
    const bool changed = check_contacts();
    m.t_check += seconds_since(t0);
    // (Friction on sliding contacts uses the normal force of the solve
    // before, as in Shi's iteration: after a tightening pass that is the
    // loose solve with the same states, a smaller lag than after a solve
    // whose states then changed.)
    if (changed) {
      tightening = false;
    } else if (m.solver->tolerance == tight) {
      settled = true;
    } else {
      tightening = true;
      --it;  // the tightening pass is free
    }
  }
  if (!settled) return static_cast<int>(Rejection::OpenCloseUnsettled);
  const auto [largest, inverted] = check_block_motion();
  m.largest_displacement = largest;
  if (largest > controls_.g2 * half_height_) return static_cast<int>(Rejection::DisplacementTooLarge);
  if (largest > contact_range() / 2.5) return static_cast<int>(Rejection::BeyondContactRange);
  if ((m.inverted_block = inverted) >= 0) return static_cast<int>(Rejection::BlockInverted);
  if (deepest_penetration() > controls_.g2 * half_height_) return static_cast<int>(Rejection::PenetrationTooDeep);
  return static_cast<int>(Rejection::None);
}

void World::assemble_block_terms(double dt) {
  Impl& m = *impl_;
  const int n = static_cast<int>(block_count());
  m.own_k.resize(n);
  m.own_f.resize(n);
  const Vec2 g = controls_.gravity;
  const double gg = controls_.gg;
  parallel_for_each(n, [&](std::size_t b) {
    Mat6 k = Mat6::Zero();
    Vec6 f = Vec6::Zero();
    const double area = area_[b];
    // Elasticity and initial stress act on the strain terms (εx, εy, γxy).
    k.bottomRightCorner<3, 3>() += area * m.elastic[material_[b]];
    f.tail<3>() -= area * stress_[b];
    // Inertia (Shi): with d = v0·Δt + a·Δt²/2 the inertia force is
    // -ρ∫TᵀT(2/Δt²·d - 2/Δt·v0), v0 = gg × last velocity.
    const double rho = mass_[b] / area;
    const Mat6 tt = integrated_tt(area, sxx_[b], syy_[b], sxy_[b]);
    k += (2 * rho / (dt * dt)) * tt;
    f += (2 * rho / dt) * (tt * (gg * velocity_[b]));
    // Body force.
    f[0] += mass_[b] * g.x();
    f[1] += mass_[b] * g.y();
    m.own_k[b] = Symmetric6(k);
    m.own_f[b] = f;
  });
  assemble_point_terms(dt);
}

// Terms at material points: few next to the blocks, added serially in a
// fixed order. Histories are evaluated at the end of the step, t + Δt.
void World::assemble_point_terms(double dt) {
  Impl& m = *impl_;
  const double t_end = time_ + dt;
  auto add_force = [&](BlockId b, const Vec2& at, const Vec2& force) {
    m.own_f[b] += displacement_matrix(at, centroid_[b]).transpose() * force;
  };
  // A spring of stiffness matrix k pulling the point towards `goal`.
  auto add_spring = [&](BlockId b, const Vec2& at, const Eigen::Matrix2d& k, const Vec2& goal) {
    const Mat26 t = displacement_matrix(at, centroid_[b]);
    m.own_k[b] = Symmetric6(m.own_k[b].full() + t.transpose() * k * t);
    m.own_f[b] += t.transpose() * (k * (goal - at));
  };

  for (const PointLoadHistory& h : point_load_histories_)
    point_loads_[h.load].force = h.direction * h.magnitude.value(t_end);
  for (const PointLoad& p : point_loads_) add_force(p.block, p.point, p.force);

  // SHI: ∫ Tᵀ(−p n) dl over a straight edge is l·Tᵀ(midpoint)·(−p n).
  for (PressureLoad& load : pressure_loads_) {
    if (load.from_history) load.pressure = load.history.value(t_end);
    for (const EdgeRef& e : load.edges) {
      const Vec2& a = vertices_[vertex_start_[e.block] + e.edge];
      const Vec2& b =
          vertices_[vertex_start_[e.block] + (e.edge + 1) % (vertex_start_[e.block + 1] - vertex_start_[e.block])];
      const Vec2 outward((b - a).y(), -(b - a).x());  // length l, outward for a counter-clockwise outline
      add_force(e.block, 0.5 * (a + b), -load.pressure * outward);
    }
  }

  const double kf = controls_.fixed_point_factor * m.g0;
  const Eigen::Matrix2d stiff = kf * Eigen::Matrix2d::Identity();
  // Fixed points: back to where they started, residual included.
  for (const FixedPoint& p : fixed_points_) add_spring(p.block, p.point, stiff, p.origin);

  // DHI: towards start + target, along the direction only when one is given.
  for (DisplacementTarget& t : targets_) {
    if (t.mode == DisplacementTarget::Displacement) t.target = t.history.value(t_end) * t.direction;
    if (t.mode == DisplacementTarget::Velocity) t.target = t.history.integral(t_end) * t.direction;
    if (t.direction.norm() > 0) {
      // Only the component along the direction is driven: goal = point moved
      // along the direction by what is still missing.
      const double missing = (t.origin + t.target - t.point).dot(t.direction);
      add_spring(t.block, t.point, kf * t.direction * t.direction.transpose(), t.point + missing * t.direction);
    } else {
      add_spring(t.block, t.point, stiff, t.origin + t.target);
    }
  }

  // VBC dashpots and SBC springs. A dashpot's force at the end-of-step
  // velocity v1 = T(2D/Δt − v0) is −c·v1: (2/Δt)·TᵀcT joins the matrix,
  // TᵀcT·v0 the right-hand side (v0 = gg × last velocity).
  for (const BoundaryPoint& p : boundary_points_) {
    const Mat26 t = displacement_matrix(p.point, centroid_[p.block]);
    if (boundaries_[p.boundary].kind == BoundaryKind::Viscous) {
      m.own_k[p.block] = Symmetric6(m.own_k[p.block].full() + (2.0 / dt) * t.transpose() * p.c * t);
      m.own_f[p.block] += t.transpose() * (p.c * (t * (controls_.gg * velocity_[p.block])));
    } else {
      // SBC: the fixed-point sub-matrix without the fixed point's residual
      // term (the paper's §3.3.1): the spring acts on this step's
      // displacement only, so it draws p·l·Δu from a moving boundary.
      add_spring(p.block, p.point, p.k * Eigen::Matrix2d::Identity(), p.point);
    }
  }
}

void World::assemble_contacts(bool all_rows) {
  Impl& m = *impl_;
  const int n = static_cast<int>(block_count());
  const double kn_full = m.g0, ks_full = controls_.shear_ratio * m.g0;
  m.rhs.resize(6 * n);
  // The springs each contact acts with in this solve: normal on a closed
  // contact, shear too on a locked one.
  parallel_for_each(
      contacts_.size(),
      [&](std::size_t i) {
        const Contact& c = contacts_[i];
        ContactOperator::Springs& k = m.system.springs(static_cast<int>(i));
        k.kn = c.state == ContactState::Open ? 0.0 : c.scale * kn_full;
        k.ks = c.state == ContactState::Locked ? c.scale * ks_full : 0.0;
      },
      1024);
  // Each block row is gathered by one task, adding its contacts in contact
  // order: no races, and the same sums whatever the thread count.
  m.row_reassembled.resize(n);
  parallel_for_each(
      n,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        const std::span<const int> row = m.system.row_contacts(b);
        // A row none of whose contacts changed state since the last assembly of
        // this step keeps its diagonal block and, without a sliding contact (whose
        // friction follows the latest N), its right-hand side: either would come
        // out the same to the bit.
        bool matrix_too = all_rows, sliding = false;
        for (std::size_t r = 0; r < row.size() && !matrix_too; ++r) {
          matrix_too = m.contact_changed[row[r]];
          sliding = sliding || contacts_[row[r]].state == ContactState::Sliding;
        }
        m.row_reassembled[b] = matrix_too || sliding;
        if (!matrix_too && !sliding) return;
        Symmetric6 diag = m.own_k[b];
        Vec6 f = m.own_f[b];
        for (const int i : row) {
          const Contact& c = contacts_[i];
          if (c.state == ContactState::Open) continue;
          const ContactGradients& k = m.gradients[i];
          const ContactOperator::Springs& springs = m.system.springs(i);
          const bool is_vertex_block = c.vblock == b;
          const Vec6& en_self = is_vertex_block ? k.en_v : k.en_e;
          const Vec6& es_self = is_vertex_block ? k.es_v : k.es_e;
          // Normal spring on dn = d0 + en·D (and, locked, shear spring on
          // ds = s0 + es·D): kn·en enᵀ (+ ks·es esᵀ) on the diagonal (its upper
          // triangle); the coupling to the other block stays with the operator
          // (assembly/contact_operator.hpp).
          if (matrix_too) diag.add_outer(springs.kn, en_self);
          f -= springs.kn * m.offsets[i].d0 * en_self;
          if (c.state == ContactState::Locked) {
            if (matrix_too) diag.add_outer(springs.ks, es_self);
            f -= springs.ks * m.iterate[i].s0 * es_self;
          } else {
            // Sliding: friction N·tanφ against the sliding direction, with N
            // from the previous iteration.
            const double friction = std::max(0.0, m.iterate[i].normal_force) * m.tan_friction[c.joint];
            f -= c.slide_sign * friction * es_self;
          }
        }
        m.rhs.segment<6>(6 * b) = f;
        if (matrix_too) m.system.rewrite_diagonal(b) = diag;
      },
      16);
  m.system.set_kinematics(m.gradients);
  m.system.assembled();
}

namespace {
// A contact's normal gap and shear motion under the displacement d of a solve
// (or of a warm start).
struct ContactMotion {
  double dn;       // gap after the step (penetration positive)
  double ds_step;  // shear motion in the step
};

ContactMotion contact_motion(const ContactGradients& k, const ContactOffsets& o, const VecX& d, const Contact& c) {
  const auto dv = d.segment<6>(6 * c.vblock);
  const auto de = d.segment<6>(6 * c.eblock);
  return {o.d0 + k.en_v.dot(dv) + k.en_e.dot(de), k.es_v.dot(dv) + k.es_e.dot(de)};
}

// A contact's springs: g0 (normal) and shear_ratio·g0 (shear), scaled.
ContactSprings contact_springs(const Contact& c, double g0, double shear_ratio, double tolerance) {
  return {c.scale * g0, c.scale * shear_ratio * g0, tolerance};
}
}  // namespace

// The open-close iteration's first guess in wave problems (short solves):
// instead of the last step's states, those the warm start implies (the
// displacement the last step's motion extrapolates to), so that the first
// solve is more often the last (blast(2): 2.95 → 2.08 open-close iterations
// per step over its 0.05 s). After long solves (quasi-static walls) the warm
// start is the last step's own displacement, which has little to tell:
// predicting from it took wall(10) 3.7 % more CG iterations (555 against
// 536 per step) and wall(20) the same, so it is not done there. Only
// transitions a wrong guess cannot harm are taken, since the solves that
// follow undo a wrong guess only where the solved displacement contradicts
// it:
//   * a contact closes (locked first, as in the iteration); a wrong close
//     shows up as tension in the solve and opens again;
//   * a closed contact starts or stops sliding (friction, from the predicted
//     shear against N·tanφ, or the predicted motion reversing); a wrong
//     slide meets full friction against its direction, moves back in the
//     solve and locks again;
// and not:
//   * a closed contact opening: on a contact at rest the predicted gap is
//     round-off around the (small) penetration, and a contact wrongly opened
//     closes again locked, dropping its sliding history (a block sliding down
//     an incline would stick a step at a time);
//   * an intact joint failing: failure is for good, only a solve may cause it;
// and the friction of sliding contacts in the first solve still uses the
// normal force of the last accepted solve (Shi's lag), not a predicted one.
void World::predict_contact_states() {
  Impl& m = *impl_;
  const double tolerance = controls_.contact_tolerance * half_height_;
  parallel_for_each(
      contacts_.size(),
      [&](std::size_t i) {
        Contact& c = contacts_[i];
        if (c.intact) return;
        const ContactIterationState before = iteration_state(c);
        const ContactIterate iterate = m.iterate[i];
        const ContactMotion d = contact_motion(m.gradients[i], m.offsets[i], m.solution, c);
        const ContactSprings springs = contact_springs(c, m.g0, controls_.shear_ratio, tolerance);
        update_contact_state(c, m.iterate[i], joints_[c.joint], m.tan_friction[c.joint], springs, d.dn,
                             iterate.s0 + d.ds_step, d.ds_step);
        if (before.state != ContactState::Open && c.state == ContactState::Open) {
          set_iteration_state(c, before);
          m.iterate[i] = iterate;
        }
        m.iterate[i].normal_force = iterate.normal_force;
      },
      1024);
}

bool World::check_contacts() {
  Impl& m = *impl_;
  const std::size_t nc = contacts_.size();
  const double tolerance = controls_.contact_tolerance * half_height_;
  m.contact_changed.resize(nc);
  const int any_changed = parallel_max<int>(nc, 0, [&](std::size_t i) {
    Contact& c = contacts_[i];
    const ContactSprings springs = contact_springs(c, m.g0, controls_.shear_ratio, tolerance);
    const auto [dn, ds_step] = contact_motion(m.gradients[i], m.offsets[i], m.solution, c);
    const double ds = m.iterate[i].s0 + ds_step;
    const bool changed =
        update_contact_state(c, m.iterate[i], joints_[c.joint], m.tan_friction[c.joint], springs, dn, ds, ds_step);
    m.contact_changed[i] = changed;
    c.penetration = dn;
    c.normal_force = m.iterate[i].normal_force;
    c.shear_force = c.state == ContactState::Locked ? springs.ks * ds
                    : c.state == ContactState::Sliding
                        ? -c.slide_sign * std::max(0.0, c.normal_force) * m.tan_friction[c.joint]
                        : 0.0;
    return changed ? 1 : 0;
  });
  return any_changed != 0;
}

// Moves every vertex with its block's solved displacement (once: update()
// reuses the motion). A step whose largest vertex motion exceeds the g2 bound
// must be cut, and so must one in which a block's moved outline has zero or
// negative area (a sliver crushed by stiff springs, say).
std::pair<double, BlockId> World::check_block_motion() {
  Impl& m = *impl_;
  const std::size_t n = block_count();
  m.block_inverted.resize(n);
  m.vertex_motion.resize(vertices_.size());
  const double largest = parallel_max<double>(n, 0.0, [&](std::size_t b) {
    const BlockMotion motion(m.solution.segment<6>(6 * b), centroid_[b]);
    const int first = vertex_start_[b], count = vertex_start_[b + 1] - first;
    const Vec2 moved_first = motion(vertices_[first]), moved_second = motion(vertices_[first + 1]);
    m.vertex_motion[first] = moved_first;
    m.vertex_motion[first + 1] = moved_second;
    double worst = std::max(moved_first.norm(), moved_second.norm());
    const Vec2 o = vertices_[first] + moved_first;
    Vec2 p = vertices_[first + 1] + moved_second - o;
    double twice = 0;  // twice the moved outline's area, as a fan from its first vertex
    for (int k = 1; k + 1 < count; ++k) {
      const Vec2 moved = motion(vertices_[first + k + 1]);
      m.vertex_motion[first + k + 1] = moved;
      worst = std::max(worst, moved.norm());
      const Vec2 q = vertices_[first + k + 1] + moved - o;
      twice += cross(p, q);
      p = q;
    }
    m.block_inverted[b] = !(twice > 0);
    return worst;
  });
  const auto it = std::find(m.block_inverted.begin(), m.block_inverted.end(), 1);
  return {largest, it == m.block_inverted.end() ? -1 : static_cast<BlockId>(it - m.block_inverted.begin())};
}

double World::deepest_penetration() const {
  return parallel_max<double>(contacts_.size(), 0.0, [&](std::size_t i) {
    return contacts_[i].state == ContactState::Open ? 0.0 : contacts_[i].penetration;
  });
}

// ---- Stage: Update ----------------------------------------------------------

void World::update(double dt) {
  Impl& m = *impl_;
  const int n = static_cast<int>(block_count());
  auto d_of = [&](BlockId b) -> Vec6 { return m.solution.segment<6>(6 * b); };
  // Material points first: they move with their block's old centroid.
  for (FixedPoint& p : fixed_points_) p.point += point_displacement(p.point, centroid_[p.block], d_of(p.block));
  for (PointLoad& p : point_loads_) p.point += point_displacement(p.point, centroid_[p.block], d_of(p.block));
  for (TrackedPoint& p : tracked_) p.point += point_displacement(p.point, centroid_[p.block], d_of(p.block));
  for (DisplacementTarget& p : targets_) p.point += point_displacement(p.point, centroid_[p.block], d_of(p.block));
  for (BoundaryPoint& p : boundary_points_) {
    const Mat26 t = displacement_matrix(p.point, centroid_[p.block]);
    // Force at the end of the step: −c·v1 (dashpot) or −k·Δu (spring).
    if (boundaries_[p.boundary].kind == BoundaryKind::Viscous)
      p.force = -p.c * (t * (2.0 / dt * d_of(p.block) - controls_.gg * velocity_[p.block]));
    const Vec2 moved = point_displacement(p.point, centroid_[p.block], d_of(p.block));
    if (boundaries_[p.boundary].kind == BoundaryKind::Spring) p.force = -p.k * moved;
    p.point += moved;
  }

  const double gg = controls_.gg;
  parallel_for_each(
      n,
      [&](std::size_t b) {
        const Vec6 d = d_of(static_cast<BlockId>(b));
        // The vertices' motion as the accepted solve's checks computed it.
        for (int v = vertex_start_[b]; v < vertex_start_[b + 1]; ++v) vertices_[v] += m.vertex_motion[v];
        const PolygonMoments pm = polygon_moments(
            std::span<const Vec2>(vertices_).subspan(vertex_start_[b], vertex_start_[b + 1] - vertex_start_[b]));
        centroid_[b] = pm.centroid;
        area_[b] = pm.area;
        sxx_[b] = pm.sxx;
        syy_[b] = pm.syy;
        sxy_[b] = pm.sxy;
        stress_[b] += m.elastic[material_[b]] * d.tail<3>();
        // v1 = 2d/Δt - v0 (exact for constant acceleration).
        velocity_[b] = 2.0 / dt * d - gg * velocity_[b];
        last_displacement_[b] = d;
        m.rotation_since_detection[b] += d[2];
      },
      32);

  // Contacts: a contact that ends the step locked keeps (or takes) its shear
  // reference point; others drop it.
  parallel_for_each(
      contacts_.size(),
      [&](std::size_t i) {
        Contact& c = contacts_[i];
        if (c.state == ContactState::Locked) {
          if (!c.ref_valid || m.iterate[i].s0 != m.offsets[i].s0) {
            c.ref_param = m.offsets[i].param;
            c.ref_valid = true;
          }
        } else {
          c.ref_valid = false;
        }
      },
      256);
  time_ += dt;
  ++steps_;
}

}  // namespace dda
