// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// dda.Model: controls, stepping, statistics, contacts. (Geometry methods are
// in wrap_geometry.cpp; materials, blocks, edges, loads and monitors add their
// constructors to the model from their own files.)
#include <cinttypes>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>

#include "background_run.hpp"
#include "session.hpp"
#include "stepping.hpp"
#include "wrap.hpp"

namespace dda::script {

// ---- controls -----------------------------------------------------------------------------

// Read, written and checked through the engine's table of controls
// (world/controls.hpp): names, types, checks and their messages come from
// there, so a control added there needs nothing here.

Names control_option_names() {
  static const std::vector<Name> names = [] {
    static std::vector<std::string> defaults;
    const Controls c;
    for (const ControlSpec& s : control_specs()) defaults.push_back(s.default_text ? s.default_text : s.value_text(c));
    std::vector<Name> n;
    for (std::size_t k = 0; k < control_specs().size(); ++k)
      n.push_back({control_specs()[k].name, control_specs()[k].doc, defaults[k].c_str()});
    return n;
  }();
  return names;
}

void parse_controls(const Options& o, Controls& c) {
  const std::string& call = o.call();
  for (const ControlSpec& s : control_specs()) {
    if (!o.has(s.name)) continue;
    switch (s.type) {
      case ControlType::Number:
        s.number(c) = o.number(s.name);
        break;
      case ControlType::Integer: {
        const long n = o.integer(s.name, 0);
        if (!s.range.admits(static_cast<double>(n))) fail(call, ": option '", s.name, "' ", s.range.rule, ", got ", n);
        if (n < INT_MIN || n > INT_MAX) fail(call, ": option '", s.name, "' must be at most ", INT_MAX, ", got ", n);
        s.integer(c) = static_cast<int>(n);
        break;
      }
      case ControlType::Flag:
        s.flag(c) = o.boolean(s.name, s.flag(c));
        break;
      case ControlType::Vector:
        s.vector(c) = o.point(s.name);
        break;
      case ControlType::Choice: {
        const std::string name = o.string(s.name);
        const int i = s.find_choice(name);
        if (i < 0) fail(call, ": option '", s.name, "' must be ", s.choice_list(), ", got \"", name, "\"");
        s.set_choice(c, i);
        break;
      }
    }
    if (const char* rule = s.violated(c)) fail(call, ": option '", s.name, "' ", rule, ", got ", s.value_text(c));
  }
}

Options controls_options(lua_State* L, int idx, const char* call) {
  return Options(L, idx, call, control_option_names());
}

namespace {

void push_controls(lua_State* L, const Controls& current) {
  Controls c = current;  // the table's accessors take a writable Controls
  lua_createtable(L, 0, static_cast<int>(control_specs().size()));
  for (const ControlSpec& s : control_specs()) {
    switch (s.type) {
      case ControlType::Number:
        set_number_field(L, s.name, s.number(c));
        continue;
      case ControlType::Integer:
        set_integer_field(L, s.name, s.integer(c));
        continue;
      case ControlType::Flag:
        lua_pushboolean(L, s.flag(c));
        break;
      case ControlType::Vector:
        push_point(L, s.vector(c));
        break;
      case ControlType::Choice:
        lua_pushstring(L, s.choices[s.get_choice(c)]);
        break;
    }
    lua_setfield(L, -2, s.name);
  }
}

// m:controls{...} sets; m:controls() returns the current controls as a table.
int m_controls(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:controls");
  if (!lua_isnoneornil(L, 2)) {
    check_not_busy(m, "m:controls");
    Controls c = m.world().controls();
    parse_controls(controls_options(L, 2, "m:controls"), c);
    m.world().controls() = c;
  }
  push_controls(L, m.world().controls());
  return 1;
}

// m:gravity(gx, gy)
int m_gravity(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:gravity");
  check_not_busy(m, "m:gravity");
  const double gx = check_number(L, 2, "m:gravity", "argument 1 (gx)");
  const double gy = check_number(L, 3, "m:gravity", "argument 2 (gy)");
  m.world().controls().gravity = Vec2(gx, gy);
  return 0;
}

// ---- stepping -----------------------------------------------------------------------------------

std::string where_now(const World& w) { return msg("at step ", w.step_count(), ", t = ", w.time(), " s"); }

// dda run --restart: the model the checkpoint was written from (by its
// number in the run) takes the checkpoint's state at its first stepping
// call, once the script has built it again with its loads and monitors.
void restart_if_pending(lua_State* L, ScriptModel& m) {
  Session& s = session(L);
  if (!s.restart || s.restart->number != m.number) return;
  const long mark = m.world().step_count();  // where the straight run stood at this call
  m.restore(*s.restart, msg("--restart ", s.restart_file));
  s.restart.reset();
  m.replay_mark = mark;
  m.last_checkpoint_time = m.world().time();
  s.log.line(msg("restart: model ", m.number, " continues from ", s.restart_file, " ", where_now(m.world())));
}

// Between steps: stop if Ctrl-C was pressed (worded only then: no string is
// built in a step loop that goes on), with a checkpoint first when the run
// writes them.
void stop_if_interrupted(ScriptModel& m, Stepping* run) {
  if (!interrupt_requested()) return;
  if (run) run->checkpoint_now();
  check_interrupt(where_now(m.world()).c_str());
}

// The run log gets each model's controls at its first stepping call (what
// the script set by then), as the key = value pairs of m:controls().
void log_controls_once(lua_State* L, ScriptModel& m) {
  Session& s = session(L);
  if (!s.log.is_open() || m.controls_logged) return;
  m.controls_logged = true;
  Controls c = m.world().controls();
  if (s.threads >= 0) c.threads = s.threads;
  push_controls(L, c);
  std::map<std::string, std::string> items;
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    std::string v;
    if (lua_type(L, -1) == LUA_TTABLE) {
      lua_rawgeti(L, -1, 1);
      lua_rawgeti(L, -2, 2);
      v = msg("{", lua_tonumber(L, -2), ", ", lua_tonumber(L, -1), "}");
      lua_pop(L, 2);
    } else if (lua_type(L, -1) == LUA_TBOOLEAN) {
      v = lua_toboolean(L, -1) ? "true" : "false";
    } else {
      v = lua_tostring(L, -1);
    }
    items[lua_tostring(L, -2)] = v;
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::string text;
  for (const auto& [k, v] : items) text += " " + k + "=" + v;
  s.log.line(msg("model: ", m.world().block_count(), " blocks; controls:", text));
  const double g1 = m.world().controls().g1;
  s.log.line(g1 > 0 ? msg("time step: at most g1 = ", g1, " s, as the script gives")
                    : "time step: g1 = 0, the default rule (docs/time_step.md): " +
                          m.world().default_time_step().describe());
}

// Before the first step: the wave model, the functions sampled over the run
// this call asks for (to its end time, or its steps at the first step's Δt);
// what it decided goes to the run log, its warnings to stderr too.
void decide_wave_model_once(lua_State* L, ScriptModel& m, const RunPlan& plan) {
  if (m.world().wave_model().decided) return;
  const World& w = m.world();
  const double dt = w.controls().g1 > 0 ? w.controls().g1 : w.default_time_step().dt;
  const double window = plan.t_end >= 0 ? plan.t_end : static_cast<double>(std::max<long>(plan.steps, 0)) * dt;
  const WaveModel& wave = m.decide_wave_model(L, window);
  Session& s = session(L);
  for (const std::string& note : wave.notes)
    if (s.log.is_open()) s.log.line("wave model: " + note);
  // The default rule reads the smallest block: after meshing, the elements'
  // (the line logged with the controls was the blocks' before).
  if (s.log.is_open() && wave.meshed_blocks > 0 && !(w.controls().g1 > 0))
    s.log.line("time step: after meshing, the default rule (docs/time_step.md): " + w.default_time_step().describe());
  for (const std::string& warning : wave.warnings) warn(warning);
}

}  // namespace

long begin_stepping_call(lua_State* L, ScriptModel& m, const RunPlan& plan) {
  stop_if_params_only(L, "the first stepping call");
  restart_if_pending(L, m);
  const long s0 = m.replay_mark ? *m.replay_mark : m.world().step_count();
  stop_if_interrupted(m, nullptr);
  log_controls_once(L, m);
  decide_wave_model_once(L, m, plan);
  return s0;
}

namespace {

// A stepping call may not begin while a background run holds the model.
void check_no_background_run(ScriptModel& m, const char* call) {
  if (m.control().active() && m.control().background())
    fail(call, ": the model has a background run (", to_string(m.control().state()),
         "): m:wait() for its end, or m:stop() it first");
}

// The stepping loop of m:step, m:run_until and m:run, on the Lua thread
// (m:start runs the same steps on a thread of its own: background_run.cpp).
// Lua runs only between steps: load histories inside ScriptModel::step
// (before World::step), the callback after the step's monitors are written.
// Between steps a live view may take its turn at the model, and pause the
// run (the loop then waits, holding nothing).
//
// After a restart the model may stand ahead of the script: a call counts its
// steps from where the straight run stood when it began (replay_mark), so
// m:step(n) and m:run{steps = n} end where they ended in the straight run
// (at once, if that is before the checkpoint), as m:run{time = t} does.
void run_loop(lua_State* L, ScriptModel& m, RunPlan plan) {
  World& w = m.world();
  const long s0 = begin_stepping_call(L, m, plan);
  Stepping run(L, 1, m, std::move(plan), s0);
  const RunPlanView view = run.view(false);
  Progress progress(L, view.t_start, view.t_end >= 0 ? view.t_end : 0, s0, view.step_end >= 0 ? view.step_end : 0);
  RunControl& control = m.control();
  control.begin(view);
  struct End {
    RunControl& control;
    Stepping& run;
    ~End() { control.end(RunState::Idle, run.where()); }
  } end{control, run};
  for (;;) {
    if (!control.wait_between_steps(run.next_start(), interrupt_requested)) break;
    if (const std::string lag = run.take_lag_warning(); !lag.empty()) warn(lag);
    control.lock.yield();
    if (run.done()) {
      if (control.finish_unless_paused()) break;
      continue;  // paused just as it came to its end: wait for the resume
    }
    run.advance(L);
    stop_if_interrupted(m, &run);
    progress.update(w.time(), w.step_count());
    if (!run.follow_up(L)) break;
  }
  stop_if_interrupted(m, &run);
  if (const std::string pace = run.pace_report(); !pace.empty()) warn(pace);
  session(L).log.line("run: " + run.summary());
  run.settle_replay_mark();
}

int push_time_and_steps(lua_State* L, const ScriptModel& m) {
  lua_pushnumber(L, m.world().time());
  lua_pushinteger(L, m.world().step_count());
  return 2;
}

// m:step([n = 1]) → t, step
int m_step(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:step");
  check_not_busy(m, "m:step");
  check_no_background_run(m, "m:step");
  RunPlan plan;
  plan.steps = lua_isnoneornil(L, 2) ? 1 : check_integer(L, 2, "m:step", "argument 1 (number of steps)");
  if (plan.steps < 0) fail("m:step: argument 1 (number of steps) must be zero or positive, got ", plan.steps);
  run_loop(L, m, std::move(plan));
  return push_time_and_steps(L, m);
}

// m:run_until(t) → t, step
int m_run_until(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:run_until");
  check_not_busy(m, "m:run_until");
  check_no_background_run(m, "m:run_until");
  RunPlan plan;
  plan.t_end = check_number(L, 2, "m:run_until", "argument 1 (time)");
  if (plan.t_end < 0) fail("m:run_until: argument 1 (time) must be zero or positive, got ", plan.t_end);
  run_loop(L, m, std::move(plan));
  return push_time_and_steps(L, m);
}

}  // namespace

constexpr Name kRunPlanOptions[] = {
    {"time", "run until the model's time reaches this (s); give `time` or `steps`", "—"},
    {"steps", "run this many steps; give `time` or `steps`", "—"},
    {"every", "call `callback` every this many steps", "1"},
    {"callback", "function(m) called between steps; returning false stops the run", "none"},
    {"realtime", "pace the run to the wall clock: r simulated seconds per second (1: real time); 0: as fast as it goes",
     "0"}};

Names run_plan_options() { return kRunPlanOptions; }

RunPlan read_run_plan(const Options& o) {
  lua_State* L = o.state();
  const char* call = o.call().c_str();
  RunPlan plan;
  if (one_of(o, {"time", "steps"}) == 0) {
    plan.t_end = o.non_negative("time", 0);
  } else {
    plan.steps = o.integer("steps", 0);
    if (plan.steps < 0) fail(call, ": option 'steps' must be zero or positive, got ", plan.steps);
  }
  plan.every = o.integer("every", 1);
  if (plan.every < 1) fail(call, ": option 'every' must be at least 1, got ", plan.every);
  if (o.has("callback")) {
    if (o.push("callback") != LUA_TFUNCTION) {
      const std::string t = type_of(L, -1);
      lua_pop(L, 1);
      fail(call, ": option 'callback' must be a function, got ", t);
    }
    plan.callback = LuaRef(L, -1);
    lua_pop(L, 1);
  } else if (o.has("every")) {
    fail(call, ": option 'every' needs a 'callback' to call");
  }
  plan.realtime = o.non_negative("realtime", 0);
  return plan;
}

namespace {

const std::vector<Name> kRunOptions = [] {
  std::vector<Name> n(std::begin(kRunPlanOptions), std::end(kRunPlanOptions));
  n.push_back({"background", "true: the run goes on a thread of its own, as m:start{...}", "false"});
  return n;
}();

// m:run{time = t | steps = n, every = N, callback = f, realtime = r, background = false} → t, step
int m_run(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:run");
  check_not_busy(m, "m:run");
  check_no_background_run(m, "m:run");
  const Options o(L, 2, "m:run", kRunOptions);
  RunPlan plan = read_run_plan(o);
  if (o.boolean("background", false)) {
    start_background_run(L, 1, m, std::move(plan));
    return 0;
  }
  run_loop(L, m, std::move(plan));
  return push_time_and_steps(L, m);
}

constexpr Name kSettleOptions[] = {
    {"tolerance",
     "converged when every block's unbalanced force is at most this share of the largest block weight (without "
     "gravity: of the largest stress resultant |σ|·sqrt(A))",
     "1e-5"},
    {"max_steps", "settling steps before it gives up with an error", "10000"}};
constexpr Name kSettleReturns[] = {{"steps", "the settling steps taken (static, the time held)"},
                                   {"ratio", "the largest unbalanced force over the reference force at the end"}};

// m:settle{tolerance = 1e-5, max_steps = 10000} → {steps, ratio}: the model
// brought to equilibrium under what acts on it now (world/settle.hpp), then
// at rest; an error names the block furthest from balance when it does not
// settle.
int m_settle(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:settle");
  check_not_busy(m, "m:settle");
  double tolerance = 1e-5;
  long max_steps = 10000;
  if (!lua_isnoneornil(L, 2)) {
    const Options o(L, 2, "m:settle", kSettleOptions);
    tolerance = o.positive("tolerance", tolerance);
    max_steps = o.integer("max_steps", max_steps);
    if (max_steps < 1) fail("m:settle: option 'max_steps' must be at least 1, got ", max_steps);
  }
  check_no_background_run(m, "m:settle");
  begin_stepping_call(L, m, RunPlan{});
  World& w = m.world();
  lua_createtable(L, 0, 2);
  if (m.replay_mark) {  // dda run --restart: the checkpoint's model is past its settling
    set_integer_field(L, "steps", 0);
    set_number_field(L, "ratio", w.unbalanced_force().ratio);
    return 1;
  }
  const long s0 = w.step_count();
  Progress progress(L, 0, 0, s0, s0 + max_steps);
  UnbalancedForce u;
  long steps = 0;
  {
    const auto settling = w.settling();
    do {
      m.settle_step(L);
      ++steps;
      check_interrupt(msg("while settling, ", where_now(w)).c_str());
      progress.update(w.time(), w.step_count());
      m.control().lock.yield();  // a live view's turn
      u = w.unbalanced_force();
    } while (u.ratio > tolerance && steps < max_steps);
  }
  Session& s = session(L);
  if (u.ratio > tolerance) {
    const Vec2 c = w.block_centroid(u.block);
    fail("m:settle: not in equilibrium after ", steps, " steps: the unbalanced force on block ", u.block, " at (",
         c.x(), ", ", c.y(), ") is ", u.ratio, " of the largest block weight (tolerance ", tolerance,
         "). The model does not stand as it is (a block slides, topples or falls: m:contacts{state = \"sliding\"} "
         "lists the sliding contacts), or it needs more steps (option max_steps).");
  }
  w.come_to_rest();
  s.log.line(msg("settled: ", steps, " static steps, the largest unbalanced force ", u.ratio,
                 " of the largest block weight (tolerance ", tolerance, "); at rest, displacements from here"));
  set_integer_field(L, "steps", steps);
  set_number_field(L, "ratio", u.ratio);
  return 1;
}

// m:save(file) → path: a checkpoint of the model (a relative name goes into the output folder)
int m_save(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:save");
  check_not_busy(m, "m:save");
  const std::filesystem::path file = check_string(L, 2, "m:save", "argument 1 (file)");
  const Session& s = session(L);
  const std::filesystem::path path = file.is_absolute() ? file : s.out_dir / file;
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  try {
    m.save(path);
  } catch (const Error& e) {
    fail("m:save: ", e.what());
  }
  lua_pushstring(L, path.string().c_str());
  return 1;
}

// ---- read access ------------------------------------------------------------------------------------

int m_time(lua_State* L) {
  lua_pushnumber(L, check_model(L, 1, "m:time").world().time());
  return 1;
}
int m_steps(lua_State* L) {
  lua_pushinteger(L, check_model(L, 1, "m:steps").world().step_count());
  return 1;
}
int m_dt(lua_State* L) {
  lua_pushnumber(L, check_model(L, 1, "m:dt").world().current_dt());
  return 1;
}
int m_suggested_dt(lua_State* L) {
  lua_pushnumber(L, check_model(L, 1, "m:suggested_dt").world().default_time_step().dt);
  return 1;
}
int m_stats(lua_State* L) {
  push_stats(L, check_model(L, 1, "m:stats").world().last_stats());
  return 1;
}
int m_totals(lua_State* L) {
  const Totals& t = check_model(L, 1, "m:totals").totals();
  lua_createtable(L, 0, 6);
  set_integer_field(L, "steps", t.steps);
  set_integer_field(L, "step_cuts", t.step_cuts);
  set_integer_field(L, "open_close_iterations", t.open_close_iterations);
  set_integer_field(L, "cg_iterations", t.cg_iterations);
  set_integer_field(L, "patch_iterations", t.patch_iterations);
  set_number_field(L, "wall_seconds", t.wall_seconds);
  set_number_field(L, "steps_per_second", t.wall_seconds > 0 ? t.steps / t.wall_seconds : 0);
  return 1;
}
// m:energy() → {kinetic, strain, contact, gravity, ..., residual, step = {...}}
void push_energy_terms(lua_State* L, const EnergyTerms& e) {
  lua_createtable(L, 0, static_cast<int>(std::size(kEnergyTerms)));
  for (const EnergyTermName& t : kEnergyTerms) set_number_field(L, t.name, e.*t.term);
}
int m_energy(lua_State* L) {
  const EnergyBudget& e = check_model(L, 1, "m:energy").world().energy();
  push_energy_terms(L, e.total);
  push_energy_terms(L, e.last_step);
  lua_setfield(L, -2, "step");
  return 1;
}
int m_hash(lua_State* L) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016" PRIx64,
                static_cast<std::uint64_t>(check_model(L, 1, "m:hash").world().state_hash()));
  lua_pushstring(L, buf);
  return 1;
}
int m_half_height(lua_State* L) {
  lua_pushnumber(L, check_model(L, 1, "m:half_height").world().half_height());
  return 1;
}

