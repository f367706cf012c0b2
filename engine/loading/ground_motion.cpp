// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "loading/ground_motion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/memory.hpp"

namespace dda {

namespace {

constexpr double kStandardGravity = 9.80665;  // m/s²

std::ifstream open_record(const std::string& path, const char* what) {
  std::ifstream in(path);
  if (!in)
    throw Error(msg(what, " '", path,
                    "': cannot open the file (check the path; relative paths start at the "
                    "folder dda runs in)"));
  return in;
}

// The number after "INTERVALS OF" in a header line, if any.
double header_spacing(const std::string& line) {
  std::string upper = line;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  const auto at = upper.find("INTERVALS OF");
  if (at == std::string::npos) return 0;
  std::istringstream rest(line.substr(at + 12));
  double dt = 0;
  rest >> dt;
  return rest ? dt : 0;
}

// The count of a header line "%  1845  INSTRUMENT AND BASELINE CORRECTED
// DATA" (the corrected values that follow), or -1.
long header_count(const std::string& line) {
  std::string upper = line;
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  const auto at = upper.find("CORRECTED DATA");
  if (at == std::string::npos) return -1;
  std::istringstream words(line.substr(1, at));
  long n = -1;
  words >> n;
  return words && n >= 0 ? n : -1;
}

double smallest_spacing(const std::vector<std::pair<double, double>>& samples) {
  double dt = INFINITY;
  for (std::size_t i = 1; i < samples.size(); ++i) dt = std::min(dt, samples[i].first - samples[i - 1].first);
  return dt;
}

}  // namespace

AccelerationUnit parse_acceleration_unit(const std::string& name) {
  if (name == "m/s2" || name == "m/s^2" || name == "m/s²") return AccelerationUnit::MetrePerSecond2;
  if (name == "cm/s2" || name == "cm/s^2" || name == "cm/s²" || name == "gal")
    return AccelerationUnit::CentimetrePerSecond2;
  if (name == "g") return AccelerationUnit::G;
  throw Error(msg("acceleration unit '", name, "' is not known: give \"m/s2\", \"cm/s2\" (or \"gal\") or \"g\""));
}

double metres_per_second2(AccelerationUnit unit) {
  switch (unit) {
    case AccelerationUnit::MetrePerSecond2:
      return 1;
    case AccelerationUnit::CentimetrePerSecond2:
      return 0.01;
    case AccelerationUnit::G:
      return kStandardGravity;
  }
  return 1;
}

GroundMotion::GroundMotion(double dt, std::vector<double> acceleration, std::string source)
    : dt_(dt), acceleration_(std::move(acceleration)), source_(std::move(source)) {
  if (!(dt_ > 0) || !std::isfinite(dt_)) throw Error(msg(source_, ": the time step must be positive, got ", dt_));
  if (acceleration_.size() < 2)
    throw Error(msg(source_, ": needs at least two acceleration samples, got ", acceleration_.size()));
  for (std::size_t i = 0; i < acceleration_.size(); ++i)
    if (!std::isfinite(acceleration_[i])) throw Error(msg(source_, ": acceleration sample ", i + 1, " is not finite"));
  integrate();
}

GroundMotion GroundMotion::from_samples(const std::vector<std::pair<double, double>>& samples, double dt,
                                        std::string source) {
  if (samples.size() < 2) throw Error(msg(source, ": needs at least two (time, acceleration) samples"));
  const History h(samples, source);
  const double t0 = samples.front().first, t1 = samples.back().first;
  if (!(dt > 0) || !std::isfinite(dt)) throw Error(msg(source, ": the time step must be positive, got ", dt));
  // The count in floating point first: a tiny dt or a huge span must not
  // wrap it (or ask for more memory than there is) before anything is allocated.
  const double count = std::floor((t1 - t0) / dt * (1 + 1e-12)) + 1;
  const double bytes = count * kBytesPerSample;
  if (!std::isfinite(count) || count > 1e15)
    throw Error(msg(source, ": resampling ", t1 - t0, " s at dt = ", dt, " s gives ", count,
                    " samples: give a larger dt (the samples' smallest spacing is ", smallest_spacing(samples), " s)"));
  check_memory_need(bytes, memory_headroom(), msg(source, ": resampling to dt = ", dt, " s"),
                    msg(count, " samples over ", t1 - t0, " s, about ", kBytesPerSample, " bytes each"),
                    msg("give a larger dt (the samples' smallest spacing is ", smallest_spacing(samples), " s)"));
  const auto n = static_cast<std::size_t>(count);
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = h.value(t0 + static_cast<double>(i) * dt);
  return GroundMotion(dt, std::move(a), std::move(source));
}

GroundMotion GroundMotion::read_accelerogram(const std::string& path, AccelerationUnit unit, double dt) {
  std::ifstream in = open_record(path, "accelerogram");
  return parse_accelerogram(in, path, unit, dt);
}

GroundMotion GroundMotion::parse_accelerogram(std::istream& in, const std::string& path, AccelerationUnit unit,
                                              double dt) {
  std::vector<double> a;
  double header_dt = 0;
  long announced = -1;  // the header's count of values, if it gives one
  std::string line;
  int line_number = 0;
  const double factor = metres_per_second2(unit);
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line[0] == '%') {
      if (header_dt == 0) header_dt = header_spacing(line);
      if (announced < 0) announced = header_count(line);
      continue;
    }
    std::istringstream values(line);
    std::string word;
    while (values >> word) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0')
        throw Error(msg("accelerogram '", path, "' line ", line_number, ": '", printable(word, 40),
                        "' is not a number (header lines must start with %)"));
      a.push_back(v * factor);
    }
  }
  if (announced >= 0 && static_cast<long>(a.size()) < announced)
    throw Error(msg("accelerogram '", path, "' is truncated: its header announces ", announced, " values, it holds ",
                    a.size(), " (was it copied or downloaded completely?)"));
  const double spacing = header_dt > 0 ? header_dt : dt;
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw Error(msg("accelerogram '", path, "': the header gives no spacing (\"INTERVALS OF ... SEC\"): give dt"));
  GroundMotion g(spacing, std::move(a), path);
  return dt > 0 && dt != spacing ? g.resampled(dt) : g;
}

