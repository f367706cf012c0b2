// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "world/time_step_rule.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "loading/load_frequency.hpp"
#include "world/wave_model.hpp"

namespace dda {

namespace {

std::string g3(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// The sizes the rule reads off the blocks.
struct ModelScales {
  double h_min = INFINITY;  // the smallest block's height across its longest edge (m)
  double m_min = INFINITY;  // the smallest block mass (kg/m)
  double cp_max = 0;        // the largest P-wave speed (m/s)
  double e_max = 0;         // the largest Young's modulus (Pa)
};

ModelScales model_scales(const WorldState& w) {
  ModelScales s;
  const Blocks& blocks = w.blocks;
  const BlockPolygons polys = blocks.polygons();
  for (std::size_t b = 0; b < blocks.count(); ++b) {
    double longest = 0;
    const auto v = polys.of(static_cast<int>(b));
    for (std::size_t k = 0; k < v.size(); ++k) longest = std::max(longest, (v[(k + 1) % v.size()] - v[k]).norm());
    s.h_min = std::min(s.h_min, blocks.area[b] / longest);
    s.m_min = std::min(s.m_min, blocks.mass[b]);
    s.cp_max = std::max(s.cp_max, p_wave_speed(w.rocks[blocks.material[b]], w.controls.plane));
    s.e_max = std::max(s.e_max, w.rocks[blocks.material[b]].youngs);
  }
  return s;
}

TimeStepTerm motion_term(const ModelScales& s, double g) {
  return {"motion under gravity", std::sqrt(s.h_min / g) / 20,
          msg("sqrt(h_min/|g|)/20, h_min = ", g3(s.h_min), " m, |g| = ", g3(g), " m/s²")};
}

// The loads' highest frequency: the wave model's, once decided (it sampled
// the script's functions too), else the loads' own.
double loads_frequency(const WorldState& w) {
  return w.wave.decided ? w.wave.frequency : dynamic_load_frequency(w).frequency;
}

}  // namespace

std::string TimeStepChoice::describe() const {
  if (terms.empty()) return "no blocks";
  std::string text = msg("Δt = ", g3(dt), " s, ",
                         gravity_alone ? "moved by gravity alone (no loads, prescribed motions or incident waves)"
                         : bodies      ? "loaded dynamically, moving as bodies (every block within the element "
                                         "size that resolves the loads, the model within a shear wavelength)"
                                       : "loaded dynamically (loads, prescribed motions or incident waves)",
                         ":");
  for (const TimeStepTerm& t : terms)
    text += msg(t.dt == dt ? " " : " (", t.name, " ", g3(t.dt), " s = ", t.formula, t.dt == dt ? "" : ")", ";");
  text.pop_back();
  return text;
}

TimeStepChoice default_time_step(const WorldState& w) {
  TimeStepChoice choice;
  if (w.blocks.count() == 0) return choice;
  const ModelScales s = model_scales(w);
  const double g = w.controls.gravity.norm();
  choice.gravity_alone = g > 0 && w.loads.empty() && !w.boundaries.drives_motion();
  const double f = choice.gravity_alone ? 0 : loads_frequency(w);
  if (choice.gravity_alone) {
    choice.terms.push_back(motion_term(s, g));
  } else if (moves_as_bodies(w, f)) {
    choice.bodies = true;
    choice.terms.push_back({"the loads' period", 1 / (20 * f),
                            msg("1/(20·f), f = ", g3(f), " Hz, the loads' highest frequency (docs/waves.md)")});
    if (g > 0) choice.terms.push_back(motion_term(s, g));
  } else {
    // The paper's Eqs. 1–3 with a = 0.05 and b = 0.177.
    const double g0 = w.controls.g0 > 0 ? w.controls.g0 : 50 * s.e_max;
    choice.terms.push_back({"waves in the smallest block", 0.05 * s.h_min / s.cp_max,
                            msg("0.05·h_min/C_P, h_min = ", g3(s.h_min), " m, C_P = ", g3(s.cp_max), " m/s")});
    choice.terms.push_back({"contact springs", 2 * 0.177 * std::sqrt(s.m_min / g0),
                            msg("0.354·sqrt(m_min/g0), m_min = ", g3(s.m_min), " kg/m, g0 = ", g3(g0), " N/m")});
  }
  choice.dt = INFINITY;
  for (const TimeStepTerm& t : choice.terms) choice.dt = std::min(choice.dt, t.dt);
  return choice;
}

double motion_time_step(const WorldState& w) {
  const double g = w.controls.gravity.norm();
  if (w.blocks.count() == 0 || !(g > 0)) return 0;
  return motion_term(model_scales(w), g).dt;
}

}  // namespace dda