ContactState parse_state(const std::string& s, const char* call) {
  if (s == "open") return ContactState::Open;
  if (s == "sliding") return ContactState::Sliding;
  if (s == "locked") return ContactState::Locked;
  fail(call, ": option 'state' must be \"open\", \"sliding\" or \"locked\", got \"", s, "\"");
}

constexpr Name kContactsOptions[] = {
    {"state", "only contacts in this state: `\"open\"`, `\"sliding\"` or `\"locked\"`", "every state"},
    {"block", "only contacts of this block (either side)", "every block"}};
constexpr Name kContactFields[] = {{"vblock", "the block whose vertex is in contact"},
                                   {"vertex", "that vertex (from 1)"},
                                   {"eblock", "the block whose edge is in contact"},
                                   {"edge", "that edge (from 1: vertex k to k + 1)"},
                                   {"state", "`\"open\"`, `\"sliding\"` or `\"locked\"`"},
                                   {"intact", "whether the joint there is still intact (holds cohesion and tension)"},
                                   {"joint", "its JointMaterial"},
                                   {"normal_force", "N (N/m), compression positive"},
                                   {"shear_force", "S (N/m)"},
                                   {"penetration", "the vertex's depth into the edge (m, positive: penetrating)"},
                                   {"length", "the joint length the contact stands for (m)"}};

