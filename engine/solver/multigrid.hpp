// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Aggregation multigrid on the 6×6 blocks, used as a PCG preconditioner.
//
// Coarsening. Neighbouring blocks that are strongly coupled in the matrix are
// grouped greedily, in block order (deterministic), into aggregates. An
// aggregate is a "super-block" with the same six DDA unknowns
// (u0, v0, r0, εx, εy, γxy) about its reference point (the mean of its
// members' reference points). The prolongator maps a coarse solution to each
// member block with the DDA displacement function itself:
//
//   member translation  = T_aggregate(member centroid) · Dc
//   member rotation, strains = the coarse rotation and strains
//
// which reproduces exactly every displacement field linear in x and y (rigid
// motions and uniform strain): the near-null space of a jointed rock mass
// held together by stiff contact springs. Per member block i the map is
//
//   Q_i = | I2  B_i |      B_i = | -dy  dx  0   dy/2 |,  (dx, dy) = c_i − c_agg
//         | 0   I4  |            |  dx  0   dy  dx/2 |
//
// This tentative prolongator is smoothed once (smoothed aggregation, Vaněk,
// Mandel & Brezina 1996): P = (I − ω_p D⁻¹A)·P_tent. Coarse operators are
// Galerkin products PᵀAP in the same block-sparse form, recursively, down to
// a few blocks solved densely (Cholesky). Applied as a symmetric V-cycle
// (damped block-Jacobi smoothing, the same before and after the coarse
// correction), so the preconditioner is symmetric positive definite and
// plain CG stays valid.
//
// What it achieves (walls with gg = 1, Δt = 1e-3 s, cold solves to 1e-10):
// 4–4.5× fewer CG iterations than block-Jacobi (wall(10) 372 → 88, wall(20)
// 452 → 118), for about 4× the work per iteration: no faster there. It gains
// where inertia is weaker (larger Δt: 6× fewer iterations, 2× faster). What
// holds it back, from the spectrum of the preconditioned wall(10) system:
// with g0 = 50E the contact penalty dominates, and its near-null space is not
// only the fields linear over an aggregate but every continuous field that
// is linear per block — in a brick wall, a horizontal shear u(y) (and a
// normal strain v(y)) with a kink at every bed joint, coherent along the
// whole joint line, and in loosely held rows (top of the wall, sliding bed
// joints) local pair modes. Aggregates that span several rows cannot
// represent those, and a block smoother cannot remove them; about 15 % of the
// eigenvalues of the preconditioned system lie below 0.2 (κ ≈ 74).
// Candidate cures, not done: aggregates that do not cross persistent joint
// lines at any level, extra coarse candidate vectors per aggregate (adaptive
// SA), or patch (overlapping Schwarz) smoothers.
//
// Reuse. The aggregation (which blocks form which aggregate, the coarse
// sparsity, the Galerkin index maps, the smoother weight) is kept while the
// fine matrix keeps its sparsity pattern: in the DDA step that is every
// open-close iteration, and every step in which no contact entered or left
// the search range. setup() with a new pattern aggregates again.
//
// Determinism. Aggregation is serial and in block order; every parallel loop
// gives each output block row to one task and sums in a fixed order, so the
// result is bit-identical for any thread count.
#include <Eigen/Cholesky>
#include <span>
#include <vector>

#include "solver/block_sparse_matrix.hpp"
#include "solver/linear_solver.hpp"

