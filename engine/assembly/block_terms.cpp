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

// Kelvin–Voigt damping of the strain terms, σ = E(ε + β·ε̇), c = β·A·E: its
// force −c·ε̇₁ at the end-of-step strain rate ε̇₁ = velocity_factor·d −
// carried_velocity (the time scheme's), as a VBC dashpot's.
void add_strain_damping(const Blocks& blocks, std::size_t b, const Mat3& c, const TimeScheme& scheme, Mat6& k,
                        Vec6& f) {
  k.bottomRightCorner<3, 3>() += scheme.velocity_factor() * c;
  f.tail<3>() += c * scheme.carried_velocity(blocks.scheme_state(b)).tail<3>();
}

}  // namespace

void assemble_block_terms(const Blocks& blocks, std::span<const Mat3> elastic, const Vec2& gravity,
                          double strain_damping, const TimeScheme& scheme, BlockTerms& terms) {
  const std::size_t n = blocks.count();
  terms.k.resize(n);
  terms.f.resize(n);
  parallel_for_each(n, [&](std::size_t b) {
    Mat6 k = Mat6::Zero();
    Vec6 f = Vec6::Zero();
    const double area = blocks.area[b];
    // Elasticity acts on the strain terms (εx, εy, γxy).
    k.bottomRightCorner<3, 3>() += area * elastic[blocks.material[b]];
    if (strain_damping > 0)
      add_strain_damping(blocks, b, strain_damping * area * elastic[blocks.material[b]], scheme, k, f);
    // Inertia: the time scheme's terms with ∫TᵀT dA.
    scheme.add_inertia(blocks.mass[b] / area, block_tt(blocks, b, scheme.mesh_mass), blocks.scheme_state(b), k, f);
    add_stress_and_body_force(blocks, b, gravity, f);
    terms.k[b] = Symmetric6(k);
    terms.f[b] = f;
  });
}

void start_time_scheme_state(Blocks& blocks, const Vec2& gravity, const BlockTerms& loads, MeshMass mesh_mass) {
  for (std::size_t b = 0; b < blocks.count(); ++b) {
    if (!std::isnan(blocks.acceleration[b][0])) continue;
    Vec6 f = loads.f[b];
    add_stress_and_body_force(blocks, b, gravity, f);
    const Mat6 mass = (blocks.mass[b] / blocks.area[b]) * block_tt(blocks, b, mesh_mass);
    blocks.out_of_balance[b] = f;
    blocks.acceleration[b] = mass.ldlt().solve(f);
  }
}

}  // namespace dda