// m:contacts{state = "sliding", block = b} → array of contact tables
int m_contacts(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:contacts");
  std::optional<ContactState> state;
  std::optional<BlockId> block;
  if (!lua_isnoneornil(L, 2)) {
    const Options o(L, 2, "m:contacts", kContactsOptions);
    if (o.has("state")) state = parse_state(o.string("state"), "m:contacts");
    if (o.has("block")) {
      o.push("block");
      block = check_block(L, -1, &m, "m:contacts", "option 'block'");
      lua_pop(L, 1);
    }
  }
  lua_newtable(L);
  const int out = lua_gettop(L);
  lua_Integer n = 0;
  for (const Contact& c : m.world().contacts()) {
    if (state && c.state != *state) continue;
    if (block && c.vblock != *block && c.eblock != *block) continue;
    lua_createtable(L, 0, 12);
    push_block(L, 1, c.vblock);
    lua_setfield(L, -2, "vblock");
    lua_pushinteger(L, c.vertex + 1);
    lua_setfield(L, -2, "vertex");
    push_block(L, 1, c.eblock);
    lua_setfield(L, -2, "eblock");
    lua_pushinteger(L, c.edge + 1);
    lua_setfield(L, -2, "edge");
    lua_pushstring(L, to_string(c.state));
    lua_setfield(L, -2, "state");
    lua_pushboolean(L, c.intact);
    lua_setfield(L, -2, "intact");
    push_joint(L, 1, c.joint);
    lua_setfield(L, -2, "joint");
    lua_pushnumber(L, c.normal_force);
    lua_setfield(L, -2, "normal_force");
    lua_pushnumber(L, c.shear_force);
    lua_setfield(L, -2, "shear_force");
    lua_pushnumber(L, c.penetration);
    lua_setfield(L, -2, "penetration");
    lua_pushnumber(L, c.length);
    lua_setfield(L, -2, "length");
    lua_rawseti(L, out, ++n);
  }
  return 1;
}

