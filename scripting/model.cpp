// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <mutex>

#include "background_run.hpp"
#include "core/archive.hpp"
#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "session.hpp"
#include "world/checkpoint.hpp"

namespace dda::script {

// ---- fields ------------------------------------------------------------------------

namespace {
struct FieldName {
  Field field;
  const char* name;
  const char* doc;
};
constexpr FieldName kFields[] = {
    {Field::Sxx, "sxx", "σxx of the block under the point (Pa, tension positive)"},
    {Field::Syy, "syy", "σyy (Pa)"},
    {Field::Txy, "txy", "τxy (Pa)"},
    {Field::Vx, "vx", "x velocity of the material point (m/s)"},
    {Field::Vy, "vy", "y velocity (m/s)"},
    {Field::Ux, "ux", "x displacement of the material point since the start (or since m:settle) (m)"},
    {Field::Uy, "uy", "y displacement (m)"},
    {Field::X, "x", "x of the material point now (m)"},
    {Field::Y, "y", "y of the material point now (m)"}};

constexpr int kEnergyFieldCount = static_cast<int>(std::size(kEnergyTerms));
std::string energy_field_name(int k) { return std::string("energy_") + kEnergyTerms[k].name; }
}  // namespace

const char* field_name(Field f) {
  for (const auto& n : kFields)
    if (n.field == f) return n.name;
  static const std::vector<std::string> energy = [] {
    std::vector<std::string> names;
    for (int k = 0; k < kEnergyFieldCount; ++k) names.push_back(energy_field_name(k));
    return names;
  }();
  const int k = static_cast<int>(f) - static_cast<int>(Field::EnergyFirst);
  return k >= 0 && k < kEnergyFieldCount ? energy[k].c_str() : "?";
}

std::optional<Field> parse_field(std::string_view name) {
  for (const auto& n : kFields)
    if (name == n.name) return n.field;
  for (int k = 0; k < kEnergyFieldCount; ++k)
    if (name == energy_field_name(k)) return static_cast<Field>(static_cast<int>(Field::EnergyFirst) + k);
  return std::nullopt;
}

Names field_names() {
  static const std::vector<Name> names = [] {
    static std::vector<std::string> energy_docs;
    std::vector<Name> n;
    for (const auto& f : kFields) n.push_back({f.name, f.doc});
    for (int k = 0; k < kEnergyFieldCount; ++k)
      energy_docs.push_back(
          msg("the model's energy budget since the first step (J/m), whatever the point: ", kEnergyTerms[k].doc));
    for (int k = 0; k < kEnergyFieldCount; ++k)
      n.push_back({field_name(static_cast<Field>(static_cast<int>(Field::EnergyFirst) + k)), energy_docs[k].c_str()});
    return n;
  }();
  return names;
}

std::string field_list() {
  std::string s;
  for (const auto& n : kFields) s += s.empty() ? n.name : std::string(", ") + n.name;
  for (int k = 0; k < kEnergyFieldCount; ++k) s += ", " + energy_field_name(k);
  return s;
}

void Monitor::close() { file.close(); }

// ---- model -------------------------------------------------------------------------------

ScriptModel::ScriptModel(const Controls& controls)
    : world_(std::make_unique<World>(controls)), control_(std::make_shared<RunControl>(this)) {}
ScriptModel::ScriptModel(World world)
    : world_(std::make_unique<World>(std::move(world))), control_(std::make_shared<RunControl>(this)) {}

ScriptModel::~ScriptModel() {
  background.reset();                    // stops the run, if any, and waits for its thread
  std::lock_guard hold(control_->lock);  // a live view may be copying a snapshot
  control_->forget_model();
}

void ScriptModel::close() {
  background.reset();  // a paused run ends here
  hooks_.clear();      // frame sequences finish their queued frames here
  std::string failure;
  for (auto& m : monitors_) try {
      m->close();
    } catch (const Error& e) {
      if (failure.empty()) failure = e.what();
    }
  loads_.clear();
  pressures_.clear();
  world_.reset();
  if (!failure.empty()) throw Error(failure);
}

void ScriptModel::set_domain(std::vector<Vec2> polygon, int rock, int joint) {
  cut_.domain = std::move(polygon);
  cut_.default_rock_material = rock;
  boundary_joints_.domain = joint;
  has_domain_ = true;
}

int ScriptModel::add_hole(std::vector<Vec2> polygon, int joint) {
  cut_.holes.push_back(std::move(polygon));
  boundary_joints_.holes.push_back(joint);
  return static_cast<int>(cut_.holes.size()) - 1;
}

std::vector<BlockId> ScriptModel::generate() {
  const geometry::BlockSet set = geometry::cut_blocks(cut_);
  cut_stats_ = set.stats;
  generated_ = true;  // even if adding a block fails below: the World cannot take blocks back
  return add_cut_blocks(*world_, set, boundary_joints_);
}

std::optional<BlockId> ScriptModel::block_at(const Vec2& p) const {
  const auto count = static_cast<BlockId>(world_->block_count());
  // Strictly inside first; then on the boundary (within a small tolerance),
  // lowest id first, so a point on a joint picks a block deterministically.
  for (BlockId b = 0; b < count; ++b)
    if (point_in_polygon(world_->block_vertices(b), p)) return b;
  const double tol = 1e-9 * std::max(1.0, extent());
  for (BlockId b = 0; b < count; ++b) {
    const auto v = world_->block_vertices(b);
    for (std::size_t k = 0; k < v.size(); ++k) {
      const Vec2 a = v[k], e = v[(k + 1) % v.size()] - a;
      const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
      if ((p - (a + t * e)).norm() <= tol) return b;
    }
  }
  return std::nullopt;
}

std::pair<Vec2, Vec2> ScriptModel::edge_points(EdgeRef e) const {
  const auto v = world_->block_vertices(e.block);
  return {v[e.edge], v[(e.edge + 1) % v.size()]};
}

double ScriptModel::extent() const {
  const auto count = static_cast<BlockId>(world_->block_count());
  if (count == 0) return 0;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (BlockId b = 0; b < count; ++b)
    for (const Vec2& v : world_->block_vertices(b)) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  return (hi - lo).norm();
}

// ---- loads -------------------------------------------------------------------------------

namespace {
// While a load's Lua function runs (when the load is given, and before each
// step) the model is busy: the function cannot change, step or close it
// (check_not_busy), so the World is still there when it returns.
class BusyScope {
 public:
  explicit BusyScope(bool& flag) : flag_(flag), was_(flag) { flag_ = true; }
  ~BusyScope() { flag_ = was_; }
  BusyScope(const BusyScope&) = delete;
  BusyScope& operator=(const BusyScope&) = delete;

