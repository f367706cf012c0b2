// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The step's system where blocks are meshed (block/mesh.hpp), solved for the
// mesh nodes. The system is assembled as always, one row of six per block,
// the elements' rows included (ContactOperator S, right-hand side F); the
// elements' unknowns are tied to their nodes by D_e = A_e·u_e. With P the
// map from the free unknowns y (six per first-order block, two per node) to
// every block's D (identity on first-order blocks, A_e on elements) the
// tied system is
//
//   (Pᵀ S P)·y = Pᵀ F,   D = P·y.
//
// For an element, A_eᵀ (elasticity + inertia) A_e is the CST's stiffness
// and consistent mass, and A_eᵀ times a contact's 6-vector its nodal
// interpolation: the same assembly serves both kinds of block. The product
// with Pᵀ S P is formed matrix-free from S's own product (expand, multiply,
// restrict), and CG runs on y with block-Jacobi on the first-order blocks'
// 6×6 and the nodes' 2×2 diagonal blocks. Every pass is a parallel loop over
// blocks or nodes with fixed sums per row, and the dot products are
// deterministic: the result is the same for any thread count.
//
// No stored matrix of Pᵀ S P is offered, so the multigrid and CHOLMOD
// backends do not take meshed models (docs/meshed_blocks.md); the meshed
// blocks' own matrices are gathered for their factors only.
#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <array>
#include <memory>
#include <vector>

#include "block/blocks.hpp"
#include "solver/linear_solver.hpp"

namespace dda {

// An element's map A_e (D_e = A_e·u_e) by its shape functions' coefficients
// about its centroid, N_k = α_k + β_k·x + γ_k·y: a corner's (u_k, v_k) gives
// D_e = (α_k·u_k, α_k·v_k, (β_k·v_k − γ_k·u_k)/2, β_k·u_k, γ_k·v_k,
// γ_k·u_k + β_k·v_k).
struct ElementShape {
  double alpha[3], beta[3], gamma[3];
  Mat6 map() const {
    Mat6 a;
    for (int k = 0; k < 3; ++k) {
      a.col(2 * k) << alpha[k], 0, -gamma[k] / 2, beta[k], 0, gamma[k];
      a.col(2 * k + 1) << 0, alpha[k], beta[k] / 2, 0, gamma[k], beta[k];
    }
    return a;
  }
  // A_eᵀ·f: the nodal forces of a generalised force f on the element.
  Vec6 transpose_times(const Vec6& f) const {
    Vec6 u;
    for (int k = 0; k < 3; ++k) {
      u[2 * k] = alpha[k] * f[0] - gamma[k] / 2 * f[2] + beta[k] * f[3] + gamma[k] * f[5];
      u[2 * k + 1] = alpha[k] * f[1] + beta[k] / 2 * f[2] + gamma[k] * f[4] + beta[k] * f[5];
    }
    return u;
  }
};

class MeshedSolver final : public LinearSolver {
 public:
  // Once per step, before its solves: the elements' maps A_e and the nodes'
  // elements, from the blocks as they are at the step's start.
  void set_blocks(const Blocks& blocks);

  void begin_step(const SolverSettings& settings, const StepSolveInfo& info) override;
  void set_operator(const LinearOperator& a) override { a_ = &a; }
  // b and x are per block (six each), as the step assembles them; x holds
  // the initial guess, which is read at the nodes through the first element
  // that has each node.
  SolveReport solve(const VecX& b, VecX& x) override;
  const char* name() const override { return "pcg-meshed"; }
  // The meshed blocks' factors (as the entries they were made from); load
  // after set_blocks.
  void save_state(ArchiveWriter& ar) const override;
  void load_state(ArchiveReader& ar) override;

  int free_unknowns() const { return unknowns_; }

  // A solve that took more CG iterations than this with the kept factors has
  // the next solve factorise the current matrices: in a wave the nodal
  // matrices drift little from step to step (the elements hardly turn) and a
  // kept factor preconditions almost as well as a fresh one.
  static constexpr int kRefactorIterations = 6;
  // Meshed blocks of at most this many unknowns (twice their nodes) are
  // factorised dense: for small meshes a sparse factor's bookkeeping costs
  // more than the arithmetic it saves.
  static constexpr int kDenseUnknowns = 96;

 private:
  void expand(const VecX& y, VecX& d) const;    // d = P·y
  void restrict(const VecX& f, VecX& y) const;  // y = Pᵀ·f (uses scratch element_force_)
  void apply(const VecX& y, VecX& out);         // out = Pᵀ S P y
  void set_up_preconditioner();
  void precondition(const VecX& r, VecX& z) const;
  void set_up_mesh_groups(const Blocks& blocks);
  void factorise_meshes();
  struct MeshGroup;
  template <class ElementMatrix>
  void gather_entries(MeshGroup& group, ElementMatrix element_matrix) const;
  static void factorise(MeshGroup& group);
  void precondition_meshes(const VecX& r, VecX& z) const;

  // One meshed block: its elements and nodes, and the Cholesky factor of its
  // nodal matrix (the elements' A_eᵀ S_ee A_e gathered on its nodes).
  struct MeshGroup {
    std::vector<int> elements;              // block ids, ascending
    std::vector<int> nodes;                 // global node ids, ascending; the local index is the position
    std::vector<std::array<int, 3>> local;  // per element, its nodes' local indices
    // The lower triangles of its elements' matrices, in element order: what
    // its factor was last made from (a checkpoint saves them).
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::SparseMatrix<double> matrix;
    std::unique_ptr<Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>> factor;
    bool dense = false;  // a small mesh: a dense factor (no sparse bookkeeping per solve)
    Eigen::MatrixXd dense_matrix;
    Eigen::LLT<Eigen::MatrixXd> dense_factor;
    bool analysed = false, factored = false;
    std::vector<Eigen::Matrix2d> diagonal_inverse;  // per node, where the factorisation failed
    mutable Eigen::VectorXd rhs, solution;
  };

  const LinearOperator* a_ = nullptr;
  int blocks_ = 0, nodes_ = 0, unknowns_ = 0, node_base_ = 0, size_ = 0;
  std::vector<int> offset_;                       // per block: its first free unknown (first-order), or -1
  std::vector<std::array<int, 3>> element_node_;  // per block: its nodes (elements)
  std::vector<ElementShape> shape_;               // per block: A_e (elements)
  std::vector<Mat6> corners_;                     // per block: A_e⁻¹, T at the three corners (elements)
  std::vector<int> node_start_;                   // per node: its (element, corner) entries, by element
  std::vector<std::pair<int, int>> node_corner_;
  std::vector<Mat6> block_inverse_;            // preconditioner, per first-order block
  std::vector<Eigen::Matrix2d> node_inverse_;  // preconditioner, per node (NodeJacobi)
  MeshPreconditioning mesh_preconditioning_ = MeshPreconditioning::BlockFactor;
  std::vector<MeshGroup> groups_;  // per meshed block (BlockFactor)
  std::vector<int> group_mesh_;    // the blocks' mesh ids the groups were made for
  bool refactor_ = true;
  int factorisations_ = 0;  // so far; each factorises every meshed block (SolveReport::factorisations)
  mutable std::vector<Vec6> element_force_;
  VecX d_, s_d_, br_, xr_, r_, z_, p_, q_;
};

// Makes `solver` a MeshedSolver when the blocks are meshed (keeping one it
// already is) and gives it the blocks; leaves it alone otherwise.
void use_meshed_solver(std::unique_ptr<LinearSolver>& solver, const Blocks& blocks);

}  // namespace dda
