// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// What a step that cannot be completed says about its contacts: the deepest
// one, named as a user finds it (m:contacts()), and a cure that is true for
// the way it got that deep.
#include <span>
#include <string>

#include "block/blocks.hpp"
#include "contact/contact.hpp"
#include "contact/contact_detection.hpp"
#include "contact/contact_model.hpp"

namespace dda {

// The deepest closed contact after the last solve, against the g2 bound
// (`bound`, m) of a model `half_height` high: the two blocks, the vertex and
// the edge (numbered from 1, as m:contacts() does; blocks by id), its state,
// its depth now and at the step's start, and the cure:
//   * its vertex has gone round the corner of its edge (passed_corner): an
//     engine fault, which neither g0 nor g2 cures;
//   * it was deeper than the bound at the step's start, where no cut of Δt
//     reaches: g2 above its depth, or a spring that carries its force within
//     the bound (g0 × depth / bound);
//   * it went deeper within the step even at the smallest Δt: its load exceeds
//     what its spring holds within the bound: a stiffer spring or a larger g2.
// Empty when no contact is closed.
std::string describe_deepest_contact(const Blocks& blocks, std::span<const Contact> contacts,
                                     const ContactLinearisation& lin, const ContactParameters& law, double bound,
                                     double half_height);

}  // namespace dda