namespace dda {

struct MultigridOptions {
  // Blocks i, j are strongly coupled when ‖L_i⁻¹ A_ij L_j⁻ᵀ‖_F ≥ this
  // (L the Cholesky factors of the diagonal blocks): scale-free, and zero for
  // open contacts.
  double strength_threshold = 0.02;
  int coarsest_blocks = 24;  // stop coarsening at this many blocks: dense Cholesky
  int max_levels = 12;
  // Stop coarsening before a level whose operator has more blocks per row
  // than this and than twice the level above (smoothed aggregation of weakly
  // coupled blocks fills in fast).
  int max_coarse_fill = 24;
  int smoothing_steps = 1;  // block-Jacobi sweeps before and after the coarse correction
  // Smoothed aggregation: P = (I − ω_p D⁻¹A)·P_tentative, ω_p = (4/3)/λmax(D⁻¹A).
  // The tentative (piecewise-linear) P alone leaves jumps between aggregates
  // that the stiff contact springs make expensive; smoothing spreads them out.
  bool smooth_prolongator = true;
  double min_smoothed_ratio = 4;  // smooth P only where blocks / aggregates ≥ this
  // Smoother weight ω in x += ω·D⁻¹(b − A·x). 0 → ω = (4/3) / λmax(D⁻¹A),
  // λmax estimated by a few power iterations whenever the pattern changes.
  double jacobi_weight = 0;
  int power_iterations = 12;   // for the λmax(D⁻¹A) estimate, whenever the pattern changes
  double lambda_safety = 1.1;  // the estimate (a lower bound) × this
};

class Multigrid final : public Preconditioner {
 public:
  explicit Multigrid(const MultigridOptions& options = {});
  void set_block_centroids(std::span<const Vec2> centroids) override;
  void setup(const LinearOperator& a) override;
  void apply(const VecX& r, VecX& z) const override;
  // The hierarchy, kept while the fine pattern holds (its aggregates and
  // λmax estimates come from the matrix it was built on).
  void save_state(ArchiveWriter& ar) const override;
  void load_state(ArchiveReader& ar) override;

  // For tests and benchmarks.
  int levels() const { return static_cast<int>(levels_.size()); }
  int level_blocks(int level) const;
  int aggregations() const { return aggregations_; }  // times the hierarchy was rebuilt
  double smoother_weight(int level) const;
  const MultigridOptions& options() const { return options_; }

 private:
  struct Level {
    BlockSparseMatrix owned;     // the operator of levels ≥ 1 (level 0: the caller's)
    std::vector<Vec2> centroid;  // reference points of this level's blocks
    std::vector<Mat6> dinv;      // D_i⁻¹ per block
    double lambda = 1;           // estimate of λmax(D⁻¹A)
    double weight = 0;           // smoother weight ω
    // Transfer to the next coarser level (empty on the coarsest).
    std::vector<int> aggregate;                  // block → coarse block
    std::vector<int> member_start, members;      // coarse block → its blocks, ascending
    std::vector<Eigen::Matrix<double, 2, 4>> b;  // per block: B_i of the tentative Q_i
    bool smooth = false;                         // P smoothed (else the tentative P)
    // P (block rows of this level → coarse blocks), compressed rows.
    std::vector<int> p_start, p_col, p_source;  // p_source[k]: P entry fed by stored block k of A
    std::vector<Mat6> p_val;
    // Pᵀ by coarse rows: (fine row, P entry), ascending fine row.
    std::vector<int> pt_start, pt_row, pt_entry;
    // A·P, compressed rows; ap_index in traversal order (row i, its A entries, their P entries).
    std::vector<int> ap_start, ap_col, ap_index, ap_offset;
    std::vector<Mat6> ap_val;
    // PᵀAP: target coarse entry in traversal order (coarse row, its Pᵀ entries, their AP entries).
    std::vector<int> g_start, g_index;
    mutable VecX x, y, rhs, res;  // work vectors
    template <class Archive>
    void fields(Archive& ar) {
      ar(owned, centroid, dinv, lambda, weight, aggregate, member_start, members, b, smooth, p_start, p_col, p_source,
         p_val, pt_start, pt_row, pt_entry, ap_start, ap_col, ap_index, ap_offset, ap_val, g_start, g_index, x, y, rhs,
         res);
    }
  };

  const BlockSparseMatrix& op(std::size_t level) const;
  void build_hierarchy();
  void remake_transfer_patterns();
  void size_work_vectors();
  int aggregate(std::size_t level);
  void update_transfer(std::size_t level);
  void build_transfer_pattern(std::size_t level);
  void galerkin(std::size_t level);
  void update_smoother(std::size_t level, bool estimate_weight);
  void factor_coarsest();
  void vcycle(std::size_t level, const VecX& b, VecX& x) const;

  MultigridOptions options_;
  const BlockSparseMatrix* fine_ = nullptr;
  std::vector<Vec2> fine_centroids_;
  std::vector<Level> levels_;
  std::vector<int> pattern_rows_, pattern_cols_;  // the fine sparsity the hierarchy was built for
  Eigen::MatrixXd coarse_dense_;
  Eigen::LLT<Eigen::MatrixXd> coarse_llt_;
  bool dense_coarse_ = false;
  int aggregations_ = 0;
  bool patterns_restored_ = false;  // levels read from a checkpoint: patterns to make at the next setup
};

}  // namespace dda
