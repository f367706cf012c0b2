// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// ParaView output from Lua (vtu.hpp):
//   m:vtu{folder = "vtu", every = N | every_time = dt, prefix = "", contacts = true} → dda.Vtu
//   vtu:write() → path         a frame now
// and `dda run --vtu N` (every model, every N steps, into <out>/vtu).
#include "session.hpp"
#include "vtu.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

constexpr const char* kVtuType = "dda.Vtu";

// The model's VTU series, written between steps like frames.
struct VtuHook : StepHook {
  std::vector<std::unique_ptr<VtuSeries>> series;
  void before_step(const World& w) override {
    for (auto& s : series) s->maybe_write(w);  // the state before the first step
  }
  void after_step(const World& w) override {
    for (auto& s : series) s->maybe_write(w);
  }
  void restarted(const World& w) override {
    for (auto& s : series) s->continue_from(w);
  }
};

VtuHook& vtu_hook(ScriptModel& m) {
  for (const auto& h : m.hooks())
    if (auto* v = dynamic_cast<VtuHook*>(h.get())) return *v;
  return static_cast<VtuHook&>(m.add_hook(std::make_unique<VtuHook>()));
}

std::filesystem::path in_out_dir(lua_State* L, const std::string& p) {
  const std::filesystem::path path(p);
  return path.is_absolute() ? path : session(L).out_dir / path;
}

constexpr Name kVtuOptions[] = {{"folder", "its folder (a relative name goes into the output folder)", "\"vtu\""},
                                {"every", "files every this many steps", "—"},
                                {"every_time", "files each time the simulated time passes a multiple of this (s)", "—"},
                                {"prefix", "put before the files' names (blocks_00000.vtu, ...)", "\"\""},
                                {"contacts", "write the contacts too (contacts_NNNNN.vtu, contacts.pvd)", "true"}};

// m:vtu{...} → dda.Vtu
int m_vtu(lua_State* L) {
  ScriptModel& m = check_model(L, 1, "m:vtu");
  check_not_busy(m, "m:vtu");
  const Options o(L, 2, "m:vtu", kVtuOptions);
  VtuOptions v;
  v.folder = in_out_dir(L, o.string("folder", "vtu"));
  v.prefix = o.string("prefix", "");
  v.every_steps = o.integer("every", 0);
  if (v.every_steps < 0) fail("m:vtu: option 'every' must be positive, got ", v.every_steps);
  v.every_time = o.non_negative("every_time", 0);
  if (v.every_steps > 0 && v.every_time > 0) fail("m:vtu: give 'every' or 'every_time', not both");
  v.contacts = o.boolean("contacts", true);
  auto& hook = vtu_hook(m);
  hook.series.push_back(std::make_unique<VtuSeries>(std::move(v)));
  push_handle(L, 1, kVtuType, static_cast<int>(hook.series.size()) - 1);
  return 1;
}

VtuSeries& self_series(lua_State* L, const char* call, Handle** handle = nullptr) {
  Handle* h = check_handle(L, 1, kVtuType, call, "self");
  auto& hook = vtu_hook(*h->model);
  if (h->id < 0 || h->id >= static_cast<int>(hook.series.size())) fail(call, ": attempt to use an invalid VTU series");
  if (handle) *handle = h;
  return *hook.series[h->id];
}

int vtu_write(lua_State* L) {
  Handle* h = nullptr;
  VtuSeries& s = self_series(L, "vtu:write", &h);
  lua_pushstring(L, s.write(h->model->world()).c_str());
  return 1;
}
int vtu_count(lua_State* L) {
  lua_pushinteger(L, self_series(L, "vtu:count").count());
  return 1;
}
int vtu_pvd(lua_State* L) {
  VtuSeries& s = self_series(L, "vtu:pvd");
  const std::string kind = lua_isnoneornil(L, 2) ? "blocks" : check_string(L, 2, "vtu:pvd", "argument 1 (kind)");
  if (kind != "blocks" && kind != "contacts")
    fail("vtu:pvd: argument 1 must be \"blocks\" or \"contacts\", got \"", kind, "\"");
  lua_pushstring(L, s.pvd(kind).c_str());
  return 1;
}
int vtu_tostring(lua_State* L) {
  auto* h = static_cast<Handle*>(luaL_checkudata(L, 1, kVtuType));
  lua_pushfstring(L, "dda.Vtu %d", static_cast<int>(h->id + 1));
  return 1;
}

}  // namespace

void register_vtu(lua_State* L) {
  static const Method model_methods[] = {
      {"vtu", guarded<m_vtu>,
       "m:vtu{...} → Vtu\nParaView files (blocks_00000.vtu, contacts_00000.vtu, ... and the series blocks.pvd, "
       "contacts.pvd) every N steps or dt seconds, the first before the first step; with neither, only when "
       "vtu:write() is called.",
       kVtuOptions},
      {}};
  add_model_methods(L, model_methods, "ParaView files");
  static const Method methods[] = {
      {"write", guarded<vtu_write>, "vtu:write() → path of the blocks file: a frame now"},
      {"count", guarded<vtu_count>, "vtu:count() → frames written"},
      {"pvd", guarded<vtu_pvd>, "vtu:pvd([\"blocks\" | \"contacts\"]) → the path of the time series ParaView opens"},
      {}};
  static const luaL_Reg meta[] = {{"__tostring", vtu_tostring}, {nullptr, nullptr}};
  define_type(L, kVtuType, methods, meta);
}

void attach_session_vtu(lua_State* L, int model_idx) {
  const Session& s = session(L);
  if (s.vtu_every <= 0) return;
  auto* box = static_cast<ModelBox*>(lua_touserdata(L, model_idx));
  VtuOptions v;
  v.folder = s.out_dir / (s.models_created <= 1 ? std::string("vtu") : msg("vtu_", s.models_created));
  v.every_steps = s.vtu_every;
  try {
    vtu_hook(*box->model).series.push_back(std::make_unique<VtuSeries>(std::move(v)));
  } catch (const Error& e) {  // the command line's option, not the script's line, is the cause
    fail("dda run --vtu ", s.vtu_every, " (the command line): ", e.what());
  }
}

}  // namespace dda::script
