// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// `dda sweep`: a parameter study as one command. Every combination of the
// --grid values runs as its own `dda run` process in its own folder
// (<out>/run_NNN: the run's outputs, its run.log, output.txt with what it
// printed, status.txt with its exit status), --jobs N of them at a time, and
// one summary table gathers what each run returned (result.csv: `return
// {...}` or dda.result{...}) with its status. --task ID runs one combination
// (a Slurm job array runs the same command with --task $SLURM_ARRAY_TASK_ID),
// --collect only writes the summary from the folders.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app.hpp"
#include "core/error.hpp"
#include "lua_support.hpp"
#include "output_file.hpp"

extern char** environ;

namespace dda::script {

namespace {

const char* kSweepUsage =
    "usage:\n"
    "  dda sweep SCRIPT.lua --grid NAME=V1,V2,... [--grid NAME=...]... [--jobs N] [--out DIR]\n"
    "                       [--task ID | --collect] [dda run options: --set, --threads, --frames, ...]\n"
    "Runs SCRIPT once per combination of the grid values (the last --grid varies fastest), each\n"
    "as `dda run SCRIPT --out DIR/run_NNN --set NAME=V ...` in its own process and folder, and\n"
    "writes DIR/summary.csv: task, status, exit code, wall time, the grid values and what each\n"
    "run returned (`return {name = value, ...}` at the end of the script, or dda.result{...}).\n"
    "  --jobs N     N runs at a time (default 1); each gets --threads CPUS/N unless --threads is given,\n"
    "               CPUS the CPUs this process may use (its affinity; SLURM_CPUS_PER_TASK when smaller)\n"
    "  --out DIR    the sweep's folder (default: sweep)\n"
    "  --task ID    run combination ID only (0-based; e.g. --task $SLURM_ARRAY_TASK_ID), no summary\n"
    "  --collect    run nothing: write DIR/summary.csv from the run folders (after --task runs)\n"
    "  --list       print the combinations with their task IDs and run nothing\n"
    "Before running anything, every grid name must be a parameter the script reads (dda run SCRIPT\n"
    "--list-params lists them); a result named like a grid parameter gets the column NAME_result.\n"
    "exit status: 0 every run ok, 1 a run failed (its row says how), 2 bad command line\n";

int usage(const std::string& text) {
  std::fprintf(stderr,
               "dda sweep: %s\nusage: dda sweep SCRIPT.lua --grid NAME=V1,V2,... [options]  (dda sweep --help "
               "lists the options)\n",
               text.c_str());
  return 2;
}

struct Axis {
  std::string name;
  std::vector<std::string> values;
};

struct Plan {
  std::string script;
  std::vector<Axis> grid;
  std::vector<std::string> passthrough;  // options for every `dda run`
  std::filesystem::path out = "sweep";
  int jobs = 1;
  long task = -1;
  bool collect = false, list = false, threads_given = false;

