// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Shared machinery of the Lua layer: raising errors safely, reading option
// tables strictly, and parsing the value shapes every wrapper accepts (points,
// polygons, boxes, time histories).
//
// Error discipline (as LÖVE's luax_catchexcept): code behind a Lua
// C function never calls lua_error / luaL_error itself. It throws a C++
// exception (ScriptError for a user mistake, LuaCallError for an error raised
// by a Lua function we called with lua_pcall, anything else from the engine);
// `guarded<F>` catches it, copies the message into a plain char buffer, leaves
// the catch block and only then raises the Lua error. Lua functions are only
// ever called from C++ through lua_pcall, so no longjmp crosses a C++ frame.
#include <lua.hpp>

#include <array>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/load_check.hpp"
#include "core/types.hpp"
#include "loading/history.hpp"

namespace dda::script {

using dda::LoadCheck;

// A mistake in a script (wrong type, unknown option, bad value). The message
// names the call and the argument; the script position is added when it is
// raised as a Lua error.
class ScriptError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run stopped at a step boundary because the user pressed Ctrl-C.
class Interrupted : public ScriptError {
 public:
  using ScriptError::ScriptError;
};

// dda run --list-params: the script has read its parameters (it reached its
// first step, or the first file it would write) and is stopped there.
class ParamsOnlyStop : public ScriptError {
 public:
  using ScriptError::ScriptError;
};

// An error raised by a Lua function that C++ called through lua_pcall. The
// error object itself is kept in the registry and raised again unchanged (it
// already carries the position of the failing line).
class LuaCallError : public std::exception {
 public:
  LuaCallError(lua_State* L, int ref, std::string text) : L_(L), ref_(ref), text_(std::move(text)) {}
  LuaCallError(LuaCallError&& o) noexcept : L_(o.L_), ref_(o.ref_), text_(std::move(o.text_)) { o.ref_ = LUA_NOREF; }
  LuaCallError(const LuaCallError&) = delete;
  ~LuaCallError() override;
  const char* what() const noexcept override { return text_.c_str(); }
  // Hands the registry reference over to the caller (who must unref it).
  int release() const noexcept {
    int r = ref_;
    ref_ = LUA_NOREF;
    return r;
  }

 private:
  lua_State* L_;
  mutable int ref_;
  std::string text_;
};

template <typename... Parts>
[[noreturn]] void fail(const Parts&... parts) {
  throw ScriptError(msg(parts...));
}

// Runs f(L); turns any C++ exception into a Lua error raised outside the catch
// block. See the header comment.
int protected_call(lua_State* L, lua_CFunction f);

template <lua_CFunction F>
int guarded(lua_State* L) {
  return protected_call(L, F);
}

// Calls the value at the top of the stack with `nargs` arguments below it
// (lua_pcall with a traceback-free handler), expecting `nresults` results.
// On error throws LuaCallError holding the error object.
void pcall(lua_State* L, int nargs, int nresults);

// "number", "table", or a userdata's type name ("dda.Block").
std::string type_of(lua_State* L, int idx);
// "function at foo.lua:12" for a Lua function at idx.
std::string function_where(lua_State* L, int idx);

// ---- Reading plain values (throw ScriptError naming `call` and `what`) -----
double check_number(lua_State* L, int idx, std::string_view call, std::string_view what);
double opt_number(lua_State* L, int idx, double def, std::string_view call, std::string_view what);
long check_integer(lua_State* L, int idx, std::string_view call, std::string_view what);
std::string check_string(lua_State* L, int idx, std::string_view call, std::string_view what);
// {x, y}
Vec2 check_point(lua_State* L, int idx, std::string_view call, std::string_view what);
// {{x, y}, {x, y}, ...} (at least 3 points) or the array part of an options table.
std::vector<Vec2> check_polygon(lua_State* L, int idx, std::string_view call, std::string_view what);
// {x1, y1, x2, y2}: a box (x1 < x2, y1 < y2 after sorting) or a segment.
std::array<double, 4> check_quad(lua_State* L, int idx, std::string_view call, std::string_view what);
std::vector<Vec2> box_polygon(const std::array<double, 4>& b);

double require_positive(double v, std::string_view call, std::string_view what);
double require_non_negative(double v, std::string_view call, std::string_view what);

// ---- Names of the API -------------------------------------------------------
// One name of the Lua API that is not a function: an option of an options
// table, a field of an object, a key of a table a function returns. `doc`
// says what it is, with its unit (Markdown); `fallback`, for an option, what
// leaving it out means (nullptr: it is required). The same tables read the
// options and document them (help(), docs/lua_api*.md), so an option cannot
// be accepted without its documentation.
struct Name {
  const char* name = nullptr;
  const char* doc = nullptr;
  const char* fallback = nullptr;
};
using Names = std::span<const Name>;

// ---- Option tables ---------------------------------------------------------
// Wraps the table at `idx`. Every string key must be one of `known`; integer
// keys 1..n are accepted only with allow_array (e.g. a polygon given inline).
// Values are read with raw access (no metamethods run).
class Options {
 public:
  Options(lua_State* L, int idx, std::string call, Names known, bool allow_array = false);

  lua_State* state() const { return L_; }
  int index() const { return idx_; }
  const std::string& call() const { return call_; }
  std::string what(const char* key) const;  // "m:joint_set{spacing}"

  bool has(const char* key) const;
  // Pushes the value of `key` (nil when absent) and returns its Lua type.
  int push(const char* key) const;
  std::size_t array_size() const;

