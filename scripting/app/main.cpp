// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The dda executable's command line: dda run | console | sweep, --help on
// each, --version. A command-line error prints its cause and one line of
// usage (exit status 2); --help prints the options (the man page is made
// from `dda --help`).
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "app.hpp"
#include "lua_support.hpp"

#ifdef DDA_HAVE_RENDER
#include "core/error.hpp"
#include "frame/renderer.hpp"
#include "scene/field.hpp"
#endif

namespace {

// The options of dda run and dda console, as --help prints them (help2man
// makes the man page from `dda --help`: "Usage:", then sections headed
// "Name:" with items indented under them).
const char* kRunOptions =
    "Options:\n"
    "  --out DIR          output folder for monitor CSV files (default: out)\n"
    "  --threads N        worker threads for every model (0: every core); overrides the script\n"
    "  --set NAME=VALUE   a parameter the script reads with dda.param(\"NAME\", default)\n"
    "  --list-params      run the script up to its first step and list the parameters it reads\n"
    "                     (name, default, value) instead of running it\n"
    "  --quiet            no progress line\n"
    "  --live [ADDR:]PORT serve a live view of the run at http://ADDR:PORT/ (ADDR: 127.0.0.1, this\n"
    "                     machine only; 0.0.0.0: every address; PORT 0: any free port)\n"
    "  --realtime F       pace every run to F simulated seconds per wall-clock second (1: real time);\n"
    "                     a run that cannot keep up says so\n"
    "  --frames N         every model writes a PNG frame every N steps into DIR/frames\n"
    "  --frames A:B:N     ... from step A to step B (B empty: to the end)\n"
    "  --frame-range MIN,MAX  a fixed colour range in SI units (default: each frame's own)\n"
    "  --frame-view X1,Y1,X2,Y2  the world window they show in m (default: the first frame's)\n"
    "  --movie FILE       with --frames: DIR/FILE made with ffmpeg when the run ends (if on the PATH)\n"
    "  --frame-field F    the field of those frames: sigma_yy (default, as m:frame), sigma_xx,\n"
    "                     tau_xy, sigma_1, von_mises, velocity, displacement, none\n"
    "  --frame-size WxH   their size in pixels (default 1280x720)\n"
    "  --vtu N            every model writes ParaView files (VTU, PVD) every N steps into DIR/vtu\n"
    "  --checkpoint-every N | Ts  every model writes DIR/checkpoint.ckpt every N steps or T s of\n"
    "                     simulated time (e.g. 0.01s), and when Ctrl-C or SIGTERM stops the run\n"
    "  --restart FILE     (dda run) continue from a checkpoint: the script runs again, and its model\n"
    "                     takes the checkpoint's state at its first stepping call\n"
    "  -h, --help         this text\n"
    "\n"
    "Exit status:\n"
    "  0 success, 1 error in the script, 2 bad command line, 130 interrupted (Ctrl-C),\n"
    "  143 stopped by SIGTERM (both after a final checkpoint, with --checkpoint-every)\n";

const char* kCommands =
    "Commands:\n"
    "  run SCRIPT.lua     run a script to its end (batch); dda SCRIPT.lua is the same\n"
    "  console [SCRIPT.lua]  a Lua prompt with the dda module (runs SCRIPT first)\n"
    "  sweep SCRIPT.lua --grid NAME=V1,V2,...\n"
    "                     one run per combination of the values, a summary table (dda sweep --help)\n"
    "  --version          the version and the commit it is built from\n"
    "dda COMMAND --help describes one command. The Lua API: docs/lua_api.md, or help() in the console.\n"
    "\n";

// The one line a command-line error prints under its message.
std::string short_usage(const std::string& command) {
  if (command == "run") return "usage: dda run SCRIPT.lua [options] [-- ARGS...]  (dda run --help lists the options)";
  if (command == "console") return "usage: dda console [SCRIPT.lua] [options]  (dda console --help lists the options)";
  return "usage: dda run|console|sweep SCRIPT.lua [options]  (dda --help for more)";
}

void print_help(const std::string& command) {
  if (command == "run") {
    std::fputs(
        "Usage: dda run SCRIPT.lua [options] [-- ARGS...]\n"
        "Runs SCRIPT.lua (a model in Lua: docs/scripting.md) to its end. What it writes goes into the output\n"
        "folder, with its run log (DIR/run.log); ARGS after -- reach the script as arg[1], arg[2], ...\n"
        "SCRIPT.lua not found as given: an installed dda runs its scene of that name.\n\n",
        stdout);
  } else if (command == "console") {
    std::fputs(
        "Usage: dda console [SCRIPT.lua] [options]\n"
        "Runs SCRIPT.lua (if given) and leaves a Lua prompt with its models alive: help() documents the\n"
        "API, Tab completes names, Ctrl-C stops a run at the next step, Ctrl-D leaves.\n\n",
        stdout);
  } else {
    std::fputs(
        "Usage: dda run SCRIPT.lua [options] [-- ARGS...]\n"
        "  or:  dda console [SCRIPT.lua] [options]\n"
        "  or:  dda sweep SCRIPT.lua --grid NAME=V1,V2,... [options]\n"
        "2-D Discontinuous Deformation Analysis of jointed rock under dynamic loads, driven by Lua scripts.\n\n",
        stdout);
    std::fputs(kCommands, stdout);
  }
  std::fputs(kRunOptions, stdout);
}

// "unknown option '--frame'" (did you mean '--frames'?)
std::string unknown_option(const std::string& given) {
  static const char* const known[] = {
      "--out",        "--threads",  "--set",         "--list-params", "--quiet", "--frames",           "--frame-range",
      "--frame-view", "--movie",    "--frame-field", "--frame-size",  "--vtu",   "--checkpoint-every", "--restart",
      "--live",       "--realtime", "--help"};
  std::string text = "unknown option '" + given + "'";
  const char* best = nullptr;
  int best_distance = 3;  // suggest only a near miss
  for (const char* k : known)
    if (const int d = dda::script::edit_distance(given, k); d < best_distance) best = k, best_distance = d;
  if (best) text += std::string(" (did you mean '") + best + "'?)";
  return text;
}

int usage_error(const std::string& command, const char* fmt, const char* arg) {
  std::fprintf(stderr, "dda: ");
  std::fprintf(stderr, fmt, arg);
  std::fprintf(stderr, "\n%s\n", short_usage(command).c_str());
  return 2;
}

// A whole number of at least `min` (no sign, no exponent, no overflow).
bool whole_number(const char* v, long min, long& n) {
  if (!v || !*v) return false;
  char* end = nullptr;
  errno = 0;
  n = std::strtol(v, &end, 10);
  return *end == '\0' && errno == 0 && n >= min;
}

#ifdef DDA_HAVE_RENDER
// The frame options of the command line, checked here as the renderer
// checks them: a bad value is the command line's error (exit 2), not one of
// the script line that makes the model. "" when they are good.
std::string frame_options_error(const dda::script::Session& s) {
  dda::render::FrameOptions f;
  f.width = s.frames_width;
  f.height = s.frames_height;
  if (s.frames_range_set) f.range = dda::render::ValueRange{s.frames_range[0], s.frames_range[1]};
  if (s.frames_view_set)
    f.view = dda::render::Box{s.frames_view[0], s.frames_view[1], s.frames_view[2], s.frames_view[3]};
  try {
    f.validate();
  } catch (const dda::Error& e) {
    return e.what();
  }
  return "";
}
#endif

}  // namespace

