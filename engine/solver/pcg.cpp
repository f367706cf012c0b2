// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/pcg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>

#include "core/archive.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "solver/preconditioner_choice.hpp"

namespace dda {

namespace {
// Whether the preconditioner block made from `basis` still serves for `now`:
// every entry within `tolerance` times the largest entry of basis.
bool close_enough(const Symmetric6& basis, const Mat6& now, double tolerance) {
  const auto& u = basis.upper();
  double largest = 0;
  for (const double v : u) largest = std::max(largest, std::abs(v));
  const double allowed = tolerance * largest;
  for (int i = 0, k = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j, ++k)
      if (!(std::abs(now(i, j) - u[k]) <= allowed)) return false;
  return true;
}
}  // namespace

void BlockJacobi::setup(const LinearOperator& a) {
  // Re-invert only the diagonal blocks that changed enough to matter. A row
  // the operator did not rewrite since the last setup (its revision number
  // holds) is skipped outright: between the open-close iterations of a step
  // that is every row whose contacts kept their state. A rewritten row keeps
  // its inverse while every entry stays within refresh_tolerance (relative to
  // the largest entry) of the block that inverse was made from: in wave
  // problems a block's terms drift by 1e-6 or less a step, while a contact
  // that closes, opens or starts to slide changes them at once. A preconditioner
  // a little off only changes how fast the CG converges, never to what.
  const std::size_t n = a.rows();
  const bool fresh = revision_.size() != n;  // a new matrix shape: invert every block
  if (fresh) {
    revision_.assign(n, 0);
    basis_.resize(n);
    inverse_.resize(n);
  }
  parallel_for_each(n, [&](std::size_t i) {
    const std::uint64_t revision = a.diagonal_revision(static_cast<int>(i));
    if (!fresh && revision != 0 && revision == revision_[i]) return;
    revision_[i] = revision;
    const Mat6 d = a.diagonal_block(static_cast<int>(i));
    if (!fresh && close_enough(basis_[i], d, refresh_tolerance)) return;
    basis_[i] = Symmetric6(d);
    Mat6 inverse;
    invert_spd6(d, inverse);
    inverse_[i] = Symmetric6(inverse);
  });
}

void BlockJacobi::save_state(ArchiveWriter& ar) const { ar(basis_, inverse_, std::uint64_t(revision_.size())); }

void BlockJacobi::load_state(ArchiveReader& ar) {
  std::uint64_t rows = 0;
  ar(basis_, inverse_, rows);
  if (basis_.size() != rows || inverse_.size() != rows)
    throw Error(msg(ar.what(), " is damaged: its block-Jacobi preconditioner has ", basis_.size(), " blocks and ",
                    inverse_.size(), " inverses for ", rows, " rows"));
  revision_.assign(rows, 0);  // 0: no revision seen, every block is compared with its basis
}

void BlockJacobi::apply(const VecX& r, VecX& z) const {
  z.resize(r.size());
  parallel_for_each(
      inverse_.size(), [&](std::size_t i) { apply_rows(i, i + 1, r, z); }, 128);
}

void BlockJacobi::apply_rows(std::size_t begin, std::size_t end, const VecX& r, VecX& z) const {
  for (std::size_t i = begin; i < end; ++i) z.segment<6>(6 * i) = inverse_[i] * Vec6(r.segment<6>(6 * i));
}

PcgSolver::PcgSolver(std::unique_ptr<Preconditioner> pre) : pre_(std::move(pre)) {}

void PcgSolver::begin_step(const SolverSettings& settings, const StepSolveInfo& info) {
  // Auto switches on the last step's CG iterations per solve, which are the
  // same for any thread count, so the choice stays deterministic. The
  // preconditioner is rebuilt only when the choice changes.
  SystemTraits traits(info.blocks);
  if (kind_ && info.last_step_solves > 0) {
    traits.last_kind = *kind_;
    traits.last_cg_per_solve = static_cast<double>(info.last_step_iterations) / info.last_step_solves;
  }
  const Preconditioning kind = choose_preconditioning(settings.pcg.preconditioner, traits);
  if (!kind_ || *kind_ != kind) {
    pre_ = make_preconditioner(kind);
    kind_ = kind;
  }
  pre_->configure(settings.pcg);
  pre_->set_block_centroids(info.block_centroids);
  patch_hops = info.local_resolves ? settings.pcg.patch_hops : 0;
}

void PcgSolver::save_state(ArchiveWriter& ar) const {
  ar(kind_);
  if (kind_) pre_->save_state(ar);
}

void PcgSolver::load_state(ArchiveReader& ar) {
  ar(kind_);
  if (!kind_) return;
  pre_ = make_preconditioner(*kind_);
  pre_->load_state(ar);
}

void PcgSolver::set_operator(const LinearOperator& a) {
  a_ = &a;
  pre_->setup(a);
  if (patch_hops > 0) size_patch_buffers(static_cast<std::size_t>(a.rows()));
}

// The patch's buffers, sized for any patch when the system is: a re-solve
// then allocates nothing, whenever its first patch comes.
void PcgSolver::size_patch_buffers(std::size_t blocks) {
  if (patch_mark_.size() == blocks) return;
  patch_mark_.assign(blocks, 0);  // all zero between calls
  patch_.reserve(blocks);
  patch_boundary_.reserve(blocks);
  neighbours_.reserve(256);
  patch_p_ = VecX::Zero(6 * static_cast<Eigen::Index>(blocks));
  patch_d_ = VecX::Zero(6 * static_cast<Eigen::Index>(blocks));
  z_.resize(6 * static_cast<Eigen::Index>(blocks));
}

// Fused vector kernels. Each works over fixed chunks of kPcgChunk blocks,
// f(begin, end) returning the chunk's share of a dot product (or, in
// chunked_sums, writing its shares of two); the shares are summed in chunk
// order: the same bits for any thread count, and no
// allocation (partial_ is reused). The mat-vec runs chunk by chunk inside
// them, so its rows are still in cache for the dot product.
namespace {
constexpr std::size_t kPcgChunk = 64;
}

template <typename F>
std::pair<double, double> PcgSolver::chunked_sums(std::size_t blocks, F&& f) {
  const std::size_t chunks = (blocks + kPcgChunk - 1) / kPcgChunk;
  partial_.resize(chunks);
  partial2_.resize(chunks);
  parallel_for_each(
      chunks,
      [&](std::size_t c) {
        partial_[c] = partial2_[c] = 0;
        f(c * kPcgChunk, std::min(blocks, (c + 1) * kPcgChunk), partial_[c], partial2_[c]);
      },
      1);
  double first = 0, second = 0;
  for (std::size_t c = 0; c < chunks; ++c) {
    first += partial_[c];
    second += partial2_[c];
  }
  return {first, second};
}

template <typename F>
double PcgSolver::chunked_sum(std::size_t blocks, F&& f) {
  return chunked_sums(blocks,
                      [&](std::size_t begin, std::size_t end, double& share, double&) { share = f(begin, end); })
      .first;
}

SolveReport PcgSolver::solve_from(const VecX& b, VecX& x, std::span<const char> changed_rows) {
  DDA_ASSERT(a_ != nullptr, "PcgSolver::solve before set_operator");
  const LinearOperator& a = *a_;
  SolveReport report;
  const std::size_t n = static_cast<std::size_t>(b.size());
  const std::size_t blocks = n / 6;
  // The last solve's residual serves where neither A nor b changed (it is the
  // recursively updated one, within round-off of b − A·x).
  const bool reuse = residual_valid_ && !changed_rows.empty() && changed_rows.size() == blocks &&
                     static_cast<std::size_t>(x.size()) == n && static_cast<std::size_t>(r_.size()) == n;
  residual_valid_ = false;
  if (x.size() != b.size()) x = VecX::Zero(b.size());
  r_.resize(n);
  p_.resize(n);
  ap_.resize(n);
  const double bnorm = std::sqrt(chunked_sum(blocks, [&](std::size_t begin, std::size_t end) {
    return b.segment(6 * begin, 6 * (end - begin)).squaredNorm();
  }));
  if (!std::isfinite(bnorm)) {
    report.finite = false;
    return report;
  }
  if (bnorm == 0) {
    x.setZero();
    report.converged = true;
    return report;
  }
  // r = b − A·x (on the changed rows only, when the last residual serves), and ‖r‖².
  double rr = chunked_sum(blocks, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end;) {
      if (reuse && !changed_rows[i]) {
        ++i;
        continue;
      }
      std::size_t stop = i + 1;  // a run of rows to recompute
      while (stop < end && !(reuse && !changed_rows[stop])) ++stop;
      a.multiply_rows(static_cast<int>(i), static_cast<int>(stop), x, r_);
      auto r = r_.segment(6 * i, 6 * (stop - i));
      r = b.segment(6 * i, 6 * (stop - i)) - r;
      i = stop;
    }
    return r_.segment(6 * begin, 6 * (end - begin)).squaredNorm();
  });
  // Records the relative residual of ‖r‖² = r2; true when the solve ends
  // there (converged, or not finite).
  auto ends_at = [&](double r2) {
    report.relative_residual = std::sqrt(r2) / bnorm;
    if (!std::isfinite(r2)) {
      report.finite = false;
      return true;
    }
    if (report.relative_residual <= tolerance) {
      report.converged = residual_valid_ = true;
      return true;
    }
    return false;
  };
  if (ends_at(rr)) return report;
  const bool by_rows = pre_->applies_by_rows();
  if (reuse && patch_hops > 0 && by_rows && build_patch(changed_rows) && ends_at(solve_on_patch(x, bnorm, report)))
    return report;
  pre_->apply(r_, z_);
  double rz = chunked_sum(blocks, [&](std::size_t begin, std::size_t end) {
    const std::size_t o = 6 * begin, len = 6 * (end - begin);
    p_.segment(o, len) = z_.segment(o, len);
    return r_.segment(o, len).dot(z_.segment(o, len));
  });
  for (int it = 1; it <= max_iterations; ++it) {
    // ap = A·p and pᵀAp in one pass.
    const double pap = chunked_sum(blocks, [&](std::size_t begin, std::size_t end) {
      a.multiply_rows(static_cast<int>(begin), static_cast<int>(end), p_, ap_);
      const std::size_t o = 6 * begin, len = 6 * (end - begin);
      return p_.segment(o, len).dot(ap_.segment(o, len));
    });
    report.iterations = it;
    if (!std::isfinite(pap) || pap <= 0 || !(rz > 0)) {
      report.finite = std::isfinite(pap) && std::isfinite(rz);
      return report;  // not converged: breakdown (matrix or preconditioner not SPD, or NaN)
    }
    const double alpha = rz / pap;
    // x += α·p, r −= α·Ap, and ‖r‖² in one pass; with a preconditioner
    // applied by rows, z = M⁻¹r and rᵀz in the same pass (the same sums, in
    // the same chunks, as the separate passes below).
    double rz_next = 0;
    if (by_rows) {
      std::tie(rr, rz_next) = chunked_sums(blocks, [&](std::size_t begin, std::size_t end, double& r2, double& r_z) {
        const std::size_t o = 6 * begin, len = 6 * (end - begin);
        x.segment(o, len) += alpha * p_.segment(o, len);
        r_.segment(o, len) -= alpha * ap_.segment(o, len);
        r2 = r_.segment(o, len).squaredNorm();
        pre_->apply_rows(begin, end, r_, z_);
        r_z = r_.segment(o, len).dot(z_.segment(o, len));
      });
    } else {
      rr = chunked_sum(blocks, [&](std::size_t begin, std::size_t end) {
        const std::size_t o = 6 * begin, len = 6 * (end - begin);
        x.segment(o, len) += alpha * p_.segment(o, len);
        r_.segment(o, len) -= alpha * ap_.segment(o, len);
        return r_.segment(o, len).squaredNorm();
      });
    }
    const bool ends = ends_at(rr);
    if (monitor) monitor(it, report.relative_residual);
    if (ends) return report;
    if (!by_rows) {
      pre_->apply(r_, z_);
      rz_next = chunked_sum(blocks, [&](std::size_t begin, std::size_t end) {
        const std::size_t o = 6 * begin, len = 6 * (end - begin);
        return r_.segment(o, len).dot(z_.segment(o, len));
      });
    }
    const double beta = rz_next / rz;
    rz = rz_next;
    parallel_for_each(
        blocks, [&](std::size_t i) { p_.segment<6>(6 * i) = z_.segment<6>(6 * i) + beta * p_.segment<6>(6 * i); },
        kPcgChunk);
  }
  return report;
}

