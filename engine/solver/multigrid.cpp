// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/multigrid.hpp"

#include <algorithm>
#include <cmath>

#include "core/archive.hpp"
#include "core/error.hpp"
#include "core/load_check.hpp"
#include "core/parallel.hpp"

namespace dda {

namespace {

using Mat24 = Eigen::Matrix<double, 2, 4>;

// B of Q = [[I2, B], [0, I4]] for a block whose reference point is offset by
// (dx, dy) from its aggregate's: columns r0, εx, εy, γxy of T.
Mat24 offset_map(const Vec2& d) {
  Mat24 b;
  b << -d.y(), d.x(), 0, 0.5 * d.y(),  //
      d.x(), 0, d.y(), 0.5 * d.x();
  return b;
}

// Q = [[I2, B], [0, I4]].
inline Mat6 Q(const Mat24& b) {
  Mat6 q = Mat6::Identity();
  q.topRightCorner<2, 4>() = b;
  return q;
}

// The inverse of a diagonal block (Cholesky); the reciprocal diagonal if it
// is not positive definite (should not happen: every block has inertia).
inline Mat6 inverse_of_diagonal(const Mat6& d) {
  Mat6 inv;
  invert_spd6(d, inv);
  return inv;
}

}  // namespace

Multigrid::Multigrid(const MultigridOptions& options) : options_(options) {}

void Multigrid::set_block_centroids(std::span<const Vec2> centroids) {
  fine_centroids_.assign(centroids.begin(), centroids.end());
}

int Multigrid::level_blocks(int level) const { return level == 0 ? fine_->rows() : levels_[level].owned.rows(); }

double Multigrid::smoother_weight(int level) const { return levels_[level].weight; }

const BlockSparseMatrix& Multigrid::op(std::size_t level) const { return level == 0 ? *fine_ : levels_[level].owned; }

void Multigrid::save_state(ArchiveWriter& ar) const { ar(levels_, pattern_rows_, pattern_cols_, aggregations_); }

// Of the hierarchy read, only the decisions are taken as they are (each
// level's aggregates, smoothing and λmax estimate, checked against the
// sizes they imply); the transfers' patterns, which follow from those and
// the fine pattern, are made again at the next setup (the same bits), so no
// index from the file reaches them.
void Multigrid::load_state(ArchiveReader& ar) {
  ar(levels_, pattern_rows_, pattern_cols_, aggregations_);
  const LoadCheck check(ar.what());
  check.require(aggregations_ >= 0 && aggregations_ < (1 << 30), "its multigrid's rebuild count is ", aggregations_);
  patterns_restored_ = false;
  if (levels_.empty()) return;
  check.require(!pattern_rows_.empty(), "its multigrid has levels but no fine pattern");
  std::size_t n = pattern_rows_.size() - 1;  // blocks of the level
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const Level& lv = levels_[l];
    check.require(std::isfinite(lv.lambda) && lv.lambda > 0 && std::isfinite(lv.weight), "its multigrid level ", l,
                  "'s smoother has λmax ", lv.lambda, " and weight ", lv.weight);
    if (l + 1 == levels_.size()) {
      check.require(lv.aggregate.empty(), "its coarsest multigrid level has aggregates");
      break;
    }
    check.size(lv.aggregate.size(), n, "blocks", "multigrid level ", l, "'s aggregates");
    std::vector<char> used(n, 0);
    for (const int a : lv.aggregate) {
      check.index(a, n, "blocks", "an aggregate of multigrid level ", l);
      used[a] = 1;
    }
    const std::size_t nc = n == 0 ? 0 : 1 + *std::max_element(lv.aggregate.begin(), lv.aggregate.end());
    check.require(std::all_of(used.begin(), used.begin() + nc, [](char u) { return u != 0; }) && nc > 0,
                  "multigrid level ", l, " has an empty aggregate");
    n = nc;
  }
  patterns_restored_ = true;
}

