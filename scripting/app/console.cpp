// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// `dda console [SCRIPT]`: an interactive prompt in the style of Lua's own
// lua.c: `return <line>` is tried first so expressions print, input continues
// while the chunk is incomplete (its error ends in "<eof>"), errors print a
// traceback and the prompt stays up. Results print as values, tables as
// tables (bounded in depth and length). With readline (when found at build
// time, on a terminal): line editing, Tab completion of Lua names (globals,
// fields, methods; never file names) and history kept between sessions.
//
// What never ends the console: Ctrl-C at the prompt clears the line (at a
// continuation prompt it drops the unfinished statement); Ctrl-C during a
// command stops it at the next step; input ending inside an unfinished
// statement reports that statement's syntax error, and the console then ends
// as at any end of input.
#include <signal.h>
#include <sys/select.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "app.hpp"
#include "core/error.hpp"
#include "live_server.hpp"
#include "run_control.hpp"

#ifdef DDA_HAVE_READLINE
#include <readline/history.h>
#include <readline/readline.h>
#endif

namespace dda::script {

namespace {

constexpr const char* kPrompt = "dda> ";
constexpr const char* kPrompt2 = "...> ";
constexpr const char* kEofMark = "<eof>";
constexpr int kEnd = -1;        // load_statement: the input is over
constexpr int kCancelled = -2;  // load_statement: Ctrl-C dropped the input

// ---- reading lines -------------------------------------------------------------------

enum class Read { Line, End, Interrupted };

// Waiting for input, the console lets go of Lua: a background run whose
// loads are Lua functions steps meanwhile (run_control.hpp).
struct WithoutLua {
  template <class F>
  auto call(F f) {
    const int depth = lua_gate().release_all();
    auto result = f();
    const int saved_errno = errno;  // f's, for the caller
    lua_gate().take_back(depth);
    errno = saved_errno;
    return result;
  }
};

// While the console waits for input, Ctrl-C only sets this flag; the read
// returns (no SA_RESTART) and the line is dropped.
volatile std::sig_atomic_t g_prompt_interrupt = 0;
extern "C" void on_prompt_sigint(int) { g_prompt_interrupt = 1; }

struct PromptSignals {
  struct sigaction old {};
  PromptSignals() {
    g_prompt_interrupt = 0;
    struct sigaction sa {};
    sa.sa_handler = on_prompt_sigint;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    sigaction(SIGINT, &sa, &old);
  }
  ~PromptSignals() { sigaction(SIGINT, &old, nullptr); }
};

bool use_readline() {
#ifdef DDA_HAVE_READLINE
  return isatty(fileno(stdin));
#else
  return false;
#endif
}

#ifdef DDA_HAVE_READLINE
std::string* g_rl_line = nullptr;
bool g_rl_done = false, g_rl_end = false;

void on_rl_line(char* s) {
  if (!s) {
    g_rl_end = true;
  } else {
    *g_rl_line = s;
    std::free(s);
  }
  g_rl_done = true;
  rl_callback_handler_remove();  // no new prompt until we ask for one
}

// readline's callback interface: a select loop the Ctrl-C flag can break,
// which prints what background runs have to say above the prompt.
Read readline_line(std::string& line, const char* prompt) {
  g_rl_line = &line;
  g_rl_done = g_rl_end = false;
  rl_callback_handler_install(prompt, on_rl_line);
  const int fd = fileno(rl_instream ? rl_instream : stdin);
  while (!g_rl_done) {
    fd_set fds;
    FD_ZERO(&fds);
    FD_SET(fd, &fds);
    timeval tick{0, 250000};
    const int r = WithoutLua().call([&] { return select(fd + 1, &fds, nullptr, nullptr, &tick); });
    if (r == 0) {
      const std::vector<std::string> notes = background_run_notices();
      if (notes.empty()) continue;
      rl_clear_visible_line();
      for (const std::string& n : notes) std::fprintf(stdout, "dda: %s\n", n.c_str());
      std::fflush(stdout);
      rl_on_new_line();
      rl_redisplay();
      continue;
    }
    if (r < 0 && errno == EINTR && g_prompt_interrupt) {
      g_prompt_interrupt = 0;
      rl_free_line_state();
      rl_callback_sigcleanup();
      rl_replace_line("", 0);
      rl_callback_handler_remove();
      std::fputs("^C\n", stdout);
      std::fflush(stdout);
      return Read::Interrupted;
    }
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      rl_callback_handler_remove();
      return Read::End;
    }
    rl_callback_read_char();
  }
  return g_rl_end ? Read::End : Read::Line;
}
#endif

Read read_line(std::string& line, const char* prompt) {
  PromptSignals signals;
  line.clear();
#ifdef DDA_HAVE_READLINE
  if (use_readline()) return readline_line(line, prompt);
#endif
  if (isatty(fileno(stdin))) {
    std::fputs(prompt, stdout);
    std::fflush(stdout);
  }
  char buf[4096];
  for (;;) {
    if (!WithoutLua().call([&] { return std::fgets(buf, sizeof buf, stdin); })) {
      if (g_prompt_interrupt) {
        clearerr(stdin);
        std::fputc('\n', stdout);
        return Read::Interrupted;
      }
      return line.empty() ? Read::End : Read::Line;
    }
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      return Read::Line;
    }
  }
}