// m:contact_summary() → {total, open, sliding, locked, intact}
int m_contact_summary(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:contact_summary");
  long open = 0, sliding = 0, locked = 0, intact = 0;
  for (const Contact& c : m.world().contacts()) {
    open += c.state == ContactState::Open;
    sliding += c.state == ContactState::Sliding;
    locked += c.state == ContactState::Locked;
    intact += c.intact;
  }
  lua_createtable(L, 0, 5);
  lua_pushinteger(L, static_cast<lua_Integer>(m.world().contacts().size()));
  lua_setfield(L, -2, "total");
  lua_pushinteger(L, open);
  lua_setfield(L, -2, "open");
  lua_pushinteger(L, sliding);
  lua_setfield(L, -2, "sliding");
  lua_pushinteger(L, locked);
  lua_setfield(L, -2, "locked");
  lua_pushinteger(L, intact);
  lua_setfield(L, -2, "intact");
  return 1;
}

// m:close(): frees the model now; every handle into it becomes invalid.
int m_close(lua_State* L) {
  auto* box = static_cast<ModelBox*>(luaL_testudata(L, 1, kModelType));
  if (!box || !box->model) fail("m:close: expected a model as self, got ", type_of(L, 1));
  if (on_stepping_thread()) fail("m:close: not from a callback of a background run (it would wait for itself)");
  hold_for_call(*box->model);
  check_not_busy(*box->model, "m:close");
  box->model->close();
  return 0;
}

