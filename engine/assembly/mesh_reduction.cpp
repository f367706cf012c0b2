// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "assembly/mesh_reduction.hpp"

#include <Eigen/LU>  // the nodes' 2×2 inverses
#include <algorithm>
#include <cmath>

#include "block/displacement.hpp"
#include "block/mesh.hpp"
#include "core/archive.hpp"
#include "core/error.hpp"
#include "core/load_check.hpp"
#include "core/parallel.hpp"

namespace dda {

namespace {

// A_e = [T(p1); T(p2); T(p3)]⁻¹ written out: the linear field through the
// corners' displacements (u_k, v_k) is u = a0 + a1·x + a2·y, v = b0 + b1·x +
// b2·y about the centroid c, with the CST's shape functions
// N_k = α_k + β_k·x + γ_k·y (over 2A: β_k = (y_{k+1} − y_{k+2})/2A, γ_k =
// (x_{k+2} − x_{k+1})/2A, α_k = (x_{k+1}·y_{k+2} − x_{k+2}·y_{k+1})/2A,
// corners about c); DDA's unknowns are D = (a0, b0, (b1 − a2)/2, a1, b2,
// a2 + b1). Nine numbers instead of 36: the products read a quarter of the
// memory.
ElementShape element_shape(const Vec2* corner, const Vec2& centroid) {
  Vec2 p[3];
  for (int k = 0; k < 3; ++k) p[k] = corner[k] - centroid;
  const double two_area = (p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[2] - p[0]).x() * (p[1] - p[0]).y();
  ElementShape n;
  for (int k = 0; k < 3; ++k) {
    const Vec2 &q = p[(k + 1) % 3], &r = p[(k + 2) % 3];
    n.alpha[k] = (q.x() * r.y() - r.x() * q.y()) / two_area;
    n.beta[k] = (q.y() - r.y()) / two_area;
    n.gamma[k] = (r.x() - q.x()) / two_area;
  }
  return n;
}

}  // namespace

void MeshedSolver::set_blocks(const Blocks& blocks) {
  blocks_ = static_cast<int>(blocks.count());
  nodes_ = mesh_node_count(blocks);
  offset_.assign(blocks_, -1);
  element_node_.resize(blocks_);
  shape_.resize(blocks_);
  corners_.resize(blocks_);
  int next = 0;
  for (int b = 0; b < blocks_; ++b)
    if (!blocks.is_element(b)) offset_[b] = next, next += 6;
  const int node_base = next;
  unknowns_ = node_base + 2 * nodes_;
  // Vectors are padded with zeros to whole groups of six: deterministic_dot
  // sums by six.
  size_ = (unknowns_ + 5) / 6 * 6;
  // A_e = [T(p1); T(p2); T(p3)]⁻¹ about the element's centroid: the D_e whose
  // field T·D_e takes the nodes' displacements at the corners.
  parallel_for_each(
      blocks_,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        if (offset_[b] >= 0) return;
        const int start = blocks.vertex_start[b];
        Mat6 corners;
        for (int k = 0; k < 3; ++k) {
          corners.middleRows<2>(2 * k) = displacement_matrix(blocks.vertices[start + k], blocks.centroid[b]);
          element_node_[b][k] = blocks.node[start + k];
        }
        corners_[b] = corners;
        shape_[b] = element_shape(&blocks.vertices[start], blocks.centroid[b]);
      },
      64);
  // Each node's (element, corner) entries, in element order.
  node_start_.assign(nodes_ + 1, 0);
  for (int b = 0; b < blocks_; ++b)
    if (offset_[b] < 0)
      for (const int n : element_node_[b]) ++node_start_[n + 1];
  for (int n = 0; n < nodes_; ++n) node_start_[n + 1] += node_start_[n];
  node_corner_.resize(node_start_[nodes_]);
  std::vector<int> fill(node_start_.begin(), node_start_.end() - 1);
  for (int b = 0; b < blocks_; ++b)
    if (offset_[b] < 0)
      for (int k = 0; k < 3; ++k) node_corner_[fill[element_node_[b][k]]++] = {b, k};
  // Node n's unknowns follow the first-order blocks'.
  for (int n = 0; n < nodes_; ++n)
    if (node_start_[n] == node_start_[n + 1])
      throw Error(msg("mesh node ", n, " belongs to no element (a meshed block lost an element)"));
  node_base_ = node_base;
  element_force_.resize(blocks_);
  if (group_mesh_ != blocks.mesh) set_up_mesh_groups(blocks);
}