GroundMotion GroundMotion::read_csv(const std::string& path, AccelerationUnit unit, double dt) {
  std::ifstream in = open_record(path, "accelerogram CSV");
  return parse_csv(in, path, unit, dt);
}

GroundMotion GroundMotion::parse_csv(std::istream& in, const std::string& path, AccelerationUnit unit, double dt) {
  std::vector<std::pair<double, double>> samples;
  std::string line;
  int line_number = 0;
  const double factor = metres_per_second2(unit);
  while (std::getline(in, line)) {
    ++line_number;
    std::replace_if(
        line.begin(), line.end(), [](char c) { return c == ',' || c == ';' || c == '\t'; }, ' ');
    std::istringstream fields(line);
    std::string first;
    if (!(fields >> first) || first[0] == '#' || first[0] == '%') continue;
    std::string second, extra;
    fields >> second >> extra;
    char *end1 = nullptr, *end2 = nullptr;
    const double t = std::strtod(first.c_str(), &end1);
    const double v = second.empty() ? 0 : std::strtod(second.c_str(), &end2);
    const bool numbers = end1 != first.c_str() && *end1 == '\0' && !second.empty() && *end2 == '\0';
    if (!numbers && samples.empty() && line_number == 1) continue;  // a heading
    if (!numbers || !extra.empty())
      throw Error(msg("accelerogram CSV '", path, "' line ", line_number,
                      ": expected two numbers, time (s) and acceleration, got '", printable(line), "'"));
    if (!std::isfinite(t) || !std::isfinite(v))
      throw Error(
          msg("accelerogram CSV '", path, "' line ", line_number, ": the time or the acceleration is not finite"));
    if (!samples.empty() && !(t > samples.back().first))
      throw Error(msg("accelerogram CSV '", path, "' line ", line_number, ": times must increase (t = ", t,
                      " after t = ", samples.back().first, ")"));
    samples.emplace_back(t, v * factor);
  }
  if (samples.size() < 2)
    throw Error(msg("accelerogram CSV '", path, "': needs at least two (time, acceleration) rows"));
  return from_samples(samples, dt > 0 ? dt : smallest_spacing(samples), path);
}

GroundMotion GroundMotion::resampled(double dt) const {
  std::vector<std::pair<double, double>> samples(size());
  for (std::size_t i = 0; i < size(); ++i) samples[i] = {static_cast<double>(i) * dt_, acceleration_[i]};
  return from_samples(samples, dt, source_);
}

GroundMotion GroundMotion::scaled(double factor) const {
  if (!std::isfinite(factor)) throw Error(msg(source_, ": the scale factor is not finite"));
  std::vector<double> a = acceleration_;
  for (double& x : a) x *= factor;
  return GroundMotion(dt_, std::move(a), source_);
}

GroundMotion GroundMotion::baseline_corrected(int order) const {
  if (order < 0 || order > 6)
    throw Error(msg(source_, ": the baseline polynomial's order must be 0 (none) to 6, got ", order));
  if (order == 0) return *this;
  // Least squares p(t) = Σ c_k t^k, k = 1..order, to the velocity, in the
  // scaled time s = t/T (well conditioned), through QR.
  const auto n = static_cast<Eigen::Index>(size());
  const double T = duration();
  Eigen::MatrixXd basis(n, order);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) * dt_ / T;
    for (int k = 0; k < order; ++k) basis(i, k) = std::pow(s, k + 1);
    v[i] = velocity_[i];
  }
  const Eigen::VectorXd c = basis.colPivHouseholderQr().solve(v);
  std::vector<double> a = acceleration_;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = static_cast<double>(i) * dt_ / T;
    double slope = 0;  // dp/dt
    for (int k = 0; k < order; ++k) slope += c[k] * (k + 1) * std::pow(s, k) / T;
    a[i] -= slope;
  }
  return GroundMotion(dt_, std::move(a), source_);
}

void GroundMotion::integrate() {
  const std::size_t n = size();
  velocity_.assign(n, 0.0);
  displacement_.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const double a0 = acceleration_[i - 1], a1 = acceleration_[i];
    velocity_[i] = velocity_[i - 1] + 0.5 * dt_ * (a0 + a1);
    displacement_[i] = displacement_[i - 1] + dt_ * velocity_[i - 1] + dt_ * dt_ * (a0 / 3 + a1 / 6);
  }
}

GroundMotion::Peak GroundMotion::peak(const std::vector<double>& x) const {
  std::size_t at = 0;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (std::abs(x[i]) > std::abs(x[at])) at = i;
  return {x[at], static_cast<double>(at) * dt_};
}

History GroundMotion::history(const std::vector<double>& x, const char* what) const {
  std::vector<std::pair<double, double>> points(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) points[i] = {static_cast<double>(i) * dt_, x[i]};
  return History(std::move(points), msg(source_, " ", what));
}

}  // namespace dda
