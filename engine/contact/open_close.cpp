#include "contact/open_close.hpp"

#include <algorithm>

#include "core/parallel.hpp"

namespace dda {

void save_contact_states(std::span<const Contact> contacts, OpenCloseState& s) {
  s.saved.resize(contacts.size());
  parallel_for_each(
      contacts.size(), [&](std::size_t i) { s.saved[i] = iteration_state(contacts[i]); }, 1024);
}

void restore_contact_states(std::span<Contact> contacts, const OpenCloseState& s) {
  parallel_for_each(
      contacts.size(), [&](std::size_t i) { set_iteration_state(contacts[i], s.saved[i]); }, 1024);
}

void start_open_close(std::span<const Contact> contacts, const ContactLinearisation& lin, OpenCloseState& s) {
  s.iterate.resize(contacts.size());
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        s.iterate[i] = {lin.offsets[i].s0, contacts[i].normal_force};
      },
      1024);
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

// A contact's springs (ContactParameters::springs), scaled.
ContactSprings contact_springs(const Contact& c, const ContactParameters& p) {
  const ContactParameters::Springs k = p.springs(c);
  return {c.scale * k.kn, c.scale * k.ks, p.tolerance};
}
}  // namespace

// The open-close iteration's first guess in wave problems (short solves):
// instead of the last step's states, those the warm start implies (the
// displacement the last step's motion extrapolates to), so that the first
// solve is more often the last (blast(2): 2.95 → 2.08 open-close iterations
// per step over its 0.05 s). After long solves (quasi-static walls) the warm
// start is the last step's own displacement, which has little to tell:
// predicting from it took wall(10) 3.7 % more CG iterations (555 against
// 536 per step) and wall(20) the same, so it is not done there
// (solve_regime.hpp). Only transitions a wrong guess cannot harm are taken,
// since the solves that follow undo a wrong guess only where the solved
// displacement contradicts it:
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
void predict_contact_states(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                            const ContactParameters& p, OpenCloseState& s) {
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        Contact& c = contacts[i];
        if (c.intact) return;
        const ContactIterationState before = iteration_state(c);
        const ContactIterate iterate = s.iterate[i];
        const ContactMotion m = contact_motion(lin.gradients[i], lin.offsets[i], d, c);
        const ContactSprings springs = contact_springs(c, p);
        update_contact_state(c, s.iterate[i], p.joints[c.joint], p.tan_friction[c.joint], springs, m.dn,
                             iterate.s0 + m.ds_step, m.ds_step);
        if (before.state != ContactState::Open && c.state == ContactState::Open) {
          set_iteration_state(c, before);
          s.iterate[i] = iterate;
        }
        s.iterate[i].normal_force = iterate.normal_force;
      },
      1024);
}

bool check_contact_states(std::span<Contact> contacts, const ContactLinearisation& lin, const VecX& d,
                          const ContactParameters& p, OpenCloseState& s) {
  const std::size_t nc = contacts.size();
  s.changed.resize(nc);
  const int any_changed = parallel_max<int>(nc, 0, [&](std::size_t i) {
    Contact& c = contacts[i];
    const ContactSprings springs = contact_springs(c, p);
    const auto [dn, ds_step] = contact_motion(lin.gradients[i], lin.offsets[i], d, c);
    const double ds = s.iterate[i].s0 + ds_step;
    const double tan_phi = p.tan_friction[c.joint];
    const bool changed = update_contact_state(c, s.iterate[i], p.joints[c.joint], tan_phi, springs, dn, ds, ds_step);
    s.changed[i] = changed;
    c.penetration = dn;
    c.normal_force = s.iterate[i].normal_force;
    c.shear_force = c.state == ContactState::Locked    ? springs.ks * ds
                    : c.state == ContactState::Sliding ? -c.slide_sign * std::max(0.0, c.normal_force) * tan_phi
                                                       : 0.0;
    return changed ? 1 : 0;
  });
  return any_changed != 0;
}

double deepest_penetration(std::span<const Contact> contacts) {
  return parallel_max<double>(contacts.size(), 0.0, [&](std::size_t i) {
    return contacts[i].state == ContactState::Open ? 0.0 : contacts[i].penetration;
  });
}

void keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, const OpenCloseState& s) {
  parallel_for_each(
      contacts.size(),
      [&](std::size_t i) {
        Contact& c = contacts[i];
        if (c.state == ContactState::Locked) {
          if (!c.ref_valid || s.iterate[i].s0 != lin.offsets[i].s0) {
            c.ref_param = lin.offsets[i].param;
            c.ref_valid = true;
          }
        } else {
          c.ref_valid = false;
        }
      },
      256);
}

}  // namespace dda