 private:
  bool& flag_;
  bool was_;
};
}  // namespace

int ScriptModel::add_point_load(BlockId b, const Vec2& point, ForceInput force, lua_State* L) {
  ScriptPointLoad load;
  load.block = b;
  load.point = point;
  load.force = std::move(force);
  load.world_id = world_->add_point_load(b, point, Vec2::Zero());
  hand_over(load, L);
  loads_.push_back(std::move(load));
  return static_cast<int>(loads_.size()) - 1;
}

void ScriptModel::set_point_load(int id, ForceInput force, lua_State* L) {
  ScriptPointLoad& load = loads_.at(id);
  load.force = std::move(force);
  hand_over(load, L);
}

void ScriptModel::hand_over(ScriptPointLoad& load, lua_State* L) {
  if (load.force.engine_driven()) {
    world_->set_point_load_history(load.world_id, load.force.direction, load.force.magnitude.engine_history());
    load.engine_history = true;
  } else {
    Vec2 f;
    {
      BusyScope busy(busy_);
      f = load.force.at(L, load_time());
    }
    push_force(load, f);
  }
}

void ScriptModel::push_force(ScriptPointLoad& load, const Vec2& f) {
  load.current = f;
  if (!load.engine_history) {
    world_->set_point_load(load.world_id, f);
    return;
  }
  // Once the World follows a history for this load it overrides the force
  // at every step: hand it a constant one instead.
  const double n = f.norm();
  world_->set_point_load_history(load.world_id, n > 0 ? Vec2(f / n) : Vec2::UnitX(), dda::History::constant(n));
}

Vec2 ScriptModel::point_load_value(int id, lua_State* L) const {
  const ScriptPointLoad& load = loads_.at(id);
  return load.force.engine_driven() ? load.force.at(L, world_->time()) : load.current;
}

int ScriptModel::add_target(const std::vector<std::pair<BlockId, Vec2>>& points, const std::vector<Vec2>& directions,
                            ScriptTarget target, lua_State* L) {
  for (std::size_t i = 0; i < points.size(); ++i)
    target.world_ids.push_back(world_->add_displacement_target(
        points[i].first, points[i].second, directions.empty() ? Vec2(Vec2::Zero()) : directions[i]));
  hand_over(target, L);
  targets_.push_back(std::move(target));
  return static_cast<int>(targets_.size()) - 1;
}

void ScriptModel::set_target(int id, ScriptTarget input, lua_State* L) {
  ScriptTarget& t = targets_.at(id);
  input.world_ids = std::move(t.world_ids);
  t = std::move(input);
  hand_over(t, L);
}

void ScriptModel::hand_over(ScriptTarget& t, lua_State* L) {
  switch (t.mode) {
    case ScriptTarget::Mode::Vector:
      for (int id : t.world_ids) world_->set_target_displacement(id, t.vector);
      break;
    case ScriptTarget::Mode::Displacement:
      if (t.input.is_function()) {
        {
          BusyScope busy(busy_);
          t.current = t.input.at(L, load_time());
        }
        for (int id : t.world_ids) world_->set_target_displacement(id, Vec2(t.current, 0));
      } else {
        for (int id : t.world_ids) world_->set_target_history(id, t.input.engine_history());
      }
      break;
    case ScriptTarget::Mode::Velocity:
      for (int id : t.world_ids) world_->set_target_velocity_history(id, t.input.engine_history());
      break;
    case ScriptTarget::Mode::Acceleration:
      for (int id : t.world_ids) world_->set_target_acceleration_history(id, t.input.engine_history());
      break;
  }
}

int ScriptModel::add_edge_targets(const std::vector<EdgeRef>& edges, const Vec2& direction, ScriptTarget target,
                                  lua_State* L) {
  target.world_ids = world_->add_edge_targets(edges, target.mode != ScriptTarget::Mode::Vector, direction);
  target.on_edges = true;
  hand_over(target, L);
  targets_.push_back(std::move(target));
  return static_cast<int>(targets_.size()) - 1;
}

int ScriptModel::add_pressure(std::vector<EdgeRef> edges, TimeInput p, lua_State* L) {
  ScriptPressure pr;
  pr.world_id = world_->add_pressure_load(edges, 0);
  pr.edges = std::move(edges);
  pr.pressure = std::move(p);
  hand_over(pr, L);
  pressures_.push_back(std::move(pr));
  return static_cast<int>(pressures_.size()) - 1;
}

void ScriptModel::set_pressure(int id, TimeInput p, lua_State* L) {
  ScriptPressure& pr = pressures_.at(id);
  pr.pressure = std::move(p);
  hand_over(pr, L);
}

void ScriptModel::hand_over(ScriptPressure& pr, lua_State* L) {
  if (pr.pressure.is_function()) {
    {
      BusyScope busy(busy_);
      pr.current = pr.pressure.at(L, load_time());
    }
    world_->set_pressure(pr.world_id, pr.current);
  } else {
    world_->set_pressure_history(pr.world_id, pr.pressure.engine_history());
  }
}

double ScriptModel::pressure_value(int id, lua_State* L) const {
  const ScriptPressure& pr = pressures_.at(id);
  return pr.pressure.is_function() ? pr.current : pr.pressure.at(L, world_->time());
}

int ScriptModel::add_fixed_point(BlockId b, const Vec2& p) {
  world_->add_fixed_point(b, p);
  return fixed_points_++;
}

StepHook& ScriptModel::add_hook(std::unique_ptr<StepHook> hook) {
  hooks_.push_back(std::move(hook));
  return *hooks_.back();
}

int ScriptModel::add_monitor(std::unique_ptr<Monitor> m) {
  for (auto& h : hooks_) h->monitor_added(m->tracked, m->name);
  monitors_.push_back(std::move(m));
  return static_cast<int>(monitors_.size()) - 1;
}

double ScriptModel::field_value(const Monitor& m, Field f) const {
  const World& w = *world_;
  const BlockId b = w.tracked_block(m.tracked);
  switch (f) {
    case Field::Sxx:
      return w.block_stress(b)[0];
    case Field::Syy:
      return w.block_stress(b)[1];
    case Field::Txy:
      return w.block_stress(b)[2];
    case Field::Vx:
      return w.velocity_at(b, w.tracked_position(m.tracked)).x();
    case Field::Vy:
      return w.velocity_at(b, w.tracked_position(m.tracked)).y();
    case Field::Ux:
      return w.tracked_displacement(m.tracked).x();
    case Field::Uy:
      return w.tracked_displacement(m.tracked).y();
    case Field::X:
      return w.tracked_position(m.tracked).x();
    case Field::Y:
      return w.tracked_position(m.tracked).y();
    default:
      return w.energy().total.*kEnergyTerms[static_cast<int>(f) - static_cast<int>(Field::EnergyFirst)].term;
  }
}

void ScriptModel::record(Monitor& m) {
  const long step = world_->step_count();
  const double t = world_->time();
  m.steps.push_back(step);
  m.times.push_back(t);
  if (m.values.size() != m.fields.size()) m.values.resize(m.fields.size());
  char number[64];
  std::snprintf(number, sizeof number, "%ld,%.12g", step, t);
  std::string row = number;
  for (std::size_t k = 0; k < m.fields.size(); ++k) {
    const double v = field_value(m, m.fields[k]);
    m.values[k].push_back(v);
    std::snprintf(number, sizeof number, ",%.12g", v);
    row += number;
  }
  row += '\n';
  if (!m.write_error.empty()) throw Error(m.write_error);
  if (!m.file.is_open()) return;
  // One whole row at a time, straight to the file: an error, Ctrl-C or a
  // full disk later keeps every row written so far complete.
  try {
    m.file.append(row);
  } catch (const Error& e) {
    m.write_error = msg("monitor '", m.name, "': ", e.what());
    m.file = AppendFile();
    throw Error(m.write_error);
  }
}

double ScriptModel::load_time() const {
  // The World takes Δt = min(current Δt, g1), g1 from the controls or the
  // default rule (see Stepper::derive_automatic_controls); a settling step
  // holds the time.
  const World& w = *world_;
  if (w.settling()) return w.time();
  double g1 = w.controls().g1;
  if (!(g1 > 0)) g1 = w.default_time_step().dt;
  double dt = w.current_dt();
  if (!(dt > 0) || dt > g1) dt = g1;
  return w.time() + dt;
}

void ScriptModel::apply_loads(lua_State* L, double t) {
  BusyScope busy(busy_);
  for (ScriptPointLoad& load : loads_) {
    if (load.force.constant() || load.force.engine_driven()) continue;
    push_force(load, load.force.at(L, t));
  }
  for (ScriptTarget& target : targets_) {
    if (target.mode != ScriptTarget::Mode::Displacement || !target.input.is_function()) continue;
    target.current = target.input.at(L, t);
    for (int id : target.world_ids) world_->set_target_displacement(id, Vec2(target.current, 0));
  }
  for (ScriptPressure& pr : pressures_) {
    if (!pr.pressure.is_function()) continue;  // the engine follows constants and tables itself
    pr.current = pr.pressure.at(L, t);
    world_->set_pressure(pr.world_id, pr.current);
  }
}

const WaveModel& ScriptModel::decide_wave_model(lua_State* L, double window) {
  if (world_->wave_model().decided) return world_->wave_model();
  // The functions sampled as the steps will apply them, every Δt (at most
  // 65,536 samples), over the run and at least 1000 steps: a short first run
  // must not cut a pulse short. Not where the user states the frequency.
  const double dt = world_->controls().g1 > 0 ? world_->controls().g1 : world_->default_time_step().dt;
  window = std::max(window, 1000 * dt);
  if (world_->controls().max_frequency > 0) window = 0;
  const int count = static_cast<int>(std::min(65536.0, std::ceil(window / dt)));
  std::vector<LoadSignal> signals;
  // Each input once per sample time, its components as signals of their own.
  // A function that fails at a later time is read up to there: its error
  // belongs to the step that reaches that time, not to this look ahead.
  auto sample = [&](SignalKind kind, const std::string& what, int components, auto values_at) {
    std::vector<LoadSignal> s(components, LoadSignal{{}, kind, what});
    for (int i = 0; i <= count; ++i) {
      const double t = window * i / count;
      Vec2 v;
      try {
        v = values_at(t);
      } catch (const std::exception&) {
        break;
      }
      for (int c = 0; c < components; ++c) s[c].samples.emplace_back(t, v[c]);
    }
    for (LoadSignal& one : s) signals.push_back(std::move(one));
  };
  busy_ = true;
  try {
    if (window > 0) {
      for (std::size_t i = 0; i < pressures_.size(); ++i)
        if (pressures_[i].pressure.is_function())
          sample(SignalKind::Force, msg("the function of pressure ", i + 1), 1,
                 [&](double t) { return Vec2(pressures_[i].pressure.at(L, t), 0); });
      for (std::size_t i = 0; i < loads_.size(); ++i)
        if (!loads_[i].force.engine_driven() && !loads_[i].force.constant())
          sample(SignalKind::Force, msg("the function of point load ", i + 1), 2,
                 [&](double t) { return loads_[i].force.at(L, t); });
      for (std::size_t i = 0; i < targets_.size(); ++i)
        if (targets_[i].mode == ScriptTarget::Mode::Displacement && targets_[i].input.is_function())
          sample(SignalKind::Displacement, msg("the function of target ", i + 1), 1,
                 [&](double t) { return Vec2(targets_[i].input.at(L, t), 0); });
    }
  } catch (...) {
    busy_ = false;
    throw;
  }
  busy_ = false;
  const WaveModel& wave = world_->decide_wave_model(signals);
  if (wave.meshed_blocks > 0) {
    for (ScriptPressure& p : pressures_) p.edges = world_->pressure_edges(p.world_id);
    for (ScriptPointLoad& p : loads_) p.block = world_->point_load_block(p.world_id);
    for (ScriptTarget& t : targets_)
      if (t.on_edges) t.world_ids = world_->edge_target_ids(t.world_ids.front());
  }
  return wave;
}

bool ScriptModel::loads_call_lua() const {
  for (const ScriptPointLoad& load : loads_)
    if (load.force.is_function()) return true;
  for (const ScriptTarget& target : targets_)
    if (target.mode == ScriptTarget::Mode::Displacement && target.input.is_function()) return true;
  for (const ScriptPressure& pr : pressures_)
    if (pr.pressure.is_function()) return true;
  return false;
}

StepStats ScriptModel::step(lua_State* L) {
  if (threads_override >= 0) world_->controls().threads = threads_override;
  for (auto& m : monitors_)
    if (!m->started) {
      m->started = true;
      record(*m);  // the state before the first step this monitor sees
    }
  apply_loads(L, load_time());
  for (auto& h : hooks_) h->before_step(*world_);
  const StepStats st = counted_step();
  const long n = world_->step_count();
  for (auto& m : monitors_)
    if (n % m->every == 0) record(*m);
  for (auto& h : hooks_) h->after_step(*world_);
  return st;
}

StepStats ScriptModel::settle_step(lua_State* L) {
  apply_loads(L, load_time());
  return counted_step();
}

StepStats ScriptModel::counted_step() {
  const auto t0 = std::chrono::steady_clock::now();
  const StepStats st = world_->step();
  totals_.wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++totals_.steps;
  totals_.step_cuts += st.step_cuts;
  totals_.open_close_iterations += st.open_close_iterations;
  totals_.cg_iterations += st.cg_iterations;
  totals_.patch_iterations += st.patch_iterations;
  return st;
}

// ---- checkpoints -----------------------------------------------------------------------------

template <class Archive>
void ScriptModel::script_fields(Archive& ar, std::vector<SavedMonitor>& monitors) {
  ar.section("script model");
  ar(number, loads_, pressures_, targets_, fixed_points_, has_domain_, generated_, totals_);
  ar.section("monitors");
  ar(monitors);
}

void ScriptModel::check_loaded(const LoadCheck& check) {
  const World& w = *world_;
  check.require(number >= 1, "its model number is ", number);
  for (std::size_t i = 0; i < loads_.size(); ++i) {
    ScriptPointLoad& l = loads_[i];
    check.index(l.world_id, w.point_load_count(), "point loads", "script point load ", i, "'s load");
    check.index(l.block, w.block_count(), "blocks", "script point load ", i, "'s block");
    check.require(l.point.allFinite() && l.current.allFinite() && l.force.direction.allFinite(), "script point load ",
                  i, " is not finite");
    l.force.xy.check_loaded(check, msg("script point load ", i, "'s force"));
    l.force.magnitude.check_loaded(check, msg("script point load ", i, "'s magnitude"));
  }
  for (std::size_t i = 0; i < pressures_.size(); ++i) {
    ScriptPressure& p = pressures_[i];
    check.index(p.world_id, w.pressure_count(), "pressures", "script pressure ", i, "'s pressure");
    for (const EdgeRef& e : p.edges) {
      check.index(e.block, w.block_count(), "blocks", "script pressure ", i, "'s block");
      check.index(e.edge, w.block_vertices(e.block).size(), "edges", "script pressure ", i, "'s edge");
    }
    check.finite(p.current, "script pressure ", i, "'s value");
    p.pressure.check_loaded(check, msg("script pressure ", i));
  }
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    ScriptTarget& t = targets_[i];
    for (const int id : t.world_ids) check.index(id, w.target_count(), "targets", "script target ", i, "'s target");
    check.require(t.vector.allFinite() && std::isfinite(t.current), "script target ", i, " is not finite");
    t.input.check_loaded(check, msg("script target ", i));
  }
  check.require(fixed_points_ >= 0 && static_cast<std::size_t>(fixed_points_) <= w.fixed_point_count(), "it counts ",
                fixed_points_, " script fixed points of ", w.fixed_point_count());
  for (std::size_t i = 0; i < saved_monitors_.size(); ++i) {
    SavedMonitor& m = saved_monitors_[i];
    m.name = printable(m.name);
    check.size(m.times.size(), m.steps.size(), "steps", "monitor ", i, "'s times");
    for (const auto& v : m.values) check.size(v.size(), m.steps.size(), "steps", "monitor ", i, "'s values");
  }
}

