// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/landing.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "core/error.hpp"

namespace dda {

namespace {
// Projected Gauss–Seidel: sweeps over the landing contacts until no impulse
// changes a contact's rate by more than this share of the fastest approach
// (or of the deepest penetration, for the positions).
constexpr double kSweepTolerance = 1e-12;
constexpr int kMaxSweeps = 1000;
}  // namespace

void validate_landing_law(double restitution, Integrator integrator, const Blocks& blocks) {
  if (restitution < 0) return;
  if (integrator != Integrator::Shi)
    throw Error(
        msg("controls: restitution (the landing law) works with integrator = \"shi\" only: the second-order "
            "schemes' acceleration follows from the step displacement, which an impact does not change alike; "
            "set integrator = \"shi\" or restitution = -1 (off)"));
  if (blocks.has_meshes())
    throw Error(
        msg("controls: restitution (the landing law) works with first-order blocks only (an impact on one "
            "element of a meshed block would part it from its neighbours); use blocks without a mesh "
            "(mesh_size = 0) or restitution = -1 (off)"));
}

double landing_speed_threshold(const Vec2& gravity, double dt, double ring_time) {
  return 2 * gravity.norm() * std::max(dt, ring_time);
}

namespace {
// A block's rigid inverse mass (u, v, r), zero for a held block.
Mat3 rigid_inverse_mass(const Blocks& blocks, BlockId b, bool held, MeshMass mesh_mass) {
  if (held) return Mat3::Zero();
  const Mat6 mass = block_tt(blocks, b, mesh_mass).scaled(blocks.mass[b] / blocks.area[b]).full();
  return mass.topLeftCorner<3, 3>().inverse();
}
}  // namespace

int LandingLaw::slot_of(BlockId b, const Blocks& blocks, const VecX& d, const TimeScheme& scheme,
                        std::span<const char> held) {
  if (slot_index_[b] >= 0) return slot_index_[b];
  Slot s;
  s.block = b;
  s.held = held[b] != 0;
  s.mass = block_tt(blocks, b, scheme.mesh_mass).scaled(blocks.mass[b] / blocks.area[b]);
  s.rigid_inverse = rigid_inverse_mass(blocks, b, s.held, scheme.mesh_mass);
  s.dd = Vec3::Zero();
  s.force = Vec6::Zero();
  s.d_pre = d.segment<6>(6 * b);
  s.v_pre = s.v = scheme.end_velocity(s.d_pre, blocks.scheme_state(b));
  s.end = {Vec6::Zero(), Vec6::Zero(), Vec6::Zero()};
  slot_index_[b] = static_cast<int>(slots_.size());
  slots_.push_back(s);
  return slot_index_[b];
}

int LandingLaw::resolve(std::span<Contact> contacts, const ContactLinearisation& lin,
                        std::span<ContactIterate> iterates, std::span<const double> solved_friction_normal,
                        const ContactParameters& p, const ImpactInputs& in, VecX& d) {
  const Blocks& blocks = in.blocks;
  const TimeScheme& scheme = in.scheme;
  const std::span<const char> held = in.held;
  const double restitution = p.restitution;
  landings_.clear();
  slots_.clear();
  energy_ = {};
  if (restitution < 0) return 0;
  const double dt = scheme.dt;
  // The contacts that may land: open at the step's start, approaching then
  // faster than the threshold.
  slot_index_.assign(blocks.count(), -1);
  candidates_.clear();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (c.intact || iterates[i].closed_at_start) continue;
    if (held[c.vblock] && held[c.eblock]) continue;
    const ContactGradients& g = lin.gradients[i];
    const double approach = scheme.gg * (g.en_v.dot(blocks.velocity[c.vblock]) + g.en_e.dot(blocks.velocity[c.eblock]));
    if (!(approach > landing_speed_threshold(in.gravity, dt, 0))) continue;  // the cheaper test first
    // The slowest ring of the contact: on its spring, 1/ω = √(m/k_n) (m its
    // effective rigid mass), or in either block, a wave's time across it,
    // √A/c = √(mass/E') (c² = E'/ρ).
    const Vec3 na = g.en_v.head<3>(), nb = g.en_e.head<3>();
    const double inverse_mass = na.dot(rigid_inverse_mass(blocks, c.vblock, held[c.vblock], scheme.mesh_mass) * na) +
                                nb.dot(rigid_inverse_mass(blocks, c.eblock, held[c.eblock], scheme.mesh_mass) * nb);
    double ring_time = 1 / std::sqrt(contact_springs(c, p).kn * inverse_mass);
    for (const BlockId b : {c.vblock, c.eblock})
      ring_time = std::max(ring_time, std::sqrt(blocks.mass[b] / in.elastic[blocks.material[b]](0, 0)));
    if (!(approach > landing_speed_threshold(in.gravity, dt, ring_time))) continue;
    Landing l{};
    l.contact = static_cast<int>(i);
    l.approach = approach;
    candidates_.push_back(l);
  }
  // A free block held by another closed contact as well (a block in a
  // packed mass, or resting on a corner) is confined: its landings are left
  // to the springs. The correction moves a block against its landing
  // contacts only, and a confined block, moved into its other contacts, is
  // thrown back by their springs: in blast(2) and a jointed slope that made
  // energy (docs/landings.md, Tried and not kept).
  if (!candidates_.empty()) {
    confined_.assign(blocks.count(), 0);
    std::size_t next = 0;
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      while (next < candidates_.size() && static_cast<std::size_t>(candidates_[next].contact) < i) ++next;
      const bool candidate = next < candidates_.size() && static_cast<std::size_t>(candidates_[next].contact) == i;
      const Contact& c = contacts[i];
      if (candidate || c.state == ContactState::Open) continue;
      confined_[c.vblock] = confined_[c.eblock] = 1;
    }
    std::erase_if(candidates_, [&](const Landing& l) {
      const Contact& c = contacts[l.contact];
      return (!held[c.vblock] && confined_[c.vblock]) || (!held[c.eblock] && confined_[c.eblock]);
    });
  }
  // Those the solve closed land. The step without their forces, N·Jnᵀ +
  // S·Jtᵀ at the step's end, taken out of each block's own system (own: its
  // elasticity, inertia and loads; exact for a block whose only closed
  // contacts are landing ones): d_pre = d + K_own⁻¹(N·Jnᵀ + S·Jtᵀ), the
  // blocks' free motion over the step, strains included (the solve's landing
  // force, which stops a block within one step, strains it by ∝ 1/Δt: an
  // elastic bounce the next step would release).
  for (const Landing& candidate : candidates_) {
    const Contact& c = contacts[candidate.contact];
    if (c.state == ContactState::Open) continue;
    Landing l = candidate;
    l.va = slot_of(c.vblock, blocks, d, scheme, held);
    l.vb = slot_of(c.eblock, blocks, d, scheme, held);
    landings_.push_back(l);
  }
  for (Landing& l : landings_) {
    const Contact& c = contacts[l.contact];
    const ContactIterate& it = iterates[l.contact];
    const ContactGradients& g = lin.gradients[l.contact];
    const ContactSprings k = contact_springs(c, p);
    const double n = c.normal_force;
    const double shear = c.state == ContactState::Locked
                             ? k.ks * it.shear
                             : c.slide_sign * solved_friction_normal[l.contact] * p.tan_friction[c.joint];
    slots_[l.va].force += n * g.en_v + shear * g.es_v;
    slots_[l.vb].force += n * g.en_e + shear * g.es_e;
  }
  for (Slot& k : slots_) {
    k.d_pre += in.own_stiffness[k.block].full().ldlt().solve(k.force);
    k.v_pre = scheme.end_velocity(k.d_pre, blocks.scheme_state(k.block));
    k.v = k.v_pre;
  }
  // A contact the solve left open lands too where the step without the
  // landing forces takes it in: the solve's landing force elsewhere (the
  // friction of a block landing flat pitches it) held it off.
  for (const Landing& candidate : candidates_) {
    const Contact& c = contacts[candidate.contact];
    if (c.state != ContactState::Open) continue;
    const ContactGradients& g = lin.gradients[candidate.contact];
    auto d_pre = [&](BlockId b) -> Vec6 {
      return slot_index_[b] >= 0 ? slots_[slot_index_[b]].d_pre : Vec6(d.segment<6>(6 * b));
    };
    if (!(lin.offsets[candidate.contact].d0 + g.en_v.dot(d_pre(c.vblock)) + g.en_e.dot(d_pre(c.eblock)) > 0)) continue;
    Landing l = candidate;
    l.va = slot_of(c.vblock, blocks, d, scheme, held);
    l.vb = slot_of(c.eblock, blocks, d, scheme, held);
    landings_.push_back(l);
  }
  if (landings_.empty()) return 0;
  for (Landing& l : landings_) {
    const ContactGradients& g = lin.gradients[l.contact];
    const Slot &a = slots_[l.va], &b = slots_[l.vb];
    const double approach = l.approach;
    const double pre = g.en_v.dot(a.v_pre) + g.en_e.dot(b.v_pre);
    const double accel = (pre - approach) / dt;  // of the approach, from the other forces
    // Closes at t* (gap = approach·t + accel·t²/2), at v_imp.
    const double gap = std::max(0.0, -lin.offsets[l.contact].d0);
    const double disc = approach * approach + 2 * accel * gap;
    const double t_impact = gap == 0   ? 0.0
                            : disc < 0 ? dt
                                       : std::clamp(2 * gap / (approach + std::sqrt(disc)), 0.0, dt);
    const double v_impact = approach + accel * t_impact;
    const double rest = dt - t_impact;
    l.target_rate = std::min(0.0, -restitution * v_impact + accel * rest);
    l.target_penetration = -std::max(0.0, restitution * v_impact * rest - 0.5 * accel * rest * rest);
    l.penetration = lin.offsets[l.contact].d0 + g.en_v.dot(a.d_pre) + g.en_e.dot(b.d_pre);
    l.p_n = l.p_t = 0;
    l.mu = p.tan_friction[contacts[l.contact].joint];
    const Vec3 na = g.en_v.head<3>(), nb = g.en_e.head<3>(), ta = g.es_v.head<3>(), tb = g.es_e.head<3>();
    l.w_n = na.dot(a.rigid_inverse * na) + nb.dot(b.rigid_inverse * nb);
    l.w_t = ta.dot(a.rigid_inverse * ta) + tb.dot(b.rigid_inverse * tb);
  }
  solve_velocities(lin);
  solve_positions(lin);

  // The contacts' and the blocks' corrected state, and what the impacts
  // changed (the contacts first: their friction as booked is the solved d's).
  for (const Landing& l : landings_) {
    Contact& c = contacts[l.contact];
    ContactIterate& it = iterates[l.contact];
    const ContactGradients& g = lin.gradients[l.contact];
    const ContactSprings k = contact_springs(c, p);
    // The springs' energy as the budget counted it (world/energy.cpp) ...
    double before = k.kn > 0 ? 0.5 * c.normal_force * c.normal_force / k.kn : 0.0;
    if (c.state == ContactState::Locked && k.ks > 0) before += 0.5 * c.shear_force * c.shear_force / k.ks;
    energy_.from_solve += before;
    if (c.state == ContactState::Sliding)
      energy_.friction -=
          std::abs(c.shear_force * (g.es_v.dot(d.segment<6>(6 * c.vblock)) + g.es_e.dot(d.segment<6>(6 * c.eblock))));
    const Slot &a = slots_[l.va], &b = slots_[l.vb];
    c.penetration = l.penetration + g.en_v.head<3>().dot(a.dd) + g.en_e.head<3>().dot(b.dd);
    it.shear = lin.offsets[l.contact].s0 + g.es_v.dot(a.d_pre) + g.es_e.dot(b.d_pre) + g.es_v.head<3>().dot(a.dd) +
               g.es_e.head<3>().dot(b.dd);
    // ... and after: unloaded (a penetration left by an unconverged sweep
    // keeps its force).
    c.normal_force = it.normal_force = std::max(0.0, k.kn * c.penetration);
    c.shear_force = 0;
    // Stuck or sliding as the impact left it (the next step's iteration
    // goes on from there).
    if (std::abs(l.p_t) < l.mu * l.p_n) {
      c.state = ContactState::Locked;
    } else {
      c.state = ContactState::Sliding;
      c.slide_sign = l.p_t >= 0 ? 1 : -1;
    }
    energy_.contact += (k.kn > 0 ? 0.5 * c.normal_force * c.normal_force / k.kn : 0.0) - before;
  }
  for (Slot& k : slots_) {
    const BlockId b = k.block;
    Vec6 d_new = k.d_pre;
    d_new.head<3>() += k.dd;
    const Vec6 d_solved = d.segment<6>(6 * b);
    const Vec6 v_solved = scheme.end_velocity(d_solved, blocks.scheme_state(b));
    k.end = scheme.end_state_after_impact(k.v, blocks.scheme_state(b), k.mass);
    auto kinetic = [&](const Vec6& v) { return 0.5 * v.dot(k.mass * v); };
    const Mat3& e = in.elastic[blocks.material[b]];
    const Mat3 c = e.inverse();
    auto strain = [&](const Vec6& db) {
      const Vec3 sigma = blocks.stress[b] + e * db.tail<3>();
      return 0.5 * blocks.area[b] * sigma.dot(c * sigma);
    };
    auto lift = [&](const Vec6& db) { return blocks.mass[b] * in.gravity.dot(db.head<2>()); };
    energy_.kinetic += kinetic(k.v) - kinetic(v_solved);
    energy_.strain += strain(d_new) - strain(d_solved);
    energy_.gravity += lift(d_new) - lift(d_solved);
    energy_.from_solve +=
        kinetic(v_solved) - kinetic(k.v_pre) + strain(d_solved) - strain(k.d_pre) - (lift(d_solved) - lift(k.d_pre));
    d.segment<6>(6 * b) = d_new;
  }
  return static_cast<int>(landings_.size());
}

