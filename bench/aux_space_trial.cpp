// Trial (issue 8): an auxiliary-space preconditioner for the quasi-static
// brick walls. DDA with stiff penalty springs (g0 = 50E) behaves like an
// interior-penalty discontinuous Galerkin method with one linear field per
// block: its near-null space is every continuous field that is linear per
// block, which neither block-Jacobi nor aggregates of whole blocks capture.
// Here the continuous fields are those interpolated from displacements at the
// blocks' vertices (shared where vertices coincide or a vertex lies on a
// neighbour's edge), each block's DDA unknowns the least-squares linear fit to
// the displacements of the nodes on its outline (Π). The preconditioner adds a
// correction in that space, solved exactly here (sparse Cholesky of ΠᵀAΠ), to
// block-Jacobi, additively or symmetrically multiplicatively. It prints the
// CG iterations from a cold start; only the iteration counts are of interest
// (the exact auxiliary solve is far too costly to keep). Two more variants:
// the auxiliary operator from the blocks' own terms only (inertia and
// elasticity, no contact springs: sparse, like a finite-element stiffness),
// an inexact auxiliary solve (2×2 block-Jacobi on the nodes plus an exact
// solve on square cells of nodes carrying their rigid motions, no product by
// ΠᵀAΠ; also in symmetric form, and as a two-level V-cycle on ΠᵀAΠ), a
// multilevel V-cycle on ΠᵀAΠ (cells of 1, 2, 4 m ...), the auxiliary system
// alone under block-Jacobi CG, and the Galerkin operator kept while the wall
// steps on 10 more steps.
//
// Run: build/bench/aux_space_trial [N ...]   (walls wall(N), default 10 20 40)
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <vector>

#include "scenes.hpp"

using namespace dda;

namespace {

using SpMat = Eigen::SparseMatrix<double>;

struct Aux {
  SpMat pi;  // 6·blocks × 2·nodes
  SpMat ac;  // ΠᵀAΠ
  Eigen::SimplicialLDLT<SpMat> chol, chol_elastic;
  int nodes = 0;
  std::vector<Vec2> node;
};

// An inexact auxiliary solve with no product by ΠᵀAΠ: 2×2 block-Jacobi on the
// nodes plus an exact solve on aggregates of nodes (square cells of side h),
// each carrying the three rigid motions (additive two-level).
struct TwoLevelAux {
  std::vector<Eigen::Matrix2d> dinv;
  SpMat p;  // 2·nodes × 3·aggregates
  Eigen::SimplicialLDLT<SpMat> coarse;
  int aggregates = 0;
  TwoLevelAux(const Aux& aux, double h) {
    const int m = aux.nodes;
    dinv.resize(m);
    double largest = 0;
    for (int k = 0; k < m; ++k) largest = std::max(largest, Eigen::Matrix2d(aux.ac.block(2 * k, 2 * k, 2, 2)).norm());
    int weak = 0;
    for (int k = 0; k < m; ++k) {
      const Eigen::Matrix2d d = aux.ac.block(2 * k, 2 * k, 2, 2);
      if (d.norm() < 1e-8 * largest) ++weak;
      dinv[k] = d.completeOrthogonalDecomposition().pseudoInverse();
    }
    if (weak) std::printf("  %d nodes with a diagonal under 1e-8 of the largest\n", weak);
    std::map<std::pair<int, int>, int> cell;
    std::vector<int> agg(m);
    for (int k = 0; k < m; ++k) {
      auto [it, fresh] = cell.emplace(std::make_pair(static_cast<int>(std::floor(aux.node[k].x() / h)),
                                                     static_cast<int>(std::floor(aux.node[k].y() / h))),
                                      static_cast<int>(cell.size()));
      agg[k] = it->second;
    }
    aggregates = static_cast<int>(cell.size());
    std::vector<Vec2> centre(aggregates, Vec2::Zero());
    std::vector<int> count(aggregates, 0);
    for (int k = 0; k < m; ++k) {
      centre[agg[k]] += aux.node[k];
      ++count[agg[k]];
    }
    for (int a = 0; a < aggregates; ++a) centre[a] /= count[a];
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < m; ++k) {
      const Vec2 d = aux.node[k] - centre[agg[k]];
      const int c = 3 * agg[k];
      t.emplace_back(2 * k, c, 1);
      t.emplace_back(2 * k + 1, c + 1, 1);
      t.emplace_back(2 * k, c + 2, -d.y());
      t.emplace_back(2 * k + 1, c + 2, d.x());
    }
    p.resize(2 * m, 3 * aggregates);
    p.setFromTriplets(t.begin(), t.end());
    // A cell holding one node has no rotation: a zero row and column, which a
    // tiny shift keeps out of the factorisation's way.
    const SpMat ac = SpMat(p.transpose() * aux.ac * p);
    coarse.setShift(1e-12 * ac.diagonal().cwiseAbs().maxCoeff());
    coarse.compute(ac);
  }
  VecX jacobi(const VecX& r) const {
    VecX z(r.size());
    for (std::size_t k = 0; k < dinv.size(); ++k) z.segment<2>(2 * k) = dinv[k] * r.segment<2>(2 * k);
    return z;
  }
  VecX cells(const VecX& r) const { return p * coarse.solve(VecX(p.transpose() * r)); }
  VecX solve(const VecX& r) const { return jacobi(r) + cells(r); }
  // A symmetric two-level V-cycle on the auxiliary system ac (weight ω):
  // smooth, correct on the cells, smooth.
  VecX vcycle(const SpMat& ac, const VecX& r, double omega) const {
    const VecX x1 = omega * jacobi(r);
    const VecX x2 = x1 + cells(VecX(r - ac * x1));
    return x2 + omega * jacobi(VecX(r - ac * x2));
  }
};

