// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Lua states with the dda module, and running files and strings in them
// with a traceback handler.
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "core/error.hpp"
#include "lua_support.hpp"
#include "run_control.hpp"
#include "scripting.hpp"

namespace dda::script {

namespace {

// As lua.c's msghandler: the message plus a traceback.
int message_handler(lua_State* L) {
  const char* text = lua_tostring(L, 1);
  if (text == nullptr) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    text = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  luaL_traceback(L, L, text, 1);
  return 1;
}

// Calls the chunk at the top of the stack (nargs arguments above it) with
// the handler; leaves the results (LUA_MULTRET) or the error message.
int docall(lua_State* L, int nargs, int nresults) {
  const int base = lua_gettop(L) - nargs;
  lua_pushcfunction(L, message_handler);
  lua_insert(L, base);
  const int status = lua_pcall(L, nargs, nresults, base);
  lua_remove(L, base);
  return status;
}

// A returned table counts as results when it is plain data: no metatable,
// string keys, number / string / boolean values. Scripts that also serve as
// modules return other things (the paper's figure scripts return their
// Figure object for validation_report.lua); those leave no results.
// dda.result{...} is the strict form: anything else there is an error.
bool is_results_table(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  if (!lua_istable(L, idx)) return false;
  if (lua_getmetatable(L, idx)) {
    lua_pop(L, 1);
    return false;
  }
  bool plain = true;
  lua_pushnil(L);
  while (plain && lua_next(L, idx) != 0) {
    const int v = lua_type(L, -1);
    plain = lua_type(L, -2) == LUA_TSTRING && (v == LUA_TNUMBER || v == LUA_TSTRING || v == LUA_TBOOLEAN);
    lua_pop(L, plain ? 1 : 2);
  }
  return plain;
}

std::string pop_error(lua_State* L) {
  std::string e = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error object is not a string)";
  lua_pop(L, 1);
  return e;
}

// Precompiled bytecode is never loaded: Lua does not verify it, and a
// corrupted or hostile chunk crashes the interpreter. load, loadfile, dofile
// and require (its searcher for Lua files) take source text only; the
// message of a refusal carries the caller's file and line.
constexpr const char* kBinaryRefused =
    "binary chunks (precompiled bytecode) are refused: Lua cannot check them and a corrupted one crashes the "
    "interpreter; give the source text";

bool binary_mode(lua_State* L, int idx) {
  const char* mode = luaL_optstring(L, idx, "bt");
  return std::strchr(mode, 't') == nullptr;
}

// Calls the saved library function (the upvalue) with its mode argument, at
// position mode_arg, forced to "t"; a mode that asks for binary chunks is an
// error naming `what`.
int call_in_text_mode(lua_State* L, int mode_arg, const char* what) {
  if (binary_mode(L, mode_arg)) return luaL_error(L, "%s: %s", what, kBinaryRefused);
  if (lua_gettop(L) < mode_arg) lua_settop(L, mode_arg);
  lua_pushliteral(L, "t");
  lua_replace(L, mode_arg);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// load(chunk [, chunkname [, mode [, env]]]) with mode forced to "t".
int text_load(lua_State* L) { return call_in_text_mode(L, 3, "load"); }

// loadfile([filename [, mode [, env]]]) with mode forced to "t".
int text_loadfile(lua_State* L) { return call_in_text_mode(L, 2, "loadfile"); }

// dofile(filename): as Lua's, text only, and a file that cannot be loaded is
// an error at the calling line.
int text_dofile(lua_State* L) {
  const char* name = luaL_optstring(L, 1, nullptr);
  lua_settop(L, 1);
  if (luaL_loadfilex(L, name, "t") != LUA_OK) {
    luaL_where(L, 1);
    lua_insert(L, -2);
    lua_pushfstring(L, "dofile: %s", lua_tostring(L, -1));
    lua_replace(L, -2);
    lua_concat(L, 2);
    return lua_error(L);
  }
  lua_call(L, 0, LUA_MULTRET);
  return lua_gettop(L) - 1;
}

// package.searchers[2]: Lua files on package.path, loaded as text.
int search_lua_text(lua_State* L) {
  const char* name = luaL_checkstring(L, 1);
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "searchpath");
  lua_pushstring(L, name);
  lua_getfield(L, -3, "path");
  if (!lua_isstring(L, -1)) return luaL_error(L, "'package.path' must be a string");
  lua_call(L, 2, 2);
  if (lua_isnil(L, -2)) return 1;  // the "no file ..." list
  const char* file = lua_tostring(L, -2);
  if (luaL_loadfilex(L, file, "t") != LUA_OK)
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name, file, lua_tostring(L, -1));
  lua_pushstring(L, file);
  return 2;
}

// os.exit([code]): as Lua's (true: success, false: failure, else the
// number), but the state is closed first, so every model finishes its
// outputs (no model is left with frames queued on its writer thread while
// exit() destroys the statics that thread uses, the font cache). The
// session's on_exit, when set (`dda run`), ends the run as when the script
// returns and gives the exit status.
int script_exit(lua_State* L) {
  const int requested = lua_isboolean(L, 1) ? (lua_toboolean(L, 1) ? EXIT_SUCCESS : EXIT_FAILURE)
                                            : static_cast<int>(luaL_optinteger(L, 1, EXIT_SUCCESS));
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  lua_State* main = lua_tothread(L, -1);
  lua_pop(L, 1);
  // A copy: the session goes with the state that on_exit closes.
  if (const std::function<int(lua_State*, int)> on_exit = session(main).on_exit) std::exit(on_exit(main, requested));
  stop_background_runs();
  lua_close(main);  // the console, tests: close every model, then exit
  std::exit(requested);
}