// ---- history -----------------------------------------------------------------------------

// ~/.dda_history, or $DDA_HISTORY (empty: no history file).
std::string history_path() {
  if (const char* p = std::getenv("DDA_HISTORY")) return p;
  const char* home = std::getenv("HOME");
  return home && *home ? std::string(home) + "/.dda_history" : std::string();
}

constexpr int kHistoryLines = 1000;

void load_history() {
#ifdef DDA_HAVE_READLINE
  if (!use_readline()) return;
  const std::string path = history_path();
  if (path.empty()) return;
  if (FILE* f = std::fopen(path.c_str(), "a")) std::fclose(f);  // append_history needs the file
  read_history(path.c_str());
#endif
}

void save_line(const std::string& line) {
#ifdef DDA_HAVE_READLINE
  if (line.empty() || !use_readline()) return;
  add_history(line.c_str());
  const std::string path = history_path();
  if (!path.empty()) append_history(1, path.c_str());  // kept even if the console is killed later
#else
  (void)line;
#endif
}

void trim_history() {
#ifdef DDA_HAVE_READLINE
  const std::string path = history_path();
  if (use_readline() && !path.empty()) history_truncate_file(path.c_str(), kHistoryLines);
#endif
}

// ---- completion ---------------------------------------------------------------------------

#ifdef DDA_HAVE_READLINE
lua_State* g_completion_state = nullptr;
std::vector<std::string> g_matches;
std::size_t g_match_index = 0;

bool is_identifier(const char* s) {
  if (!s || !(std::isalpha(static_cast<unsigned char>(*s)) || *s == '_')) return false;
  for (; *s; ++s)
    if (!(std::isalnum(static_cast<unsigned char>(*s)) || *s == '_')) return false;
  return true;
}

// Adds the identifier keys of the table at idx starting with `part`.
void add_keys(lua_State* L, int idx, const std::string& part, bool functions_only, const std::string& prefix,
              std::set<std::string>& out) {
  idx = lua_absindex(L, idx);
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING) {
      const char* k = lua_tostring(L, -2);
      const bool fn = lua_isfunction(L, -1);
      if (is_identifier(k) && std::strncmp(k, part.c_str(), part.size()) == 0 && (fn || !functions_only))
        out.insert(prefix + k + (fn ? "(" : ""));
    }
    lua_pop(L, 1);
  }
}

// What the table or object at idx offers: its keys, its metatable's
// __methods (dda types) or __index table.
void add_members(lua_State* L, int idx, const std::string& part, bool methods, const std::string& prefix,
                 std::set<std::string>& out) {
  idx = lua_absindex(L, idx);
  if (lua_istable(L, idx)) add_keys(L, idx, part, methods, prefix, out);
  if (lua_type(L, idx) == LUA_TSTRING) {
    lua_getglobal(L, "string");
    if (lua_istable(L, -1)) add_keys(L, -1, part, methods, prefix, out);
    lua_pop(L, 1);
  }
  if (lua_getmetatable(L, idx)) {
    if (lua_getfield(L, -1, "__methods") == LUA_TTABLE) add_keys(L, -1, part, methods, prefix, out);
    lua_pop(L, 1);
    if (lua_getfield(L, -1, "__index") == LUA_TTABLE) add_keys(L, -1, part, methods, prefix, out);
    lua_pop(L, 2);
  }
}

