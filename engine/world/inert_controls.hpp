// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Controls the model in use does not read. A control set away from its
// default where nothing in this configuration reads it is refused at the
// step's start, with why and the cure, instead of being silently ignored
// (a user who set it expects it to act). This is the one list of such
// combinations, beside each contact law's own declaration
// (ContactModel::ignored_controls, contact/contact_model.hpp), which it
// reads. Controls whose use depends on what a step meets (the solve
// regimes' tolerances, predict_states, patch_hops) are not in it: a step
// may use them later in the same run.
#include <span>

#include "contact/contact_model.hpp"
#include "world/controls.hpp"

namespace dda {

struct ControlUse {
  const Controls& controls;
  Integrator integrator;                        // the one the step uses ("auto" resolved)
  bool meshed = false;                          // the model has meshed blocks
  std::span<const IgnoredControl> law_ignores;  // what the contact law in use does not read
};

// Throws dda::Error naming the first control set away from its default
// that `use` does not read, why, and the cure.
void refuse_inert_controls(const ControlUse& use);

}  // namespace dda
