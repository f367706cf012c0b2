// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "geometry/joint_sets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "geometry/random.hpp"

namespace dda::geometry {
namespace {

// Generous limits that no usable model reaches but a typo (spacing 1e-9)
// does: past them we refuse instead of exhausting memory.
constexpr double kMaxLinesPerSet = 1e5;
constexpr double kMaxTracesPerSet = 2e7;

// Tags of the random streams, so the gap after line k and line k's own
// numbers never share a stream.
constexpr std::uint64_t kGapStream = 1;
constexpr std::uint64_t kLineStream = 2;

Vec2 rotate(const Vec2& v, double angle) {
  if (angle == 0) return v;
  const double c = std::cos(angle), s = std::sin(angle);
  return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
}

// Liang–Barsky: narrows [t0, t1] to where p + t·d lies in the box [lo, hi].
bool clip_to_box(const Vec2& p, const Vec2& d, const Vec2& lo, const Vec2& hi, double& t0, double& t1) {
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0) {
      if (p[axis] < lo[axis] || p[axis] > hi[axis]) return false;
      continue;
    }
    double ta = (lo[axis] - p[axis]) / d[axis], tb = (hi[axis] - p[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1;
}

// Origins farther than this many spacings (across the joints) or trace
// periods (along them) from the domain are refused: fuzzing found origins at
// 1e308 overflowing the line numbers and never reaching the box.
constexpr double kMaxOriginSpacings = 1e15;

// A sample of a positive quantity: mean + sd·N(0,1), truncated at 10 % of the mean.
double positive_sample(SplitMix64& rng, double mean, double sd) {
  if (sd <= 0) return mean;
  return std::max(mean + sd * rng.normal(), 0.1 * mean);
}

SplitMix64 stream(const JointSet& set, int set_index, std::uint64_t tag, long long k) {
  return SplitMix64(derive_seed({set.seed, static_cast<std::uint64_t>(set_index), tag, static_cast<std::uint64_t>(k)}));
}

// Offsets (along the set's normal, from its origin) of the joint lines that
// can reach [pmin, pmax], with their line numbers. Line 0 passes through the
// origin; with spacing variation the gap between line k and k+1 is drawn from
// its own stream, so every line keeps its place whatever the box.
std::vector<std::pair<long long, double>> line_offsets(const JointSet& set, int set_index, double pmin, double pmax) {
  std::vector<std::pair<long long, double>> lines;
  const double s = set.spacing;
  // Line numbers are counted from the origin: they must stay exact in a
  // double (and fit a long long) however far the origin lies from the box.
  const double far = std::max(std::abs(pmin), std::abs(pmax)) / s;
  if (!(far <= kMaxOriginSpacings))
    throw Error(msg("joint set ", set_index + 1, ": its origin lies about ", far, " spacings from the domain (limit ",
                    kMaxOriginSpacings, "); place the origin near the domain"));
  if (set.spacing_sd <= 0) {
    const double k0 = std::ceil(pmin / s), k1 = std::floor(pmax / s);
    for (double k = k0; k <= k1; k += 1) lines.push_back({static_cast<long long>(k), k * s});
    return lines;
  }
  auto gap = [&](long long k) {
    SplitMix64 rng = stream(set, set_index, kGapStream, k);
    return positive_sample(rng, s, set.spacing_sd);
  };
  double o = 0;
  for (long long k = 0; o <= pmax; ++k) {
    if (o >= pmin) lines.push_back({k, o});
    o += gap(k);
  }
  o = 0;
  for (long long k = 0;;) {
    o -= gap(k - 1);
    --k;
    if (o < pmin) break;
    if (o <= pmax) lines.push_back({k, o});
  }
  std::sort(lines.begin(), lines.end());
  return lines;
}

}  // namespace

Vec2 dip_direction(double dip_deg) {
  double r = std::fmod(dip_deg, 360.0);  // exact
  if (r < 0) r += 360.0;
  if (r == 0) return Vec2(1, 0);
  if (r == 90) return Vec2(0, 1);
  if (r == 180) return Vec2(-1, 0);
  if (r == 270) return Vec2(0, -1);
  const double rad = deg_to_rad(r);
  return Vec2(std::cos(rad), std::sin(rad));
}

void validate_joint_set(const JointSet& set, int index, double box_size) {
  const std::string what = msg("joint set ", index + 1);
  if (!std::isfinite(set.dip_deg)) throw Error(msg(what, ": dip angle is not a finite number (", set.dip_deg, ")"));
  if (!std::isfinite(set.spacing) || !(set.spacing > 0))
    throw Error(msg(what, ": spacing must be a positive finite length, got ", set.spacing));
  if (!std::isfinite(set.origin.x()) || !std::isfinite(set.origin.y()))
    throw Error(msg(what, ": origin has a non-finite coordinate"));
  if (set.joint_material < 0) throw Error(msg(what, ": joint material must be ≥ 0, got ", set.joint_material));
  auto check_non_negative = [&](double v, const char* name) {
    if (!std::isfinite(v) || v < 0) throw Error(msg(what, ": ", name, " must be a finite length ≥ 0, got ", v));
  };
  check_non_negative(set.trace_length, "trace length");
  check_non_negative(set.bridge_length, "bridge length");
  check_non_negative(set.spacing_sd, "spacing standard deviation");
  check_non_negative(set.trace_sd, "trace standard deviation");
  if (!std::isfinite(set.dip_sd_deg) || set.dip_sd_deg < 0)
    throw Error(msg(what, ": dip standard deviation must be a finite angle ≥ 0, got ", set.dip_sd_deg));
  if (set.trace_length == 0 && set.bridge_length > 0)
    throw Error(msg(what, ": a bridge length needs a trace length (trace 0 means persistent joints)"));
  if (set.trace_length == 0 && set.trace_sd > 0)
    throw Error(msg(what, ": a trace standard deviation needs a trace length (trace 0 means persistent joints)"));

  // Lines needed: with spacing variation the walk starts at the origin, so
  // count from there to the far side of the box.
  const double reach =
      set.spacing_sd > 0 ? 2 * (box_size + std::max(std::abs(set.origin.x()), std::abs(set.origin.y()))) : 2 * box_size;
  const double lines = reach / set.spacing;
  if (!(lines <= kMaxLinesPerSet))
    throw Error(msg(what, ": spacing ", set.spacing, " would make about ", lines, " joint lines (limit ",
                    kMaxLinesPerSet, "); check the spacing and the domain size",
                    set.spacing_sd > 0 ? ", and keep the origin of a set with spacing variation near the domain" : ""));
  if (set.trace_length > 0) {
    const double traces = (2 * box_size / set.spacing) * (2 * box_size / (set.trace_length + set.bridge_length));
    if (!(traces <= kMaxTracesPerSet))
      throw Error(msg(what, ": trace length ", set.trace_length, " and bridge length ", set.bridge_length,
                      " would make about ", traces, " joint traces (limit ", kMaxTracesPerSet, ")"));
  }
}

std::vector<JointSegment> joint_set_segments(const JointSet& set, int set_index, const Vec2& lo, const Vec2& hi,
                                             double margin) {
  const Vec2 d = dip_direction(set.dip_deg);
  const Vec2 n(-d.y(), d.x());
  const Vec2 wide_lo = lo.array() - margin, wide_hi = hi.array() + margin;
  const double dip_sd = deg_to_rad(set.dip_sd_deg);
  const bool persistent = set.trace_length == 0;

  // The box in the set's frame: offsets along n and positions along d,
  // relative to the origin.
  double pmin = std::numeric_limits<double>::infinity(), pmax = -pmin;
  double tmin = pmin, tmax = -pmin;
  for (const Vec2& c : {lo, hi, Vec2(lo.x(), hi.y()), Vec2(hi.x(), lo.y())}) {
    pmin = std::min(pmin, n.dot(c - set.origin));
    pmax = std::max(pmax, n.dot(c - set.origin));
    tmin = std::min(tmin, d.dot(c - set.origin));
    tmax = std::max(tmax, d.dot(c - set.origin));
  }
  // Traces are laid from the origin along the line: as for the offsets
  // (line_offsets), positions must stay exact in a double, or t + period == t
  // never reaches the box (fuzzing found an origin at x = -1.8e308 hanging here).
  if (!persistent) {
    const double far = std::max(std::abs(tmin), std::abs(tmax)) / (set.trace_length + set.bridge_length);
    if (!(far <= kMaxOriginSpacings))
      throw Error(msg("joint set ", set_index + 1, ": its origin lies about ", far,
                      " trace periods (trace + bridge length) from the domain along its joints (limit ",
                      kMaxOriginSpacings, "); place the origin near the domain"));
  }
  const double diameter = (hi - lo).norm();
  // Joints turned by the dip variation can reach the box from lines a little
  // outside it: widen the range of lines by how far a turned line (or trace)
  // can swing, taking 3 standard deviations as the practical extreme.
  double swing = 0;
  if (dip_sd > 0) {
    const double reach = persistent ? diameter : 0.5 * (set.trace_length + 4 * set.trace_sd);
    swing = reach * std::sin(std::min(0.5 * kPi, 3 * dip_sd));
  }
  // A line lying on the box edge is kept: it may coincide with the boundary.
  const double slack = 1e-9 * diameter;
  const auto lines = line_offsets(set, set_index, pmin - swing - slack, pmax + swing + slack);

  std::vector<JointSegment> out;
  const double tmid = 0.5 * (tmin + tmax);
  for (const auto& [k, offset] : lines) {
    SplitMix64 rng = stream(set, set_index, kLineStream, k);
    const Vec2 anchor = set.origin + offset * n;  // on line k, level with the origin
    if (persistent) {
      // A turned line pivots about its point nearest the box centre.
      const double turn = dip_sd > 0 ? dip_sd * rng.normal() : 0.0;
      const Vec2 pivot = turn == 0 ? anchor : Vec2(anchor + tmid * d);
      const Vec2 dk = rotate(d, turn);
      double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
      if (!clip_to_box(pivot, dk, wide_lo, wide_hi, t0, t1)) continue;
      out.push_back({pivot + t0 * dk, pivot + t1 * dk});
      continue;
    }
    // Non-persistent: traces and bridges alternate along the line, starting
    // at a random phase so neighbouring lines do not line their bridges up.
    const double period = set.trace_length + set.bridge_length;
    const double phase = period * rng.uniform();
    double t = phase + period * (std::floor((tmin - margin - phase) / period) - 1);
    const double t_end = tmax + margin;
    while (t < t_end) {
      const double trace = positive_sample(rng, set.trace_length, set.trace_sd);
      const double turn = dip_sd > 0 ? dip_sd * rng.normal() : 0.0;
      const Vec2 centre = anchor + (t + 0.5 * trace) * d;
      const Vec2 half = 0.5 * trace * rotate(d, turn);
      const Vec2 a = centre - half, b = centre + half;
      double t0 = 0, t1 = 1;
      if (clip_to_box(a, b - a, wide_lo, wide_hi, t0, t1)) out.push_back({a + t0 * (b - a), a + t1 * (b - a)});
      t += trace + set.bridge_length;
    }
  }
  return out;
}

}  // namespace dda::geometry
