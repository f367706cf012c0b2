// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "loading/load_frequency.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "core/error.hpp"
#include "core/types.hpp"
#include "world/world_state.hpp"

namespace dda {

namespace {

using Samples = std::vector<std::pair<double, double>>;

// The wave signal of an input (the header): a force or velocity as it is, a
// displacement differentiated (constant between samples: a step at each
// sample), an acceleration integrated from rest (exactly at the samples).
Samples wave_signal(const LoadSignal& s) {
  const Samples& in = s.samples;
  Samples out;
  switch (s.kind) {
    case SignalKind::Force:
    case SignalKind::Velocity:
      return in;
    case SignalKind::Displacement:
      for (std::size_t j = 0; j + 1 < in.size(); ++j) {
        const double h = in[j + 1].first - in[j].first;
        if (!(h > 0)) continue;
        const double v = (in[j + 1].second - in[j].second) / h;
        out.emplace_back(in[j].first, v);
        out.emplace_back(in[j + 1].first, v);
      }
      return out;
    case SignalKind::Acceleration: {
      double v = 0;
      out.emplace_back(in.front().first, 0.0);
      for (std::size_t j = 0; j + 1 < in.size(); ++j) {
        v += 0.5 * (in[j].second + in[j + 1].second) * (in[j + 1].first - in[j].first);
        out.emplace_back(in[j + 1].first, v);
      }
      return out;
    }
  }
  return in;
}

// |∫ s(t)·e^{−2πift} dt|² of the piecewise-linear s, exactly.
double energy_density(const Samples& s, double f) {
  const std::complex<double> iw(0, -2 * kPi * f);
  std::complex<double> sum = 0;
  for (std::size_t j = 0; j + 1 < s.size(); ++j) {
    const auto [t0, v0] = s[j];
    const auto [t1, v1] = s[j + 1];
    const double h = t1 - t0;
    if (!(h > 0)) continue;
    const std::complex<double> z = iw * h;
    std::complex<double> i0, i1;  // ∫₀ʰ e^{iwτ}dτ, ∫₀ʰ τ·e^{iwτ}dτ
    if (std::abs(z) < 1e-3) {
      i0 = h * (1.0 + z / 2.0 + z * z / 6.0);
      i1 = h * h * (0.5 + z / 3.0 + z * z / 8.0);
    } else {
      const std::complex<double> e = std::exp(z);
      i0 = (e - 1.0) / iw;
      i1 = (h * e - i0) / iw;
    }
    sum += std::exp(iw * t0) * (v0 * i0 + (v1 - v0) / h * i1);
  }
  return std::norm(sum);
}

// The frequency below which `share` of the energy lies (trapezoids on the
// energy density, of width step(f) from f), or f_end.
template <class Step>
double energy_quantile(const Samples& s, Step step, double f_end, double share) {
  double cumulative = 0, f = 0, previous = energy_density(s, 0);
  while (f < f_end) {
    const double df = std::min(step(f), f_end - f);
    const double density = energy_density(s, f + df);
    const double area = 0.5 * df * (previous + density);
    if (cumulative + area >= share) return f + df * (share - cumulative) / area;
    cumulative += area;
    previous = density;
    f += df;
  }
  return f_end;
}

}  // namespace

double signal_frequency(const LoadSignal& signal) {
  if (signal.samples.size() < 2) return 0;
  for (const auto& [t, v] : signal.samples)
    if (!std::isfinite(t) || !std::isfinite(v)) throw Error(msg(signal.what, ": a sample is not finite"));
  // Less its final value: what a load holds once it has risen (a load
  // switched on and kept, the end of a ramp) is static, and a history holds
  // its last value after its end; what varies before is the wave.
  Samples s = wave_signal(signal);
  if (s.size() < 2) return 0;
  const double last = s.back().second;
  for (auto& p : s) p.second -= last;
  // A load switched on at its first sample and held (a jump to its final
  // value, however fast) is static: nothing of it varies after the start.
  if (std::all_of(s.begin() + 1, s.end(), [](const auto& p) { return p.second == 0; })) return 0;
  // The whole energy (one-sided: ½∫s²dt) and the smallest sample spacing.
  double total = 0, spacing = 1e300;
  for (std::size_t j = 0; j + 1 < s.size(); ++j) {
    const double h = s[j + 1].first - s[j].first, a = s[j].second, b = s[j + 1].second;
    if (h > 0) spacing = std::min(spacing, h);
    total += 0.5 * h * (a * a + a * b + b * b) / 3;
  }
  const double low = std::min_element(s.begin(), s.end(), [](auto& x, auto& y) { return x.second < y.second; })->second;
  const double high =
      std::max_element(s.begin(), s.end(), [](auto& x, auto& y) { return x.second < y.second; })->second;
  if (!(total > 0) || high - low <= 1e-12 * std::max(std::abs(high), std::abs(low))) return 0;
  // Its spectrum varies over 1/duration, up to where the samples can say
  // anything (half their finest rate, which one short interval can make
  // very high). A coarse pass finds the frequency roughly: steps of an
  // eighth of 1/duration, so that no lobe of the spectrum is stepped over
  // where the energy lies, growing to 1 % of the frequency far above it (a
  // few thousand steps up to any rate). A fine one (500 steps below it)
  // finds it exactly.
  const double duration = s.back().first - s.front().first, f_end = 0.5 / spacing;
  const double share = kEnergyShare * total;
  const double coarse = energy_quantile(
      s, [&](double f) { return std::max(1 / (8 * duration), 0.01 * f); }, f_end, share);
  return energy_quantile(
      s, [&](double) { return coarse / 500; }, f_end, share);
}

LoadFrequency dynamic_load_frequency(const WorldState& w, std::span<const LoadSignal> script_signals) {
  if (w.controls.max_frequency > 0) return {w.controls.max_frequency, "max_frequency (stated)"};
  std::vector<LoadSignal> signals = w.loads.dynamic_signals();
  for (LoadSignal& s : w.boundaries.dynamic_signals()) signals.push_back(std::move(s));
  signals.insert(signals.end(), script_signals.begin(), script_signals.end());
  LoadFrequency result;
  std::vector<const LoadSignal*> seen;  // the same history on many points is analysed once
  for (const LoadSignal& s : signals) {
    bool repeated = false;
    for (const LoadSignal* p : seen) repeated = repeated || (p->kind == s.kind && p->samples == s.samples);
    if (repeated) continue;
    seen.push_back(&s);
    const double f = signal_frequency(s);
    if (f > result.frequency) result = {f, s.what};
  }
  return result;
}

}  // namespace dda