int m_gc(lua_State* L) {
  auto* box = static_cast<ModelBox*>(luaL_testudata(L, 1, kModelType));
  if (!box) return 0;
  delete box->model;
  box->model = nullptr;
  return 0;
}

int m_tostring(lua_State* L) {
  auto* box = static_cast<ModelBox*>(luaL_testudata(L, 1, kModelType));
  if (!box || !box->model || box->model->closed()) {
    lua_pushliteral(L, "dda.Model (closed)");
    return 1;
  }
  int blocks, contacts, step;
  double t;
  {
    std::lock_guard hold(box->model->control().lock);  // between two steps of a background run
    const World& w = box->model->world();
    blocks = static_cast<int>(w.block_count()), contacts = static_cast<int>(w.contacts().size());
    step = static_cast<int>(w.step_count()), t = w.time();
  }
  lua_pushfstring(L, "dda.Model (%d blocks, %d contacts, step %d, t = %f s)", blocks, contacts, step, t);
  return 1;
}

}  // namespace

namespace {

std::vector<Name> stats_names() {
  std::vector<Name> n = {
      {"dt", "the step's Δt (s)"},
      {"open_close_iterations", "open-close iterations (one solve each)"},
      {"cg_iterations", "conjugate-gradient iterations, over all rows"},
      {"patch_iterations", "CG iterations confined to the patch of a re-solve"},
      {"solver",
       "the backend the step started with: `\"pcg\"` or `\"cholmod\"` (a trial of the factor that gives up "
       "finishes its step with PCG)"},
      {"factorisations",
       "numeric factorisations of the system (cholmod; under `\"auto\"` a step on PCG counts the one "
       "it makes as it ends, for a trial of the factor in the next step)"},
      {"factor_iterations", "of `cg_iterations`, those preconditioned with the factor (cholmod)"},
      {"solve_regime", "`\"short\"` or `\"long\"` solves"},
      {"step_cuts", "times Δt was cut and the step redone"},
      {"cut_reason", "why the last cut was made (empty: none)"},
      {"contacts", "contacts in the list"},
      {"closed_contacts", "contacts not open"},
      {"contacts_searched", "whether a full contact search ran (else the list was reused)"},
      {"max_displacement_ratio", "the largest vertex displacement over its bound g2·(half the model height)"},
      {"landings", "contacts the landing law resolved"}};
  static const std::vector<std::string> stage_names = [] {
    std::vector<std::string> k;
    for (int i = 0; i < kStageCount; ++i) k.push_back(msg("t_", kStageKeys[i]));
    return k;
  }();
  for (const std::string& k : stage_names) n.push_back({k.c_str(), "seconds in that stage of the step"});
  n.push_back({"t_total", "seconds of the whole step"});
  return n;
}

Names energy_names() {
  static const std::vector<Name> names = [] {
    std::vector<Name> n;
    for (const EnergyTermName& t : kEnergyTerms) n.push_back({t.name, t.doc});
    n.push_back({"step", "the same terms for the last step alone"});
    return n;
  }();
  return names;
}

}  // namespace