void Multigrid::setup(const LinearOperator& op) {
  // The Galerkin products need the fine matrix's entries.
  const BlockSparseMatrix* stored = op.stored_matrix();
  if (!stored)
    throw Error("the multigrid preconditioner needs the operator's entries, and this operator is matrix-free only");
  const BlockSparseMatrix& a = *stored;
  fine_ = &a;
  const auto rows = a.row_starts(), cols = a.columns();
  const bool same_pattern = !levels_.empty() &&
                            std::equal(rows.begin(), rows.end(), pattern_rows_.begin(), pattern_rows_.end()) &&
                            std::equal(cols.begin(), cols.end(), pattern_cols_.begin(), pattern_cols_.end());
  if (same_pattern) {
    if (patterns_restored_) remake_transfer_patterns();
    for (std::size_t l = 0; l < levels_.size(); ++l) {
      update_smoother(l, false);
      if (l + 1 == levels_.size()) break;
      update_transfer(l);
      galerkin(l);
    }
    factor_coarsest();
    return;
  }
  pattern_rows_.assign(rows.begin(), rows.end());
  pattern_cols_.assign(cols.begin(), cols.end());
  patterns_restored_ = false;
  build_hierarchy();
  ++aggregations_;
}

// A hierarchy read from a checkpoint: the transfer patterns of its
// aggregates on the fine pattern, and the work vectors.
void Multigrid::remake_transfer_patterns() {
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) build_transfer_pattern(l);
  size_work_vectors();
  patterns_restored_ = false;
}

// ---- Hierarchy ----------------------------------------------------------------

void Multigrid::build_hierarchy() {
  levels_.clear();
  levels_.emplace_back();
  for (;;) {
    const std::size_t l = levels_.size() - 1;
    const int n = op(l).rows();
    if (n <= options_.coarsest_blocks || static_cast<int>(levels_.size()) >= options_.max_levels) break;
    update_smoother(l, true);  // D⁻¹ and λmax: needed by the smoothed prolongator
    const int nc = aggregate(l);
    // Coarsening by less than half (weakly coupled blocks: inertia-dominated
    // systems, many open contacts) would only make dense coarse operators:
    // stop here, and end in smoothing (or a dense solve when small enough).
    if (2 * nc > n) {
      levels_[l].aggregate.clear();
      break;
    }
    levels_.emplace_back();  // invalidates references into levels_
    build_transfer_pattern(l);
    // A coarse operator much denser than its fine one costs more than it saves.
    const double fine_fill = double(op(l).nonzero_blocks()) / n, coarse_fill = double(op(l + 1).nonzero_blocks()) / nc;
    if (coarse_fill > std::max(2.0 * fine_fill, double(options_.max_coarse_fill))) {
      levels_.pop_back();
      levels_[l].aggregate.clear();
      break;
    }
    update_transfer(l);
    galerkin(l);
  }
  update_smoother(levels_.size() - 1, true);
  factor_coarsest();
  size_work_vectors();
}

void Multigrid::size_work_vectors() {
  for (std::size_t l = 0; l < levels_.size(); ++l) {
    const int n = op(l).rows();
    levels_[l].x.resize(6 * n);
    levels_[l].y.resize(6 * n);
    levels_[l].rhs.resize(6 * n);
    levels_[l].res.resize(6 * n);
  }
}

