#include "assembly/mesh_reduction.hpp"

#include <Eigen/LU>
#include <cmath>

#include "block/displacement.hpp"
#include "block/mesh.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"

namespace dda {

void MeshedSolver::set_blocks(const Blocks& blocks) {
  blocks_ = static_cast<int>(blocks.count());
  nodes_ = mesh_node_count(blocks);
  offset_.assign(blocks_, -1);
  element_node_.resize(blocks_);
  map_.resize(blocks_);
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
        map_[b] = corners.partialPivLu().inverse();
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
        Vec6 u;
        for (int k = 0; k < 3; ++k) u.segment<2>(2 * k) = y.segment<2>(node_base_ + 2 * element_node_[b][k]);
        d.segment<6>(6 * b) = map_[b] * u;
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
          element_force_[b] = map_[b].transpose() * f.segment<6>(6 * b);
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

// Block-Jacobi on y: a first-order block's own 6×6 block of S; a node's 2×2
// block of Σ A_eᵀ S_ee A_e over its elements (elements of one mesh share no
// contact, so S couples a node to itself through diagonal blocks only).
void MeshedSolver::set_up_preconditioner() {
  block_inverse_.resize(blocks_);
  parallel_for_each(
      blocks_,
      [&](std::size_t bi) {
        const int b = static_cast<int>(bi);
        if (offset_[b] >= 0) {
          invert_spd6(a_->diagonal_block(b), block_inverse_[b]);
        } else {
          // Kept in block_inverse_ for the node pass: A_eᵀ S_ee A_e.
          block_inverse_[b] = map_[b].transpose() * a_->diagonal_block(b) * map_[b];
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
  parallel_for_each(
      nodes_,
      [&](std::size_t n) { z.segment<2>(node_base_ + 2 * n) = node_inverse_[n] * r.segment<2>(node_base_ + 2 * n); },
      512);
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
  set_up_preconditioner();
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