// Candidates for `text`: "pri" → globals and keywords; "m:st" → m's
// methods; "dda.mo", "centre.na" → fields. Only raw lookups: completing
// never runs Lua code.
std::vector<std::string> candidates(lua_State* L, const std::string& text) {
  std::set<std::string> out;
  const int top = lua_gettop(L);
  const auto sep = text.find_last_of(".:");
  if (sep == std::string::npos) {
    static const char* kKeywords[] = {"and",      "break",  "do",   "else", "elseif", "end",  "false", "for",
                                      "function", "goto",   "if",   "in",   "local",  "nil",  "not",   "or",
                                      "repeat",   "return", "then", "true", "until",  "while"};
    for (const char* k : kKeywords)
      if (std::strncmp(k, text.c_str(), text.size()) == 0) out.insert(k);
    lua_pushglobaltable(L);
    add_keys(L, -1, text, false, "", out);
  } else {
    lua_pushglobaltable(L);
    const std::string base = text.substr(0, sep);
    std::size_t start = 0;
    bool ok = true;
    while (ok && start <= base.size()) {
      std::size_t end = base.find('.', start);
      if (end == std::string::npos) end = base.size();
      const std::string name = base.substr(start, end - start);
      if (!lua_istable(L, -1) || !is_identifier(name.c_str())) {
        ok = false;
        break;
      }
      lua_pushlstring(L, name.data(), name.size());
      lua_rawget(L, -2);
      lua_remove(L, -2);
      start = end + 1;
    }
    if (ok && !lua_isnil(L, -1))
      add_members(L, -1, text.substr(sep + 1), text[sep] == ':', text.substr(0, sep + 1), out);
  }
  lua_settop(L, top);
  return {out.begin(), out.end()};
}

char* completion_generator(const char* text, int state) {
  if (state == 0) {
    g_matches = g_completion_state ? candidates(g_completion_state, text) : std::vector<std::string>{};
    g_match_index = 0;
  }
  if (g_match_index < g_matches.size()) return strdup(g_matches[g_match_index++].c_str());
  return nullptr;
}

char** complete(const char* text, int, int) {
  rl_attempted_completion_over = 1;    // never fall back to file names
  rl_completion_append_character = 0;  // "m:step(" is complete as it stands
  return rl_completion_matches(text, completion_generator);
}

void setup_readline(lua_State* L) {
  if (!use_readline()) return;
  g_completion_state = L;
  rl_readline_name = "dda";
  rl_catch_signals = 0;  // Ctrl-C is ours (PromptSignals)
  static char breaks[] = " \t\n\"\\'><=;|&{(,+-*/%^#~[]";
  rl_completer_word_break_characters = breaks;
  rl_attempted_completion_function = complete;
}
#else
void setup_readline(lua_State*) {}
#endif

// ---- compiling input ------------------------------------------------------------------------

// A syntax error that ends in "<eof>": the statement continues on the next line.
bool incomplete(lua_State* L, int status) {
  if (status != LUA_ERRSYNTAX) return false;
  std::size_t len;
  const char* text = lua_tolstring(L, -1, &len);
  const std::size_t mark = std::strlen(kEofMark);
  return text && len >= mark && std::strcmp(text + len - mark, kEofMark) == 0;
}

// Reads and compiles one statement. Returns LUA_OK with the chunk pushed, an
// error status with the message pushed, kEnd at the end of the input, or
// kCancelled (Ctrl-C) with nothing pushed.
int load_statement(lua_State* L) {
  lua_settop(L, 0);
  std::string chunk;
  switch (read_line(chunk, kPrompt)) {
    case Read::End:
      return kEnd;
    case Read::Interrupted:
      return kCancelled;
    case Read::Line:
      break;
  }
  // An expression prints its value: "return " .. line first.
  const std::string ret = "return " + chunk + ";";
  if (luaL_loadbufferx(L, ret.data(), ret.size(), "=stdin", "t") == LUA_OK) {
    save_line(chunk);
    return LUA_OK;
  }
  lua_pop(L, 1);
  for (;;) {
    int status = luaL_loadbufferx(L, chunk.data(), chunk.size(), "=stdin", "t");
    if (!incomplete(L, status)) {
      save_line(chunk);
      return status;
    }
    lua_pop(L, 1);
    std::string more;
    const Read r = read_line(more, kPrompt2);
    if (r == Read::Interrupted) {
      save_line(chunk);
      return kCancelled;
    }
    if (r == Read::End) {
      // The input ended inside the statement: report it (the message again).
      save_line(chunk);
      status = luaL_loadbufferx(L, chunk.data(), chunk.size(), "=stdin", "t");
      lua_pushfstring(L, "%s (the input ended inside this unfinished statement; it was not run)", lua_tostring(L, -1));
      lua_remove(L, -2);
      return status;
    }
    chunk += "\n" + more;
  }
}

