#pragma once
// The energy budget's accounting (energy_budget.hpp), in Update: from the
// accepted step displacement, before anything moves.
#include <span>

#include "contact/contact_detection.hpp"
#include "contact/open_close.hpp"
#include "world/world_state.hpp"

namespace dda {

// Adds the accepted step d to w.energy: held energy from the blocks' state
// before and after d (the end-of-step velocity from the time scheme), the
// contacts' forces from the last check, the loads' and boundaries' work.
// `elastic` per rock material, `fixed_spring` = fixed_point_factor × g0.
void account_step_energy(WorldState& w, const VecX& d, const TimeScheme& scheme, std::span<const Mat3> elastic,
                         const ContactLinearisation& lin, const ContactParameters& contact_law, double fixed_spring);

}  // namespace dda
