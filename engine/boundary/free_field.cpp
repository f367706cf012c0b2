// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "boundary/free_field.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace dda {

FreeFieldColumn::FreeFieldColumn(double y0, std::vector<Segment> segments, double base_zs, double base_zp,
                                 History incident_vx, History incident_vy)
    : segments_(std::move(segments)),
      zs_(base_zs),
      zp_(base_zp),
      vx_in_(std::move(incident_vx)),
      vy_in_(std::move(incident_vy)) {
  if (segments_.empty()) throw Error("free-field column: the side has no edges");
  const std::size_t n = segments_.size() + 1;
  y_.assign(n, y0);
  for (std::size_t s = 0; s < segments_.size(); ++s) {
    const Segment& g = segments_[s];
    if (!(g.height > 0)) throw Error("free-field column: a side edge has no height (a side must be vertical)");
    y_[s + 1] = y_[s] + g.height;
    k_shear_.push_back(g.shear_modulus / g.height);
    k_axial_.push_back((g.lame + 2 * g.shear_modulus) / g.height);
  }
  state_.u.assign(n, 0.0);
  state_.vu.assign(n, 0.0);
  state_.w.assign(n, 0.0);
  state_.vw.assign(n, 0.0);
  trial_ = state_;
}

// (2M/Δt²)·d + K·(u + d) + z·v1 = (2M/Δt)·v0 + z·2·v_in at the base node,
// v1 = 2d/Δt − gg·v0: Shi's scheme whatever the model's integrator (a
// second-order column is not written yet; docs/seismic.md says so), as a
// tridiagonal system (Thomas algorithm).
void FreeFieldColumn::advance_component(const std::vector<double>& k, double z, double v_in, const TimeScheme& scheme,
                                        const std::vector<double>& u, const std::vector<double>& v,
                                        std::vector<double>& u1, std::vector<double>& v1) const {
  const std::size_t n = y_.size();
  const double dt = scheme.dt;
  std::vector<double> lower(n, 0.0), diag(n, 0.0), upper(n, 0.0), rhs(n, 0.0);
  // Consistent mass of each segment (u linear along it): m/3 on the
  // diagonal, m/6 off it, the inertia the DDA blocks beside it have.
  for (std::size_t s = 0; s + 1 < n; ++s) {
    const double m = segments_[s].density * segments_[s].height, f = 2 / (dt * dt);
    const double c0 = scheme.gg * v[s], c1 = scheme.gg * v[s + 1];
    diag[s] += f * m / 3;
    diag[s + 1] += f * m / 3;
    upper[s] += f * m / 6;
    lower[s + 1] += f * m / 6;
    rhs[s] += 2 / dt * (m / 3 * c0 + m / 6 * c1);
    rhs[s + 1] += 2 / dt * (m / 6 * c0 + m / 3 * c1);
  }
  for (std::size_t s = 0; s + 1 < n; ++s) {  // spring between nodes s and s + 1
    diag[s] += k[s];
    diag[s + 1] += k[s];
    upper[s] -= k[s];
    lower[s + 1] -= k[s];
    const double stretch = u[s + 1] - u[s];
    rhs[s] += k[s] * stretch;
    rhs[s + 1] -= k[s] * stretch;
  }
  diag[0] += z * (2 / dt);
  rhs[0] += z * (scheme.gg * v[0] + 2 * v_in);
  // Forward sweep, back substitution.
  for (std::size_t i = 1; i < n; ++i) {
    const double f = lower[i] / diag[i - 1];
    diag[i] -= f * upper[i - 1];
    rhs[i] -= f * rhs[i - 1];
  }
  std::vector<double> d(n);
  d[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) d[i] = (rhs[i] - upper[i] * d[i + 1]) / diag[i];
  u1.resize(n);
  v1.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    u1[i] = u[i] + d[i];
    v1[i] = 2 / dt * d[i] - scheme.gg * v[i];
  }
}

void FreeFieldColumn::advance(double t_end, const TimeScheme& scheme) {
  advance_component(k_shear_, zs_, vx_in_.value(t_end), scheme, state_.u, state_.vu, trial_.u, trial_.vu);
  advance_component(k_axial_, zp_, vy_in_.value(t_end), scheme, state_.w, state_.vw, trial_.w, trial_.vw);
}

void FreeFieldColumn::commit() { state_ = trial_; }

double FreeFieldColumn::shear_stress(int s) const {
  return segments_[s].shear_modulus * (trial_.u[s + 1] - trial_.u[s]) / segments_[s].height;
}

double FreeFieldColumn::lateral_stress(int s) const {
  return segments_[s].lame * (trial_.w[s + 1] - trial_.w[s]) / segments_[s].height;
}

int FreeFieldColumn::segment_at(double y) const {
  const auto it = std::upper_bound(y_.begin(), y_.end(), y);
  const int s = static_cast<int>(it - y_.begin()) - 1;
  return std::clamp(s, 0, static_cast<int>(segments_.size()) - 1);
}

int FreeFieldColumn::node_at(double y) const {
  int best = 0;
  for (int i = 1; i < nodes(); ++i)
    if (std::abs(y_[i] - y) < std::abs(y_[best] - y)) best = i;
  return best;
}

void FreeFieldColumn::check_loaded(const std::string& what) const {
  const std::size_t n = y_.size();
  bool sized = n >= 2 && k_shear_.size() == n - 1 && k_axial_.size() == n - 1 && segments_.size() == n - 1;
  for (const State* s : {&state_, &trial_})
    sized = sized && s->u.size() == n && s->vu.size() == n && s->w.size() == n && s->vw.size() == n;
  if (!sized) throw Error(msg(what, " is damaged: a free-field column's lists do not match its ", n, " nodes"));
  for (const Segment& g : segments_)
    if (!(g.height > 0)) throw Error(msg(what, " is damaged: a free-field column has a segment of height ", g.height));
}

}  // namespace dda
