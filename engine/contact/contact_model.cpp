// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/contact_model.hpp"

#include "contact/holding_law.hpp"
#include "contact/shi_law.hpp"
#include "core/parallel.hpp"

namespace dda {

ContactModel::~ContactModel() = default;

const ImpactEnergy& ContactModel::impact_energy() const {
  static const ImpactEnergy none;
  return none;
}

// The one place that knows every law.
std::unique_ptr<ContactModel> make_contact_model(ContactLaw law) {
  switch (law) {
    case ContactLaw::Holding:
      return std::make_unique<HoldingLaw>();
    case ContactLaw::Shi:
      return std::make_unique<ShiLaw>();
  }
  return nullptr;
}

double deepest_penetration(std::span<const Contact> contacts) {
  return parallel_max<double>(contacts.size(), 0.0, [&](std::size_t i) {
    return contacts[i].state == ContactState::Open ? 0.0 : contacts[i].penetration;
  });
}

}  // namespace dda
