// Lua states with the dda module, running files and strings with a
// traceback handler, and `dda run` (batch).
#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

#include "core/error.hpp"
#include "core/output_file.hpp"
#include "dda_version.hpp"
#include "lua_support.hpp"
#include "model.hpp"
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

int script_exit(lua_State* L);  // below, with the batch run

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

}  // namespace

int docall_with_traceback(lua_State* L, int nargs, int nresults) { return docall(L, nargs, nresults); }

lua_State* new_state(Session s) {
  lua_State* L = luaL_newstate();
  if (!L) return nullptr;
  luaL_openlibs(L);
  refuse_bytecode(L);
  lua_getglobal(L, "os");
  lua_pushcfunction(L, script_exit);
  lua_setfield(L, -2, "exit");
  lua_pop(L, 1);
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

std::filesystem::path resolve_script(const std::string& script) {
  const std::filesystem::path p(script);
  std::error_code ec;
  if (p.is_absolute() || std::filesystem::exists(p, ec)) return p;
#ifdef DDA_SCRIPTS_FROM_BIN
  // An installed dda: its scenes in <prefix>/share/dda/scripts.
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = exe.parent_path() / DDA_SCRIPTS_FROM_BIN / p;
    if (std::filesystem::exists(installed, ec)) return installed.lexically_normal();
  }
#endif
  return p;
}

const char* commit_id() { return DDA_COMMIT; }

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

namespace {

void log_start(Session& s, const RunOptions& options) {
  s.log.open(s.out_dir / "run.log");
  s.log.line("==== dda run: " + (options.command_line.empty() ? options.script : options.command_line));
  char host[256] = "?";
  gethostname(host, sizeof host - 1);
  s.log.line(msg("version ", DDA_VERSION_TEXT, ", commit ", DDA_COMMIT, ", Lua ", LUA_VERSION_MAJOR, ".",
                 LUA_VERSION_MINOR, ", host ", host));
  s.log.line(msg("script ", options.script, ", working folder ", std::filesystem::current_path().string()));
  s.log.line(msg("threads: ",
                 s.threads < 0    ? std::string("as the script sets them (--threads not given)")
                 : s.threads == 0 ? std::string("every core (--threads 0)")
                                  : msg(s.threads, " (--threads)"),
                 "; ", std::thread::hardware_concurrency(), " hardware threads"));
  std::string params;
  for (const auto& [k, v] : s.params) params += " " + k + "=" + v;
  s.log.line("parameters (--set):" + (params.empty() ? std::string(" none") : params));
  if (s.checkpoint_steps > 0 || s.checkpoint_seconds > 0)
    s.log.line(msg("checkpoints: every ",
                   s.checkpoint_steps > 0 ? msg(s.checkpoint_steps, " steps") : msg(s.checkpoint_seconds, " s"),
                   " into ", (s.out_dir / "checkpoint.ckpt").string()));
}

// *.part files of a killed run: removed before this run writes its own
// (written before this run started: a concurrent writer's are younger).
void remove_leftovers(Session& s, std::filesystem::file_time_type started) {
  const auto removed = remove_stray_part_files(s.out_dir, started);
  if (removed.empty()) return;
  std::string names;
  for (std::size_t i = 0; i < removed.size() && i < 5; ++i) names += (i ? ", " : "") + removed[i].string();
  if (removed.size() > 5) names += msg(" and ", removed.size() - 5, " more");
  s.log.line(
      msg("removed ", removed.size(), " unfinished file(s) an earlier run left (killed while writing): ", names));
}

}  // namespace