  double number(const char* key) const;              // required
  double number(const char* key, double def) const;  // optional
  double positive(const char* key) const;
  double positive(const char* key, double def) const;
  double non_negative(const char* key, double def) const;
  long integer(const char* key, long def) const;
  bool boolean(const char* key, bool def) const;
  std::string string(const char* key, const std::string& def) const;
  std::string string(const char* key) const;
  Vec2 point(const char* key) const;
  Vec2 point(const char* key, const Vec2& def) const;
  std::vector<Vec2> polygon(const char* key) const;
  std::array<double, 4> quad(const char* key) const;

 private:
  lua_State* L_;
  int idx_;
  std::string call_;
};

// Exactly one of `keys` present (returns its index), or throws.
int one_of(const Options& o, std::initializer_list<const char*> keys);

// ---- Registry references -------------------------------------------------
// Owns a reference to a Lua value in the registry (released on destruction,
// through the main thread, which outlives every coroutine).
class LuaRef {
 public:
  LuaRef() = default;
  LuaRef(lua_State* L, int idx);  // references the value at idx
  LuaRef(LuaRef&& o) noexcept : main_(o.main_), ref_(o.ref_) { o.ref_ = LUA_NOREF; }
  LuaRef& operator=(LuaRef&& o) noexcept;
  LuaRef(const LuaRef&) = delete;
  LuaRef& operator=(const LuaRef&) = delete;
  ~LuaRef() { reset(); }
  void reset();
  bool valid() const { return ref_ != LUA_NOREF && ref_ != LUA_REFNIL; }
  void push(lua_State* L) const { lua_rawgeti(L, LUA_REGISTRYINDEX, ref_); }

 private:
  lua_State* main_ = nullptr;
  int ref_ = LUA_NOREF;
};

// ---- Time histories ---------------------------------------------------------
// A scalar input that may vary in time: a constant, a table of {t, value}
// pairs (interpolated linearly, end values held outside the range), or a Lua
// function of t. Evaluated once per step, before the step, on the Lua thread.
class TimeInput {
 public:
  TimeInput() = default;
  explicit TimeInput(double constant) : value_(constant) {}

  // Reads a history at idx: number, {{t, v}, ...} or function.
  static TimeInput parse(lua_State* L, int idx, std::string_view call, std::string_view what);

  bool is_constant() const { return kind_ == Kind::Constant; }
  bool is_function() const { return kind_ == Kind::Function; }
  double at(lua_State* L, double t) const;
  // The engine's piecewise-linear history for a constant or a table (the
  // engine evaluates it itself at each step's end, t + Δt, even after a cut).
  // Not for functions.
  dda::History engine_history() const;

  // Checkpoints (core/archive.hpp): a constant or a table as it is; of a
  // function only that it was one, and where (a checkpoint cannot hold Lua
  // code): after reading, is_lost_function().
  template <class Archive>
  void fields(Archive& ar) {
    ar(kind_, value_, t_, v_, what_, where_);
  }
  bool is_lost_function() const { return kind_ == Kind::Function && !fn_.valid(); }
  const std::string& where() const { return where_; }
  // Read from a checkpoint: a finite constant, or a table of as many finite
  // values as times, the times not decreasing; its text made printable
  // (dda::printable: it reaches messages). Throws dda::Error naming the damage.
  void check_loaded(const LoadCheck& check, const std::string& name);

 private:
  enum class Kind { Constant, Table, Function };
  friend constexpr Kind enum_last(Kind) { return Kind::Function; }  // (core/archive.hpp)
  Kind kind_ = Kind::Constant;
  double value_ = 0;
  std::vector<double> t_, v_;
  LuaRef fn_;
  std::string what_;   // "m:point_load{fx}", for messages
  std::string where_;  // "function at foo.lua:12"
};

// A 2-vector input: two scalar histories, or one function of t returning two numbers.
class VecTimeInput {
 public:
  VecTimeInput() = default;
  VecTimeInput(TimeInput x, TimeInput y) : x_(std::move(x)), y_(std::move(y)) {}
  static VecTimeInput constant(const Vec2& v) { return VecTimeInput(TimeInput(v.x()), TimeInput(v.y())); }
  // A function at idx returning (x, y).
  static VecTimeInput function(lua_State* L, int idx, std::string_view call, std::string_view what);

  bool is_constant() const { return !fn_.valid() && x_.is_constant() && y_.is_constant(); }
  bool is_function() const { return fn_.valid() || x_.is_function() || y_.is_function(); }
  Vec2 at(lua_State* L, double t) const;

  // As TimeInput's.
  template <class Archive>
  void fields(Archive& ar) {
    bool function = fn_.valid() || lost_function_;
    ar(x_, y_, function, what_, where_);
    if constexpr (Archive::reading) lost_function_ = function;
  }
  bool is_lost_function() const { return lost_function_ || x_.is_lost_function() || y_.is_lost_function(); }
  std::string where() const { return lost_function_ ? where_ : x_.is_lost_function() ? x_.where() : y_.where(); }
  void check_loaded(const LoadCheck& check, const std::string& name);  // as TimeInput's

 private:
  TimeInput x_, y_;
  LuaRef fn_;
  bool lost_function_ = false;  // read from a checkpoint: was a function
  std::string what_, where_;
};

// Levenshtein distance, for "did you mean" hints.
int edit_distance(std::string_view a, std::string_view b);

}  // namespace dda::script
