// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The dda application: `dda run` (batch), `dda console`, `dda sweep`, built
// on the Lua binding (scripting.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "scripting.hpp"

namespace dda::script {

// `dda run`: returns the process exit code (0 ok, 1 script error, 130
// interrupted, 143 stopped by SIGTERM).
struct RunOptions {
  std::string command_line;  // as typed, for the run log
  std::string script;
  std::vector<std::string> script_args;
  Session session;
};
int run_batch(const RunOptions& options);

// Before a run: the output folder can be made and written (a file created
// in it and removed), and its file system has space; "" when so, else why
// not. Less than kLowSpaceBytes free gives `warning` (the run goes on).
std::string check_output_folder(const std::filesystem::path& folder, std::string& warning);
inline constexpr double kLowSpaceBytes = 100e6;

// `dda console [SCRIPT]`
int run_console(const RunOptions& options);

// The script to run: the path as given when it names a file, else (for an
// installed dda) the scene of that name in <prefix>/share/dda/scripts.
std::filesystem::path resolve_script(const std::string& script);

// `dda sweep SCRIPT --grid NAME=v1,v2 ...` (argv after "sweep"); returns the exit code.
int run_sweep(int argc, char** argv);

// The CPUs this process may use: its affinity mask (taskset, cgroups, a
// batch system's binding), and SLURM_CPUS_PER_TASK when that is smaller.
int usable_cpus();

// The commit the binary was built from ("unknown" outside git).
const char* commit_id();

}  // namespace dda::script
