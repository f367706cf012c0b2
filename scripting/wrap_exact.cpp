// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// dda.exact_plate_bar{...} and dda.exact_joint_set{...}: the exact answers the
// wave scripts compare the engine with (engine/reference/).
#include "reference/joint_set.hpp"
#include "reference/plate_bar.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

std::vector<std::pair<double, double>> read_table(const Options& o, const char* key) {
  lua_State* L = o.state();
  o.push(key);
  const int idx = lua_gettop(L);
  if (lua_type(L, idx) != LUA_TTABLE) fail(o.call(), ": option '", key, "' must be a table of {t, value} pairs");
  std::vector<std::pair<double, double>> out;
  for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, idx)); ++k) {
    lua_rawgeti(L, idx, k);
    const Vec2 p = check_point(L, -1, o.call(), msg("option '", key, "' entry ", k, " {t, value}"));
    lua_pop(L, 1);
    if (!out.empty() && !(p.x() >= out.back().first))
      fail(o.call(), ": option '", key, "': times must not decrease (entry ", k, ")");
    out.emplace_back(p.x(), p.y());
  }
  lua_pop(L, 1);
  if (out.size() < 2) fail(o.call(), ": option '", key, "' needs at least two points");
  return out;
}

constexpr Name kPlateBarOptions[] = {
    {"load", "{{t, p}, ...}: the end pressure (Pa, compression positive), piecewise linear, zero outside it", "—"},
    {"x", "m from the loaded end", "0"},
    {"y", "m from mid-height", "0"},
    {"times", "{t, ...}: the times (s) of the answer", "—"},
    {"E", "Young's modulus (Pa)", "5e10"},
    {"nu", "Poisson's ratio", "0.25"},
    {"density", "kg/m³", "2000"},
    {"height", "the strip's height (m)", "1"},
    {"plane", "`\"stress\"` or `\"strain\"`", "\"stress\""},
    {"end", "the loaded end: `\"free\"` or `\"rollers\"` (held against lateral motion)", "\"free\""},
    {"max_frequency", "Hz: the synthesis is cut (tapered) here", "20000"},
    {"frequency_step", "Hz", "5"},
    {"modes", "modes a free end's fit takes at least", "16"}};
constexpr Name kJointSetOptions[] = {{"count", "N, the joints", "1"},
                                     {"spacing", "m between neighbouring joints", "1"},
                                     {"kn", "the joints' normal stiffness (Pa/m)", "1e10"},
                                     {"E", "the rock's Young's modulus (Pa)", "5e10"},
                                     {"density", "kg/m³", "2000"},
                                     {"frequency", "Hz", "1000"}};

// dda.exact_plate_bar{load = {{t, p}, ...}, x = , y = 0, times = {...}, E = , nu = ,
//   density = , height = 1, plane = "stress", ["end"] = "free", max_frequency = 20000,
//   frequency_step = 5, modes = 16} → {sxx, ...}
int dda_exact_plate_bar(lua_State* L) {
  const Options o(L, 1, "dda.exact_plate_bar", kPlateBarOptions);
  reference::Strip strip;
  strip.youngs = o.positive("E", strip.youngs);
  strip.poisson = o.number("nu", strip.poisson);
  strip.density = o.positive("density", strip.density);
  strip.height = o.positive("height", strip.height);
  const std::string plane = o.string("plane", "stress");
  if (plane != "stress" && plane != "strain")
    fail("dda.exact_plate_bar: option 'plane' must be \"stress\" or \"strain\", got \"", plane, "\"");
  strip.plane = plane == "stress" ? PlaneMode::Stress : PlaneMode::Strain;
  reference::PlateBarOptions options;
  const std::string end = o.string("end", "free");
  if (end != "free" && end != "rollers")
    fail("dda.exact_plate_bar: option 'end' must be \"free\" or \"rollers\", got \"", end, "\"");
  options.end = end == "free" ? reference::EndCondition::Free : reference::EndCondition::Rollers;
  options.max_frequency = o.positive("max_frequency", options.max_frequency);
  options.frequency_step = o.positive("frequency_step", options.frequency_step);
  options.modes = static_cast<int>(o.integer("modes", options.modes));
  const auto load = read_table(o, "load");
  o.push("times");
  if (lua_type(L, -1) != LUA_TTABLE) fail("dda.exact_plate_bar: option 'times' must be a table of times (s)");
  std::vector<double> times;
  for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, -1)); ++k) {
    lua_rawgeti(L, -1, k);
    times.push_back(check_number(L, -1, "dda.exact_plate_bar", msg("option 'times' entry ", k)));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::vector<double> sxx;
  try {
    sxx = reference::plate_bar_stress(strip, load, o.number("x", 0), o.number("y", 0), times, options);
  } catch (const Error& e) {
    fail("dda.exact_plate_bar: ", e.what());
  }
  lua_createtable(L, static_cast<int>(sxx.size()), 0);
  for (std::size_t i = 0; i < sxx.size(); ++i) {
    lua_pushnumber(L, sxx[i]);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

// dda.exact_joint_set{count = N, spacing = s, kn = , E = , density = , frequency = f} → |T|, arg T
int dda_exact_joint_set(lua_State* L) {
  const Options o(L, 1, "dda.exact_joint_set", kJointSetOptions);
  reference::JointSet set;
  set.count = static_cast<int>(o.integer("count", 1));
  set.spacing = o.positive("spacing", set.spacing);
  set.stiffness = o.positive("kn", set.stiffness);
  const double e = o.positive("E", 50e9), rho = o.positive("density", 2000);
  set.wave_speed = std::sqrt(e / rho);
  set.impedance = rho * set.wave_speed;
  std::complex<double> t;
  try {
    t = reference::joint_set_transmission(set, 2 * kPi * o.positive("frequency", 1000));
  } catch (const Error& err) {
    fail("dda.exact_joint_set: ", err.what());
  }
  lua_pushnumber(L, std::abs(t));
  lua_pushnumber(L, std::arg(t));
  return 2;
}

}  // namespace

void register_exact_functions(lua_State* L) {
  static const Method functions[] = {
      {"exact_plate_bar", guarded<dda_exact_plate_bar>,
       "dda.exact_plate_bar{...} → {sxx, ...}\nThe exact σxx (Pa, tension positive) at (x, y) at the times, in a long "
       "elastic strip loaded at its end by the pressure p(t): Fourier synthesis of its symmetric Rayleigh–Lamb modes "
       "(engine/reference/plate_bar.hpp, docs/waves.md). A reference for the tests.",
       kPlateBarOptions},
      {"exact_joint_set", guarded<dda_exact_joint_set>,
       "dda.exact_joint_set{...} → |T|, arg T\nThe transmission coefficient of a harmonic P wave at normal incidence "
       "across N parallel joints of normal stiffness kn in a 1-D rock (transfer matrices, "
       "engine/reference/joint_set.hpp). A reference for the tests.",
       kJointSetOptions},
      {}};
  set_methods(L, functions, "dda");
}

}  // namespace dda::script
