// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "assembly/block_terms.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "block/displacement.hpp"
#include "core/parallel.hpp"

namespace dda {

namespace {

// The block's initial stress on its strain terms (εx, εy, γxy) and its body
// force: the forces of its own that do not depend on the step.
void add_stress_and_body_force(const Blocks& blocks, std::size_t b, const Vec2& gravity, Vec6& f) {
  f.tail<3>() -= blocks.area[b] * blocks.stress[b];
  f[0] += blocks.mass[b] * gravity.x();
  f[1] += blocks.mass[b] * gravity.y();
}

// k's strain terms (εx, εy, γxy) += s·m, on the upper triangle.
void add_to_strain_terms(double s, const Mat3& m, Symmetric6& k) {
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) k.at(3 + i, 3 + j) += s * m(i, j);
}

// Kelvin–Voigt damping of the strain terms, σ = E(ε + β·ε̇), c = β·A·E: its
// force −c·ε̇₁ at the end-of-step strain rate ε̇₁ = velocity_factor·d −
// carried_velocity (the time scheme's), as a VBC dashpot's.
void add_strain_damping(const Blocks& blocks, std::size_t b, const Mat3& c, const TimeScheme& scheme, Symmetric6& k,
                        Vec6& f) {
  add_to_strain_terms(scheme.velocity_factor(), c, k);
  f.tail<3>() += c * scheme.carried_velocity(blocks.scheme_state(b)).tail<3>();
}

}  // namespace

void assemble_block_terms(const Blocks& blocks, std::span<const Mat3> elastic, const Vec2& gravity,
                          double strain_damping, const TimeScheme& scheme, BlockTerms& terms) {
  const std::size_t n = blocks.count();
  terms.k.resize(n);
  terms.f.resize(n);
  parallel_for_each(n, [&](std::size_t b) {
    Symmetric6 k;
    Vec6 f = Vec6::Zero();
    const double area = blocks.area[b];
    // Elasticity acts on the strain terms (εx, εy, γxy).
    add_to_strain_terms(area, elastic[blocks.material[b]], k);
    if (strain_damping > 0)
      add_strain_damping(blocks, b, strain_damping * area * elastic[blocks.material[b]], scheme, k, f);
    // Inertia: the time scheme's terms with ∫TᵀT dA.
    scheme.add_inertia(blocks.mass[b] / area, block_tt(blocks, b, scheme.mesh_mass), blocks.scheme_state(b), k, f);
    add_stress_and_body_force(blocks, b, gravity, f);
    terms.k[b] = k;
    terms.f[b] = f;
  });
}

void start_time_scheme_state(Blocks& blocks, const Vec2& gravity, const BlockTerms& loads, MeshMass mesh_mass) {
  for (std::size_t b = 0; b < blocks.count(); ++b) {
    if (!std::isnan(blocks.acceleration[b][0])) continue;
    Vec6 f = loads.f[b];
    add_stress_and_body_force(blocks, b, gravity, f);
    const Mat6 mass = block_tt(blocks, b, mesh_mass).scaled(blocks.mass[b] / blocks.area[b]).full();
    blocks.out_of_balance[b] = f;
    blocks.acceleration[b] = mass.ldlt().solve(f);
  }
}

}  // namespace dda
