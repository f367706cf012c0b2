// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/inert_controls.hpp"

#include <string>

#include "core/error.hpp"

namespace dda {

namespace {

const ControlSpec& spec(const char* name) {
  const ControlSpec* s = find_control(name);
  if (!s) throw Error(msg("internal: no control ", name));
  return *s;
}

// Away from its default (compared as values: this runs every step).
bool is_set(const ControlSpec& s, const Controls& c) {
  static Controls defaults;
  Controls& now = const_cast<Controls&>(c);  // the access functions take a Controls&; nothing is written
  switch (s.type) {
    case ControlType::Number:
      return s.number(now) != s.number(defaults);
    case ControlType::Integer:
      return s.integer(now) != s.integer(defaults);
    case ControlType::Flag:
      return s.flag(now) != s.flag(defaults);
    case ControlType::Vector:
      return s.vector(now) != s.vector(defaults);
    case ControlType::Choice:
      return s.get_choice(c) != s.get_choice(defaults);
  }
  return false;
}

std::string choice_name(const char* control, int index) {
  return msg("\"", spec(control).choices[static_cast<std::size_t>(index)], "\"");
}

// Throws when `control` is set; the message (why, cure) is made only then:
// this runs every step, and a step allocates nothing.
template <class Why>
void refuse(const Controls& c, const char* control, Why why, const char* cure) {
  const ControlSpec& s = spec(control);
  if (is_set(s, c))
    throw Error(msg("controls: ", control, " = ", s.value_text(c), " is not read here: ", why(), "; ", cure));
}

}  // namespace

void refuse_inert_controls(const ControlUse& use) {
  const Controls& c = use.controls;
  for (const IgnoredControl& ignored : use.law_ignores)
    refuse(
        c, ignored.control,
        [&] {
          return msg("contact_law = ", choice_name("contact_law", static_cast<int>(c.contact_law)),
                     " does not use it (", ignored.why, ")");
        },
        "remove it, or choose a contact_law that reads it (docs/contacts.md)");
  if (use.integrator != Integrator::GeneralizedAlpha)
    refuse(
        c, "rho_inf",
        [&] {
          const std::string in_use = choice_name("integrator", static_cast<int>(use.integrator));
          return msg("only integrator = \"generalized_alpha\" reads it, and ",
                     c.integrator == Integrator::Auto ? msg("integrator = \"auto\" steps this model with ", in_use)
                                                      : msg("the integrator is ", in_use));
        },
        "remove it, or set integrator = \"generalized_alpha\" (docs/time_integration.md)");
  if (c.solver.kind == SolverKind::Pcg)
    for (const char* factor_control : {"refactor_iterations", "fill_ordering"})
      refuse(
          c, factor_control,
          [] { return std::string("only the CHOLMOD factor reads it, and solver = \"pcg\" never makes one"); },
          "remove it, or set solver = \"cholmod\" or \"auto\" (docs/direct_solver.md)");
  // Without meshed blocks: "consistent" is what first-order blocks have, so
  // a script may pin it; a lumped or mixed mass asks for what none has.
  const bool other_mass = c.mesh_mass == MeshMass::Lumped || c.mesh_mass == MeshMass::Mixed;
  if (!use.meshed && other_mass)
    refuse(
        c, "mesh_mass",
        [] { return std::string("the model has no meshed blocks, and first-order blocks keep their consistent mass"); },
        "remove it, or mesh the blocks with mesh_size (docs/meshed_blocks.md)");
  if (!use.meshed)
    refuse(
        c, "mesh_preconditioner",
        [] { return std::string("the model has no meshed blocks, and first-order blocks keep block-Jacobi"); },
        "remove it, or mesh the blocks with mesh_size (docs/meshed_blocks.md)");
}

}  // namespace dda
