// Lua states with the dda module, running files and strings with a
// traceback handler, and `dda run` (batch).
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "lua_support.hpp"
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

std::string pop_error(lua_State* L) {
  std::string e = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error object is not a string)";
  lua_pop(L, 1);
  return e;
}

}  // namespace

int docall_with_traceback(lua_State* L, int nargs, int nresults) { return docall(L, nargs, nresults); }

lua_State* new_state(Session s) {
  lua_State* L = luaL_newstate();
  if (!L) return nullptr;
  luaL_openlibs(L);
  set_session(L, std::move(s));
  luaL_requiref(L, "dda", open_module, 1);  // package.loaded.dda and the global dda
  lua_pop(L, 1);
  return L;
}

bool run_file(lua_State* L, const std::string& path, const std::vector<std::string>& args, std::string& error) {
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
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
    error = pop_error(L);
    return false;
  }
  if (docall(L, 0, 0) != LUA_OK) {
    error = pop_error(L);
    return false;
  }
  return true;
}

bool run_string(lua_State* L, const std::string& code, const std::string& chunkname, std::string& error) {
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

int run_batch(const RunOptions& options) {
  Session s = options.session;
  s.progress = !s.quiet && isatty(fileno(stderr)) && isatty(fileno(stdout));
  lua_State* L = new_state(std::move(s));
  if (!L) {
    std::fprintf(stderr, "dda: cannot create a Lua state (not enough memory)\n");
    return 1;
  }
  install_interrupt_handler(L);
  std::string error;
  const bool ok = run_file(L, options.script, options.script_args, error);
  const bool interrupted = interrupt_requested();
  remove_interrupt_handler();
  for (const std::string& w : unused_params(session(L))) std::fprintf(stderr, "dda: %s\n", w.c_str());
  lua_close(L);  // closes (and flushes) every monitor's CSV file
  std::fflush(stdout);
  if (!ok) {
    std::fprintf(stderr, "dda: %s\n", error.c_str());
    if (interrupted) {
      std::fprintf(stderr, "dda: interrupted; the monitor files hold every step computed so far\n");
      return 130;
    }
    return 1;
  }
  if (interrupted) return 130;
  return 0;
}

}  // namespace dda::script
