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

}  // namespace dda
