// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// `dda run` (batch): the run log, a restart's checkpoint, the script in a
// fresh state with Ctrl-C handled, and the end of the run (results, outputs
// checked, exit status).
#include <fcntl.h>
#include <sched.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

#include "app.hpp"
#include "core/error.hpp"
#include "dda_version.hpp"
#include "live_server.hpp"
#include "model.hpp"
#include "output_file.hpp"
#include "run_control.hpp"

namespace dda::script {

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

int usable_cpus() {
  int n = static_cast<int>(std::thread::hardware_concurrency());
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0) n = CPU_COUNT(&set);
  if (const char* slurm = std::getenv("SLURM_CPUS_PER_TASK")) {
    char* end = nullptr;
    const long k = std::strtol(slurm, &end, 10);
    if (end != slurm && *end == '\0' && k >= 1 && k < n) n = static_cast<int>(k);
  }
  return std::max(n, 1);
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
                 "; ", usable_cpus(), " CPUs usable (", std::thread::hardware_concurrency(), " hardware threads)"));
  std::string params;
  for (const auto& [k, v] : s.params) params += " " + k + "=" + v;
  s.log.line("parameters (--set):" + (params.empty() ? std::string(" none") : params));
  if (s.checkpoint_steps > 0 || s.checkpoint_seconds > 0)
    s.log.line(msg("checkpoints: every ",
                   s.checkpoint_steps > 0 ? msg(s.checkpoint_steps, " steps") : msg(s.checkpoint_seconds, " s"),
                   " into ", (s.out_dir / "checkpoint.ckpt").string()));
}

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

// What <out>/result.csv holds: a header of the names, one row of values.
std::string results_csv(const Session& s) {
  std::string header, row;
  for (const auto& [k, v] : s.results) {
    header.append(header.empty() ? "" : ",").append(csv_field(k));
    row.append(row.empty() ? "" : ",").append(csv_field(v.text));
  }
  return header + "\n" + row + "\n";
}

// Writes <out>/result.csv; false and `why` if it cannot.
bool write_results(const Session& s, std::string& why) {
  try {
    std::error_code ec;
    std::filesystem::create_directories(s.out_dir, ec);
    write_file_atomically(s.out_dir / "result.csv", results_csv(s));
  } catch (const std::exception& e) {
    why = msg("the results: ", e.what());
    return false;
  }
  return true;
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

// How the run ends, whether the script returns or calls os.exit: results
// and outputs written and checked, the state closed (models finish their
// queued frames and files), the run log's last line. Returns the exit status
// (`requested`: the script's os.exit status, when it is still ok).
int finish_batch(lua_State* L, bool ok, std::string error, int requested, std::chrono::steady_clock::time_point start) {
  // Background runs the script left going end first (a paused one only when
  // a live view can resume it); one that failed fails the run.
  if (ok) wait_background_runs(session(L).live != nullptr, interrupt_requested);
  for (const std::string& failure : background_failures())
    if (ok) ok = false, error = failure;
  stop_background_runs();
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

// dda run --list-params: the script runs up to its first stepping call (or
// the first file it would write, Session::params_only) in a scratch output
// folder, what it prints goes to stderr, and stdout gets the parameters it
// read: one line each, name, default and the --set value, tab-separated.
int list_params(const RunOptions& options) {
  std::string scratch = (std::filesystem::temp_directory_path() / "dda-params-XXXXXX").string();
  if (!mkdtemp(scratch.data())) {
    std::fprintf(stderr, "dda: --list-params: cannot create a scratch folder in %s: %s\n",
                 std::filesystem::temp_directory_path().c_str(), std::strerror(errno));
    return 1;
  }
  Session s;
  s.params = options.session.params;
  s.threads = options.session.threads;
  s.out_dir = scratch;
  s.params_only = true;
  lua_State* L = new_state(std::move(s));
  if (!L) {
    std::fprintf(stderr, "dda: cannot create a Lua state (not enough memory)\n");
    return 1;
  }
  std::string error;
  run_string(L,
             "print = function(...) local t = table.pack(...) for i = 1, t.n do t[i] = tostring(t[i]) end "
             "io.stderr:write(table.concat(t, '\\t', 1, t.n), '\\n') end io.output(io.stderr)",
             "list-params", error);
  const bool ran = run_file(L, resolve_script(options.script).string(), options.script_args, error);
  const bool ok = ran || session(L).params_stopped;
  if (!ok) std::fprintf(stderr, "dda: %s\n", error.c_str());
  std::printf("# the parameters %s reads%s (name, default, --set value)\n", options.script.c_str(),
              session(L).params_stopped ? " before its first step"
              : ok                      ? ""
                                        : " before its error");
  for (const auto& [name, def] : session(L).params_read) {
    const auto given = session(L).params.find(name);
    std::printf("%s\t%s\t%s\n", name.c_str(), def.c_str(),
                given == session(L).params.end() ? "" : given->second.c_str());
  }
  lua_close(L);
  std::error_code ec;
  std::filesystem::remove_all(scratch, ec);
  return ok ? 0 : 1;
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

int run_batch(const RunOptions& options) {
  if (options.session.params_only) return list_params(options);
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
  if (std::string live_error; !start_live_view(L, options.script, live_error)) {
    std::fprintf(stderr, "dda: %s\n", live_error.c_str());
    session(L).log.line("error: " + live_error);
    lua_close(L);
    return 2;
  }
  install_interrupt_handler(L);
  // os.exit ends the run as a return does: results and outputs written and checked.
  session(L).on_exit = [start](lua_State* main, int requested) {
    return finish_batch(main, true, "", requested, start);
  };
  std::string error;
  const std::filesystem::path script = resolve_script(options.script);
  bool ok = run_file(L, script.string(), options.script_args, error);
  session(L).on_exit = nullptr;
  if (ok && session(L).restart) {
    ok = false;
    error = msg("--restart ", session(L).restart_file, ": the script never stepped its model ",
                session(L).restart->number, ", which the checkpoint holds: nothing was continued");
  }
  return finish_batch(L, ok, std::move(error), 0, start);
}

}  // namespace dda::script