  long count() const {
    long n = 1;
    for (const Axis& a : grid) n *= static_cast<long>(a.values.size());
    return n;
  }
  // The values of task `id` (last axis fastest).
  std::vector<std::string> values(long id) const {
    std::vector<std::string> v(grid.size());
    for (std::size_t k = grid.size(); k-- > 0;) {
      const long n = static_cast<long>(grid[k].values.size());
      v[k] = grid[k].values[id % n];
      id /= n;
    }
    return v;
  }
  std::filesystem::path folder(long id) const {
    char name[32];
    std::snprintf(name, sizeof name, "run_%03ld", id);
    return out / name;
  }
};

std::vector<std::string> split_values(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(item);
  if (!s.empty() && s.back() == ',') out.emplace_back();
  return out;
}

// Parses the command line; returns 0 or the exit code of a usage error (-1: --help).
int parse(int argc, char** argv, Plan& p) {
  static const std::set<std::string> with_value = {
      "--set",        "--threads", "--frames", "--frame-field",      "--frame-size", "--frame-range",
      "--frame-view", "--vtu",     "--movie",  "--checkpoint-every", "--realtime",   "--live"};
  std::set<std::string> names;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    if (a == "--help" || a == "-h") {
      std::fputs(kSweepUsage, stdout);
      return -1;
    } else if (a == "--grid") {
      const char* v = value();
      const char* eq = v ? std::strchr(v, '=') : nullptr;
      if (!v || !eq || eq == v || !eq[1]) return usage(msg("--grid needs NAME=V1,V2,..., got '", v ? v : "", "'"));
      Axis axis{std::string(v, eq), split_values(eq + 1)};
      for (const std::string& x : axis.values)
        if (x.empty()) return usage(msg("--grid ", v, ": an empty value"));
      if (!names.insert(axis.name).second) return usage(msg("--grid ", axis.name, " is given twice"));
      p.grid.push_back(std::move(axis));
    } else if (a == "--jobs" || a == "-j") {
      const char* v = value();
      char* end = nullptr;
      const long n = v ? std::strtol(v, &end, 10) : 0;
      if (!v || *end || n < 1 || n > 1024)
        return usage(msg("--jobs needs a whole number >= 1, got '", v ? v : "", "'"));
      p.jobs = static_cast<int>(n);
    } else if (a == "--task") {
      const char* v = value();
      char* end = nullptr;
      const long n = v ? std::strtol(v, &end, 10) : -1;
      if (!v || !*v || *end || n < 0) return usage(msg("--task needs a task ID >= 0, got '", v ? v : "", "'"));
      p.task = n;
    } else if (a == "--collect") {
      p.collect = true;
    } else if (a == "--list") {
      p.list = true;
    } else if (a == "--out") {
      const char* v = value();
      if (!v || !*v) return usage("--out needs a folder");
      p.out = v;
    } else if (with_value.count(a)) {
      const char* v = value();
      if (!v) return usage(msg(a, " needs a value"));
      if (a == "--set") {
        const char* eq = std::strchr(v, '=');
        if (eq && names.count(std::string(v, eq)))
          return usage(msg("--set ", v, " and --grid both give '", std::string(v, eq), "'"));
      }
      if (a == "--threads") p.threads_given = true;
      p.passthrough.push_back(a);
      p.passthrough.push_back(v);
    } else if (a.rfind("-", 0) == 0) {
      p.passthrough.push_back(a);  // --quiet and the like; `dda run` checks them
    } else if (p.script.empty()) {
      p.script = a;
    } else {
      return usage(msg("unexpected argument '", a, "'"));
    }
  }
  if (p.script.empty()) return usage("dda sweep needs a script");
  if (p.grid.empty()) return usage("dda sweep needs at least one --grid NAME=V1,V2,...");
  if (p.task >= 0 && p.collect) return usage("give --task or --collect, not both");
  if (p.task >= p.count())
    return usage(
        msg("--task ", p.task, " is past the last combination (", p.count() - 1, "; there are ", p.count(), ")"));
  // Names a later --set gives must not collide with the grid either.
  for (std::size_t k = 0; k + 1 < p.passthrough.size(); ++k)
    if (p.passthrough[k] == "--set") {
      const std::string& v = p.passthrough[k + 1];
      const auto eq = v.find('=');
      if (eq != std::string::npos && names.count(v.substr(0, eq)))
        return usage(msg("--set ", v, " and --grid both give '", v.substr(0, eq), "'"));
    }
  return 0;
}

std::string describe(const Plan& p, long id) {
  const auto v = p.values(id);
  std::string s;
  for (std::size_t k = 0; k < v.size(); ++k) s.append(k ? " " : "").append(p.grid[k].name).append("=").append(v[k]);
  return s;
}

std::filesystem::path self_exe() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path("dda") : exe;
}

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_sweep_sigint(int) { g_stop = 1; }

struct Running {
  pid_t pid;
  long id;
  std::chrono::steady_clock::time_point start;
};

