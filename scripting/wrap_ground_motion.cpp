// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Earthquake input: dda.ground_motion{...} reads an accelerogram (or takes
// samples from the script), resamples it to a time step, baseline-corrects
// it and integrates it (engine/loading/ground_motion.hpp). It returns a plain
// table whose histories go straight into the boundary calls, e.g.
//   local gm = dda.ground_motion{file = "data/record.dat", dt = 0.002}
//   base_edges:target{displacement = gm.displacement, direction = {1, 0}}
//   bottom:viscous_boundary{rock = bedrock, vx = gm.velocity}   -- gm: the upgoing wave
#include "loading/ground_motion.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

void push_series(lua_State* L, const GroundMotion& g, const std::vector<double>& x) {
  lua_createtable(L, static_cast<int>(x.size()), 0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    push_point(L, Vec2(static_cast<double>(i) * g.dt(), x[i]));
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

void push_peak(lua_State* L, const GroundMotion::Peak& p) {
  lua_createtable(L, 0, 2);
  set_number_field(L, "value", p.value);
  set_number_field(L, "time", p.time);
}

// {dt, duration, source, acceleration, velocity, displacement, pga, pgv, pgd}
void push_motion(lua_State* L, const GroundMotion& g) {
  lua_createtable(L, 0, 9);
  set_number_field(L, "dt", g.dt());
  set_number_field(L, "duration", g.duration());
  lua_pushstring(L, g.source().c_str());
  lua_setfield(L, -2, "source");
  push_series(L, g, g.acceleration());
  lua_setfield(L, -2, "acceleration");
  push_series(L, g, g.velocity());
  lua_setfield(L, -2, "velocity");
  push_series(L, g, g.displacement());
  lua_setfield(L, -2, "displacement");
  push_peak(L, g.peak_acceleration());
  lua_setfield(L, -2, "pga");
  push_peak(L, g.peak_velocity());
  lua_setfield(L, -2, "pgv");
  push_peak(L, g.peak_displacement());
  lua_setfield(L, -2, "pgd");
}

constexpr Name kGroundMotionOptions[] = {
    {"file", "the record's file (data/ holds El Centro 1979); or give `samples`", "—"},
    {"samples", "{{t, a}, ...}: the record as a table", "—"},
    {"format",
     "`\"accelerogram\"` (% header lines, then values; the spacing from the header) or `\"csv\"` (rows of time, "
     "acceleration)",
     "\"csv\" for files ending .csv, else \"accelerogram\""},
    {"unit", "the acceleration's unit: `\"m/s2\"`, `\"cm/s2\"` or `\"g\"` (required for csv and samples)",
     "\"cm/s2\" (accelerogram)"},
    {"dt", "resample to this spacing (s)", "the record's"},
    {"baseline", "order of the polynomial fitted to the velocity and taken off, 0 (none) to 6", "2"},
    {"scale", "multiplies the record", "1"}};
constexpr Name kGroundMotionReturns[] = {{"dt", "the spacing (s)"},
                                         {"duration", "the record's length (s)"},
                                         {"source", "where it came from"},
                                         {"acceleration", "{{t, a}, ...} (m/s²)"},
                                         {"velocity", "{{t, v}, ...} (m/s), integrated"},
                                         {"displacement", "{{t, u}, ...} (m), integrated twice"},
                                         {"pga", "{value, time}: the peak acceleration, its sign kept"},
                                         {"pgv", "{value, time}: the peak velocity"},
                                         {"pgd", "{value, time}: the peak displacement"}};

// dda.ground_motion{file = path | samples = {{t, a}, ...}, format, unit, dt, baseline = 2, scale = 1}
int dda_ground_motion(lua_State* L) {
  const char* call = "dda.ground_motion";
  const Options o(L, 1, call, kGroundMotionOptions);
  const int which = one_of(o, {"file", "samples"});
  const double dt = o.non_negative("dt", 0);
  const long baseline = o.integer("baseline", 2);
  const double scale = o.number("scale", 1);
  std::optional<GroundMotion> g;
  if (which == 0) {
    const std::string path = o.string("file");
    const bool csv = path.size() > 4 && path.substr(path.size() - 4) == ".csv";
    const std::string format = o.string("format", csv ? "csv" : "accelerogram");
    if (format == "csv") {
      if (!o.has("unit"))
        fail(call, ": a CSV file needs unit = \"m/s2\", \"cm/s2\" or \"g\" (the unit of its acceleration column)");
      g = GroundMotion::read_csv(path, parse_acceleration_unit(o.string("unit")), dt);
    } else if (format == "accelerogram") {
      g = GroundMotion::read_accelerogram(path, parse_acceleration_unit(o.string("unit", "cm/s2")), dt);
    } else {
      fail(call, ": option 'format' must be \"accelerogram\" (% header, then values) or \"csv\", got \"", format, "\"");
    }
  } else {
    if (!o.has("unit")) fail(call, ": samples need unit = \"m/s2\", \"cm/s2\" or \"g\"");
    const double factor = metres_per_second2(parse_acceleration_unit(o.string("unit")));
    o.push("samples");
    const int idx = lua_gettop(L);
    if (lua_type(L, idx) != LUA_TTABLE) fail(call, ": option 'samples' must be a table of {t, a} pairs");
    std::vector<std::pair<double, double>> samples;
    double smallest = INFINITY;
    for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, idx)); ++k) {
      lua_rawgeti(L, idx, k);
      const Vec2 p = check_point(L, -1, call, msg("option 'samples' entry ", k, " {t, a}"));
      lua_pop(L, 1);
      if (!samples.empty()) smallest = std::min(smallest, p.x() - samples.back().first);
      samples.emplace_back(p.x(), p.y() * factor);
    }
    lua_pop(L, 1);
    g = GroundMotion::from_samples(samples, dt > 0 ? dt : smallest, "dda.ground_motion samples");
  }
  if (baseline < 0 || baseline > 6)
    fail(call, ": option 'baseline' is the order of the polynomial taken off the velocity: 0 (none) to 6, got ",
         baseline);
  push_motion(L, g->scaled(scale).baseline_corrected(static_cast<int>(baseline)));
  return 1;
}

}  // namespace

void register_ground_motion_functions(lua_State* L) {
  static const Method functions[] = {
      {"ground_motion", guarded<dda_ground_motion>,
       "dda.ground_motion{...} → a record\nReads a strong-motion record, resamples it to dt, scales it, takes off a "
       "polynomial of order `baseline` fitted to its velocity and integrates it. The series are {{t, value}, ...} "
       "in SI units, ready for edges:target{displacement = ...} and edges:viscous_boundary{vx = ...} "
       "(docs/seismic.md).",
       kGroundMotionOptions, kGroundMotionReturns},
      {}};
  set_methods(L, functions, "dda");
}

}  // namespace dda::script