// λmax of M⁻¹A by power iteration from the ones vector (a lower bound, for
// smoother weights); precondition(y) returns M⁻¹y.
template <typename Precondition>
double largest_eigenvalue(const SpMat& a, Precondition&& precondition, int iterations) {
  VecX v = VecX::Ones(a.rows());
  double lambda = 1;
  for (int k = 0; k < iterations; ++k) {
    const VecX t = precondition(VecX(a * v));
    lambda = t.norm() / v.norm();
    v = t / t.norm();
  }
  return lambda;
}

// The DDA displacement at p for a block with reference point c: T(p)·d.
Eigen::Matrix<double, 2, 6> dda_t(const Vec2& p, const Vec2& c) {
  const double dx = p.x() - c.x(), dy = p.y() - c.y();
  Eigen::Matrix<double, 2, 6> t;
  t << 1, 0, -dy, dx, 0, dy / 2, 0, 1, dx, 0, dy, dx / 2;
  return t;
}

void build_aux(World& w, const SpMat& a, Aux& aux) {
  const int n = static_cast<int>(w.block_count());
  // Nodes: block vertices, merged where they coincide (to 1e-6 m).
  std::map<std::pair<long long, long long>, int> id;
  std::vector<Vec2> node;
  auto key = [](const Vec2& p) { return std::make_pair(std::llround(p.x() * 1e6), std::llround(p.y() * 1e6)); };
  for (int b = 0; b < n; ++b)
    for (const Vec2& v : w.block_initial_vertices(b)) {
      auto [it, fresh] = id.emplace(key(v), static_cast<int>(node.size()));
      if (fresh) node.push_back(v);
    }
  aux.nodes = static_cast<int>(node.size());
  aux.node = node;
  // Nodes on each block's outline (its vertices and others' on its edges), by a grid.
  const double cell = 1.0;
  std::map<std::pair<int, int>, std::vector<int>> grid;
  for (int k = 0; k < aux.nodes; ++k)
    grid[{static_cast<int>(std::floor(node[k].x() / cell)), static_cast<int>(std::floor(node[k].y() / cell))}].push_back(k);
  std::vector<Eigen::Triplet<double>> trip;
  for (int b = 0; b < n; ++b) {
    const auto v = w.block_initial_vertices(b);
    const Vec2 c = w.block_centroid(b);
    std::vector<int> on;
    for (std::size_t e = 0; e < v.size(); ++e) {
      const Vec2 p = v[e], q = v[(e + 1) % v.size()];
      const int x0 = static_cast<int>(std::floor(std::min(p.x(), q.x()) / cell)) - 1, x1 = static_cast<int>(std::floor(std::max(p.x(), q.x()) / cell)) + 1;
      const int y0 = static_cast<int>(std::floor(std::min(p.y(), q.y()) / cell)) - 1, y1 = static_cast<int>(std::floor(std::max(p.y(), q.y()) / cell)) + 1;
      for (int gx = x0; gx <= x1; ++gx)
        for (int gy = y0; gy <= y1; ++gy) {
          auto it = grid.find({gx, gy});
          if (it == grid.end()) continue;
          for (int k : it->second) {
            const Vec2 d = q - p, r = node[k] - p;
            const double s = r.dot(d) / d.squaredNorm();
            if (s < -1e-9 || s > 1 + 1e-9) continue;
            if ((r - s * d).norm() < 1e-6) on.push_back(k);
          }
        }
    }
    std::sort(on.begin(), on.end());
    on.erase(std::unique(on.begin(), on.end()), on.end());
    Mat6 m = Mat6::Zero();
    for (int k : on) m += dda_t(node[k], c).transpose() * dda_t(node[k], c);
    const Mat6 minv = m.inverse();
    for (int k : on) {
      const Eigen::Matrix<double, 6, 2> col = minv * dda_t(node[k], c).transpose();
      for (int r = 0; r < 6; ++r)
        for (int s = 0; s < 2; ++s) trip.emplace_back(6 * b + r, 2 * k + s, col(r, s));
    }
  }
  aux.pi.resize(6 * n, 2 * aux.nodes);
  aux.pi.setFromTriplets(trip.begin(), trip.end());
  {
    // The blocks' own terms only (inertia and elasticity, no contact springs):
    // a sparse, finite-element-like auxiliary operator.
    std::vector<Eigen::Triplet<double>> kt;
    const double dt = w.controls().g1;
    for (int b = 0; b < n; ++b) {
      const RockMaterial& rock = w.rock_material(w.block_material(b));
      const auto v = w.block_initial_vertices(b);
      const Vec2 c = w.block_centroid(b);
      // Gauss 4x4 over the bounding box (the wall's blocks are rectangles).
      double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
      for (const Vec2& p : v) { x0 = std::min(x0, p.x()); x1 = std::max(x1, p.x()); y0 = std::min(y0, p.y()); y1 = std::max(y1, p.y()); }
      const double gp[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
      const double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
      Mat6 k = Mat6::Zero();
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const Vec2 p((x0 + x1) / 2 + gp[i] * (x1 - x0) / 2, (y0 + y1) / 2 + gp[j] * (y1 - y0) / 2);
          const double wq = gw[i] * gw[j] * (x1 - x0) * (y1 - y0) / 4;
          k += (2 * rock.density / (dt * dt)) * wq * dda_t(p, c).transpose() * dda_t(p, c);
        }
      const double area = (x1 - x0) * (y1 - y0), e = rock.youngs, nu = rock.poisson;
      Eigen::Matrix3d cm;
      cm << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
      k.bottomRightCorner<3, 3>() += area * e / (1 - nu * nu) * cm;
      // Π_bᵀ K_b Π_b over the block's nodes.
      SpMat rows = aux.pi.middleRows(6 * b, 6);
      SpMat kb = SpMat(rows.transpose() * k.sparseView() * rows);
      for (int o = 0; o < kb.outerSize(); ++o)
        for (SpMat::InnerIterator it(kb, o); it; ++it) kt.emplace_back(it.row(), it.col(), it.value());
    }
    SpMat ke(2 * aux.nodes, 2 * aux.nodes);
    ke.setFromTriplets(kt.begin(), kt.end());
    aux.chol_elastic.compute(ke);
    std::printf("  elastic auxiliary operator: nnz %ld (%s)\n", static_cast<long>(ke.nonZeros()),
                aux.chol_elastic.info() == Eigen::Success ? "factorised" : "factorisation failed");
  }
  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  aux.ac = SpMat(aux.pi.transpose() * a * aux.pi);
  const SpMat& ac = aux.ac;
  auto t1 = Clock::now();
  aux.chol.analyzePattern(ac);
  auto t2 = Clock::now();
  aux.chol.factorize(ac);
  auto t3 = Clock::now();
  VecX r = VecX::Ones(ac.rows()), y;
  for (int k = 0; k < 10; ++k) y = aux.chol.solve(r);
  auto t4 = Clock::now();
  auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  std::printf("  Galerkin auxiliary operator: nnz %ld; product %.1f ms, ordering %.1f ms, factorisation %.1f ms, one solve %.2f ms (1 thread)\n",
              static_cast<long>(ac.nonZeros()), ms(t0, t1), ms(t1, t2),
              ms(t2, t3), ms(t3, t4) / 10);
  if (aux.chol.info() != Eigen::Success) std::printf("  auxiliary factorisation failed\n");
}