// The velocities: normal rows to their target rates (impulse ≥ 0), shear
// rows to a stop within Coulomb's bound on the step's impulse.
void LandingLaw::solve_velocities(const ContactLinearisation& lin) {
  double scale = 0;
  for (const Landing& l : landings_) scale = std::max(scale, std::abs(l.target_rate) + std::abs(l.p_n * l.w_n));
  const double tolerance = kSweepTolerance * scale;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double change = 0;
    for (Landing& l : landings_) {
      const ContactGradients& g = lin.gradients[l.contact];
      Slot &a = slots_[l.va], &b = slots_[l.vb];
      if (l.w_n > 0) {
        const double rate = g.en_v.dot(a.v) + g.en_e.dot(b.v);
        const double p_n = std::max(0.0, l.p_n + (rate - l.target_rate) / l.w_n);
        const double dp = p_n - l.p_n;
        l.p_n = p_n;
        a.v.head<3>() -= dp * (a.rigid_inverse * g.en_v.head<3>());
        b.v.head<3>() -= dp * (b.rigid_inverse * g.en_e.head<3>());
        change = std::max(change, std::abs(dp) * l.w_n);
      }
      if (l.w_t > 0) {
        const double rate = g.es_v.dot(a.v) + g.es_e.dot(b.v);
        const double bound = l.mu * l.p_n;
        const double p_t = std::clamp(l.p_t + rate / l.w_t, -bound, bound);
        const double dp = p_t - l.p_t;
        l.p_t = p_t;
        a.v.head<3>() -= dp * (a.rigid_inverse * g.es_v.head<3>());
        b.v.head<3>() -= dp * (b.rigid_inverse * g.es_e.head<3>());
        change = std::max(change, std::abs(dp) * l.w_t);
      }
    }
    if (change <= tolerance) break;
  }
}

