// help(): the API's documentation, from the tables that register each
// function (wrap.hpp, Method), so what help prints is what is registered.
//   help()           an overview: the dda functions and the model's methods
//   help(m.step)     one function, in full
//   help(m), help(blocks), help(dda)   what the object offers, one line each
//   help("step")     every function of that name
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "scripting.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

constexpr std::size_t kWidth = 100;

// Prints `text` wrapped at kWidth columns, each line indented by `indent`.
void print_wrapped(const std::string& text, const char* indent) {
  std::string line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() + std::strlen(indent) > kWidth) {
      std::printf("%s%s\n", indent, line.c_str());
      line.clear();
    }
    line.append(line.empty() ? "" : " ").append(word);
    start = end + 1;
  }
  if (!line.empty()) std::printf("%s%s\n", indent, line.c_str());
}

// The first line of a doc, shortened for listings.
std::string summary(const std::string& doc) {
  std::string s = doc.substr(0, doc.find('\n'));
  if (s.size() > kWidth - 2) s = s.substr(0, kWidth - 5) + "...";
  return s;
}

// (name, doc) of every documented function in the table at idx, sorted by name.
std::vector<std::pair<std::string, std::string>> documented(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  std::vector<std::pair<std::string, std::string>> out;
  push_docs(L);
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_isfunction(L, -1)) {
      lua_pushvalue(L, -1);
      if (lua_rawget(L, -4) == LUA_TSTRING) out.emplace_back(lua_tostring(L, -3), lua_tostring(L, -1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::sort(out.begin(), out.end());
  return out;
}

void list(const std::vector<std::pair<std::string, std::string>>& items) {
  for (const auto& [name, doc] : items) std::printf("  %s\n", summary(doc).c_str());
}

// Pushes the method table of the object at idx (a dda userdata), or returns false.
bool push_methods(lua_State* L, int idx) {
  if (!lua_getmetatable(L, idx)) return false;
  if (lua_getfield(L, -1, "__methods") != LUA_TTABLE) {
    lua_pop(L, 2);
    return false;
  }
  lua_remove(L, -2);
  return true;
}

void overview(lua_State* L) {
  std::printf(
      "dda %s: 2-D Discontinuous Deformation Analysis of jointed rock (Lua 5.4).\n"
      "  help(f)        one function in full: help(m.step), help(dda.model), help(centre.max)\n"
      "  help(x)        what an object offers: help(dda), help(m), help(blocks), help(monitor)\n"
      "  help(\"name\")   every function of that name: help(\"run\")\n"
      "In the console: Tab completes names (m:ru<Tab>), results print as tables, Ctrl-C stops a\n"
      "run at the next step (or clears the line), Ctrl-D leaves. Full reference: docs/scripting.md.\n\n",
      DDA_VERSION_TEXT);
  std::printf("The dda module:\n");
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "loaded");
  lua_getfield(L, -1, "dda");
  if (lua_istable(L, -1)) list(documented(L, -1));
  lua_pop(L, 3);
  std::printf("\nA model (m = dda.model{...}), m:...:\n");
  luaL_getmetatable(L, kModelType);
  lua_getfield(L, -1, "__methods");
  list(documented(L, -1));
  lua_pop(L, 2);
  std::printf("\nThe objects its methods return (blocks, edges, monitors, loads, ...) list theirs with help(x).\n");
}

// help("name"): every documented function registered under that name.
void search(lua_State* L, const std::string& name) {
  push_docs(L);
  std::vector<std::string> hits;
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -1) == LUA_TSTRING) {
      const std::string doc = lua_tostring(L, -1);
      const std::string head = doc.substr(0, doc.find_first_of("({ "));
      const auto sep = head.find_last_of(".:");
      if ((sep == std::string::npos ? head : head.substr(sep + 1)) == name || head == name) hits.push_back(doc);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::sort(hits.begin(), hits.end());
  if (hits.empty()) std::printf("no dda function is called '%s' (help() lists them)\n", name.c_str());
  for (const std::string& h : hits) print_wrapped(h, "");
}

}  // namespace

int dda_help(lua_State* L) {
  if (lua_isnone(L, 1)) {
    overview(L);
    return 0;
  }
  if (lua_type(L, 1) == LUA_TSTRING) {
    search(L, lua_tostring(L, 1));
    return 0;
  }
  if (lua_isfunction(L, 1)) {
    push_docs(L);
    lua_pushvalue(L, 1);
    if (lua_rawget(L, -2) == LUA_TSTRING) {
      print_wrapped(lua_tostring(L, -1), "");
      return 0;
    }
    lua_Debug ar;
    lua_pushvalue(L, 1);
    lua_getinfo(L, ">S", &ar);
    if (std::strcmp(ar.what, "C") == 0)
      std::printf("a function of Lua's standard library (see the Lua 5.4 manual), or not documented here\n");
    else
      std::printf("a Lua function defined at %s:%d\n", ar.short_src, ar.linedefined);
    return 0;
  }
  if (lua_type(L, 1) == LUA_TUSERDATA && push_methods(L, 1)) {
    std::printf("%s methods:\n", type_of(L, 1).c_str());
    list(documented(L, -1));
    return 0;
  }
  if (lua_istable(L, 1)) {
    const auto items = documented(L, 1);
    if (!items.empty()) {
      list(items);
      return 0;
    }
  }
  std::printf("no help for a %s value (help() lists the API)\n", type_of(L, 1).c_str());
  return 0;
}

}  // namespace dda::script