// Sparsity of P, Pᵀ, A·P and PᵀAP for level → level + 1, and the index maps
// that let the values be recomputed without searching.
void Multigrid::build_transfer_pattern(std::size_t level) {
  const BlockSparseMatrix& a = op(level);
  Level& f = levels_[level];
  Level& c = levels_[level + 1];
  const int n = a.rows();
  const int nc = 1 + *std::max_element(f.aggregate.begin(), f.aggregate.end());
  f.member_start.assign(nc + 1, 0);
  for (int i = 0; i < n; ++i) ++f.member_start[f.aggregate[i] + 1];
  for (int ac = 0; ac < nc; ++ac) f.member_start[ac + 1] += f.member_start[ac];
  f.members.resize(n);
  {
    std::vector<int> fill(f.member_start.begin(), f.member_start.end() - 1);
    for (int i = 0; i < n; ++i) f.members[fill[f.aggregate[i]]++] = i;  // ascending within each aggregate
  }
  // P: row i has the aggregates of i (tentative) and, smoothed, of i's
  // neighbours. Small aggregates (coarsening by less than min_smoothed_ratio)
  // keep the tentative P: smoothing it would fill the coarse operator in.
  f.smooth = options_.smooth_prolongator && n >= options_.min_smoothed_ratio * nc;
  const bool smooth = f.smooth;
  f.p_start.assign(n + 1, 0);
  f.p_col.clear();
  std::vector<int> cols;
  for (int i = 0; i < n; ++i) {
    cols.clear();
    cols.push_back(f.aggregate[i]);
    if (smooth)
      for (int k = a.row_begin(i); k < a.row_end(i); ++k) cols.push_back(f.aggregate[a.col(k)]);
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    f.p_col.insert(f.p_col.end(), cols.begin(), cols.end());
    f.p_start[i + 1] = static_cast<int>(f.p_col.size());
  }
  f.p_val.resize(f.p_col.size());
  auto p_find = [&](int i, int col) {
    const auto begin = f.p_col.begin() + f.p_start[i], end = f.p_col.begin() + f.p_start[i + 1];
    return static_cast<int>(std::lower_bound(begin, end, col) - f.p_col.begin());
  };
  f.p_source.resize(a.nonzero_blocks());
  for (int i = 0; i < n; ++i)
    for (int k = a.row_begin(i); k < a.row_end(i); ++k)
      f.p_source[k] = (smooth || a.col(k) == i) ? p_find(i, f.aggregate[a.col(k)]) : -1;
  // Pᵀ by coarse rows, fine rows ascending.
  f.pt_start.assign(nc + 1, 0);
  for (int col : f.p_col) ++f.pt_start[col + 1];
  for (int ac = 0; ac < nc; ++ac) f.pt_start[ac + 1] += f.pt_start[ac];
  f.pt_row.resize(f.p_col.size());
  f.pt_entry.resize(f.p_col.size());
  {
    std::vector<int> fill(f.pt_start.begin(), f.pt_start.end() - 1);
    for (int i = 0; i < n; ++i)
      for (int e = f.p_start[i]; e < f.p_start[i + 1]; ++e) {
        f.pt_row[fill[f.p_col[e]]] = i;
        f.pt_entry[fill[f.p_col[e]]++] = e;
      }
  }
  // A·P: row i has the P columns of i's neighbours.
  f.ap_start.assign(n + 1, 0);
  f.ap_offset.assign(n + 1, 0);
  f.ap_col.clear();
  f.ap_index.clear();
  for (int i = 0; i < n; ++i) {
    cols.clear();
    for (int k = a.row_begin(i); k < a.row_end(i); ++k)
      for (int e = f.p_start[a.col(k)]; e < f.p_start[a.col(k) + 1]; ++e) cols.push_back(f.p_col[e]);
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    const int base = static_cast<int>(f.ap_col.size());
    f.ap_col.insert(f.ap_col.end(), cols.begin(), cols.end());
    f.ap_start[i + 1] = static_cast<int>(f.ap_col.size());
    for (int k = a.row_begin(i); k < a.row_end(i); ++k)
      for (int e = f.p_start[a.col(k)]; e < f.p_start[a.col(k) + 1]; ++e)
        f.ap_index.push_back(base +
                             static_cast<int>(std::lower_bound(cols.begin(), cols.end(), f.p_col[e]) - cols.begin()));
    f.ap_offset[i + 1] = static_cast<int>(f.ap_index.size());
  }
  f.ap_val.resize(f.ap_col.size());
  // PᵀAP: coarse (A, B) wherever P(i, A) and AP(i, B) are both stored.
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i)
    for (int e = f.p_start[i]; e < f.p_start[i + 1]; ++e)
      for (int g = f.ap_start[i]; g < f.ap_start[i + 1]; ++g)
        if (f.p_col[e] < f.ap_col[g]) pairs.emplace_back(f.p_col[e], f.ap_col[g]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  c.owned.set_structure(nc, pairs);
  f.g_start.assign(nc + 1, 0);
  f.g_index.clear();
  for (int ac = 0; ac < nc; ++ac) {
    for (int t = f.pt_start[ac]; t < f.pt_start[ac + 1]; ++t) {
      const int i = f.pt_row[t];
      for (int g = f.ap_start[i]; g < f.ap_start[i + 1]; ++g) f.g_index.push_back(c.owned.find(ac, f.ap_col[g]));
    }
    f.g_start[ac + 1] = static_cast<int>(f.g_index.size());
  }
}

