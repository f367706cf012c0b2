#include "model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "session.hpp"

namespace dda::script {

// ---- fields ------------------------------------------------------------------------

namespace {
struct FieldName {
  Field field;
  const char* name;
};
constexpr FieldName kFields[] = {{Field::Sxx, "sxx"}, {Field::Syy, "syy"}, {Field::Txy, "txy"},
                                 {Field::Vx, "vx"},   {Field::Vy, "vy"},   {Field::Ux, "ux"},
                                 {Field::Uy, "uy"},   {Field::X, "x"},     {Field::Y, "y"}};

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

std::string field_list() {
  std::string s;
  for (const auto& n : kFields) s += s.empty() ? n.name : std::string(", ") + n.name;
  for (int k = 0; k < kEnergyFieldCount; ++k) s += ", " + energy_field_name(k);
  return s;
}

Monitor::~Monitor() { close(); }

void Monitor::close() {
  if (file) std::fclose(file);
  file = nullptr;
}

// ---- model -------------------------------------------------------------------------------

ScriptModel::ScriptModel(const Controls& controls) : world_(std::make_unique<World>(controls)) {}
ScriptModel::~ScriptModel() = default;

void ScriptModel::close() {
  hooks_.clear();  // frame sequences finish their queued frames here
  for (auto& m : monitors_) m->close();
  loads_.clear();
  pressures_.clear();
  world_.reset();
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
    push_force(load, load.force.at(L, load_time()));
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
        t.current = t.input.at(L, load_time());
        for (int id : t.world_ids) world_->set_target_displacement(id, Vec2(t.current, 0));
      } else {
        for (int id : t.world_ids) world_->set_target_history(id, t.input.engine_history());
      }
      break;
    case ScriptTarget::Mode::Velocity:
      for (int id : t.world_ids) world_->set_target_velocity_history(id, t.input.engine_history());
      break;
  }
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
    pr.current = pr.pressure.at(L, load_time());
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
  if (m.file) std::fprintf(m.file, "%ld,%.12g", step, t);
  for (std::size_t k = 0; k < m.fields.size(); ++k) {
    const double v = field_value(m, m.fields[k]);
    m.values[k].push_back(v);
    if (m.file) std::fprintf(m.file, ",%.12g", v);
  }
  if (m.file) {
    // One whole row at a time, flushed: an error or Ctrl-C later keeps every
    // row written so far readable.
    std::fputc('\n', m.file);
    std::fflush(m.file);
  }
}

double ScriptModel::load_time() const {
  // The World takes Δt = min(current Δt, g1), g1 from the controls or
  // estimated from Eqs. 1–3 (see Stepper::derive_automatic_controls).
  const World& w = *world_;
  double g1 = w.controls().g1;
  if (!(g1 > 0)) g1 = w.suggested_time_step();
  double dt = w.current_dt();
  if (!(dt > 0) || dt > g1) dt = g1;
  return w.time() + dt;
}

void ScriptModel::apply_loads(lua_State* L, double t) {
  busy_ = true;
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{busy_};
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

StepStats ScriptModel::step(lua_State* L) {
  Session& s = session(L);
  if (s.threads >= 0) world_->controls().threads = s.threads;
  for (auto& m : monitors_)
    if (!m->started) {
      m->started = true;
      record(*m);  // the state before the first step this monitor sees
    }
  apply_loads(L, load_time());
  for (auto& h : hooks_) h->before_step(*world_);
  const auto t0 = std::chrono::steady_clock::now();
  const StepStats st = world_->step();
  totals_.wall_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++totals_.steps;
  totals_.step_cuts += st.step_cuts;
  totals_.open_close_iterations += st.open_close_iterations;
  totals_.cg_iterations += st.cg_iterations;
  totals_.patch_iterations += st.patch_iterations;
  const long n = world_->step_count();
  for (auto& m : monitors_)
    if (n % m->every == 0) record(*m);
  for (auto& h : hooks_) h->after_step(*world_);
  return st;
}

}  // namespace dda::script
