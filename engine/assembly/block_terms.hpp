// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Each block's own terms of the step's system: the diagonal block and the
// right-hand side from its elasticity, initial stress, inertia and body
// force, to which loads (loading/) and boundaries (boundary/) add theirs.
// The contact springs come on top in each open-close iteration
// (contact_terms.hpp).
#include <span>
#include <vector>

#include "block/blocks.hpp"
#include "block/time_scheme.hpp"
#include "core/symmetric6.hpp"

namespace dda {

struct BlockTerms {
  std::vector<Symmetric6> k;  // per block: its diagonal block (upper triangle)
  std::vector<Vec6> f;        // per block: its right-hand side
};

// Elasticity (elastic[material], plane stress or strain) and initial stress
// on the strains, inertia (the time scheme), gravity; sizes `terms`.
// strain_damping β (s, 0: none): the strains' Kelvin–Voigt damping,
// σ = E(ε + β·ε̇), a damping ratio βω/2 at angular frequency ω
// (docs/friction_flutter.md: it keeps a sliding block from chattering).
void assemble_block_terms(const Blocks& blocks, std::span<const Mat3> elastic, const Vec2& gravity,
                          double strain_damping, const TimeScheme& scheme, BlockTerms& terms);

// The time scheme's state of blocks that have none yet (a NaN acceleration:
// new blocks): the unbalanced force R₀ = the loads' forces `loads.f` (at the
// step's start) + body force − initial stress, and a₀ = M⁻¹R₀. Contacts,
// springs and dashpots are taken as unloaded, as they are when a model
// starts (its blocks do not overlap). M as the step's (mesh_mass).
void start_time_scheme_state(Blocks& blocks, const Vec2& gravity, const BlockTerms& loads, MeshMass mesh_mass);

}  // namespace dda