// Greedy aggregation in block order (Vaněk, Mandel & Brezina 1996), on the
// graph of strong couplings. Returns the number of aggregates.
int Multigrid::aggregate(std::size_t level) {
  const BlockSparseMatrix& a = op(level);
  Level& lv = levels_[level];
  const int n = a.rows();
  // Strength of each stored block: ‖L_i⁻¹ A_ij L_j⁻ᵀ‖_F.
  std::vector<Mat6> l_inv(n);
  std::vector<char> ok(n);
  parallel_for_each(n, [&](std::size_t i) {
    Eigen::LLT<Mat6> llt(a.value(a.diagonal(static_cast<int>(i))));
    ok[i] = llt.info() == Eigen::Success;
    l_inv[i] = ok[i] ? Mat6(llt.matrixL().solve(Mat6::Identity())) : Mat6::Zero();
  });
  std::vector<double> strength(a.nonzero_blocks(), 0.0);
  parallel_for_each(
      n,
      [&](std::size_t i) {
        for (int k = a.row_begin(static_cast<int>(i)); k < a.row_end(static_cast<int>(i)); ++k) {
          const int j = a.col(k);
          if (j == static_cast<int>(i) || !ok[i] || !ok[j]) continue;
          strength[k] = (l_inv[i] * a.value(k) * l_inv[j].transpose()).norm();
        }
      },
      32);
  const double theta = options_.strength_threshold;
  auto strong = [&](int k) { return strength[k] >= theta && strength[k] > 0; };

  std::vector<int>& agg = lv.aggregate;
  agg.assign(n, -1);
  int count = 0;
  // Pass 1: a block whose strong neighbours are all free starts an aggregate with them.
  for (int i = 0; i < n; ++i) {
    if (agg[i] != -1) continue;
    bool has_strong = false, all_free = true;
    for (int k = a.row_begin(i); k < a.row_end(i); ++k)
      if (a.col(k) != i && strong(k)) {
        has_strong = true;
        if (agg[a.col(k)] != -1) all_free = false;
      }
    if (!has_strong || !all_free) continue;
    agg[i] = count;
    for (int k = a.row_begin(i); k < a.row_end(i); ++k)
      if (a.col(k) != i && strong(k)) agg[a.col(k)] = count;
    ++count;
  }
  // Pass 2: a free block joins the pass-1 aggregate it is most strongly coupled to.
  const std::vector<int> first = agg;
  for (int i = 0; i < n; ++i) {
    if (agg[i] != -1) continue;
    double best = 0;
    for (int k = a.row_begin(i); k < a.row_end(i); ++k)
      if (a.col(k) != i && strong(k) && first[a.col(k)] != -1 && strength[k] > best) {
        best = strength[k];
        agg[i] = first[a.col(k)];
      }
  }
  // Pass 3: what is left forms aggregates with its free strong neighbours
  // (a block with none stays alone).
  for (int i = 0; i < n; ++i) {
    if (agg[i] != -1) continue;
    agg[i] = count;
    for (int k = a.row_begin(i); k < a.row_end(i); ++k)
      if (a.col(k) != i && strong(k) && agg[a.col(k)] == -1) agg[a.col(k)] = count;
    ++count;
  }
  return count;
}

// Reference points of the coarse blocks (mean of their members') and the
// offset maps B_i of the fine blocks.
void Multigrid::update_transfer(std::size_t level) {
  Level& f = levels_[level];
  Level& c = levels_[level + 1];
  const int n = op(level).rows(), nc = op(level + 1).rows();
  if (level == 0) {
    if (fine_centroids_.size() == static_cast<std::size_t>(n)) {
      f.centroid = fine_centroids_;
    } else {
      f.centroid.assign(n, Vec2::Zero());  // no geometry: piecewise-constant transfer
    }
  }
  c.centroid.resize(nc);
  f.b.resize(n);
  parallel_for_each(nc, [&](std::size_t ac) {
    Vec2 s = Vec2::Zero();
    const int begin = f.member_start[ac], end = f.member_start[ac + 1];
    for (int m = begin; m < end; ++m) s += f.centroid[f.members[m]];
    c.centroid[ac] = s / static_cast<double>(end - begin);
    for (int m = begin; m < end; ++m) f.b[f.members[m]] = offset_map(f.centroid[f.members[m]] - c.centroid[ac]);
  });
}

