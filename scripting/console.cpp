// `dda console [SCRIPT]`: an interactive prompt in the style of Lua's own
// lua.c: `return <line>` is tried first so expressions print, input continues
// while the chunk is incomplete (its error ends in "<eof>"), errors print a
// traceback and the prompt stays up. Line editing and history via readline
// when it was found at build time.
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "scripting.hpp"

#ifdef DDA_HAVE_READLINE
#include <readline/history.h>
#include <readline/readline.h>
#endif

namespace dda::script {

int docall_with_traceback(lua_State* L, int nargs, int nresults);  // runner.cpp

namespace {

constexpr const char* kPrompt = "dda> ";
constexpr const char* kPrompt2 = "...> ";
constexpr const char* kEofMark = "<eof>";

bool read_line(std::string& line, const char* prompt) {
#ifdef DDA_HAVE_READLINE
  if (isatty(fileno(stdin))) {
    char* s = readline(prompt);
    if (!s) return false;
    line = s;
    std::free(s);
    return true;
  }
#endif
  if (isatty(fileno(stdin))) {
    std::fputs(prompt, stdout);
    std::fflush(stdout);
  }
  char buf[4096];
  line.clear();
  for (;;) {
    if (!std::fgets(buf, sizeof buf, stdin)) return !line.empty();
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      return true;
    }
  }
}

void save_line(const std::string& line) {
#ifdef DDA_HAVE_READLINE
  if (!line.empty()) add_history(line.c_str());
#else
  (void)line;
#endif
}

void report(lua_State* L, int status) {
  if (status != LUA_OK) {
    const char* text = lua_tostring(L, -1);
    std::fprintf(stderr, "%s\n", text ? text : "(error object is not a string)");
    std::fflush(stderr);
    lua_pop(L, 1);
  }
}

// "return " .. line; leaves the chunk on the stack when it compiles.
int add_return(lua_State* L) {
  const char* line = lua_tostring(L, -1);
  const char* retline = lua_pushfstring(L, "return %s;", line);
  const int status = luaL_loadbufferx(L, retline, std::strlen(retline), "=stdin", "t");
  if (status == LUA_OK) {
    lua_remove(L, -2);  // the modified line
    if (line[0] != '\0') save_line(line);
  } else {
    lua_pop(L, 2);  // the result of loading and the modified line
  }
  return status;
}

bool incomplete(lua_State* L, int status) {
  if (status == LUA_ERRSYNTAX) {
    std::size_t len;
    const char* text = lua_tolstring(L, -1, &len);
    const std::size_t mark = std::strlen(kEofMark);
    if (len >= mark && std::strcmp(text + len - mark, kEofMark) == 0) {
      lua_pop(L, 1);
      return true;
    }
  }
  return false;
}

// Reads more lines while the chunk is incomplete.
int multiline(lua_State* L) {
  for (;;) {
    std::size_t len;
    const char* line = lua_tolstring(L, 1, &len);
    const int status = luaL_loadbufferx(L, line, len, "=stdin", "t");
    if (!incomplete(L, status)) {
      save_line(line);
      return status;
    }
    std::string more;
    if (!read_line(more, kPrompt2)) return status;
    lua_pushstring(L, more.c_str());
    lua_pushliteral(L, "\n");  // between the two lines
    lua_insert(L, -2);
    lua_concat(L, 3);
  }
}

// Pushes a compiled chunk for the next input; -1 at end of input.
int load_line(lua_State* L) {
  lua_settop(L, 0);
  std::string line;
  if (!read_line(line, kPrompt)) return -1;
  lua_pushstring(L, line.c_str());
  int status = add_return(L);
  if (status != LUA_OK) status = multiline(L);
  lua_remove(L, 1);  // the line
  return status;
}

void print_results(lua_State* L) {
  const int n = lua_gettop(L);
  if (n > 0) {
    luaL_checkstack(L, LUA_MINSTACK, "too many results to print");
    lua_getglobal(L, "print");
    lua_insert(L, 1);
    if (lua_pcall(L, n, 0, 0) != LUA_OK) std::fprintf(stderr, "error calling 'print' (%s)\n", lua_tostring(L, -1));
  }
}

int call_interruptibly(lua_State* L, int nargs, int nresults) {
  install_interrupt_handler(L);
  const int status = docall_with_traceback(L, nargs, nresults);
  remove_interrupt_handler();
  clear_interrupt();
  return status;
}

}  // namespace

int run_console(const RunOptions& options) {
  Session s = options.session;
  s.progress = !s.quiet && isatty(fileno(stderr));
  lua_State* L = new_state(std::move(s));
  if (!L) {
    std::fprintf(stderr, "dda: cannot create a Lua state (not enough memory)\n");
    return 1;
  }
  std::printf("dda console %s (Lua %s.%s). Ctrl-D leaves; Ctrl-C stops a run at the next step.\n", "0.1",
              LUA_VERSION_MAJOR, LUA_VERSION_MINOR);
  if (!options.script.empty()) {
    install_interrupt_handler(L);
    std::string error;
    if (!run_file(L, options.script, options.script_args, error)) std::fprintf(stderr, "%s\n", error.c_str());
    remove_interrupt_handler();
    clear_interrupt();
  }
  int status;
  while ((status = load_line(L)) != -1) {
    if (status == LUA_OK) status = call_interruptibly(L, 0, LUA_MULTRET);
    if (status == LUA_OK)
      print_results(L);
    else
      report(L, status);
  }
  lua_settop(L, 0);
  std::fputc('\n', stdout);
  for (const std::string& w : unused_params(session(L))) std::fprintf(stderr, "dda: %s\n", w.c_str());
  lua_close(L);
  return 0;
}

}  // namespace dda::script
