// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The Lua binding's entry points: the `dda` module, Lua states that have it,
// and running scripts in them. The application (app/: `dda run`, the
// console, sweeps) is built on these.
#include <lua.hpp>

#include <string>
#include <utility>
#include <vector>

#include "session.hpp"

// DDA_VERSION_TEXT: the project's version (CMake's project(VERSION), a
// compile definition of the binding).

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

// lua_pcall of the function below its nargs arguments, with the message
// handler that adds a traceback (as lua.c's docall).
int call_with_traceback(lua_State* L, int nargs, int nresults);

// Results (dda.result{...}, a script's return table): adds the string-keyed
// numbers, strings and booleans of the table at idx to the session's results;
// false and `why` for any other key or value.
bool add_results(lua_State* L, int idx, const char* what, std::string& why);

// help([x]): prints the API's documentation (help.cpp).
int dda_help(lua_State* L);
// The API reference, from the same tables as help(): (file name in docs/,
// Markdown) for each page (docs/lua_api.md, lua_api_model.md, ...).
std::vector<std::pair<std::string, std::string>> api_reference_pages(lua_State* L);

// Warnings for --set names the script never read (typos), one line each.
std::vector<std::string> unused_params(const Session& s);

}  // namespace dda::script