void MeshedSolver::begin_step(const SolverSettings& settings, const StepSolveInfo& /*info*/) {
  if (settings.mesh_preconditioner != mesh_preconditioning_) refactor_ = true;
  mesh_preconditioning_ = settings.mesh_preconditioner;
}

// The meshed blocks' elements and nodes, and their matrices' pattern: once
// per mesh layout (the elements of a meshed block keep their nodes).
void MeshedSolver::set_up_mesh_groups(const Blocks& blocks) {
  group_mesh_ = blocks.mesh;
  int meshes = 0;
  for (const int m : blocks.mesh) meshes = std::max(meshes, m + 1);
  groups_.clear();
  groups_.resize(meshes);
  for (int b = 0; b < blocks_; ++b)
    if (offset_[b] < 0) groups_[blocks.mesh[b]].elements.push_back(b);
  parallel_for_each(
      groups_.size(),
      [&](std::size_t g) {
        MeshGroup& group = groups_[g];
        for (const int e : group.elements)
          for (const int n : element_node_[e]) group.nodes.push_back(n);
        std::sort(group.nodes.begin(), group.nodes.end());
        group.nodes.erase(std::unique(group.nodes.begin(), group.nodes.end()), group.nodes.end());
        group.local.resize(group.elements.size());
        for (std::size_t i = 0; i < group.elements.size(); ++i)
          for (int k = 0; k < 3; ++k)
            group.local[i][k] = static_cast<int>(
                std::lower_bound(group.nodes.begin(), group.nodes.end(), element_node_[group.elements[i]][k]) -
                group.nodes.begin());
        const auto size = static_cast<Eigen::Index>(2 * group.nodes.size());
        group.matrix.resize(size, size);
        group.rhs.resize(size);
        group.solution.resize(size);
        group.dense = size <= kDenseUnknowns;
        if (group.dense)
          group.dense_matrix.resize(size, size);
        else
          group.factor = std::make_unique<std::remove_reference_t<decltype(*group.factor)>>();
        group.analysed = group.factored = false;
      },
      1);
  refactor_ = true;
}

// Each meshed block's nodal matrix Σ A_eᵀ S_ee A_e (its lower triangle, the
// elements' entries summed in element order) and its Cholesky factor. The
// fill-reducing ordering is computed once per mesh layout.
void MeshedSolver::factorise_meshes() {
  parallel_for_each(
      groups_.size(),
      [&](std::size_t g) {
        MeshGroup& group = groups_[g];
        if (group.elements.empty()) return;
        gather_entries(group, [&](int e) -> Mat6 {
          const Mat6 map = shape_[e].map();
          return map.transpose() * a_->diagonal_block(e) * map;
        });
        factorise(group);
      },
      1);
  ++factorisations_;
}

// The lower triangle of the group's nodal matrix as its elements' entries,
// in element order (duplicates are summed in that order).
template <class ElementMatrix>
void MeshedSolver::gather_entries(MeshGroup& group, ElementMatrix element_matrix) const {
  group.entries.clear();
  for (std::size_t i = 0; i < group.elements.size(); ++i) {
    const Mat6 k = element_matrix(group.elements[i]);
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) {
        const int row = 2 * group.local[i][r / 2] + r % 2, col = 2 * group.local[i][c / 2] + c % 2;
        if (row >= col) group.entries.emplace_back(row, col, k(r, c));
      }
  }
}