// PCG from zero; returns iterations to reach each tolerance.
template <typename Pre>
std::vector<int> pcg(const SpMat& a, const VecX& b, Pre&& pre, const std::vector<double>& tols) {
  VecX x = VecX::Zero(b.size()), r = b, z, p, ap;
  pre(r, z);
  p = z;
  double rz = r.dot(z);
  const double bn = b.norm();
  std::vector<int> at(tols.size(), -1);
  for (int it = 1; it <= 20000; ++it) {
    ap = a * p;
    const double alpha = rz / p.dot(ap);
    x += alpha * p;
    r -= alpha * ap;
    const double rel = r.norm() / bn;
    bool all = true;
    for (std::size_t t = 0; t < tols.size(); ++t) {
      if (at[t] < 0 && rel <= tols[t]) at[t] = it;
      all = all && at[t] >= 0;
    }
    if (all) break;
    pre(r, z);
    const double rz2 = r.dot(z);
    p = z + (rz2 / rz) * p;
    rz = rz2;
  }
  return at;
}

// A multilevel V-cycle for the auxiliary system: level 0 the nodes (2
// unknowns), then square cells of side h0·2^(l−1) carrying three rigid
// motions about their centres, Galerkin operators, block-Jacobi smoothing
// (weight 1/λmax), optionally smoothed prolongators, a sparse Cholesky at
// the coarsest level (under 600 unknowns).
struct MultilevelAux {
  struct Level {
    SpMat a, p;  // operator; prolongator from the next level (empty on the coarsest)
    std::vector<Eigen::MatrixXd> dinv;  // block inverses (2×2 or 3×3)
    int bs = 2;
    double omega = 1;
  };
  std::vector<Level> levels;
  Eigen::SimplicialLDLT<SpMat> coarsest;