// The positions: each landing contact's penetration to its target (pushing
// apart only), over the rigid unknowns.
void LandingLaw::solve_positions(const ContactLinearisation& lin) {
  std::vector<double> pushed(landings_.size(), 0.0);
  double scale = 0;
  for (const Landing& l : landings_) scale = std::max(scale, std::abs(l.penetration) + std::abs(l.target_penetration));
  const double tolerance = kSweepTolerance * scale;
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double change = 0;
    for (std::size_t j = 0; j < landings_.size(); ++j) {
      const Landing& l = landings_[j];
      if (!(l.w_n > 0)) continue;
      const ContactGradients& g = lin.gradients[l.contact];
      Slot &a = slots_[l.va], &b = slots_[l.vb];
      const double penetration = l.penetration + g.en_v.head<3>().dot(a.dd) + g.en_e.head<3>().dot(b.dd);
      const double push = std::max(0.0, pushed[j] + (penetration - l.target_penetration) / l.w_n);
      const double dp = push - pushed[j];
      pushed[j] = push;
      a.dd -= dp * (a.rigid_inverse * g.en_v.head<3>());
      b.dd -= dp * (b.rigid_inverse * g.en_e.head<3>());
      change = std::max(change, std::abs(dp) * l.w_n);
    }
    if (change <= tolerance) break;
  }
}

void LandingLaw::write_end_states(Blocks& blocks) const {
  for (const Slot& k : slots_) {
    blocks.velocity[k.block] = k.end.velocity;
    blocks.acceleration[k.block] = k.end.acceleration;
    blocks.out_of_balance[k.block] = k.end.out_of_balance;
  }
}

void LandingLaw::unload_shear_springs(std::span<Contact> contacts, const ContactLinearisation& lin,
                                      std::span<const ContactIterate> iterates, bool sliding_keeps_reference) const {
  for (const Landing& l : landings_) {
    Contact& c = contacts[l.contact];
    if (c.state == ContactState::Open || (!sliding_keeps_reference && c.state != ContactState::Locked)) continue;
    const ContactOffsets& o = lin.offsets[l.contact];
    c.ref_param = o.param + iterates[l.contact].shear / o.edge_length;
    c.ref_valid = true;
  }
}

}  // namespace dda
