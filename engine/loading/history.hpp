// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// A time history: piecewise linear through (t, value) points, constant
// before the first and after the last. Loads that follow a history are
// evaluated by the engine at the end of each step (t + Δt), so a step that
// is cut and redone still sees the right value.
#include <string>
#include <utility>
#include <vector>

namespace dda {

class History {
 public:
  History() = default;  // zero for all t
  // Throws dda::Error (naming `what`) for no points, non-finite values or
  // times that do not increase.
  explicit History(std::vector<std::pair<double, double>> points, const std::string& what = "history");
  static History constant(double value);

  double value(double t) const;
  // ∫₀ᵗ value dt (value before the first point is the first value).
  double integral(double t) const;
  // ∫₀ᵗ∫₀ˢ value dτ ds, exact for the piecewise-linear value (a ground
  // acceleration to its displacement, from rest at t = 0).
  double double_integral(double t) const;
  bool empty() const { return t_.empty(); }
  // The (t, value) points it was made from.
  std::vector<std::pair<double, double>> points() const;
  // Checkpoints (core/archive.hpp): the points and their integral; read,
  // the points are checked as the constructor checks them and both
  // integrals made again from them (the same bits).
  template <class Archive>
  void fields(Archive& ar) {
    ar(t_, v_, area_);
    if constexpr (Archive::reading) check_and_integrate(ar.what());
  }

 private:
  // The constructor's checks (throwing dda::Error naming `what`) and the integrals.
  void check_and_integrate(const std::string& what);
  std::vector<double> t_, v_, area_;  // area_[i] = ∫₀^{t_i}
  std::vector<double> area2_;         // area2_[i] = ∫₀^{t_i} ∫₀ˢ
};

}  // namespace dda