void register_model(lua_State* L) {
  static const std::vector<Name> stats = stats_names();
  static constexpr Name totals[] = {{"steps", "steps taken"},
                                    {"step_cuts", "times Δt was cut"},
                                    {"open_close_iterations", "open-close iterations"},
                                    {"cg_iterations", "CG iterations"},
                                    {"patch_iterations", "CG iterations on re-solve patches"},
                                    {"wall_seconds", "wall-clock seconds in steps"},
                                    {"steps_per_second", "steps over wall_seconds"}};
  static constexpr Name contact_summary[] = {{"total", "contacts in the list"},
                                             {"open", "open contacts"},
                                             {"sliding", "sliding contacts"},
                                             {"locked", "locked contacts"},
                                             {"intact", "contacts whose joint is intact"}};
  static const Method methods[] = {
      {"controls", guarded<m_controls>,
       "m:controls{...} → the controls as a table\nSets the controls given (the same options as dda.model{...}, "
       "checked at once); m:controls() only returns them.",
       control_option_names()},
      {"gravity", guarded<m_gravity>, "m:gravity(gx, gy)\nSets the control gravity (m/s²)."},
      {"step", guarded<m_step>, "m:step([n = 1]) → t, step\nTakes n steps; returns the time and the step count."},
      {"run_until", guarded<m_run_until>, "m:run_until(t) → t, step\nSteps until the model's time reaches t (s)."},
      {"run", guarded<m_run>,
       "m:run{...} → t, step\nSteps for a time or a number of steps, calling `callback` between steps; paced to "
       "the wall clock with `realtime`, on a thread of its own with `background` (as m:start).",
       kRunOptions},
      {"settle", guarded<m_settle>,
       "m:settle{...} → {steps, ratio}\nBrings the model to equilibrium under gravity, initial stresses and the "
       "loads' present values (static steps, the time held: docs/time_step.md, \"Settling\"), then to "
       "rest: velocities zero, displacements counted from here, the energy budget anew. An error names the "
       "block furthest from balance when it does not settle within max_steps.",
       kSettleOptions, kSettleReturns},
      {"save", guarded<m_save>,
       "m:save(file) → path\nA checkpoint of the whole model (blocks, contacts, loads, the solver's state), from "
       "which dda.load(file) or dda run --restart continues bit for bit. A relative name goes into the output "
       "folder; the file is replaced atomically."},
      {"time", guarded<m_time>, "m:time() → the simulated time (s)"},
      {"steps", guarded<m_steps>, "m:steps() → the steps taken"},
      {"dt", guarded<m_dt>, "m:dt() → the next step's Δt (s)"},
      {"suggested_dt", guarded<m_suggested_dt>,
       "m:suggested_dt() → s\nThe upper step time g1 = 0 stands for: the default rule for this model as it is "
       "now (docs/time_step.md, \"The default time step\")."},
      {"stats", guarded<m_stats>, "m:stats() → the last step's figures", {}, stats},
      {"energy",
       guarded<m_energy>,
       "m:energy() → the energy budget (J/m)\nHeld now (kinetic, strain, contact), the work on the blocks since "
       "the first step (or since m:settle), and the balance's residual.",
       {},
       energy_names()},
      {"totals", guarded<m_totals>, "m:totals() → the totals over every step", {}, totals},
      {"hash", guarded<m_hash>, "m:hash() → a hex hash of the whole state (the same for any thread count)"},
      {"half_height", guarded<m_half_height>,
       "m:half_height() → m\nHalf the model's height: the length g2 and contact_tolerance scale with."},
      {"contacts", guarded<m_contacts>,
       "m:contacts{...} → an array of contact tables\nThe contacts now, each a table with the keys below.",
       kContactsOptions, kContactFields},
      {"contact_summary",
       guarded<m_contact_summary>,
       "m:contact_summary() → the contacts counted by state",
       {},
       contact_summary},
      {"close", guarded<m_close>, "m:close()\nFrees the model now; every handle into it becomes invalid."},
      {}};
  static const luaL_Reg meta[] = {{"__gc", m_gc}, {"__tostring", m_tostring}, {nullptr, nullptr}};
  static const Method no_methods[] = {{}};
  define_type(L, kModelType, no_methods, meta);
  add_model_methods(L, methods, "Running and reading");
}

}  // namespace dda::script