void ScriptModel::save(const std::filesystem::path& path) const {
  std::vector<SavedMonitor> monitors;
  for (const auto& m : monitors_) monitors.push_back({m->name, m->steps, m->times, m->values});
  ArchiveWriter ar;
  const_cast<ScriptModel*>(this)->script_fields(ar, monitors);  // writing only reads
  save_checkpoint(*world_, path, ar.bytes());
}

std::unique_ptr<ScriptModel> ScriptModel::load(const std::filesystem::path& path, std::vector<std::string>& warnings) {
  return from_checkpoint(load_checkpoint(path), msg("checkpoint '", path.string(), "'"), warnings);
}

std::unique_ptr<ScriptModel> ScriptModel::from_checkpoint(Checkpoint c, const std::string& what,
                                                          std::vector<std::string>& warnings) {
  auto m = std::make_unique<ScriptModel>(std::move(c.world));
  ArchiveReader ar(c.extra, what);
  m->script_fields(ar, m->saved_monitors_);
  m->check_loaded(LoadCheck(ar.what()));
  // Lua functions do not travel: each such input keeps the value it gave last.
  auto lost = [&](const char* what, std::size_t i, const std::string& where, const std::string& value) {
    warnings.push_back(msg(what, " ", i + 1, " was driven by a Lua function (", where,
                           "), which a checkpoint cannot hold: it keeps its last value, ", value));
  };
  for (std::size_t i = 0; i < m->loads_.size(); ++i) {
    ScriptPointLoad& l = m->loads_[i];
    if (!l.force.is_lost_function()) continue;
    lost("point load", i, l.force.along ? l.force.magnitude.where() : l.force.xy.where(),
         msg("(", l.current.x(), ", ", l.current.y(), ") N"));
    ForceInput frozen;
    frozen.xy = VecTimeInput::constant(l.current);
    l.force = std::move(frozen);
  }
  for (std::size_t i = 0; i < m->pressures_.size(); ++i) {
    ScriptPressure& p = m->pressures_[i];
    if (!p.pressure.is_lost_function()) continue;
    lost("pressure", i, p.pressure.where(), msg(p.current, " Pa"));
    p.pressure = TimeInput(p.current);
  }
  for (std::size_t i = 0; i < m->targets_.size(); ++i) {
    ScriptTarget& t = m->targets_[i];
    if (!t.input.is_lost_function()) continue;
    lost("displacement target", i, t.input.where(), msg(t.current, " m"));
    t.input = TimeInput(t.current);
  }
  return m;
}