// Values of P, A·P and PᵀAP. Every output row is computed by one task, in
// a fixed order: bit-identical for any thread count.
void Multigrid::galerkin(std::size_t level) {
  const BlockSparseMatrix& a = op(level);
  Level& f = levels_[level];
  BlockSparseMatrix& ac = levels_[level + 1].owned;
  const int n = a.rows();
  const bool smooth = f.smooth;
  const double wp = (4.0 / 3.0) / f.lambda;
  // P = (I − ω_p D⁻¹A)·P_tent, P_tent(i, agg(i)) = Q_i.
  parallel_for_each(
      n,
      [&](std::size_t r) {
        const int i = static_cast<int>(r);
        for (int e = f.p_start[i]; e < f.p_start[i + 1]; ++e) f.p_val[e].setZero();
        for (int k = a.row_begin(i); k < a.row_end(i); ++k) {
          const int j = a.col(k);
          if (!smooth) {
            if (j == i) f.p_val[f.p_source[k]] = Q(f.b[i]);
            continue;
          }
          Mat6 m = (-wp) * (f.dinv[i] * a.value(k));
          if (j == i) m.diagonal().array() += 1.0;
          Mat6& out = f.p_val[f.p_source[k]];
          out += m;
          out.rightCols<4>().noalias() += m.leftCols<2>() * f.b[j];
        }
      },
      32);
  // A·P by fine rows (ap_index lists row i's targets from ap_offset[i] on).
  parallel_for_each(
      n,
      [&](std::size_t r) {
        const int i = static_cast<int>(r);
        for (int g = f.ap_start[i]; g < f.ap_start[i + 1]; ++g) f.ap_val[g].setZero();
        int t = f.ap_offset[i];
        for (int k = a.row_begin(i); k < a.row_end(i); ++k) {
          const int j = a.col(k);
          for (int e = f.p_start[j]; e < f.p_start[j + 1]; ++e)
            f.ap_val[f.ap_index[t++]].noalias() += a.value(k) * f.p_val[e];
        }
      },
      32);
  // PᵀAP by coarse rows.
  parallel_for_each(
      ac.rows(),
      [&](std::size_t r) {
        const int row = static_cast<int>(r);
        for (int k = ac.row_begin(row); k < ac.row_end(row); ++k) ac.value(k).setZero();
        int t = f.g_start[row];
        for (int s = f.pt_start[row]; s < f.pt_start[row + 1]; ++s) {
          const int i = f.pt_row[s];
          const Mat6& p = f.p_val[f.pt_entry[s]];
          for (int g = f.ap_start[i]; g < f.ap_start[i + 1]; ++g)
            ac.value(f.g_index[t++]).noalias() += p.transpose() * f.ap_val[g];
        }
      },
      8);
}

void Multigrid::update_smoother(std::size_t level, bool estimate_weight) {
  const BlockSparseMatrix& a = op(level);
  Level& lv = levels_[level];
  const int n = a.rows();
  lv.dinv.resize(n);
  parallel_for_each(n,
                    [&](std::size_t i) { lv.dinv[i] = inverse_of_diagonal(a.value(a.diagonal(static_cast<int>(i)))); });
  if (!estimate_weight) return;
  // λmax(D⁻¹A) by power iteration from a fixed start (the Rayleigh quotient
  // vᵀAv / vᵀDv, a lower bound that converges from below).
  VecX v(6 * n), av(6 * n), dv(6 * n);
  for (int i = 0; i < 6 * n; ++i) v[i] = 1.0 + 0.5 * std::sin(0.7 * i);
  double lambda = 1;
  for (int it = 0; it < options_.power_iterations; ++it) {
    a.multiply(v, av);
    parallel_for_each(n, [&](std::size_t i) {
      dv.segment<6>(6 * i).noalias() = a.value(a.diagonal(static_cast<int>(i))) * v.segment<6>(6 * i);
    });
    const double vdv = deterministic_dot(v, dv);
    if (!(vdv > 0)) break;
    lambda = std::max(lambda, deterministic_dot(v, av) / vdv);
    parallel_for_each(n, [&](std::size_t i) { v.segment<6>(6 * i).noalias() = lv.dinv[i] * av.segment<6>(6 * i); });
    const double norm = std::sqrt(deterministic_dot(v, v));
    if (!(norm > 0) || !std::isfinite(norm)) break;
    v /= norm;
  }
  lv.lambda = lambda * options_.lambda_safety;
  lv.weight = options_.jacobi_weight > 0 ? options_.jacobi_weight : (4.0 / 3.0) / lv.lambda;
}

