// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/contact_report.hpp"

#include "contact/narrow_phase.hpp"
#include "core/error.hpp"

#include <cmath>

namespace dda {

namespace {
// A factor the user can type, rounded up to two significant digits so that
// "at least" stays true: 1.0004 → 1.1, 23.2 → 24.
double rounded_up(double x) {
  if (!(x > 0) || !std::isfinite(x)) return x;
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1);
  return std::ceil(x / unit) * unit;
}
}  // namespace

std::string describe_deepest_contact(const Blocks& blocks, std::span<const Contact> contacts,
                                     const ContactLinearisation& lin, const ContactParameters& law, double bound,
                                     double half_height) {
  int deepest = -1;
  for (int i = 0; i < static_cast<int>(contacts.size()); ++i)
    if (contacts[i].state != ContactState::Open &&
        (deepest < 0 || contacts[i].penetration > contacts[deepest].penetration))
      deepest = i;
  if (deepest < 0) return {};
  const Contact& c = contacts[deepest];
  const double at_start = lin.offsets[deepest].d0;
  const std::string which =
      msg("The deepest contact is vertex ", c.vertex + 1, " of block ", c.vblock, " against edge ", c.edge + 1,
          " of block ", c.eblock, " (", to_string(c.state), "), ", c.penetration, " m deep (", at_start,
          " m at the step's start; the bound is ", bound, " m). ");
  if (passed_corner(blocks.polygons(), c))
    return which + "Its vertex has gone round the corner at the end of that edge and lies beside block " +
           std::to_string(c.eblock) +
           ", not inside it: a fault of the engine's contact transfer, not of the model, which neither g0 nor g2 "
           "cures; please report it with the script.";
  const ContactParameters::Springs k = law.springs(c);
  const bool own_stiffness = law.joints[c.joint].normal_stiffness > 0 && c.length > 0;
  const std::string spring = own_stiffness ? "the joint's normal stiffness" : "g0 (contact stiffness)";
  if (at_start > bound) {
    const double ratio = rounded_up(at_start / bound);
    return which + msg("It was that deep at the start of the step, where no cut of the time step reaches: raise g2 ",
                       "above ", at_start / half_height, " (its depth over half the model's height), or run with ",
                       spring, " at least ", ratio, " times larger (", ratio * k.kn,
                       " N/m or more), so that the contact carries its force within the bound.");
  }
  const double ratio = rounded_up(c.penetration / bound);
  return which + msg("It went that deep within the step even at the smallest time step: the load on it is more than ",
                     "its spring holds within the bound. Run with ", spring, " at least ", ratio,
                     " times larger, or raise g2 above ", c.penetration / half_height, ".");
}

}  // namespace dda