void MeshedSolver::factorise(MeshGroup& group) {
  if (group.dense) {
    group.dense_matrix.setZero();
    for (const Eigen::Triplet<double>& t : group.entries) group.dense_matrix(t.row(), t.col()) += t.value();
    group.dense_factor.compute(group.dense_matrix);  // reads the lower triangle
    group.factored = group.dense_factor.info() == Eigen::Success;
  } else {
    group.matrix.setFromTriplets(group.entries.begin(), group.entries.end());
    if (!group.analysed) group.factor->analyzePattern(group.matrix), group.analysed = true;
    group.factor->factorize(group.matrix);
    group.factored = group.factor->info() == Eigen::Success;
  }
  if (group.factored) return;
  // Not positive definite (the CG will say so): the nodes' own 2×2 diagonal
  // blocks, as NodeJacobi.
  group.diagonal_inverse.assign(group.nodes.size(), Eigen::Matrix2d::Zero());
  for (const Eigen::Triplet<double>& t : group.entries)
    if (t.row() / 2 == t.col() / 2) {
      Eigen::Matrix2d& d = group.diagonal_inverse[t.row() / 2];
      d(t.row() % 2, t.col() % 2) += t.value();
      if (t.row() != t.col()) d(t.col() % 2, t.row() % 2) += t.value();
    }
  for (Eigen::Matrix2d& d : group.diagonal_inverse) d = d.inverse().eval();
}

// A restart continues bit for bit only with the factors it had: each meshed
// block's factor is saved as the entries it was made from and made again
// from them (the blocks, restored first, give the pattern).
void MeshedSolver::save_state(ArchiveWriter& ar) const {
  std::vector<std::vector<double>> factorised(groups_.size());
  for (std::size_t g = 0; g < groups_.size(); ++g)
    for (const Eigen::Triplet<double>& t : groups_[g].entries) factorised[g].push_back(t.value());
  ar(mesh_preconditioning_, refactor_, factorisations_, factorised);
}

void MeshedSolver::load_state(ArchiveReader& ar) {
  std::vector<std::vector<double>> factorised;
  ar(mesh_preconditioning_, refactor_, factorisations_, factorised);
  const LoadCheck check(ar.what());
  check.require(factorisations_ >= 0, "its meshed solver's factorisations number ", factorisations_);
  check.size(factorised.size(), groups_.size(), "meshed blocks", "the meshed solver's factors");
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    MeshGroup& group = groups_[g];
    if (factorised[g].empty()) continue;
    gather_entries(group, [](int) -> Mat6 { return Mat6::Zero(); });
    check.size(factorised[g].size(), group.entries.size(), "entries", "meshed block ", g, "'s factor");
    for (std::size_t i = 0; i < group.entries.size(); ++i)
      group.entries[i] = Eigen::Triplet<double>(group.entries[i].row(), group.entries[i].col(), factorised[g][i]);
    factorise(group);
  }
}

void MeshedSolver::expand(const VecX& y, VecX& d) const {
  d.resize(6 * blocks_);
  parallel_for_each(
      blocks_,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        if (offset_[b] >= 0) {
          d.segment<6>(6 * b) = y.segment<6>(offset_[b]);
          return;
        }
        const ElementShape& n = shape_[b];
        Vec6 e = Vec6::Zero();
        for (int k = 0; k < 3; ++k) {
          const double u = y[node_base_ + 2 * element_node_[b][k]], v = y[node_base_ + 2 * element_node_[b][k] + 1];
          e[0] += n.alpha[k] * u, e[1] += n.alpha[k] * v;
          e[2] += (n.beta[k] * v - n.gamma[k] * u) / 2;
          e[3] += n.beta[k] * u, e[4] += n.gamma[k] * v;
          e[5] += n.gamma[k] * u + n.beta[k] * v;
        }
        d.segment<6>(6 * b) = e;
      },
      256);
}