int main(int argc, char** argv) {
  using dda::script::RunOptions;
  if (argc < 2) {
    std::fprintf(stderr, "%s\n", short_usage("").c_str());
    return 2;
  }
  int i = 1;
  std::string command = argv[i];
  if (command == "--help" || command == "-h" || command == "help") {
    print_help("");
    return 0;
  }
  if (command == "--version") {
    std::printf("dda %s, commit %s (Lua %s.%s)\n", DDA_VERSION_TEXT, dda::script::commit_id(), LUA_VERSION_MAJOR,
                LUA_VERSION_MINOR);
    return 0;
  }
  if (command == "sweep") return dda::script::run_sweep(argc - 2, argv + 2);
  if (command == "run" || command == "console") {
    ++i;
  } else if (command.size() > 4 && command.compare(command.size() - 4, 4, ".lua") == 0) {
    command = "run";
  } else {
    return usage_error("", "unknown command '%s'", argv[1]);
  }
  auto bad = [&command](const char* fmt, const char* arg) { return usage_error(command, fmt, arg); };

  RunOptions opt;
  for (int k = 0; k < argc; ++k) opt.command_line.append(k ? " " : "").append(argv[k]);
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* name) -> const char* {
      if (i + 1 >= argc) return nullptr;
      (void)name;
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      print_help(command);
      return 0;
    } else if (a == "--") {
      for (++i; i < argc; ++i) opt.script_args.push_back(argv[i]);
      break;
    } else if (a == "--out") {
      const char* v = value("--out");
      if (!v || !*v) return bad("%s needs a folder", "--out");
      opt.session.out_dir = v;
    } else if (a == "--threads") {
      const char* v = value("--threads");
      long n = 0;
      if (!whole_number(v, 0, n) || n > 4096)
        return bad("--threads needs a whole number from 0 (every core) to 4096, got '%s'", v ? v : "");
      opt.session.threads = static_cast<int>(n);
    } else if (a == "--set") {
      const char* v = value("--set");
      const char* eq = v ? std::strchr(v, '=') : nullptr;
      if (!v || !eq || eq == v) return bad("--set needs NAME=VALUE, got '%s'", v ? v : "");
      opt.session.params[std::string(v, eq)] = std::string(eq + 1);
    } else if (a.rfind("--set=", 0) == 0 || a.rfind("--out=", 0) == 0 || a.rfind("--threads=", 0) == 0) {
      return bad("write '%s' with a space instead of '=' after the option", a.c_str());
    } else if (a == "--frames") {
      // EVERY, or FROM:TO:EVERY (steps; TO empty: no end)
      const char* v = value("--frames");
      long from = 0, to = -1, every = -1;
      char tail = 0;
      const bool ok = v && (std::sscanf(v, "%ld%c", &every, &tail) == 1 ||
                            std::sscanf(v, "%ld:%ld:%ld%c", &from, &to, &every, &tail) == 3 ||
                            (std::sscanf(v, "%ld::%ld%c", &from, &every, &tail) == 2 && (to = -1, true)));
      if (!ok || every < 1 || from < 0 || (to >= 0 && to < from))
        return bad("--frames needs EVERY or FROM:TO:EVERY (whole steps, EVERY >= 1), got '%s'", v ? v : "");
#ifndef DDA_HAVE_RENDER
      return bad("%s: this dda was built without the renderer", "--frames");
#endif
      opt.session.frames_every = every;
      opt.session.frames_from = from;
      opt.session.frames_to = to;
    } else if (a == "--frame-range") {
      const char* v = value("--frame-range");
      double lo = 0, hi = 0;
      char tail = 0;
      if (!v || std::sscanf(v, "%lf,%lf%c", &lo, &hi, &tail) != 2 || !(hi > lo))
        return bad("--frame-range needs MIN,MAX with MIN < MAX (SI units: Pa, m/s, m), got '%s'", v ? v : "");
      opt.session.frames_range_set = true;
      opt.session.frames_range[0] = lo;
      opt.session.frames_range[1] = hi;
    } else if (a == "--frame-view") {
      const char* v = value("--frame-view");
      double q[4];
      char tail = 0;
      if (!v || std::sscanf(v, "%lf,%lf,%lf,%lf%c", &q[0], &q[1], &q[2], &q[3], &tail) != 4 || !(q[2] > q[0]) ||
          !(q[3] > q[1]))
        return bad("--frame-view needs X1,Y1,X2,Y2 (m) with X1 < X2 and Y1 < Y2, got '%s'", v ? v : "");
      opt.session.frames_view_set = true;
      for (int k = 0; k < 4; ++k) opt.session.frames_view[k] = q[k];
    } else if (a == "--movie") {
      const char* v = value("--movie");
      if (!v || !*v) return bad("%s needs a file name (e.g. run.mp4)", "--movie");
      opt.session.frames_movie = v;
    } else if (a == "--frame-field") {
      const char* v = value("--frame-field");
      if (!v || !*v) return bad("%s needs a field name", "--frame-field");
#ifdef DDA_HAVE_RENDER
      try {
        dda::render::parse_field(v);
      } catch (const dda::Error& e) {
        return bad("--frame-field: %s", e.what());
      }
#endif
      opt.session.frames_field = v;
    } else if (a == "--frame-size") {
      const char* v = value("--frame-size");
      int w = 0, h = 0;
      char tail = 0;
      if (!v || std::sscanf(v, "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16)
        return bad("--frame-size needs WIDTHxHEIGHT (e.g. 1280x720), got '%s'", v ? v : "");
      opt.session.frames_width = w;
      opt.session.frames_height = h;
    } else if (a == "--vtu") {
      const char* v = value("--vtu");
      long n = 0;
      if (!whole_number(v, 1, n)) return bad("--vtu needs a whole number of steps >= 1, got '%s'", v ? v : "");
      opt.session.vtu_every = n;
    } else if (a == "--restart") {
      const char* v = value("--restart");
      if (!v || !*v) return bad("%s needs a checkpoint file", "--restart");
      if (command != "run") return bad("%s: only dda run continues from a checkpoint", "--restart");
      opt.session.restart_file = v;
    } else if (a == "--checkpoint-every") {
      // N (steps) or Ts (seconds of simulated time)
      const char* v = value("--checkpoint-every");
      long steps = 0;
      double seconds = 0;
      char unit = 0, tail = 0;
      if (v && std::sscanf(v, "%ld%c", &steps, &tail) == 1 && steps >= 1) {
        opt.session.checkpoint_steps = steps;
      } else if (v && std::sscanf(v, "%lf%c%c", &seconds, &unit, &tail) == 2 && unit == 's' && seconds > 0) {
        opt.session.checkpoint_seconds = seconds;
      } else {
        return bad(
            "--checkpoint-every needs N (steps >= 1) or Ts (seconds of simulated time > 0, e.g. "
            "0.01s), got '%s'",
            v ? v : "");
      }
    } else if (a == "--live") {
      const char* v = value("--live");
      if (!v || !*v) return bad("%s needs [ADDR:]PORT (e.g. 8080)", "--live");
      opt.session.live_address = v;
    } else if (a == "--realtime") {
      const char* v = value("--realtime");
      char* end = nullptr;
      const double f = v ? std::strtod(v, &end) : 0;
      if (!v || !*v || *end != '\0' || !(f > 0) || !std::isfinite(f))
        return bad("--realtime needs a factor > 0 (1: simulated time at the wall clock's pace), got '%s'", v ? v : "");
      opt.session.realtime = f;
    } else if (a == "--quiet" || a == "-q") {
      opt.session.quiet = true;
    } else if (a == "--list-params") {
      if (command != "run") return bad("%s: only dda run lists a script's parameters", "--list-params");
      opt.session.params_only = true;
    } else if (a.rfind("--", 0) == 0) {
      return bad("%s", unknown_option(a).c_str());
    } else if (opt.script.empty()) {
      opt.script = a;
    } else {
      return bad("unexpected argument '%s' (script arguments go after --)", a.c_str());
    }
  }
#ifdef DDA_HAVE_RENDER
  if (opt.session.frames_every > 0)
    if (const std::string e = frame_options_error(opt.session); !e.empty())
      return bad("--frame-size, --frame-range, --frame-view: %s", e.c_str());
#endif
  if (command == "run") {
    if (opt.script.empty()) return bad("%s", "dda run needs a script");
    return dda::script::run_batch(opt);
  }
  return dda::script::run_console(opt);
}