// Starts `args` (argv[0] a path) with stdin from /dev/null, stdout into
// `out` and stderr into `err` (the same file when equal); returns its pid.
pid_t spawn(std::vector<std::string> args, const std::string& out, const std::string& err) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (err == out)
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
  else
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw Error(msg("cannot start '", argv[0], "': ", std::strerror(rc)));
  return pid;
}

// The --set options of task id's grid values.
std::vector<std::string> grid_sets(const Plan& p, long id) {
  std::vector<std::string> args;
  const auto values = p.values(id);
  for (std::size_t k = 0; k < values.size(); ++k) args.insert(args.end(), {"--set", p.grid[k].name + "=" + values[k]});
  return args;
}

// Starts `dda run` for task id, its output into the run folder's output.txt.
pid_t start_run(const Plan& p, long id) {
  const auto dir = p.folder(id);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(msg("cannot create the run folder '", dir.string(), "': ", ec.message()));
  std::filesystem::remove(dir / "status.txt", ec);
  std::filesystem::remove(dir / "result.csv", ec);
  std::string params;
  const auto values = p.values(id);
  for (std::size_t k = 0; k < values.size(); ++k) params += p.grid[k].name + "=" + values[k] + "\n";
  write_file_atomically(dir / "params.txt", params);

  std::vector<std::string> args = {self_exe().string(), "run", p.script, "--out", dir.string()};
  const auto sets = grid_sets(p, id);
  args.insert(args.end(), sets.begin(), sets.end());
  args.insert(args.end(), p.passthrough.begin(), p.passthrough.end());
  if (p.jobs > 1 && !p.threads_given)
    args.insert(args.end(), {"--threads", std::to_string(std::max(1, usable_cpus() / p.jobs))});
  const std::string out = (dir / "output.txt").string();
  return spawn(std::move(args), out, out);
}

// ---- the grid's names, checked before anything runs ------------------------------------------

// The parameters the script reads, from `dda run SCRIPT --list-params` with
// the first combination's values: the script runs up to its first step.
// False, with the reason in `why`, when that run failed.
bool params_read(const Plan& p, std::set<std::string>& names, std::string& why) {
  char scratch[] = "/tmp/dda-sweep-params-XXXXXX";
  if (!mkdtemp(scratch)) {
    why = msg("cannot create a scratch folder in /tmp: ", std::strerror(errno));
    return false;
  }
  const std::filesystem::path dir = scratch;
  std::vector<std::string> args = {self_exe().string(), "run", p.script, "--list-params", "--quiet"};
  const auto sets = grid_sets(p, 0);
  args.insert(args.end(), sets.begin(), sets.end());
  for (std::size_t k = 0; k + 1 < p.passthrough.size(); ++k)
    if (p.passthrough[k] == "--set") args.insert(args.end(), {"--set", p.passthrough[k + 1]});
  int status = -1;
  try {
    const pid_t pid = spawn(std::move(args), (dir / "params.txt").string(), (dir / "output.txt").string());
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  } catch (const std::exception& e) {
    why = e.what();
  }
  std::ifstream in(dir / "params.txt");
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#') names.insert(line.substr(0, line.find('\t')));
  const bool ok = status == 0;
  if (!ok && why.empty()) {
    std::ifstream err(dir / "output.txt");
    std::string last;
    for (std::string line; std::getline(err, line);)
      if (line.rfind("dda: ", 0) == 0 && last.empty()) last = line.substr(5);
    why = last.empty() ? msg("dda run --list-params ended with status ", status) : last;
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  return ok;
}

// Whether `name` is a string literal ("name" or 'name') of the script or of
// a Lua file beside it (a module it may require): a parameter it may read
// only after its first step.
bool named_in_sources(const std::filesystem::path& script, const std::string& name) {
  std::vector<std::filesystem::path> files = {script};
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(script.parent_path(), ec))
    if (e.path().extension() == ".lua" && e.path() != script) files.push_back(e.path());
  for (const auto& f : files) {
    std::ifstream in(f);
    std::stringstream text;
    text << in.rdbuf();
    const std::string s = text.str();
    if (s.find('"' + name + '"') != std::string::npos || s.find('\'' + name + '\'') != std::string::npos) return true;
  }
  return false;
}