void MeshedSolver::restrict(const VecX& f, VecX& y) const {
  y.resize(size_);
  y.tail(size_ - unknowns_).setZero();
  parallel_for_each(
      blocks_,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        if (offset_[b] >= 0)
          y.segment<6>(offset_[b]) = f.segment<6>(6 * b);
        else
          element_force_[b] = shape_[b].transpose_times(f.segment<6>(6 * b));
      },
      256);
  parallel_for_each(
      nodes_,
      [&](std::size_t n) {
        Vec2 sum = Vec2::Zero();
        for (int i = node_start_[n]; i < node_start_[n + 1]; ++i) {
          const auto [e, k] = node_corner_[i];
          sum += element_force_[e].segment<2>(2 * k);
        }
        y.segment<2>(node_base_ + 2 * n) = sum;
      },
      512);
}

void MeshedSolver::apply(const VecX& y, VecX& out) {
  expand(y, d_);
  s_d_.resize(6 * blocks_);
  constexpr int kRows = 64;
  parallel_for_each((blocks_ + kRows - 1) / kRows,
                    [&](std::size_t c) {
                      const int begin = static_cast<int>(c) * kRows;
                      a_->multiply_rows(begin, std::min(blocks_, begin + kRows), d_, s_d_);
                    },
                    1);
  restrict(s_d_, out);
}

// Block-Jacobi on y: a first-order block's own 6×6 block of S; a meshed
// block's nodal matrix Σ A_eᵀ S_ee A_e, factorised (factorise_meshes), or
// with NodeJacobi a node's 2×2 block of it (elements of one mesh share no
// contact, so S couples a mesh's nodes to each other through diagonal
// blocks only).
void MeshedSolver::set_up_preconditioner() {
  block_inverse_.resize(blocks_);
  if (mesh_preconditioning_ == MeshPreconditioning::BlockFactor) {
    parallel_for_each(
        blocks_,
        [&](std::size_t b) {
          if (offset_[b] >= 0) invert_spd6(a_->diagonal_block(static_cast<int>(b)), block_inverse_[b]);
        },
        64);
    const bool any_unfactored = std::any_of(groups_.begin(), groups_.end(),
                                            [](const MeshGroup& g) { return !g.elements.empty() && !g.factored; });
    if (refactor_ || any_unfactored) factorise_meshes();
    refactor_ = false;
    return;
  }
  parallel_for_each(
      blocks_,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        if (offset_[b] >= 0) {
          invert_spd6(a_->diagonal_block(b), block_inverse_[b]);
        } else {
          // Kept in block_inverse_ for the node pass: A_eᵀ S_ee A_e.
          const Mat6 map = shape_[b].map();
          block_inverse_[b] = map.transpose() * a_->diagonal_block(b) * map;
        }
      },
      64);
  node_inverse_.resize(nodes_);
  parallel_for_each(
      nodes_,
      [&](std::size_t n) {
        Eigen::Matrix2d sum = Eigen::Matrix2d::Zero();
        for (int i = node_start_[n]; i < node_start_[n + 1]; ++i) {
          const auto [e, k] = node_corner_[i];
          sum += block_inverse_[e].block<2, 2>(2 * k, 2 * k);
        }
        node_inverse_[n] = sum.inverse();
      },
      512);
}

void MeshedSolver::precondition(const VecX& r, VecX& z) const {
  z.resize(size_);
  z.tail(size_ - unknowns_).setZero();
  parallel_for_each(
      blocks_,
      [&](std::size_t b) {
        if (offset_[b] >= 0) z.segment<6>(offset_[b]) = block_inverse_[b] * r.segment<6>(offset_[b]);
      },
      256);
  if (mesh_preconditioning_ == MeshPreconditioning::BlockFactor) return precondition_meshes(r, z);
  parallel_for_each(
      nodes_,
      [&](std::size_t n) { z.segment<2>(node_base_ + 2 * n) = node_inverse_[n] * r.segment<2>(node_base_ + 2 * n); },
      512);
}

