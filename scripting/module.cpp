// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The `dda` module table: dda.model{...}, dda.load(file), dda.param(name, default),
// dda.output(name), dda.out_dir(), dda.fields, dda.version.
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "background_run.hpp"
#include "output_file.hpp"
#include "scripting.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

// dda.model{plane = "stress" | "strain", g0 = ..., ...controls} → Model
int dda_model(lua_State* L) {
  Controls c;
  if (!lua_isnoneornil(L, 1)) parse_controls(controls_options(L, 1, "dda.model"), c);
  push_new_model(L, c).number = ++session(L).models_created;
  attach_session_frames(L, lua_gettop(L));  // dda run --frames N
  attach_session_vtu(L, lua_gettop(L));     // dda run --vtu N
  return 1;
}

// dda.load(file) → the model of a checkpoint written by m:save or
// --checkpoint-every (a relative name not found as given is looked for in
// the output folder, where they write).
int dda_load(lua_State* L) {
  const std::string file = check_string(L, 1, "dda.load", "argument 1 (file)");
  Session& s = session(L);
  std::filesystem::path path = file;
  std::error_code ec;
  if (path.is_relative() && !std::filesystem::exists(path, ec) && std::filesystem::exists(s.out_dir / path, ec))
    path = s.out_dir / path;
  std::vector<std::string> warnings;
  std::unique_ptr<ScriptModel> model;
  try {
    model = ScriptModel::load(path, warnings);
  } catch (const Error& e) {
    fail("dda.load: ", e.what());
  }
  for (const std::string& w : warnings) warn("dda.load: " + w);
  ScriptModel& m = push_model(L, std::move(model));
  m.number = ++s.models_created;
  m.last_checkpoint_time = m.world().time();  // --checkpoint-every T s counts from here
  attach_session_frames(L, lua_gettop(L));
  attach_session_vtu(L, lua_gettop(L));
  return 1;
}

// dda.param(name, default) → the --set NAME=VALUE value (a number when it
// reads as one, true/false when the default is a boolean), else the default.
int dda_param(lua_State* L) {
  const std::string name = check_string(L, 1, "dda.param", "argument 1 (name)");
  Session& s = session(L);
  s.params_read.emplace(
      name, lua_isnoneornil(L, 2) ? std::string("nil") : [&] {
        lua_pushvalue(L, 2);
        std::string text = luaL_tolstring(L, -1, nullptr);
        lua_pop(L, 2);
        return text;
      }());
  const auto it = s.params.find(name);
  if (it == s.params.end()) {
    lua_settop(L, 2);
    return 1;
  }
  const std::string& v = it->second;
  const int def_type = lua_type(L, 2);
  if (def_type == LUA_TBOOLEAN) {
    if (v == "true" || v == "1" || v == "yes")
      lua_pushboolean(L, 1);
    else if (v == "false" || v == "0" || v == "no")
      lua_pushboolean(L, 0);
    else
      fail("dda.param: --set ", name, "=", v, " must be true or false (the default is a boolean)");
    return 1;
  }
  if (!v.empty() && lua_stringtonumber(L, v.c_str()) != 0) return 1;
  if (def_type == LUA_TNUMBER)
    fail("dda.param: --set ", name, "=", v, " is not a number (the default is ", lua_tonumber(L, 2), ")");
  lua_pushlstring(L, v.data(), v.size());
  return 1;
}

// dda.out_dir() → the output folder (--out, default "out")
int dda_out_dir(lua_State* L) {
  lua_pushstring(L, session(L).out_dir.string().c_str());
  return 1;
}

// dda.output(name) → path of `name` in the output folder (created if needed),
// for scripts that write their own files with io.open.
int dda_output(lua_State* L) {
  const std::string name = check_string(L, 1, "dda.output", "argument 1 (file name)");
  const Session& s = session(L);
  std::error_code ec;
  std::filesystem::create_directories(s.out_dir, ec);
  if (ec) fail("dda.output: cannot create the output folder '", s.out_dir.string(), "': ", ec.message());
  lua_pushstring(L, (s.out_dir / name).string().c_str());
  return 1;
}

// dda.result{name = value, ...}: results of the run (numbers, strings,
// booleans), written to <out>/result.csv when `dda run` ends; dda sweep
// gathers them into its summary table. Later calls add to and replace names.
int dda_result(lua_State* L) {
  std::string why;
  if (!add_results(L, 1, "argument 1", why)) fail("dda.result: ", why);
  return 0;
}

}  // namespace

