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
// steps on 10 more steps. Then continuous coarse spaces of bilinear fields on
// a square grid: interpolated to the nodes (with and without node Jacobi),
// or mapped straight to each block's centroid value and gradient (no nodes),
// solved exactly or, on the 0.5 m grid, by geometric V-cycles (Jacobi or
// Gauss-Seidel smoothing, bilinear or smoothed prolongators, with and
// without a penalty on the grid cells' hourglass modes); patch Schwarz (the
// blocks round each vertex, or each block with its neighbours), with and
// without those coarse spaces; and Eigen's incomplete Cholesky of A.
//
// Run: build/bench/aux_space_trial [N ...]   (walls wall(N), default 10 20 40)
#include <Eigen/Cholesky>
#include <Eigen/IterativeLinearSolvers>
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

// 2×2 block-Jacobi on the auxiliary nodes (pseudo-inverses: a node no fit
// sees has a zero diagonal block).
struct NodeJacobi {
  std::vector<Eigen::Matrix2d> dinv;
  explicit NodeJacobi(const Aux& aux) : dinv(aux.nodes) {
    double largest = 0;
    for (int k = 0; k < aux.nodes; ++k)
      largest = std::max(largest, Eigen::Matrix2d(aux.ac.block(2 * k, 2 * k, 2, 2)).norm());
    int weak = 0;
    for (int k = 0; k < aux.nodes; ++k) {
      const Eigen::Matrix2d d = aux.ac.block(2 * k, 2 * k, 2, 2);
      if (d.norm() < 1e-8 * largest) ++weak;
      dinv[k] = d.completeOrthogonalDecomposition().pseudoInverse();
    }
    if (weak) std::printf("  %d nodes with a diagonal under 1e-8 of the largest\n", weak);
  }
  VecX operator()(const VecX& r) const {
    VecX z(r.size());
    for (std::size_t k = 0; k < dinv.size(); ++k) z.segment<2>(2 * k) = dinv[k] * r.segment<2>(2 * k);
    return z;
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

// A smoothed prolongator, p − ω·D⁻¹·A·p, D⁻¹ given as its square diagonal
// blocks (of any fixed size).
template <typename Block>
SpMat smoothed(const SpMat& a, const std::vector<Block>& dinv, double omega, const SpMat& p) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t k = 0; k < dinv.size(); ++k) {
    const int bs = static_cast<int>(dinv[k].rows());
    for (int r = 0; r < bs; ++r)
      for (int c = 0; c < bs; ++c) t.emplace_back(bs * k + r, bs * k + c, dinv[k](r, c));
  }
  SpMat d(a.rows(), a.rows());
  d.setFromTriplets(t.begin(), t.end());
  return SpMat(p - omega * SpMat(d * SpMat(a * p)));
}