void MeshedSolver::precondition_meshes(const VecX& r, VecX& z) const {
  parallel_for_each(
      groups_.size(),
      [&](std::size_t g) {
        const MeshGroup& group = groups_[g];
        const auto n = static_cast<Eigen::Index>(group.nodes.size());
        for (Eigen::Index i = 0; i < n; ++i)
          group.rhs.segment<2>(2 * i) = r.segment<2>(node_base_ + 2 * group.nodes[i]);
        if (group.factored && group.dense)
          group.dense_factor.solveInPlace(group.rhs), group.solution.swap(group.rhs);
        else if (group.factored)
          group.solution = group.factor->solve(group.rhs);
        else
          for (Eigen::Index i = 0; i < n; ++i)
            group.solution.segment<2>(2 * i) = group.diagonal_inverse[i] * group.rhs.segment<2>(2 * i);
        for (Eigen::Index i = 0; i < n; ++i)
          z.segment<2>(node_base_ + 2 * group.nodes[i]) = group.solution.segment<2>(2 * i);
      },
      1);
}

SolveReport MeshedSolver::solve(const VecX& b, VecX& x) {
  DDA_ASSERT(a_ && a_->rows() == blocks_, "MeshedSolver: set_blocks and set_operator before solving");
  SolveReport report;
  restrict(b, br_);
  // The initial guess at the free unknowns: first-order blocks as given,
  // each node from its first element's field.
  xr_.resize(size_);
  xr_.tail(size_ - unknowns_).setZero();
  parallel_for_each(
      blocks_,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        if (offset_[b] >= 0) xr_.segment<6>(offset_[b]) = x.segment<6>(6 * b);
      },
      256);
  parallel_for_each(
      nodes_,
      [&](std::size_t n) {
        const auto [e, k] = node_corner_[node_start_[n]];
        xr_.segment<2>(node_base_ + 2 * n) = corners_[e].middleRows<2>(2 * k) * x.segment<6>(6 * e);
      },
      512);
  const int factorisations_before = factorisations_;
  set_up_preconditioner();
  report.factorisations = factorisations_ - factorisations_before;
  const double b_norm = std::sqrt(deterministic_dot(br_, br_));
  if (!std::isfinite(b_norm)) {
    report.finite = false;
    return report;
  }
  apply(xr_, q_);
  r_ = br_ - q_;
  auto finish = [&](bool converged, int iterations, double relative) {
    report.converged = converged;
    report.iterations = iterations;
    report.relative_residual = relative;
    report.finite = std::isfinite(relative) && xr_.allFinite();
    // A kept factor that no longer preconditions well is made anew for the
    // next solve.
    if (iterations > kRefactorIterations) refactor_ = true;
    expand(xr_, x);
    return report;
  };
  if (b_norm == 0) {
    xr_.setZero();
    return finish(true, 0, 0);
  }
  double relative = std::sqrt(deterministic_dot(r_, r_)) / b_norm;
  if (relative <= tolerance) return finish(true, 0, relative);
  precondition(r_, z_);
  p_ = z_;
  double rz = deterministic_dot(r_, z_);
  for (int it = 1; it <= max_iterations; ++it) {
    apply(p_, q_);
    const double pq = deterministic_dot(p_, q_);
    if (!(pq > 0)) return finish(false, it, std::isfinite(pq) ? relative : NAN);
    const double alpha = rz / pq;
    xr_ += alpha * p_;
    r_ -= alpha * q_;
    relative = std::sqrt(deterministic_dot(r_, r_)) / b_norm;
    if (monitor) monitor(it, relative);
    if (!std::isfinite(relative)) return finish(false, it, relative);
    if (relative <= tolerance) return finish(true, it, relative);
    precondition(r_, z_);
    const double rz_next = deterministic_dot(r_, z_);
    p_ = z_ + (rz_next / rz) * p_;
    rz = rz_next;
  }
  return finish(false, max_iterations, relative);
}

void use_meshed_solver(std::unique_ptr<LinearSolver>& solver, const Blocks& blocks) {
  if (!blocks.has_meshes()) return;
  auto* meshed = dynamic_cast<MeshedSolver*>(solver.get());
  if (!meshed) {
    auto made = std::make_unique<MeshedSolver>();
    meshed = made.get();
    solver = std::move(made);
  }
  meshed->set_blocks(blocks);
}

}  // namespace dda