void Multigrid::factor_coarsest() {
  const std::size_t last = levels_.size() - 1;
  const BlockSparseMatrix& a = op(last);
  const int n = a.rows();
  // Coarsening that stalled well above the target (blocks without strong
  // couplings) ends in symmetric smoothing instead of a large dense solve.
  dense_coarse_ = n <= 2 * std::max(options_.coarsest_blocks, 1);
  if (!dense_coarse_) return;
  coarse_dense_.setZero(6 * n, 6 * n);
  for (int i = 0; i < n; ++i)
    for (int k = a.row_begin(i); k < a.row_end(i); ++k) coarse_dense_.block<6, 6>(6 * i, 6 * a.col(k)) = a.value(k);
  coarse_llt_.compute(coarse_dense_);
  if (coarse_llt_.info() != Eigen::Success) dense_coarse_ = false;
}

// ---- Application ------------------------------------------------------------

void Multigrid::apply(const VecX& r, VecX& z) const {
  DDA_ASSERT(fine_ != nullptr && !levels_.empty(), "Multigrid::apply before setup");
  z.resize(r.size());
  vcycle(0, r, z);
}

void Multigrid::vcycle(std::size_t level, const VecX& b, VecX& x) const {
  const BlockSparseMatrix& a = op(level);
  const Level& lv = levels_[level];
  const int n = a.rows();
  const bool coarsest = level + 1 == levels_.size();
  if (coarsest && dense_coarse_) {
    x = coarse_llt_.solve(b);
    return;
  }
  const double w = lv.weight;
  // Pre-smoothing from a zero guess: x = ωD⁻¹b, then further sweeps.
  parallel_for_each(
      n, [&](std::size_t i) { x.segment<6>(6 * i).noalias() = w * (lv.dinv[i] * b.segment<6>(6 * i)); }, 128);
  auto sweep = [&] {  // y = x + ωD⁻¹(b − A·x); x ↔ y
    parallel_for_each(
        n,
        [&](std::size_t i) {
          Vec6 s = b.segment<6>(6 * i);
          for (int k = a.row_begin(static_cast<int>(i)); k < a.row_end(static_cast<int>(i)); ++k)
            s.noalias() -= a.value(k) * x.segment<6>(6 * a.col(k));
          lv.y.segment<6>(6 * i).noalias() = x.segment<6>(6 * i) + w * (lv.dinv[i] * s);
        },
        32);
    x.swap(lv.y);
  };
  for (int s = 1; s < options_.smoothing_steps; ++s) sweep();
  if (coarsest) {  // no dense solve: symmetric smoothing only
    for (int s = 0; s < options_.smoothing_steps; ++s) sweep();
    return;
  }
  // Residual, then restriction rc = Pᵀr by coarse rows.
  parallel_for_each(
      n,
      [&](std::size_t i) {
        Vec6 s = b.segment<6>(6 * i);
        for (int k = a.row_begin(static_cast<int>(i)); k < a.row_end(static_cast<int>(i)); ++k)
          s.noalias() -= a.value(k) * x.segment<6>(6 * a.col(k));
        lv.res.segment<6>(6 * i) = s;
      },
      32);
  const Level& c = levels_[level + 1];
  parallel_for_each(
      c.owned.rows(),
      [&](std::size_t ac) {
        Vec6 rc = Vec6::Zero();
        for (int t = lv.pt_start[ac]; t < lv.pt_start[ac + 1]; ++t)
          rc.noalias() += lv.p_val[lv.pt_entry[t]].transpose() * lv.res.segment<6>(6 * lv.pt_row[t]);
        c.rhs.segment<6>(6 * ac) = rc;
      },
      16);
  vcycle(level + 1, c.rhs, c.x);
  // Prolongation: x += P·xc.
  parallel_for_each(
      n,
      [&](std::size_t i) {
        Vec6 s = Vec6::Zero();
        for (int e = lv.p_start[i]; e < lv.p_start[i + 1]; ++e)
          s.noalias() += lv.p_val[e] * c.x.segment<6>(6 * lv.p_col[e]);
        x.segment<6>(6 * i) += s;
      },
      64);
  for (int s = 0; s < options_.smoothing_steps; ++s) sweep();
}

}  // namespace dda