  static std::vector<Eigen::MatrixXd> block_inverses(const SpMat& a, int bs) {
    std::vector<Eigen::MatrixXd> inv(a.rows() / bs);
    for (std::size_t k = 0; k < inv.size(); ++k) {
      Eigen::MatrixXd d = Eigen::MatrixXd(a.block(bs * k, bs * k, bs, bs));
      inv[k] = d.completeOrthogonalDecomposition().pseudoInverse();
    }
    return inv;
  }
  VecX jacobi(const Level& l, const VecX& r) const {
    VecX z(r.size());
    for (std::size_t k = 0; k < l.dinv.size(); ++k) z.segment(l.bs * k, l.bs) = l.dinv[k] * r.segment(l.bs * k, l.bs);
    return z;
  }
  MultilevelAux(const Aux& aux, double h0, bool smooth) {
    std::vector<Vec2> pos = aux.node;
    Level l0;
    l0.a = aux.ac;
    l0.bs = 2;
    levels.push_back(l0);
    double h = h0;
    while (levels.back().a.rows() > 600) {
      Level& f = levels.back();
      f.dinv = block_inverses(f.a, f.bs);
      f.omega = 1.0 / largest_eigenvalue(f.a, [&](const VecX& y) { return jacobi(f, y); }, 20);
      // Cells of side h over this level's points.
      std::map<std::pair<int, int>, int> cell;
      std::vector<int> of(pos.size());
      for (std::size_t k = 0; k < pos.size(); ++k)
        of[k] = cell.emplace(std::make_pair(static_cast<int>(std::floor(pos[k].x() / h)), static_cast<int>(std::floor(pos[k].y() / h))),
                             static_cast<int>(cell.size())).first->second;
      const int nc = static_cast<int>(cell.size());
      std::vector<Vec2> centre(nc, Vec2::Zero());
      std::vector<int> count(nc, 0);
      for (std::size_t k = 0; k < pos.size(); ++k) {
        centre[of[k]] += pos[k];
        ++count[of[k]];
      }
      for (int c = 0; c < nc; ++c) centre[c] /= count[c];
      std::vector<Eigen::Triplet<double>> t3;
      for (std::size_t k = 0; k < pos.size(); ++k) {
        const Vec2 d = pos[k] - centre[of[k]];
        const int r0 = f.bs * static_cast<int>(k), c0 = 3 * of[k];
        t3.emplace_back(r0, c0, 1);
        t3.emplace_back(r0 + 1, c0 + 1, 1);
        t3.emplace_back(r0, c0 + 2, -d.y());
        t3.emplace_back(r0 + 1, c0 + 2, d.x());
        if (f.bs == 3) t3.emplace_back(r0 + 2, c0 + 2, 1);
      }
      SpMat p(f.a.rows(), 3 * nc);
      p.setFromTriplets(t3.begin(), t3.end());
      if (smooth) {
        // P = (I − (4/3)ω D⁻¹A)·P_tent
        SpMat dinv(f.a.rows(), f.a.rows());
        std::vector<Eigen::Triplet<double>> td;
        for (std::size_t k = 0; k < f.dinv.size(); ++k)
          for (int r = 0; r < f.bs; ++r)
            for (int c = 0; c < f.bs; ++c) td.emplace_back(f.bs * k + r, f.bs * k + c, f.dinv[k](r, c));
        dinv.setFromTriplets(td.begin(), td.end());
        p = SpMat(p - (4.0 / 3.0) * f.omega * SpMat(dinv * SpMat(f.a * p)));
      }
      f.p = p;
      Level c;
      c.a = SpMat(p.transpose() * f.a * p);
      c.bs = 3;
      levels.push_back(c);
      pos = centre;
      h *= 2;
    }
    const SpMat& ac = levels.back().a;
    coarsest.setShift(1e-12 * ac.diagonal().cwiseAbs().maxCoeff());
    coarsest.compute(ac);
  }
  VecX vcycle(std::size_t l, const VecX& r) const {
    if (l + 1 == levels.size()) return coarsest.solve(r);
    const Level& f = levels[l];
    VecX x = f.omega * jacobi(f, r);
    x += f.p * vcycle(l + 1, VecX(f.p.transpose() * VecX(r - f.a * x)));
    x += f.omega * jacobi(f, VecX(r - f.a * x));
    return x;
  }
};

