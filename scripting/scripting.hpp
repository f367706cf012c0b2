#pragma once
// The Lua layer's entry points: the `dda` module, batch runs and the console.
#include <lua.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "session.hpp"

#define DDA_VERSION_TEXT "0.1"

namespace dda::script {

// lua_CFunction for require "dda": registers every type (once per state) and
// returns the module table.
int open_module(lua_State* L);

// A fresh state with the standard libraries, `dda` preloaded for require and
// set as a global. The caller owns the state (lua_close).
lua_State* new_state(Session session);

// Loads a script (as text only, never bytecode) and runs it with a
// traceback handler. Returns true on success; on failure `error` holds the
// message and traceback. `args` become the global `arg` table (arg[0] = script).
bool run_file(lua_State* L, const std::string& path, const std::vector<std::string>& args, std::string& error);

// Runs a chunk of source text (tests, console).
bool run_string(lua_State* L, const std::string& code, const std::string& chunkname, std::string& error);

// `dda run`: returns the process exit code (0 ok, 1 script error, 130 interrupted).
struct RunOptions {
  std::string command_line;  // as typed, for the run log
  std::string script;
  std::vector<std::string> script_args;
  Session session;
};
int run_batch(const RunOptions& options);

// `dda console [SCRIPT]`
int run_console(const RunOptions& options);

// The script to run: the path as given when it names a file, else (for an
// installed dda) the scene of that name in <prefix>/share/dda/scripts.
std::filesystem::path resolve_script(const std::string& script);

// `dda sweep SCRIPT --grid NAME=v1,v2 ...` (argv after "sweep"); returns the exit code.
int run_sweep(int argc, char** argv);

// Results (dda.result{...}, a script's return table): adds the string-keyed
// numbers, strings and booleans of the table at idx to the session's results;
// false and `why` for any other key or value.
bool add_results(lua_State* L, int idx, const char* what, std::string& why);
// Writes <out>/result.csv (a header of the names, one row of values); false and `why` if it cannot.
bool write_results(const Session& s, std::string& why);
// What result.csv holds (dda run prints it on stderr when it cannot be written).
std::string results_csv(const Session& s);

// Before a run: the output folder can be made and written (a file created
// in it and removed), and its file system has space; "" when so, else why
// not. Less than kLowSpaceBytes free gives `warning` (the run goes on).
std::string check_output_folder(const std::filesystem::path& folder, std::string& warning);
inline constexpr double kLowSpaceBytes = 100e6;

// help([x]): prints the API's documentation (help.cpp).
int dda_help(lua_State* L);

// The commit the binary was built from ("unknown" outside git).
const char* commit_id();

// Warnings for --set names the script never read (typos), one line each.
std::vector<std::string> unused_params(const Session& s);

}  // namespace dda::script