// ---- printing results ------------------------------------------------------------------------

constexpr int kMaxDepth = 3;          // nested tables deeper than this print as {...}
constexpr int kMaxEntries = 20;       // entries shown per table
constexpr std::size_t kInline = 100;  // longer top-level tables print one entry per line

void format_value(lua_State* L, int idx, std::string& out, int depth, std::vector<const void*>& open);

// A table without __tostring or __name (those print as tostring does).
bool plain_table(lua_State* L, int idx) {
  if (lua_type(L, idx) != LUA_TTABLE) return false;
  for (const char* f : {"__tostring", "__name"})
    if (luaL_getmetafield(L, idx, f) != LUA_TNIL) {
      lua_pop(L, 1);
      return false;
    }
  return true;
}

void format_key(lua_State* L, int idx, std::string& out, std::vector<const void*>& open) {
  if (lua_type(L, idx) == LUA_TSTRING) {
    const char* k = lua_tostring(L, idx);
    bool ident = (std::isalpha(static_cast<unsigned char>(*k)) || *k == '_');
    for (const char* c = k; *c && ident; ++c) ident = std::isalnum(static_cast<unsigned char>(*c)) || *c == '_';
    if (ident) {
      out += k;
      return;
    }
  }
  out += "[";
  format_value(L, idx, out, kMaxDepth, open);
  out += "]";
}

// The entries of the table at idx as "value" (array part) and "key = value" strings.
std::vector<std::string> table_entries(lua_State* L, int idx, int depth, std::vector<const void*>& open,
                                       std::size_t& hidden) {
  idx = lua_absindex(L, idx);
  std::vector<std::string> items;
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  hidden = 0;
  for (lua_Integer i = 1; i <= n; ++i) {
    if (static_cast<int>(items.size()) >= kMaxEntries) {
      hidden += static_cast<std::size_t>(n - i + 1);
      break;
    }
    lua_rawgeti(L, idx, i);
    std::string v;
    format_value(L, -1, v, depth + 1, open);
    items.push_back(v);
    lua_pop(L, 1);
  }
  std::vector<std::pair<std::string, std::string>> keyed;
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    const bool in_array = lua_isinteger(L, -2) && lua_tointeger(L, -2) >= 1 && lua_tointeger(L, -2) <= n;
    if (!in_array) {
      std::string k, v;
      lua_pushvalue(L, -2);
      format_key(L, -1, k, open);
      lua_pop(L, 1);
      format_value(L, -1, v, depth + 1, open);
      keyed.emplace_back(k, v);
    }
    lua_pop(L, 1);
  }
  std::sort(keyed.begin(), keyed.end());
  for (const auto& [k, v] : keyed) {
    if (static_cast<int>(items.size()) >= kMaxEntries) {
      ++hidden;
      continue;
    }
    items.push_back(k + " = " + v);
  }
  return items;
}

void format_value(lua_State* L, int idx, std::string& out, int depth, std::vector<const void*>& open) {
  idx = lua_absindex(L, idx);
  const int t = lua_type(L, idx);
  if (t == LUA_TSTRING) {
    std::size_t len;
    const char* s = lua_tolstring(L, idx, &len);
    out += '"';
    for (std::size_t i = 0; i < len; ++i) {
      const char c = s[i];
      if (c == '"' || c == '\\')
        out += '\\', out += c;
      else if (c == '\n')
        out += "\\n";
      else
        out += c;
    }
    out += '"';
    return;
  }
  if (plain_table(L, idx)) {
    const void* p = lua_topointer(L, idx);
    if (std::find(open.begin(), open.end(), p) != open.end()) {
      out += "<cycle>";
      return;
    }
    if (depth >= kMaxDepth) {
      out += "{...}";
      return;
    }
    open.push_back(p);
    std::size_t hidden = 0;
    const auto items = table_entries(L, idx, depth, open, hidden);
    open.pop_back();
    out += "{";
    for (std::size_t i = 0; i < items.size(); ++i) out.append(i ? ", " : "").append(items[i]);
    if (hidden) out += msg(items.empty() ? "" : ", ", "... (", hidden, " more)");
    out += "}";
    return;
  }
  std::size_t len;
  const char* s = luaL_tolstring(L, idx, &len);
  out.append(s, len);
  lua_pop(L, 1);
}