// The changed rows and every row within patch_hops couplings of them
// (breadth first, then sorted), and the rows one coupling further out. False,
// with nothing marked, when the operator cannot name its couplings or the
// patch would exceed patch_max_share of the rows.
bool PcgSolver::build_patch(std::span<const char> changed_rows) {
  const LinearOperator& a = *a_;
  const std::size_t blocks = changed_rows.size();
  const std::size_t limit = static_cast<std::size_t>(patch_max_share * static_cast<double>(blocks));
  size_patch_buffers(blocks);  // (done by set_operator unless patch_hops was set after it)
  patch_.clear();
  patch_boundary_.clear();
  for (std::size_t i = 0; i < blocks; ++i)
    if (changed_rows[i]) {
      patch_mark_[i] = 1;
      patch_.push_back(static_cast<int>(i));
    }
  bool ok = !patch_.empty() && patch_.size() <= limit;
  std::size_t layer_begin = 0;
  for (int hop = 1; ok && hop <= patch_hops + 1; ++hop) {
    // Rows one coupling beyond the last layer: the next layer, or, after
    // the last hop, the boundary.
    const bool boundary = hop > patch_hops;
    std::vector<int>& into = boundary ? patch_boundary_ : patch_;
    const std::size_t layer_end = patch_.size();
    for (std::size_t k = layer_begin; k < layer_end && ok; ++k) {
      neighbours_.clear();
      ok = a.append_neighbours(patch_[k], neighbours_);
      for (const int j : neighbours_)
        if (!patch_mark_[j]) {
          patch_mark_[j] = 1;
          into.push_back(j);
        }
    }
    layer_begin = layer_end;
    ok = ok && patch_.size() <= limit;
  }
  if (!ok) {
    for (const int i : patch_) patch_mark_[i] = 0;
    for (const int i : patch_boundary_) patch_mark_[i] = 0;
    return false;
  }
  std::sort(patch_.begin(), patch_.end());
  std::sort(patch_boundary_.begin(), patch_boundary_.end());
  return true;
}