bool add_results(lua_State* L, int idx, const char* what, std::string& why) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE) {
    why = msg(what, " must be a table {name = value, ...}, got ", type_of(L, idx));
    return false;
  }
  std::map<std::string, ResultValue> add;
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      why = msg(what, ": result names must be strings, got a ", luaL_typename(L, -2), " key");
      lua_pop(L, 2);
      return false;
    }
    const std::string key = lua_tostring(L, -2);
    ResultValue v;
    switch (lua_type(L, -1)) {
      case LUA_TNUMBER:
        v.number = true;
        v.text = lua_isinteger(L, -1) ? msg(lua_tointeger(L, -1)) : [&] {
          char buf[40];
          std::snprintf(buf, sizeof buf, "%.17g", lua_tonumber(L, -1));
          return std::string(buf);
        }();
        break;
      case LUA_TSTRING:
        v.text = lua_tostring(L, -1);
        break;
      case LUA_TBOOLEAN:
        v.text = lua_toboolean(L, -1) ? "true" : "false";
        break;
      default:
        why = msg(what, ": result '", key, "' must be a number, a string or a boolean, got ", type_of(L, -1));
        lua_pop(L, 2);
        return false;
    }
    add[key] = std::move(v);
    lua_pop(L, 1);
  }
  for (auto& [k, v] : add) session(L).results[k] = std::move(v);
  return true;
}

int open_module(lua_State* L) {
  if (luaL_getmetatable(L, kModelType) == LUA_TNIL) {
    lua_pop(L, 1);
    register_model(L);  // first: the others add methods to dda.Model
    register_background(L);
    register_geometry(L);
    register_materials(L);
    register_block(L);
    register_edges(L);
    register_loads(L);
    register_boundaries(L);
    register_monitor(L);
    register_render(L);
    register_vtu(L);
  } else {
    lua_pop(L, 1);
  }
  static const Method functions[] = {
      {"model", guarded<dda_model>,
       "dda.model{...} → Model\nA new, empty model; its options are the controls (e.g. dda.model{ plane = "
       "\"strain\", gravity = {0, -9.81} }).",
       control_option_names()},
      {"load", guarded<dda_load>,
       "dda.load(file) → Model\nThe model of a checkpoint (m:save, dda run --checkpoint-every), as it was when "
       "saved; it steps on exactly as the saved one would have. A relative name not found as given is looked for in "
       "the output folder. Loads given as Lua functions keep their last value (a warning names each); monitors and "
       "frame sequences are the script's to add again."},
      {"param", guarded<dda_param>,
       "dda.param(name, default) → value\nThe --set NAME=VALUE value (a number when it reads as one, true/false "
       "when the default is a boolean), else the default. `dda run SCRIPT --list-params` lists what a script "
       "reads."},
      {"out_dir", guarded<dda_out_dir>, "dda.out_dir() → the output folder (--out, default \"out\")"},
      {"output", guarded<dda_output>,
       "dda.output(name) → path\nThe path of `name` in the output folder (created if needed), for scripts that "
       "write their own files with io.open."},
      {"help", guarded<dda_help>,
       "dda.help([x])\n`help` in the console: help() an overview, help(f) a function in full (help(m.step)), "
       "help(x) what an object offers (help(m)), help(\"name\") every function of that name."},
      {"result", guarded<dda_result>,
       "dda.result{name = value, ...}\nResults of the run (numbers, strings, booleans), written to "
       "<out>/result.csv when `dda run` ends; dda sweep gathers them into its summary table. Later calls add to "
       "and replace names; a script's `return {name = value, ...}` does the same."},
      {}};
  lua_newtable(L);
  set_methods(L, functions, "dda");
  register_render_functions(L);
  register_ground_motion_functions(L);
  register_exact_functions(L);
  lua_pushliteral(L, DDA_VERSION_TEXT);
  lua_setfield(L, -2, "version");
  const std::string fields = field_list();
  lua_newtable(L);
  int k = 0;
  for (std::size_t start = 0; start < fields.size();) {
    std::size_t end = fields.find(", ", start);
    if (end == std::string::npos) end = fields.size();
    lua_pushlstring(L, fields.data() + start, end - start);
    lua_rawseti(L, -2, ++k);
    start = end + 2;
  }
  lua_setfield(L, -2, "fields");
#ifdef DDA_HAVE_RENDER
  lua_pushboolean(L, 1);
#else
  lua_pushboolean(L, 0);
#endif
  lua_setfield(L, -2, "has_render");
  return 1;
}

std::vector<std::string> unused_params(const Session& s) {
  std::vector<std::string> out;
  for (const auto& [name, value] : s.params)
    if (!s.params_read.count(name))
      out.push_back(msg("warning: --set ", name, "=", value, " was never read by the script (no dda.param(\"", name,
                        "\", ...))"));
  return out;
}

}  // namespace dda::script
