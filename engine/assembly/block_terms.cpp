#include "assembly/block_terms.hpp"

#include "block/displacement.hpp"
#include "core/parallel.hpp"

namespace dda {

void assemble_block_terms(const Blocks& blocks, std::span<const Mat3> elastic, const Vec2& gravity,
                          const TimeScheme& scheme, BlockTerms& terms) {
  const std::size_t n = blocks.count();
  terms.k.resize(n);
  terms.f.resize(n);
  parallel_for_each(n, [&](std::size_t b) {
    Mat6 k = Mat6::Zero();
    Vec6 f = Vec6::Zero();
    const double area = blocks.area[b];
    // Elasticity and initial stress act on the strain terms (εx, εy, γxy).
    k.bottomRightCorner<3, 3>() += area * elastic[blocks.material[b]];
    f.tail<3>() -= area * blocks.stress[b];
    // Inertia: the time scheme's terms with ∫TᵀT dA.
    const double rho = blocks.mass[b] / area;
    const Mat6 tt = integrated_tt(area, blocks.sxx[b], blocks.syy[b], blocks.sxy[b]);
    scheme.add_inertia(rho, tt, blocks.velocity[b], k, f);
    // Body force.
    f[0] += blocks.mass[b] * gravity.x();
    f[1] += blocks.mass[b] * gravity.y();
    terms.k[b] = Symmetric6(k);
    terms.f[b] = f;
  });
}

}  // namespace dda
