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
// No stored matrix is offered, so the multigrid and CHOLMOD backends do not
// take meshed models (docs/meshed_blocks.md).
#include <array>
#include <memory>
#include <vector>

#include "block/blocks.hpp"
#include "solver/linear_solver.hpp"

namespace dda {

class MeshedSolver final : public LinearSolver {
 public:
  // Once per step, before its solves: the elements' maps A_e and the nodes'
  // elements, from the blocks as they are at the step's start.
  void set_blocks(const Blocks& blocks);

  void set_operator(const LinearOperator& a) override { a_ = &a; }
  // b and x are per block (six each), as the step assembles them; x holds
  // the initial guess, which is read at the nodes through the first element
  // that has each node.
  SolveReport solve(const VecX& b, VecX& x) override;
  const char* name() const override { return "pcg-meshed"; }

  int free_unknowns() const { return unknowns_; }

 private:
  void expand(const VecX& y, VecX& d) const;    // d = P·y
  void restrict(const VecX& f, VecX& y) const;  // y = Pᵀ·f (uses scratch element_force_)
  void apply(const VecX& y, VecX& out);         // out = Pᵀ S P y
  void set_up_preconditioner();
  void precondition(const VecX& r, VecX& z) const;

  const LinearOperator* a_ = nullptr;
  int blocks_ = 0, nodes_ = 0, unknowns_ = 0, node_base_ = 0, size_ = 0;
  std::vector<int> offset_;                       // per block: its first free unknown (first-order), or -1
  std::vector<std::array<int, 3>> element_node_;  // per block: its nodes (elements)
  std::vector<Mat6> map_;                         // per block: A_e (elements)
  std::vector<Mat6> corners_;                     // per block: A_e⁻¹, T at the three corners (elements)
  std::vector<int> node_start_;                   // per node: its (element, corner) entries, by element
  std::vector<std::pair<int, int>> node_corner_;
  std::vector<Mat6> block_inverse_;            // preconditioner, per first-order block
  std::vector<Eigen::Matrix2d> node_inverse_;  // preconditioner, per node
  mutable std::vector<Vec6> element_force_;
  VecX d_, s_d_, br_, xr_, r_, z_, p_, q_;
};

// Makes `solver` a MeshedSolver when the blocks are meshed (keeping one it
// already is) and gives it the blocks; leaves it alone otherwise.
void use_meshed_solver(std::unique_ptr<LinearSolver>& solver, const Blocks& blocks);

}  // namespace dda