// 0, or the exit status of a usage error: a grid name the script never
// reads would run every combination alike (a typo, --grid kn_typo=...).
int check_grid_names(const Plan& p) {
  std::set<std::string> read;
  std::string why;
  if (!params_read(p, read, why)) {
    std::fprintf(stderr,
                 "dda sweep: warning: the grid names are not checked: with the first combination's values the "
                 "script stops before its first step (%s)\n",
                 why.c_str());
    return 0;
  }
  for (const Axis& a : p.grid) {
    if (read.count(a.name) || named_in_sources(p.script, a.name)) continue;
    std::string known, near;
    int best = 3;
    for (const std::string& n : read) {
      known.append(known.empty() ? "" : ", ").append(n);
      if (const int d = edit_distance(a.name, n); d < best) best = d, near = n;
    }
    return usage(msg("--grid ", a.name, ": the script never reads a parameter '", a.name, "'",
                     near.empty() ? std::string() : msg(" (did you mean '", near, "'?)"),
                     "; it reads: ", known.empty() ? std::string("none") : known, ". Nothing was run."));
  }
  return 0;
}

std::string status_name(int code) {
  if (code == 0) return "ok";
  if (code == 1) return "error";
  if (code == 2) return "bad command line";
  if (code == 130) return "interrupted";
  if (code > 128) return msg("killed by signal ", code - 128);
  return msg("exit ", code);
}

// What a run folder says about its run.
struct Row {
  std::string status;
  int code = -1;
  std::string wall;
  std::map<std::string, std::string> results;
};

Row read_row(const Plan& p, long id) {
  Row r;
  const auto dir = p.folder(id);
  std::ifstream st(dir / "status.txt");
  double wall = 0;
  if (st >> r.code >> wall) {
    r.status = status_name(r.code);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", wall);
    r.wall = buf;
  } else {
    std::error_code ec;
    r.status = std::filesystem::exists(dir / "output.txt", ec) ? "unfinished" : "not run";
  }
  std::ifstream in(dir / "result.csv");
  std::string header, values;
  if (std::getline(in, header) && std::getline(in, values)) {
    const auto h = csv_split(header), v = csv_split(values);
    for (std::size_t k = 0; k < h.size() && k < v.size(); ++k) r.results[h[k]] = v[k];
  }
  return r;
}

// DIR/summary.csv from every run folder; returns how many runs are not ok.
long write_summary(const Plan& p) {
  const long n = p.count();
  std::vector<Row> rows;
  std::set<std::string> result_names;
  for (long id = 0; id < n; ++id) {
    rows.push_back(read_row(p, id));
    for (const auto& [k, v] : rows.back().results) result_names.insert(k);
  }
  // A result named like a column before it (a grid name, task, status, ...)
  // gets the column NAME_result: every column name is once in the header.
  std::set<std::string> taken = {"task", "status", "exit_code", "wall_s"};
  for (const Axis& a : p.grid) taken.insert(a.name);
  std::string text = "task,status,exit_code,wall_s";
  for (const Axis& a : p.grid) text.append(",").append(csv_field(a.name));
  for (const std::string& k : result_names) {
    std::string column = k;
    while (taken.count(column)) column += "_result";
    if (column != k)
      std::printf("summary: the result '%s' is named like a column before it: its column is '%s'\n", k.c_str(),
                  column.c_str());
    taken.insert(column);
    text.append(",").append(csv_field(column));
  }
  text += "\n";
  long bad = 0;
  for (long id = 0; id < n; ++id) {
    const Row& r = rows[id];
    bad += r.status != "ok";
    text += msg(id, ",", csv_field(r.status), ",", r.code >= 0 ? std::to_string(r.code) : "", ",", r.wall);
    for (const std::string& v : p.values(id)) text.append(",").append(csv_field(v));
    for (const std::string& k : result_names) {
      const auto it = r.results.find(k);
      text.append(",").append(it == r.results.end() ? std::string() : csv_field(it->second));
    }
    text += "\n";
  }
  std::error_code ec;
  std::filesystem::create_directories(p.out, ec);
  write_file_atomically(p.out / "summary.csv", text);
  std::printf("summary: %s (%ld runs: %ld ok, %ld not)\n", (p.out / "summary.csv").c_str(), n, n - bad, bad);
  return bad;
}

