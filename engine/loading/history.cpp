// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "loading/history.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace dda {

History::History(std::vector<std::pair<double, double>> points, const std::string& what) {
  if (points.empty()) throw Error(msg(what, ": needs at least one (t, value) point"));
  for (const auto& [t, v] : points) t_.push_back(t), v_.push_back(v);
  check_and_integrate(what);
}

void History::check_and_integrate(const std::string& what) {
  if (t_.size() != v_.size())
    throw Error(msg(what, " is damaged: a history has ", t_.size(), " times and ", v_.size(), " values"));
  for (std::size_t i = 0; i < t_.size(); ++i) {
    const double t = t_[i], v = v_[i];
    if (!std::isfinite(t) || !std::isfinite(v))
      throw Error(msg(what, ": point ", i + 1, " is not finite (t = ", t, ", value = ", v, ")"));
    if (i > 0 && !(t > t_[i - 1]))
      throw Error(msg(what, ": times must increase, but point ", i + 1, " has t = ", t, " after t = ", t_[i - 1]));
  }
  area_.resize(t_.size());
  area2_.resize(t_.size());
  if (t_.empty()) return;
  area_[0] = v_[0] * t_[0];  // constant first value from t = 0
  for (std::size_t i = 1; i < t_.size(); ++i) area_[i] = area_[i - 1] + 0.5 * (v_[i] + v_[i - 1]) * (t_[i] - t_[i - 1]);
  area2_[0] = 0.5 * v_[0] * t_[0] * t_[0];
  for (std::size_t i = 1; i < t_.size(); ++i) {
    const double h = t_[i] - t_[i - 1];
    area2_[i] = area2_[i - 1] + area_[i - 1] * h + h * h * (v_[i - 1] / 3 + v_[i] / 6);
  }
}

History History::constant(double value) { return History({{0.0, value}}, "constant history"); }

double History::value(double t) const {
  if (t_.empty()) return 0;
  if (t <= t_.front()) return v_.front();
  if (t >= t_.back()) return v_.back();
  const std::size_t i = std::upper_bound(t_.begin(), t_.end(), t) - t_.begin();  // t_[i-1] < t ≤ t_[i]
  const double s = (t - t_[i - 1]) / (t_[i] - t_[i - 1]);
  return v_[i - 1] + s * (v_[i] - v_[i - 1]);
}

double History::double_integral(double t) const {
  if (t_.empty()) return 0;
  if (t <= t_.front()) return 0.5 * v_.front() * t * t;
  if (t >= t_.back()) {
    const double s = t - t_.back();
    return area2_.back() + area_.back() * s + 0.5 * v_.back() * s * s;
  }
  const std::size_t i = std::upper_bound(t_.begin(), t_.end(), t) - t_.begin();
  const double s = t - t_[i - 1], slope = (v_[i] - v_[i - 1]) / (t_[i] - t_[i - 1]);
  return area2_[i - 1] + area_[i - 1] * s + v_[i - 1] * s * s / 2 + slope * s * s * s / 6;
}

double History::integral(double t) const {
  if (t_.empty()) return 0;
  if (t <= t_.front()) return v_.front() * t;
  if (t >= t_.back()) return area_.back() + v_.back() * (t - t_.back());
  const std::size_t i = std::upper_bound(t_.begin(), t_.end(), t) - t_.begin();
  return area_[i - 1] + 0.5 * (v_[i - 1] + value(t)) * (t - t_[i - 1]);
}

std::vector<std::pair<double, double>> History::points() const {
  std::vector<std::pair<double, double>> p;
  for (std::size_t i = 0; i < t_.size(); ++i) p.emplace_back(t_[i], v_[i]);
  return p;
}

}  // namespace dda