// An inexact auxiliary solve with no product by ΠᵀAΠ: 2×2 block-Jacobi on the
// nodes plus an exact solve on aggregates of nodes (square cells of side h),
// each carrying the three rigid motions (additive two-level).
struct TwoLevelAux {
  NodeJacobi jacobi;
  SpMat p;  // 2·nodes × 3·aggregates
  Eigen::SimplicialLDLT<SpMat> coarse;
  int aggregates = 0;
  TwoLevelAux(const Aux& aux, double h) : jacobi(aux) {
    const int m = aux.nodes;
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

// A continuous coarse space: bilinear hat functions on a square grid of side
// h over the nodes (only grid points whose cells hold nodes), interpolated to
// the auxiliary nodes (Q: 2·nodes × 2·grid points), its Galerkin operator
// QᵀΠᵀAΠQ factorised.
struct BilinearCoarse {
  SpMat q;
  Eigen::SimplicialLDLT<SpMat> chol;
  int points = 0;
  BilinearCoarse(const Aux& aux, const SpMat& ac, double h) {
    Vec2 lo = aux.node[0];
    for (const Vec2& p : aux.node) lo = lo.cwiseMin(p);
    std::map<std::pair<int, int>, int> id;
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < aux.nodes; ++k) {
      const Vec2 s = (aux.node[k] - lo) / h;
      const int i = static_cast<int>(std::floor(s.x())), j = static_cast<int>(std::floor(s.y()));
      const double fx = s.x() - i, fy = s.y() - j;
      for (int di = 0; di < 2; ++di)
        for (int dj = 0; dj < 2; ++dj) {
          const double wgt = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy);
          if (wgt < 1e-12) continue;
          auto [it, fresh] = id.emplace(std::make_pair(i + di, j + dj), static_cast<int>(id.size()));
          t.emplace_back(2 * k, 2 * it->second, wgt);
          t.emplace_back(2 * k + 1, 2 * it->second + 1, wgt);
        }
    }
    points = static_cast<int>(id.size());
    q.resize(2 * aux.nodes, 2 * points);
    q.setFromTriplets(t.begin(), t.end());
    chol.compute(SpMat(q.transpose() * ac * q));
    if (chol.info() != Eigen::Success) std::printf("  bilinear coarse factorisation failed (h %g)\n", h);
  }
  VecX solve(const VecX& r) const { return q * chol.solve(VecX(q.transpose() * r)); }
};

// The same continuous coarse space mapped straight to the blocks: each
// block's six unknowns the bilinear field's value and derivatives at its
// centroid (rotation, strains), from the four grid points of the cell that
// holds the centroid; no nodes. Z: 6·blocks × 2·grid points.
struct CentroidCoarse {
  SpMat z, ac;
  Eigen::SimplicialLDLT<SpMat> chol;
  int points = 0;
  std::vector<std::pair<int, int>> index;  // each grid point's (i, j)
  CentroidCoarse(const World& w, const SpMat& a, double h) {
    const int n = static_cast<int>(w.block_count());
    Vec2 lo = w.block_centroid(0);
    for (int b = 0; b < n; ++b) lo = lo.cwiseMin(w.block_centroid(b));
    std::map<std::pair<int, int>, int> id;
    std::vector<Eigen::Triplet<double>> t;
    for (int b = 0; b < n; ++b) {
      const Vec2 s = (w.block_centroid(b) - lo) / h;
      const int i = static_cast<int>(std::floor(s.x())), j = static_cast<int>(std::floor(s.y()));
      const double fx = s.x() - i, fy = s.y() - j;
      for (int di = 0; di < 2; ++di)
        for (int dj = 0; dj < 2; ++dj) {
          const double nx = di ? fx : 1 - fx, ny = dj ? fy : 1 - fy;
          const double wv = nx * ny, wx = (di ? 1 : -1) * ny / h, wy = nx * (dj ? 1 : -1) / h;
          auto [it, fresh] = id.emplace(std::make_pair(i + di, j + dj), static_cast<int>(id.size()));
          const int cu = 2 * it->second, cv = cu + 1;
          // u-component: (w, 0, -w_y/2, w_x, 0, w_y); v-component: (0, w, w_x/2, 0, w_y, w_x).
          const double col_u[6] = {wv, 0, -wy / 2, wx, 0, wy}, col_v[6] = {0, wv, wx / 2, 0, wy, wx};
          for (int r = 0; r < 6; ++r) {
            if (col_u[r] != 0) t.emplace_back(6 * b + r, cu, col_u[r]);
            if (col_v[r] != 0) t.emplace_back(6 * b + r, cv, col_v[r]);
          }
        }
    }
    points = static_cast<int>(id.size());
    index.resize(points);
    for (const auto& [ij, k] : id) index[k] = ij;
    z.resize(6 * n, 2 * points);
    z.setFromTriplets(t.begin(), t.end());
    ac = SpMat(z.transpose() * a * z);
    chol.setShift(1e-12 * ac.diagonal().cwiseAbs().maxCoeff());
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    chol.compute(ac);
    const auto t1 = Clock::now();
    VecX y = VecX::Ones(ac.rows());
    for (int k = 0; k < 10; ++k) y = chol.solve(y);
    const auto t2 = Clock::now();
    auto ms = [](auto from, auto to) { return std::chrono::duration<double, std::milli>(to - from).count(); };
    std::printf(
        "  bilinear %g m at centroids: grid system nnz %ld, factor nnz %ld; factorisation %.1f ms, one solve %.2f ms "
        "(1 thread)\n",
        h, static_cast<long>(ac.nonZeros()), static_cast<long>(chol.matrixL().nestedExpression().nonZeros()),
        ms(t0, t1), ms(t1, t2) / 10);
    if (chol.info() != Eigen::Success) std::printf("  centroid coarse factorisation failed (h %g)\n", h);
  }
  VecX solve(const VecX& r) const { return z * chol.solve(VecX(z.transpose() * r)); }
  // ZᵀAZ plus an hourglass penalty on every grid cell with four points: the
  // field's cross term (f00 − f10 − f01 + f11) in each component, which no
  // block's centroid value and gradient see, weighted by alpha times the mean
  // diagonal of the grid system.
  SpMat stabilised(double alpha) const {
    std::map<std::pair<int, int>, int> id;
    for (int k = 0; k < points; ++k) id[index[k]] = k;
    const double d = alpha * ac.diagonal().mean();
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 0; k < points; ++k) {
      const auto [i, j] = index[k];
      int c[4] = {k, -1, -1, -1};
      const std::pair<int, int> other[3] = {{i + 1, j}, {i, j + 1}, {i + 1, j + 1}};
      bool all = true;
      for (int m = 0; m < 3; ++m) {
        auto it = id.find(other[m]);
        if (it == id.end()) {
          all = false;
          break;
        }
        c[m + 1] = it->second;
      }
      if (!all) continue;
      const double sign[4] = {1, -1, -1, 1};
      for (int comp = 0; comp < 2; ++comp)
        for (int m = 0; m < 4; ++m)
          for (int n2 = 0; n2 < 4; ++n2) t.emplace_back(2 * c[m] + comp, 2 * c[n2] + comp, d * sign[m] * sign[n2]);
    }
    SpMat s(ac.rows(), ac.cols());
    s.setFromTriplets(t.begin(), t.end());
    return SpMat(ac + s);
  }
};

