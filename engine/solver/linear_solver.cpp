// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "solver/linear_solver.hpp"

#include <cmath>

#include "core/parallel.hpp"
#include "solver/solver_choice.hpp"

namespace dda {

std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& /*settings*/) {
  return std::make_unique<AutoSolver>();
}

double deterministic_dot(const VecX& a, const VecX& b) {
  const std::size_t blocks = static_cast<std::size_t>(a.size()) / 6;
  return deterministic_sum<double>(blocks, [&](std::size_t i) { return a.segment<6>(6 * i).dot(b.segment<6>(6 * i)); });
}

bool invert_spd6(const Mat6& a, Mat6& inverse) {
  // a = L·Lᵀ (lower triangle of a), then L⁻¹ by forward substitution, then a⁻¹ = L⁻ᵀ·L⁻¹.
  double l[6][6] = {}, li[6][6] = {};
  for (int j = 0; j < 6; ++j) {
    double d = a(j, j);
    for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
    if (!(d > 0) || !std::isfinite(d)) {
      // Not positive definite (should not happen: every block has inertia).
      // Fall back to the diagonal so the solve can still report what happened.
      inverse.setZero();
      for (int k = 0; k < 6; ++k) inverse(k, k) = a(k, k) > 0 ? 1.0 / a(k, k) : 1.0;
      return false;
    }
    l[j][j] = std::sqrt(d);
    for (int i = j + 1; i < 6; ++i) {
      double s = a(i, j);
      for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
      l[i][j] = s / l[j][j];
    }
  }
  for (int j = 0; j < 6; ++j) {
    li[j][j] = 1.0 / l[j][j];
    for (int i = j + 1; i < 6; ++i) {
      double s = 0;
      for (int k = j; k < i; ++k) s -= l[i][k] * li[k][j];
      li[i][j] = s / l[i][i];
    }
  }
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = 0;
      for (int k = i; k < 6; ++k) s += li[k][i] * li[k][j];
      inverse(i, j) = s;
      inverse(j, i) = s;
    }
  return true;
}

}  // namespace dda
