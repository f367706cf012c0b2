#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "solver/linear_solver.hpp"

namespace dda {

double deterministic_dot(const VecX& a, const VecX& b) {
  const std::size_t blocks = static_cast<std::size_t>(a.size()) / 6;
  return deterministic_sum<double>(blocks, [&](std::size_t i) { return a.segment<6>(6 * i).dot(b.segment<6>(6 * i)); });
}

void BlockJacobi::setup(const BlockSparseMatrix& a) {
  inverse_.resize(a.rows());
  parallel_for_each(a.rows(), [&](std::size_t i) {
    const Mat6& d = a.value(a.diagonal(static_cast<int>(i)));
    Eigen::LLT<Mat6> llt(d);
    if (llt.info() == Eigen::Success) {
      inverse_[i] = llt.solve(Mat6::Identity());
    } else {
      // Not positive definite (should not happen: every block has inertia).
      // Fall back to the diagonal so the solve can still report what happened.
      inverse_[i] = Mat6::Zero();
      for (int k = 0; k < 6; ++k) inverse_[i](k, k) = d(k, k) != 0 ? 1.0 / d(k, k) : 1.0;
    }
  });
}

void BlockJacobi::apply(const VecX& r, VecX& z) const {
  z.resize(r.size());
  parallel_for_each(inverse_.size(), [&](std::size_t i) { z.segment<6>(6 * i).noalias() = inverse_[i] * r.segment<6>(6 * i); }, 128);
}

PcgSolver::PcgSolver(std::unique_ptr<Preconditioner> pre) : pre_(std::move(pre)) {}

void PcgSolver::set_operator(const BlockSparseMatrix& a) {
  a_ = &a;
  pre_->setup(a);
}

SolveReport PcgSolver::solve(const VecX& b, VecX& x) {
  DDA_ASSERT(a_ != nullptr, "PcgSolver::solve before set_operator");
  SolveReport report;
  const std::size_t n = static_cast<std::size_t>(b.size());
  if (x.size() != b.size()) x = VecX::Zero(b.size());
  const double bnorm = std::sqrt(deterministic_dot(b, b));
  if (!std::isfinite(bnorm)) {
    report.finite = false;
    return report;
  }
  if (bnorm == 0) {
    x.setZero();
    report.converged = true;
    return report;
  }
  a_->multiply(x, ap_);
  r_ = b - ap_;
  double rnorm = std::sqrt(deterministic_dot(r_, r_));
  report.relative_residual = rnorm / bnorm;
  if (report.relative_residual <= tolerance) {
    report.converged = true;
    return report;
  }
  pre_->apply(r_, z_);
  p_ = z_;
  double rz = deterministic_dot(r_, z_);
  const std::size_t blocks = n / 6;
  for (int it = 1; it <= max_iterations; ++it) {
    a_->multiply(p_, ap_);
    const double pap = deterministic_dot(p_, ap_);
    if (!std::isfinite(pap) || pap <= 0) {
      report.finite = std::isfinite(pap);
      report.iterations = it;
      return report;  // not converged: breakdown (matrix not SPD, or NaN)
    }
    const double alpha = rz / pap;
    parallel_for_each(blocks, [&](std::size_t i) {
      x.segment<6>(6 * i) += alpha * p_.segment<6>(6 * i);
      r_.segment<6>(6 * i) -= alpha * ap_.segment<6>(6 * i);
    }, 256);
    rnorm = std::sqrt(deterministic_dot(r_, r_));
    report.iterations = it;
    report.relative_residual = rnorm / bnorm;
    if (monitor) monitor(it, report.relative_residual);
    if (!std::isfinite(rnorm)) {
      report.finite = false;
      return report;
    }
    if (report.relative_residual <= tolerance) {
      report.converged = true;
      return report;
    }
    pre_->apply(r_, z_);
    const double rz_next = deterministic_dot(r_, z_);
    const double beta = rz_next / rz;
    rz = rz_next;
    parallel_for_each(blocks, [&](std::size_t i) { p_.segment<6>(6 * i) = z_.segment<6>(6 * i) + beta * p_.segment<6>(6 * i); }, 256);
  }
  return report;
}

SolveReport DirectSolver::solve(const VecX& b, VecX& x) {
  DDA_ASSERT(a_ != nullptr, "DirectSolver::solve before set_operator");
  SolveReport report;
  Eigen::SparseMatrix<double> a = a_->to_sparse();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
  if (ldlt.info() != Eigen::Success) return report;
  x = ldlt.solve(b);
  report.finite = x.allFinite();
  report.converged = report.finite;
  const double bn = b.norm();
  report.relative_residual = bn > 0 ? (b - a * x).norm() / bn : 0;
  report.iterations = 1;
  return report;
}

}  // namespace dda