namespace {
// The step of a monitor CSV row ("step,time,..."), or -1.
long row_step(const std::string& line) {
  char* end = nullptr;
  const long step = std::strtol(line.c_str(), &end, 10);
  return end != line.c_str() && *end == ',' ? step : -1;
}
}  // namespace

void ScriptModel::restore(ScriptModel& saved, const std::string& what) {
  const World& here = *world_;
  const World& there = *saved.world_;
  auto same = [&](const char* things, std::size_t n_here, std::size_t n_there) {
    if (n_here != n_there)
      throw Error(msg(what, " holds a model with ", n_there, " ", things, "; the script built model ", number, " with ",
                      n_here, ": restart with the script (and --set values) that wrote the checkpoint"));
  };
  same("blocks", here.block_count(), there.block_count());
  for (BlockId b = 0; b < static_cast<BlockId>(here.block_count()); ++b) {
    const auto a = here.block_initial_vertices(b), c = there.block_initial_vertices(b);
    if (!std::equal(a.begin(), a.end(), c.begin(), c.end()))
      throw Error(msg(what, " holds a model whose block ", b + 1, " started elsewhere than the script's block ", b + 1,
                      ": restart with the script (and --set values) that wrote the checkpoint"));
  }
  same("rock materials", here.rock_material_count(), there.rock_material_count());
  same("joint materials", here.joint_material_count(), there.joint_material_count());
  same("point loads", loads_.size(), saved.loads_.size());
  same("pressures", pressures_.size(), saved.pressures_.size());
  same("displacement targets", targets_.size(), saved.targets_.size());
  same("fixed points", fixed_points_, saved.fixed_points_);
  same("monitors", monitors_.size(), saved.saved_monitors_.size());
  for (std::size_t i = 0; i < monitors_.size(); ++i) {
    const SavedMonitor& s = saved.saved_monitors_[i];
    if (s.name != monitors_[i]->name || s.values.size() != monitors_[i]->fields.size())
      throw Error(msg(what, " holds a model whose monitor ", i + 1, " is '", s.name, "' with ", s.values.size(),
                      " fields; the script's is '", monitors_[i]->name, "' with ", monitors_[i]->fields.size(),
                      ": restart with the script (and --set values) that wrote the checkpoint"));
  }

  const int threads = world_->controls().threads;  // of this run, not of the state
  *world_ = std::move(*saved.world_);
  saved.world_.reset();
  world_->controls().threads = threads;
  for (std::size_t i = 0; i < loads_.size(); ++i) loads_[i].current = saved.loads_[i].current;
  for (std::size_t i = 0; i < pressures_.size(); ++i) pressures_[i].current = saved.pressures_[i].current;
  for (std::size_t i = 0; i < targets_.size(); ++i) targets_[i].current = saved.targets_[i].current;
  totals_ = saved.totals_;  // since the start of the run being continued

  // Each monitor: the straight run's records up to the checkpoint, in
  // memory and in its file, then this run's.
  const long step = world_->step_count();
  for (std::size_t i = 0; i < monitors_.size(); ++i) {
    Monitor* m = monitors_[i].get();
    SavedMonitor& s = saved.saved_monitors_[i];
    m->steps = std::move(s.steps);
    m->times = std::move(s.times);
    m->values = std::move(s.values);
    m->started = !m->steps.empty();
    std::string rows;
    for (std::size_t k = 1; k < m->previous_lines.size(); ++k) {
      const long row = row_step(m->previous_lines[k]);
      if (row >= 0 && row <= step) rows.append(m->previous_lines[k]).append("\n");
    }
    if (m->file.is_open() && !rows.empty()) m->file.append(rows);
    m->previous_lines.clear();
  }
  for (auto& h : hooks_) h->restarted(*world_);
}

}  // namespace dda::script