void refuse_bytecode(lua_State* L) {
  const std::pair<const char*, lua_CFunction> text_only_loaders[] = {{"load", text_load}, {"loadfile", text_loadfile}};
  for (const auto& [name, text_only] : text_only_loaders) {
    lua_getglobal(L, name);
    lua_pushcclosure(L, text_only, 1);
    lua_setglobal(L, name);
  }
  lua_pushcfunction(L, text_dofile);
  lua_setglobal(L, "dofile");
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "searchers");
  lua_pushcfunction(L, search_lua_text);
  lua_rawseti(L, -2, 2);
  lua_pop(L, 2);
}

// dda run --list-params: a file written or a command run stops the script,
// whose parameters are read by then (their use is the real run's). The
// closure's upvalues: the library function and its name ("io.open"). No
// C++ object lives in this frame: it raises and calls Lua directly.
int stop_before_writing(lua_State* L) {
  const char* name = lua_tostring(L, lua_upvalueindex(2));
  bool writes = true;
  if (std::strcmp(name, "io.open") == 0) writes = std::strpbrk(luaL_optstring(L, 2, "r"), "wa+") != nullptr;
  if (std::strcmp(name, "io.output") == 0) writes = lua_type(L, 1) == LUA_TSTRING;
  if (writes) {
    session(L).params_stopped = true;
    return luaL_error(L, "--list-params: stopped at %s", name);
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

void stop_params_only_before_writing(lua_State* L) {
  static const std::pair<const char*, const char*> writers[] = {{"io", "open"},    {"io", "output"}, {"io", "popen"},
                                                                {"os", "execute"}, {"os", "remove"}, {"os", "rename"},
                                                                {"os", "tmpname"}};
  for (const auto& [library, function] : writers) {
    lua_getglobal(L, library);
    lua_getfield(L, -1, function);
    lua_pushfstring(L, "%s.%s", library, function);
    lua_pushcclosure(L, stop_before_writing, 2);
    lua_setfield(L, -2, function);
    lua_pop(L, 1);
  }
}

}  // namespace

int call_with_traceback(lua_State* L, int nargs, int nresults) { return docall(L, nargs, nresults); }

lua_State* new_state(Session s) {
  lua_State* L = luaL_newstate();
  if (!L) return nullptr;
  luaL_openlibs(L);
  refuse_bytecode(L);
  lua_getglobal(L, "os");
  lua_pushcfunction(L, script_exit);
  lua_setfield(L, -2, "exit");
  lua_pop(L, 1);
  const bool params_only = s.params_only;
  set_session(L, std::move(s));
  if (params_only) stop_params_only_before_writing(L);
  luaL_requiref(L, "dda", open_module, 1);  // package.loaded.dda and the global dda
  lua_pop(L, 1);
  return L;
}

bool run_file(lua_State* L, const std::string& path, const std::vector<std::string>& args, std::string& error) {
  const std::lock_guard lua(lua_gate());  // run_control.hpp
  // arg table, as lua.c: arg[0] = script, arg[1..] = its arguments.
  lua_createtable(L, static_cast<int>(args.size()), 1);
  lua_pushstring(L, path.c_str());
  lua_rawseti(L, -2, 0);
  for (std::size_t i = 0; i < args.size(); ++i) {
    lua_pushstring(L, args[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setglobal(L, "arg");
  // Modules beside the script can be required (scripts/paper/bars.lua).
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "path");
  const std::string old = lua_tostring(L, -1) ? lua_tostring(L, -1) : "";
  lua_pop(L, 1);
  const std::string prefix = (dir / "?.lua").string() + ";";
  if (old.rfind(prefix, 0) != 0) {
    lua_pushstring(L, (prefix + old).c_str());
    lua_setfield(L, -2, "path");
  }
  lua_pop(L, 1);
  session(L).script = path;

  // Text only: precompiled bytecode is refused.
  if (const int status = luaL_loadfilex(L, path.c_str(), "t"); status != LUA_OK) {
    error = pop_error(L);
    if (error.find("attempt to load a binary chunk") != std::string::npos) error = msg(path, ": ", kBinaryRefused);
    if (status == LUA_ERRMEM) error = msg(path, ": not enough memory to load the script");
    return false;
  }
  if (const int status = docall(L, 0, 1); status != LUA_OK) {
    error = pop_error(L);
    // Lua unwinds a memory error without the message handler: no line to give.
    if (status == LUA_ERRMEM)
      error = msg(path,
                  ": not enough memory (Lua could not allocate more: the machine's memory or a ulimit -v ran "
                  "out; Lua gives no line for this error)");
    return false;
  }
  // return {ppv = ..., ...}: the run's results (dda sweep tabulates them).
  if (is_results_table(L, -1)) {
    std::string why;
    add_results(L, lua_gettop(L), "the script's return value", why);  // cannot fail: checked above
  }
  lua_pop(L, 1);
  return true;
}

bool run_string(lua_State* L, const std::string& code, const std::string& chunkname, std::string& error) {
  const std::lock_guard lua(lua_gate());  // run_control.hpp
  if (luaL_loadbufferx(L, code.data(), code.size(), ("=" + chunkname).c_str(), "t") != LUA_OK) {
    error = pop_error(L);
    return false;
  }
  if (docall(L, 0, 0) != LUA_OK) {
    error = pop_error(L);
    return false;
  }
  return true;
}

}  // namespace dda::script