std::string check_output_folder(const std::filesystem::path& folder, std::string& warning) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return msg("cannot create it: ", ec.message());
  if (!std::filesystem::is_directory(folder, ec)) return "it is not a folder";
  // Writable: a file created there and removed (access() would pass a
  // read-only file system for root).
  const std::filesystem::path probe = folder / msg(".dda-write-check-", getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
  if (fd < 0) return msg("cannot write in it: ", std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
  struct statvfs fs {};
  if (::statvfs(folder.c_str(), &fs) == 0) {
    const double free_bytes = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
    if (fs.f_bavail == 0) return "its file system has no space left";
    if (free_bytes < kLowSpaceBytes)
      warning = msg("the output folder '", folder.string(), "' has only ", free_bytes / 1e6,
                    " MB free: outputs may not fit (monitors, frames, checkpoints)");
  }
  return "";
}

namespace {

// --restart FILE: read and checked before the script runs (a wrong file
// fails at once, not at the first step).
bool read_restart(Session& s, std::string& error) {
  if (s.restart_file.empty()) return true;
  try {
    std::vector<std::string> ignored;  // the script gives its Lua functions again
    s.restart = ScriptModel::load(s.restart_file, ignored);
  } catch (const Error& e) {
    error = msg("--restart: ", e.what());
    return false;
  }
  s.log.line(msg("restart from ", s.restart_file, ": model ", s.restart->number, " at step ",
                 s.restart->world().step_count(), ", t = ", s.restart->world().time(), " s"));
  return true;
}

}  // namespace

namespace {

// How the run ends, whether the script returns or calls os.exit: results
// and outputs written and checked, the state closed (models finish their
// queued frames and files), the run log's last line. Returns the exit status
// (`requested`: the script's os.exit status, when it is still ok).
int finish_batch(lua_State* L, bool ok, std::string error, int requested, std::chrono::steady_clock::time_point start) {
  const bool interrupted = interrupt_requested();
  const int interrupted_status = 128 + interrupt_signal();  // 130 (Ctrl-C), 143 (SIGTERM)
  remove_interrupt_handler();
  // A script that failed early never reached its dda.param calls: no warnings then.
  if (ok)
    for (const std::string& w : unused_params(session(L))) warn(w.substr(w.rfind("warning: ", 0) == 0 ? 9 : 0));
  if (!session(L).results.empty()) {
    std::string why;
    if (!write_results(session(L), why)) {
      // Computed and not written: on stderr, so that nothing is lost.
      std::fprintf(stderr, "dda: %s; the results are:\n%s", why.c_str(), results_csv(session(L)).c_str());
      if (ok) error = why;
      ok = false;
    }
  }
  // lua_close closes every model: frame sequences finish their queued
  // frames, monitors close their CSV files. The log outlives it.
  RunLog log = std::move(session(L).log);
  set_run_log(&log);
  lua_close(L);
  // What the script printed is an output too (dda run > table.txt).
  errno = 0;
  if ((std::fflush(stdout) != 0 || std::ferror(stdout)) && ok) {
    error = msg("cannot write the standard output: ", errno ? std::strerror(errno) : "a write failed");
    ok = false;
  }
  if (!log.failure().empty() && ok) {
    error = msg("run log: ", log.failure());
    ok = false;
  }
  int status = ok ? requested : 1;
  if (!ok) {
    std::fprintf(stderr, "dda: %s\n", error.c_str());
    log.line("error: " + error);
    if (interrupted) {
      std::fprintf(stderr, "dda: %s; the monitor files hold every step computed so far\n", interrupt_name());
      status = interrupted_status;
    }
  } else if (interrupted) {
    status = interrupted_status;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  set_run_log(nullptr);
  log.line(msg("end: exit status ", status,
               status == 0                                   ? " (ok)"
               : interrupted && status == interrupted_status ? (status == 130 ? " (interrupted)" : " (terminated)")
                                                             : " (error)",
               " after ", wall, " s"));
  return status;
}

// The batch run in progress, for os.exit.
struct BatchInProgress {
  lua_State* L;
  std::chrono::steady_clock::time_point start;
};
BatchInProgress* g_batch = nullptr;

// os.exit([code]): as Lua's (true: success, false: failure, else the
// number), but the run ends as when the script returns: the state is
// closed first, so no model is left with frames queued on its writer thread
// while exit() destroys the statics that thread uses (the font cache), and
// every output is finished and checked.
int script_exit(lua_State* L) {
  const int requested = lua_isboolean(L, 1) ? (lua_toboolean(L, 1) ? EXIT_SUCCESS : EXIT_FAILURE)
                                            : static_cast<int>(luaL_optinteger(L, 1, EXIT_SUCCESS));
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
  lua_State* main = lua_tothread(L, -1);
  lua_pop(L, 1);
  if (g_batch && main == g_batch->L) {
    const BatchInProgress batch = *g_batch;
    g_batch = nullptr;
    std::exit(finish_batch(batch.L, true, "", requested, batch.start));
  }
  lua_close(main);  // the console, tests: close every model, then exit
  std::exit(requested);
}

}  // namespace

int run_batch(const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const auto started = std::filesystem::file_time_type::clock::now();
  Session s = options.session;
  if (!s.quiet) s.progress = isatty(fileno(stderr)) && isatty(fileno(stdout)) ? ProgressMode::Bar : ProgressMode::Lines;
  if (const char* env = std::getenv("DDA_PROGRESS_SECONDS"); env && *env) s.progress_seconds = std::atof(env);
  // The output folder first: a run whose results cannot be written is not started.
  std::string folder_warning;
  if (const std::string why = check_output_folder(s.out_dir, folder_warning); !why.empty()) {
    std::fprintf(stderr, "dda: the output folder '%s' cannot be used: %s; give another with --out\n",
                 s.out_dir.string().c_str(), why.c_str());
    return 1;
  }
  log_start(s, options);
  remove_leftovers(s, started);
  if (!folder_warning.empty()) {
    std::fprintf(stderr, "dda: warning: %s\n", folder_warning.c_str());
    s.log.line("warning: " + folder_warning);
  }
  std::string restart_error;
  if (!read_restart(s, restart_error)) {
    std::fprintf(stderr, "dda: %s\n", restart_error.c_str());
    s.log.line("error: " + restart_error);
    s.log.line("end: exit status 1 (error)");
    return 1;
  }
  lua_State* L = new_state(std::move(s));
  if (!L) {
    std::fprintf(stderr, "dda: cannot create a Lua state (not enough memory)\n");
    return 1;
  }
  set_run_log(&session(L).log);
  install_interrupt_handler(L);
  BatchInProgress batch{L, start};
  g_batch = &batch;
  std::string error;
  const std::filesystem::path script = resolve_script(options.script);
  bool ok = run_file(L, script.string(), options.script_args, error);
  g_batch = nullptr;
  if (ok && session(L).restart) {
    ok = false;
    error = msg("--restart ", session(L).restart_file, ": the script never stepped its model ",
                session(L).restart->number, ", which the checkpoint holds: nothing was continued");
  }
  return finish_batch(L, ok, std::move(error), 0, start);
}

}  // namespace dda::script