// Block-Jacobi: z = D⁻¹r with the inverse 6×6 diagonal blocks of m.
struct BlockJacobi {
  std::vector<Mat6> dinv;
  explicit BlockJacobi(const BlockSparseMatrix& m) : dinv(m.rows()) {
    for (int i = 0; i < m.rows(); ++i) dinv[i] = m.value(m.diagonal(i)).inverse();
  }
  void operator()(const VecX& r, VecX& z) const {
    z.resize(r.size());
    for (std::size_t i = 0; i < dinv.size(); ++i) z.segment<6>(6 * i) = dinv[i] * r.segment<6>(6 * i);
  }
};

// One row of the table: iterations to each tolerance ("-" where it never got there).
void row(const char* label, const std::vector<int>& at) {
  std::printf("    %-48s", label);
  for (int i : at) i < 0 ? std::printf(" %5s", "-") : std::printf(" %5d", i);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> walls;
  for (int i = 1; i < argc; ++i) walls.push_back(std::atoi(argv[i]));
  if (walls.empty()) walls = {10, 20, 40};
  const std::vector<double> tols = {1e-4, 1e-6, 1e-10};
  for (int wn : walls) {
    World w = test::brick_wall(wn);
    w.controls().threads = 1;
    w.controls().preconditioner = Preconditioning::BlockJacobi;
    for (int s = 0; s < 3; ++s) w.step();
    const BlockSparseMatrix& bsm = w.last_matrix();
    const SpMat a = bsm.to_sparse();
    const VecX b = w.last_rhs();
    const int n = bsm.rows();
    const BlockJacobi jacobi(bsm);
    std::printf("wall(%d): %d blocks\n", wn, n);
    Aux aux;
    build_aux(w, a, aux);
    auto coarse = [&](const VecX& r) -> VecX { return aux.pi * aux.chol.solve(VecX(aux.pi.transpose() * r)); };
    auto additive = [&](const VecX& r, VecX& z) {
      jacobi(r, z);
      z += coarse(r);
    };
    // λmax(D⁻¹A), for the smoother weight.
    const double lambda = largest_eigenvalue(a, [&](const VecX& y) {
      VecX z;
      jacobi(y, z);
      return z;
    }, 30);
    const double omega = 1.0 / lambda;
    auto coarse_elastic = [&](const VecX& r) -> VecX { return aux.pi * aux.chol_elastic.solve(VecX(aux.pi.transpose() * r)); };
    auto additive_elastic = [&](const VecX& r, VecX& z) {
      jacobi(r, z);
      z += coarse_elastic(r);
    };
    auto multiplicative = [&](const VecX& r, VecX& z) {
      VecX s;
      jacobi(r, s);
      VecX x1 = omega * s;
      VecX x2 = x1 + coarse(VecX(r - a * x1));
      jacobi(VecX(r - a * x2), s);
      z = x2 + omega * s;
    };
    const auto bj = pcg(a, b, jacobi, tols), ad = pcg(a, b, additive, tols), mu = pcg(a, b, multiplicative, tols), ae = pcg(a, b, additive_elastic, tols);
    std::printf("  %d nodes (%d auxiliary unknowns), lambda_max(D^-1 A) %.2f\n", aux.nodes, 2 * aux.nodes, lambda);
    std::printf("  CG iterations to 1e-4 / 1e-6 / 1e-10 from zero:\n");
    row("block-Jacobi", bj);
    row("+ auxiliary, additive", ad);
    row("+ auxiliary, symmetric", mu);
    row("+ elastic auxiliary operator, additive", ae);
    for (double h : {1.0, 2.0, 4.0}) {
      const TwoLevelAux two(aux, h);
      auto inexact = [&](const VecX& r, VecX& z) {
        jacobi(r, z);
        z += aux.pi * two.solve(VecX(aux.pi.transpose() * r));
      };
      const auto in = pcg(a, b, inexact, tols);
      char label[96];
      std::snprintf(label, sizeof label, "+ auxiliary, inexact (nodes + %g m cells, %d)", h, two.aggregates);
      row(label, in);
      auto inexact_symmetric = [&](const VecX& r, VecX& z) {
        VecX s;
        jacobi(r, s);
        VecX x1 = omega * s;
        VecX x2 = x1 + aux.pi * two.solve(VecX(aux.pi.transpose() * VecX(r - a * x1)));
        jacobi(VecX(r - a * x2), s);
        z = x2 + omega * s;
      };
      const auto ins = pcg(a, b, inexact_symmetric, tols);
      std::snprintf(label, sizeof label, "  the same, symmetric (smooth, correct, smooth)");
      row(label, ins);
      // The auxiliary system solved by a two-level V-cycle of its own (smoothing
      // on the nodes needs products by ΠᵀAΠ: in the engine, fine products).
      const double lambda_aux = largest_eigenvalue(aux.ac, [&](const VecX& y) { return two.jacobi(y); }, 30);
      auto aux_vcycle = [&](const VecX& r, VecX& z) {
        jacobi(r, z);
        z += aux.pi * two.vcycle(aux.ac, VecX(aux.pi.transpose() * r), 1.0 / lambda_aux);
      };
      const auto vc = pcg(a, b, aux_vcycle, tols);
      std::snprintf(label, sizeof label, "  auxiliary by a V-cycle (smooth, cells, smooth)");
      row(label, vc);
    }
    // The same auxiliary factorisation, 10 steps later (a stale operator is
    // still a symmetric positive definite preconditioner).
    for (int s = 0; s < 10; ++s) w.step();
    const BlockSparseMatrix& later = w.last_matrix();
    const SpMat a2 = later.to_sparse();
    const VecX b2 = w.last_rhs();
    {
      // How hard the auxiliary system is by itself: 2×2 block-Jacobi PCG on it.
      const TwoLevelAux nodes_only(aux, 1.0);
      const VecX b_aux = aux.pi.transpose() * b;
      const auto alone = pcg(aux.ac, b_aux, [&](const VecX& r, VecX& z) { z = nodes_only.jacobi(r); }, tols);
      row("(the auxiliary system alone, node block-Jacobi)", alone);
    }
    for (bool smooth : {false, true}) {
      const MultilevelAux ml(aux, 1.0, smooth);
      auto multilevel = [&](const VecX& r, VecX& z) {
        jacobi(r, z);
        z += aux.pi * ml.vcycle(0, VecX(aux.pi.transpose() * r));
      };
      const auto mlr = pcg(a, b, multilevel, tols);
      char label[96];
      std::snprintf(label, sizeof label, "+ auxiliary by a %zu-level V-cycle%s", ml.levels.size(), smooth ? " (smoothed P)" : "");
      row(label, mlr);
    }
    const BlockJacobi jacobi_later(later);
    auto stale = [&](const VecX& r, VecX& z) {
      jacobi_later(r, z);
      z += coarse(r);
    };
    const auto st = pcg(a2, b2, stale, tols);
    row("+ auxiliary, additive, 10 steps later", st);
  }
}