// Runs the given tasks, `jobs` at a time; returns how many did not end with 0.
long run_tasks(const Plan& p, const std::vector<long>& tasks) {
  g_stop = 0;
  struct sigaction sa {
  }, old_int{}, old_term{};
  sa.sa_handler = on_sweep_sigint;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &old_int);
  sigaction(SIGTERM, &sa, &old_term);
  std::vector<Running> running;
  std::size_t next = 0;
  long failed = 0, done = 0;
  const long total = static_cast<long>(tasks.size());
  for (;;) {
    while (!g_stop && next < tasks.size() && static_cast<int>(running.size()) < p.jobs) {
      const long id = tasks[next++];
      try {
        running.push_back({start_run(p, id), id, std::chrono::steady_clock::now()});
      } catch (const std::exception& e) {
        std::fprintf(stderr, "dda sweep: %s\n", e.what());
        ++failed, ++done;
      }
    }
    if (running.empty()) break;
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto it = std::find_if(running.begin(), running.end(), [&](const Running& r) { return r.pid == pid; });
    if (it == running.end()) continue;
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
    try {
      write_file_atomically(p.folder(it->id) / "status.txt", msg(code, " ", wall, "\n"));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "dda sweep: %s\n", e.what());
      failed += code == 0;  // the run's record is lost: the sweep does not end with 0
    }
    ++done;
    failed += code != 0;
    std::printf("[%ld/%ld] %s %s: %s (%.1f s)%s\n", done, total, p.folder(it->id).filename().c_str(),
                describe(p, it->id).c_str(), status_name(code).c_str(), wall,
                code ? msg(", see ", (p.folder(it->id) / "output.txt").string()).c_str() : "");
    std::fflush(stdout);
    running.erase(it);
  }
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  if (g_stop) std::fprintf(stderr, "dda sweep: interrupted; runs not started are marked 'not run'\n");
  return failed + static_cast<long>(tasks.size() - next);
}

}  // namespace

int run_sweep(int argc, char** argv) {
  Plan p;
  if (const int rc = parse(argc, argv, p)) return rc < 0 ? 0 : rc;
  if (!p.collect) {
    const auto script = resolve_script(p.script);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(script, ec)) return usage(msg("no script '", p.script, "'"));
    p.script = std::filesystem::absolute(script).string();
  }
  if (!p.collect && !p.list)
    if (const int rc = check_grid_names(p)) return rc;
  if (p.list) {
    for (long id = 0; id < p.count(); ++id)
      std::printf("%ld %s %s\n", id, p.folder(id).c_str(), describe(p, id).c_str());
    return 0;
  }
  try {
    if (p.collect) return write_summary(p) ? 1 : 0;
    std::vector<long> tasks;
    if (p.task >= 0)
      tasks.push_back(p.task);
    else
      for (long id = 0; id < p.count(); ++id) tasks.push_back(id);
    std::printf("dda sweep: %zu run(s) of %s into %s, %d at a time\n", tasks.size(), p.script.c_str(), p.out.c_str(),
                p.jobs);
    std::fflush(stdout);
    const long failed = run_tasks(p, tasks);
    if (p.task >= 0) return failed ? 1 : 0;  // a job array's task: --collect writes the table
    return write_summary(p) || failed ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dda sweep: %s\n", e.what());
    return 1;
  }
}

}  // namespace dda::script