// PCG on the patch rows with x held elsewhere (the patch's principal
// submatrix: SPD as A is), then the residual of the rows just outside
// corrected for the patch's change. Sums run over fixed chunks of the sorted
// patch: the same bits for any thread count. Returns ‖b − A·x‖² over all rows.
double PcgSolver::solve_on_patch(VecX& x, double bnorm, SolveReport& report) {
  const LinearOperator& a = *a_;
  const std::size_t n = static_cast<std::size_t>(x.size()), rows = patch_.size();
  report.patch_rows = static_cast<int>(rows);
  auto row = [&](std::size_t k) { return static_cast<std::size_t>(patch_[k]); };
  double rz = chunked_sum(rows, [&](std::size_t begin, std::size_t end) {
    double share = 0;
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t i = row(k);
      pre_->apply_rows(i, i + 1, r_, z_);
      patch_p_.segment<6>(6 * i) = z_.segment<6>(6 * i);
      share += r_.segment<6>(6 * i).dot(z_.segment<6>(6 * i));
    }
    return share;
  });
  // Half the global target: the rows outside keep the last solve's residual.
  const double target = 0.5 * tolerance * bnorm;
  for (int it = 1; it <= 4 * patch_hops; ++it) {
    const double pap = chunked_sum(rows, [&](std::size_t begin, std::size_t end) {
      double share = 0;
      for (std::size_t k = begin; k < end; ++k) {
        const int i = patch_[k];
        a.multiply_rows(i, i + 1, patch_p_, ap_);
        share += patch_p_.segment<6>(6 * i).dot(ap_.segment<6>(6 * i));
      }
      return share;
    });
    report.patch_iterations = it;
    if (!std::isfinite(pap) || !(pap > 0) || !(rz > 0)) break;  // the global PCG reports the breakdown
    const double alpha = rz / pap;
    const auto [rr_patch, rz_next] =
        chunked_sums(rows, [&](std::size_t begin, std::size_t end, double& r2, double& r_z) {
          for (std::size_t k = begin; k < end; ++k) {
            const std::size_t i = row(k);
            const Vec6 step = alpha * patch_p_.segment<6>(6 * i);
            x.segment<6>(6 * i) += step;
            patch_d_.segment<6>(6 * i) += step;
            r_.segment<6>(6 * i) -= alpha * ap_.segment<6>(6 * i);
            r2 += r_.segment<6>(6 * i).squaredNorm();
            pre_->apply_rows(i, i + 1, r_, z_);
            r_z += r_.segment<6>(6 * i).dot(z_.segment<6>(6 * i));
          }
        });
    if (!std::isfinite(rr_patch) || rr_patch <= target * target) break;
    const double beta = rz_next / rz;
    rz = rz_next;
    parallel_for_each(
        rows,
        [&](std::size_t k) {
          const std::size_t i = row(k);
          patch_p_.segment<6>(6 * i) = z_.segment<6>(6 * i) + beta * patch_p_.segment<6>(6 * i);
        },
        kPcgChunk);
  }
  // The rows just outside: r −= A·d there (d is zero off the patch).
  parallel_for_each(
      patch_boundary_.size(),
      [&](std::size_t k) {
        const int i = patch_boundary_[k];
        a.multiply_rows(i, i + 1, patch_d_, ap_);
        r_.segment<6>(6 * i) -= ap_.segment<6>(6 * i);
        patch_mark_[i] = 0;
      },
      kPcgChunk);
  parallel_for_each(
      rows,
      [&](std::size_t k) {
        const std::size_t i = row(k);
        patch_p_.segment<6>(6 * i).setZero();
        patch_d_.segment<6>(6 * i).setZero();
        patch_mark_[i] = 0;
      },
      kPcgChunk);
  return chunked_sum(n / 6, [&](std::size_t begin, std::size_t end) {
    return r_.segment(6 * begin, 6 * (end - begin)).squaredNorm();
  });
}

}  // namespace dda