// A geometric V-cycle on the grid system ZᵀAZ: grids of side h, 2h, 4h ...
// with bilinear prolongation (fine points between coarse ones take their
// average), Galerkin operators, damped 2×2 point-Jacobi (sweeps each way) or
// symmetric Gauss-Seidel smoothing, sparse Cholesky under 600 unknowns.
struct GridMultigrid {
  struct Level {
    SpMat a, p;
    std::vector<Eigen::Matrix2d> dinv;
    double omega = 1;
  };
  std::vector<Level> levels;
  Eigen::SimplicialLDLT<SpMat> coarsest;
  int sweeps = 1;
  bool gauss_seidel = false;
  VecX jacobi(const Level& l, const VecX& r) const {
    VecX z(r.size());
    for (std::size_t k = 0; k < l.dinv.size(); ++k) z.segment<2>(2 * k) = l.dinv[k] * r.segment<2>(2 * k);
    return z;
  }
  // prolongator_smoothing: damped Jacobi steps applied to each bilinear P.
  GridMultigrid(const SpMat& a0, std::vector<std::pair<int, int>> index, int sweeps_, bool gs,
                int prolongator_smoothing)
      : sweeps(sweeps_), gauss_seidel(gs) {
    levels.push_back({a0, {}, {}, 1});
    while (levels.back().a.rows() > 600) {
      Level& f = levels.back();
      f.dinv.resize(f.a.rows() / 2);
      for (std::size_t k = 0; k < f.dinv.size(); ++k)
        f.dinv[k] = Eigen::Matrix2d(f.a.block(2 * k, 2 * k, 2, 2)).inverse();
      f.omega = (4.0 / 3.0) / largest_eigenvalue(
                                  f.a, [&](const VecX& y) { return jacobi(f, y); }, 20);
      std::map<std::pair<int, int>, int> id;
      std::vector<Eigen::Triplet<double>> t;
      auto floor2 = [](int i) { return i >= 0 ? i / 2 : -((1 - i) / 2); };
      for (std::size_t k = 0; k < index.size(); ++k) {
        const auto [i, j] = index[k];
        std::vector<std::pair<int, double>> xs, ys;
        if (i % 2 == 0)
          xs = {{floor2(i), 1.0}};
        else
          xs = {{floor2(i), 0.5}, {floor2(i) + 1, 0.5}};
        if (j % 2 == 0)
          ys = {{floor2(j), 1.0}};
        else
          ys = {{floor2(j), 0.5}, {floor2(j) + 1, 0.5}};
        for (auto [ci, wx] : xs)
          for (auto [cj, wy] : ys) {
            const int c = id.emplace(std::make_pair(ci, cj), static_cast<int>(id.size())).first->second;
            t.emplace_back(2 * k, 2 * c, wx * wy);
            t.emplace_back(2 * k + 1, 2 * c + 1, wx * wy);
          }
      }
      f.p.resize(f.a.rows(), 2 * static_cast<int>(id.size()));
      f.p.setFromTriplets(t.begin(), t.end());
      for (int m = 0; m < prolongator_smoothing; ++m) {
        f.p = smoothed(f.a, f.dinv, f.omega, f.p);
        f.p.prune(1e-14, 1);
      }
      index.assign(id.size(), {});
      for (const auto& [ij, k] : id) index[k] = ij;
      Level c;
      c.a = SpMat(f.p.transpose() * f.a * f.p);
      levels.push_back(c);
    }
    const SpMat& ac = levels.back().a;
    coarsest.setShift(1e-12 * ac.diagonal().cwiseAbs().maxCoeff());
    coarsest.compute(ac);
  }
  VecX smooth(const Level& f, const VecX& r, VecX x, bool forward) const {
    for (int s = 0; s < sweeps; ++s) {
      const VecX res = r - f.a * x;
      if (gauss_seidel) {
        if (forward)
          x += f.a.triangularView<Eigen::Lower>().solve(res);
        else
          x += f.a.triangularView<Eigen::Upper>().solve(res);
      } else {
        x += f.omega * jacobi(f, res);
      }
    }
    return x;
  }
  VecX vcycle(std::size_t l, const VecX& r) const {
    if (l + 1 == levels.size()) return coarsest.solve(r);
    const Level& f = levels[l];
    VecX x = smooth(f, r, VecX::Zero(r.size()), true);
    x += f.p * vcycle(l + 1, VecX(f.p.transpose() * VecX(r - f.a * x)));
    return smooth(f, r, x, false);
  }
};

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
    grid[{static_cast<int>(std::floor(node[k].x() / cell)), static_cast<int>(std::floor(node[k].y() / cell))}]
        .push_back(k);
  std::vector<Eigen::Triplet<double>> trip;
  for (int b = 0; b < n; ++b) {
    const auto v = w.block_initial_vertices(b);
    const Vec2 c = w.block_centroid(b);
    std::vector<int> on;
    for (std::size_t e = 0; e < v.size(); ++e) {
      const Vec2 p = v[e], q = v[(e + 1) % v.size()];
      const int x0 = static_cast<int>(std::floor(std::min(p.x(), q.x()) / cell)) - 1,
                x1 = static_cast<int>(std::floor(std::max(p.x(), q.x()) / cell)) + 1;
      const int y0 = static_cast<int>(std::floor(std::min(p.y(), q.y()) / cell)) - 1,
                y1 = static_cast<int>(std::floor(std::max(p.y(), q.y()) / cell)) + 1;
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
      for (const Vec2& p : v) {
        x0 = std::min(x0, p.x());
        x1 = std::max(x1, p.x());
        y0 = std::min(y0, p.y());
        y1 = std::max(y1, p.y());
      }
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
  std::printf(
      "  Galerkin auxiliary operator: nnz %ld; product %.1f ms, ordering %.1f ms, factorisation %.1f ms, one solve "
      "%.2f ms (1 thread)\n",
      static_cast<long>(ac.nonZeros()), ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t3, t4) / 10);
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
    SpMat a, p;                         // operator; prolongator from the next level (empty on the coarsest)
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
      f.omega = 1.0 / largest_eigenvalue(
                          f.a, [&](const VecX& y) { return jacobi(f, y); }, 20);
      // Cells of side h over this level's points.
      std::map<std::pair<int, int>, int> cell;
      std::vector<int> of(pos.size());
      for (std::size_t k = 0; k < pos.size(); ++k)
        of[k] = cell.emplace(std::make_pair(static_cast<int>(std::floor(pos[k].x() / h)),
                                            static_cast<int>(std::floor(pos[k].y() / h))),
                             static_cast<int>(cell.size()))
                    .first->second;
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
      if (smooth) p = smoothed(f.a, f.dinv, (4.0 / 3.0) * f.omega, p);  // (I − (4/3)ω D⁻¹A)·P_tent
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

// Additive Schwarz on vertex patches: for every auxiliary node, the blocks
// whose outline holds it, their rows of A solved exactly together (a patch
// holds the continuous fields local to it, which block-Jacobi cannot see).
// Star patches instead: each block with every block it is coupled to.
struct Patches {
  std::vector<std::vector<int>> blocks;
  std::vector<Eigen::LDLT<Eigen::MatrixXd>> solve;
  static std::vector<std::vector<int>> at_vertices(const Aux& aux) {
    std::vector<std::vector<int>> all;
    for (int k = 0; k < aux.nodes; ++k) {
      std::vector<int> p;
      for (SpMat::InnerIterator it(aux.pi, 2 * k); it; ++it) p.push_back(static_cast<int>(it.row()) / 6);
      std::sort(p.begin(), p.end());
      p.erase(std::unique(p.begin(), p.end()), p.end());
      if (p.size() >= 2) all.push_back(p);
    }
    return all;
  }
  static std::vector<std::vector<int>> stars(const BlockSparseMatrix& m) {
    std::vector<std::vector<int>> all(m.rows());
    for (int i = 0; i < m.rows(); ++i)
      for (int k = m.row_begin(i); k < m.row_end(i); ++k) all[i].push_back(m.col(k));
    return all;
  }
  Patches(const BlockSparseMatrix& m, const std::vector<std::vector<int>>& lists) {
    for (const auto& p : lists) {
      const int q = static_cast<int>(p.size());
      Eigen::MatrixXd d = Eigen::MatrixXd::Zero(6 * q, 6 * q);
      for (int i = 0; i < q; ++i)
        for (int j = 0; j < q; ++j) {
          const int at = m.find(p[i], p[j]);
          if (at >= 0) d.block<6, 6>(6 * i, 6 * j) = m.value(at);
        }
      blocks.push_back(p);
      solve.emplace_back(d);
    }
  }
  VecX apply(const VecX& r) const {
    VecX z = VecX::Zero(r.size());
    for (std::size_t k = 0; k < blocks.size(); ++k) {
      const auto& p = blocks[k];
      VecX rp(6 * p.size());
      for (std::size_t i = 0; i < p.size(); ++i) rp.segment<6>(6 * i) = r.segment<6>(6 * p[i]);
      const VecX zp = solve[k].solve(rp);
      for (std::size_t i = 0; i < p.size(); ++i) z.segment<6>(6 * p[i]) += zp.segment<6>(6 * i);
    }
    return z;
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
    w.controls().solver.pcg.preconditioner = Preconditioning::BlockJacobi;
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
    const double lambda = largest_eigenvalue(
        a,
        [&](const VecX& y) {
          VecX z;
          jacobi(y, z);
          return z;
        },
        30);
    const double omega = 1.0 / lambda;
    auto coarse_elastic = [&](const VecX& r) -> VecX {
      return aux.pi * aux.chol_elastic.solve(VecX(aux.pi.transpose() * r));
    };
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
    const auto bj = pcg(a, b, jacobi, tols), ad = pcg(a, b, additive, tols), mu = pcg(a, b, multiplicative, tols),
               ae = pcg(a, b, additive_elastic, tols);
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
      const double lambda_aux = largest_eigenvalue(aux.ac, two.jacobi, 30);
      auto aux_vcycle = [&](const VecX& r, VecX& z) {
        jacobi(r, z);
        z += aux.pi * two.vcycle(aux.ac, VecX(aux.pi.transpose() * r), 1.0 / lambda_aux);
      };
      const auto vc = pcg(a, b, aux_vcycle, tols);
      std::snprintf(label, sizeof label, "  auxiliary by a V-cycle (smooth, cells, smooth)");
      row(label, vc);
    }
    for (double h : {1.0, 2.0, 4.0}) {
      const BilinearCoarse bc(aux, aux.ac, h);
      const NodeJacobi nodes(aux);
      char label[96];
      auto direct = [&](const VecX& r, VecX& z) {
        jacobi(r, z);
        z += aux.pi * bc.solve(VecX(aux.pi.transpose() * r));
      };
      std::snprintf(label, sizeof label, "+ bilinear %g m coarse only (%d points)", h, bc.points);
      row(label, pcg(a, b, direct, tols));
      auto with_nodes = [&](const VecX& r, VecX& z) {
        jacobi(r, z);
        const VecX ra = aux.pi.transpose() * r;
        z += aux.pi * VecX(nodes(ra) + bc.solve(ra));
      };
      std::snprintf(label, sizeof label, "+ auxiliary, node Jacobi + bilinear %g m", h);
      row(label, pcg(a, b, with_nodes, tols));
      const VecX b_aux = aux.pi.transpose() * b;
      const auto alone = pcg(
          aux.ac, b_aux, [&](const VecX& r, VecX& z) { z = nodes(r) + bc.solve(r); }, tols);
      row("  (auxiliary system alone, node Jacobi + bilinear)", alone);
    }
    // The continuous coarse space mapped to the blocks' centroids: solved
    // exactly on grids of 0.5 to 4 m; on the 0.5 m grid also by geometric
    // V-cycles (and, for comparison, the grid system alone under them).
    for (double h : {0.5, 1.0, 2.0, 4.0}) {
      const CentroidCoarse cc(w, a, h);
      char label[96];
      auto additive_c = [&](const VecX& r, VecX& z) {
        jacobi(r, z);
        z += cc.solve(r);
      };
      std::snprintf(label, sizeof label, "+ bilinear %g m at centroids (%d points)", h, cc.points);
      row(label, pcg(a, b, additive_c, tols));
      auto symmetric_c = [&](const VecX& r, VecX& z) {
        VecX s;
        jacobi(r, s);
        VecX x1 = omega * s;
        VecX x2 = x1 + cc.solve(VecX(r - a * x1));
        jacobi(VecX(r - a * x2), s);
        z = x2 + omega * s;
      };
      row("  the same, symmetric", pcg(a, b, symmetric_c, tols));
      if (h > 0.5) continue;
      const VecX b_grid = cc.z.transpose() * b;
      // One V-cycle on grid operator g as the coarse solve; variant 0: Jacobi,
      // 1: two Jacobi sweeps, 2: symmetric Gauss-Seidel.
      auto vcycle_rows = [&](const SpMat& g, const char* what, bool alone, int p_smoothing) {
        for (int variant = 0; variant < 3; ++variant) {
          const GridMultigrid mg(g, cc.index, variant == 1 ? 2 : 1, variant == 2, p_smoothing);
          auto vc = [&](const VecX& r, VecX& z) {
            jacobi(r, z);
            z += cc.z * mg.vcycle(0, VecX(cc.z.transpose() * r));
          };
          std::snprintf(label, sizeof label, "  %s, %zu-level V-cycle, %s", what, mg.levels.size(),
                        variant == 0   ? "Jacobi"
                        : variant == 1 ? "Jacobi x2"
                                       : "sym. GS");
          row(label, pcg(a, b, vc, tols));
          if (alone)
            row("    (the grid system alone under it)",
                pcg(
                    g, b_grid, [&](const VecX& r, VecX& z) { z = mg.vcycle(0, r); }, tols));
        }
      };
      vcycle_rows(cc.ac, "grid", true, 0);
      vcycle_rows(cc.ac, "P smoothed twice", false, 2);
      for (double alpha : {0.01, 0.1}) {
        const SpMat stable = cc.stabilised(alpha);
        const Eigen::SimplicialLDLT<SpMat> exact(stable);
        auto ex = [&](const VecX& r, VecX& z) {
          jacobi(r, z);
          z += cc.z * VecX(exact.solve(VecX(cc.z.transpose() * r)));
        };
        std::snprintf(label, sizeof label, "  hourglass penalty %g, exact", alpha);
        row(label, pcg(a, b, ex, tols));
        char what[48];
        std::snprintf(what, sizeof what, "hourglass penalty %g", alpha);
        vcycle_rows(stable, what, false, 0);
      }
    }
    for (bool star : {false, true}) {
      // Patch Schwarz, alone and with continuous coarse spaces solved exactly.
      const Patches patches(bsm, star ? Patches::stars(bsm) : Patches::at_vertices(aux));
      std::size_t largest = 0;
      for (const auto& p : patches.blocks) largest = std::max(largest, p.size());
      std::printf("  %zu %s patches, up to %zu blocks\n", patches.blocks.size(), star ? "star" : "vertex", largest);
      row(star ? "star patches (additive Schwarz)" : "vertex patches (additive Schwarz)",
          pcg(
              a, b, [&](const VecX& r, VecX& z) { z = patches.apply(r); }, tols));
      for (double h : {2.0, 4.0, 8.0}) {
        const CentroidCoarse cc(w, a, h);
        char label[96];
        std::snprintf(label, sizeof label, "  + bilinear %g m at centroids", h);
        row(label, pcg(
                       a, b, [&](const VecX& r, VecX& z) { z = patches.apply(r) + cc.solve(r); }, tols));
      }
    }
    {
      // Incomplete Cholesky of A (Eigen's: Lin & Moré, as many entries a
      // column as A has, with a diagonal shift where needed): how far an
      // incomplete factorisation gets, apart from the cost of its sequential
      // triangular solves. Natural ordering keeps the blocks' order.
      Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::NaturalOrdering<int>> ic;
      ic.compute(a);
      if (ic.info() == Eigen::Success)
        row("incomplete Cholesky", pcg(
                                       a, b, [&](const VecX& r, VecX& z) { z = ic.solve(r); }, tols));
      else
        std::printf("  incomplete Cholesky failed\n");
    }
    // The same auxiliary factorisation, 10 steps later (a stale operator is
    // still a symmetric positive definite preconditioner).
    for (int s = 0; s < 10; ++s) w.step();
    const BlockSparseMatrix& later = w.last_matrix();
    const SpMat a2 = later.to_sparse();
    const VecX b2 = w.last_rhs();
    {
      // How hard the auxiliary system is by itself: 2×2 block-Jacobi PCG on it.
      const NodeJacobi nodes_only(aux);
      const VecX b_aux = aux.pi.transpose() * b;
      const auto alone = pcg(
          aux.ac, b_aux, [&](const VecX& r, VecX& z) { z = nodes_only(r); }, tols);
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
      std::snprintf(label, sizeof label, "+ auxiliary by a %zu-level V-cycle%s", ml.levels.size(),
                    smooth ? " (smoothed P)" : "");
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
