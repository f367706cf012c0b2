// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "contact/shi_law.hpp"

#include "core/parallel.hpp"

namespace dda {

// A contact that ends the step locked keeps the point it locked at (or takes
// its position at the step start, where it locked again unloaded); others
// drop it.
void ShiLaw::keep_shear_references(std::span<Contact> contacts, const ContactLinearisation& lin, std::size_t begin,
                                   std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    Contact& c = contacts[i];
    if (c.state == ContactState::Locked) {
      if (!c.ref_valid || iterate_[i].s0 != lin.offsets[i].s0) {
        c.ref_param = lin.offsets[i].param;
        c.ref_valid = true;
      }
    } else {
      c.ref_valid = false;
    }
  }
}

}  // namespace dda