// One result: tables as tables, one entry per line when long.
std::string format_result(lua_State* L, int idx) {
  std::vector<const void*> open;
  std::string line;
  format_value(L, idx, line, 0, open);
  if (line.size() <= kInline || !plain_table(L, idx)) return line;
  std::size_t hidden = 0;
  open.push_back(lua_topointer(L, idx));
  const auto items = table_entries(L, idx, 0, open, hidden);
  std::string text = "{\n";
  for (const std::string& item : items) text += "  " + item + ",\n";
  if (hidden) text += msg("  ... (", hidden, " more)\n");
  return text + "}";
}

void print_results(lua_State* L) {
  const int n = lua_gettop(L);
  if (n == 0) return;
  luaL_checkstack(L, LUA_MINSTACK, "too many results to print");
  std::string text;
  for (int i = 1; i <= n; ++i) text.append(i > 1 ? "\t" : "").append(format_result(L, i));
  std::printf("%s\n", text.c_str());
  std::fflush(stdout);
}

void report(lua_State* L) {
  const char* text = lua_tostring(L, -1);
  std::fprintf(stderr, "%s\n", text ? text : "(error object is not a string)");
  std::fflush(stderr);
  lua_pop(L, 1);
}

// Ctrl-C pauses every background run (and stops the command in progress).
void pause_background_runs_and_say() {
  for (const std::string& line : pause_background_runs()) std::fprintf(stderr, "dda: %s\n", line.c_str());
  std::fflush(stderr);
}

void print_notices() {
  for (const std::string& n : background_run_notices()) std::fprintf(stdout, "dda: %s\n", n.c_str());
  std::fflush(stdout);
}

int call_interruptibly(lua_State* L, int nargs, int nresults) {
  install_interrupt_handler(L);
  const int status = call_with_traceback(L, nargs, nresults);
  remove_interrupt_handler();
  release_call_holds();  // any an error unwound past
  if (interrupt_requested()) pause_background_runs_and_say();
  clear_interrupt();
  return status;
}

}  // namespace

int run_console(const RunOptions& options) {
  Session s = options.session;
  s.progress = !s.quiet && isatty(fileno(stderr)) ? ProgressMode::Bar : ProgressMode::None;
  lua_State* L = new_state(std::move(s));
  if (!L) {
    std::fprintf(stderr, "dda: cannot create a Lua state (not enough memory)\n");
    return 1;
  }
  if (std::string live_error; !start_live_view(L, options.script, live_error)) {
    std::fprintf(stderr, "dda: %s\n", live_error.c_str());
    lua_close(L);
    return 2;
  }
  const std::lock_guard lua(lua_gate());  // let go while waiting for input and in m:wait()
  // help() at the prompt: the module's dda.help.
  lua_getglobal(L, "dda");
  lua_getfield(L, -1, "help");
  lua_setglobal(L, "help");
  lua_pop(L, 1);
  std::printf(
      "dda console %s (Lua %s.%s). help() lists the API; Tab completes names; Ctrl-C stops a run at the next "
      "step (and pauses background runs); Ctrl-D leaves.\n",
      DDA_VERSION_TEXT, LUA_VERSION_MAJOR, LUA_VERSION_MINOR);
  std::fflush(stdout);
  setup_readline(L);
  load_history();
  if (!options.script.empty()) {
    install_interrupt_handler(L);
    std::string error;
    if (!run_file(L, resolve_script(options.script).string(), options.script_args, error))
      std::fprintf(stderr, "%s\n", error.c_str());
    remove_interrupt_handler();
    release_call_holds();
    if (interrupt_requested()) pause_background_runs_and_say();
    clear_interrupt();
  }
  for (;;) {
    print_notices();
    int status = load_statement(L);
    if (status == kEnd) break;
    if (status == kCancelled) {
      pause_background_runs_and_say();
      continue;
    }
    if (status == LUA_OK) status = call_interruptibly(L, 0, LUA_MULTRET);
    if (status == LUA_OK)
      print_results(L);
    else
      report(L);
  }
  lua_settop(L, 0);
  trim_history();
  std::fputc('\n', stdout);
  for (const std::string& w : unused_params(session(L))) std::fprintf(stderr, "dda: %s\n", w.c_str());
  stop_background_runs();  // before the models close
  lua_close(L);
  return 0;
}

}  // namespace dda::script
