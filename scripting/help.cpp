// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// help() and the API reference (docs/lua_api*.md), both from the tables
// that register each function (wrap.hpp: Method, its options and the keys
// it returns; the types' fields; the monitor fields; the engine's controls),
// so what they say is what is registered.
//   help()           an overview: the dda functions and the model's methods
//   help(m.step)     one function, in full: its call, what it does, its
//                    options with their defaults, the keys it returns
//   help(m), help(blocks), help(dda)   what the object offers, one line each
//   help("step")     every function of that name
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "scripting.hpp"
#include "world/controls.hpp"
#include "wrap.hpp"

namespace dda::script {

namespace {

constexpr std::size_t kWidth = 100;

// ---- the text of one function --------------------------------------------------------

// The first line of the doc with "{...}" written out as the options' names.
std::string call_line(const Method& m) {
  std::string line = std::string(m.doc).substr(0, std::string(m.doc).find('\n'));
  const auto at = line.find("{...}");
  if (at != std::string::npos && !m.options.empty()) {
    std::string names;
    for (const Name& o : m.options) names.append(names.empty() ? "" : ", ").append(o.name);
    if (m.options.data() == control_option_names().data()) names = "controls...";  // a table of their own
    line.replace(at, 5, "{" + names + "}");
  }
  return line;
}

// What the function does: the doc after its first line.
std::string description(const Method& m) {
  const std::string doc = m.doc;
  const auto nl = doc.find('\n');
  return nl == std::string::npos ? std::string() : doc.substr(nl + 1);
}

// Markdown for a terminal: backticks dropped.
std::string plain(const std::string& markdown) {
  std::string s;
  for (char c : markdown)
    if (c != '`') s += c;
  return s;
}

// Prints `text` wrapped at kWidth columns, each line indented by `indent`.
void print_wrapped(const std::string& text, const std::string& indent) {
  std::string line;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() + indent.size() > kWidth) {
      std::printf("%s%s\n", indent.c_str(), line.c_str());
      line.clear();
    }
    line.append(line.empty() ? "" : " ").append(word);
    start = end + 1;
  }
  if (!line.empty()) std::printf("%s%s\n", indent.c_str(), line.c_str());
}

void print_names(const char* title, Names names, bool with_defaults) {
  if (names.empty()) return;
  std::printf("  %s:\n", title);
  for (const Name& n : names) {
    std::string text = msg(n.name, ": ", plain(n.doc));
    if (with_defaults) text += n.fallback ? msg(" (default: ", plain(n.fallback), ")") : std::string(" (required)");
    print_wrapped(text, "    ");
  }
}

void print_method(const Method& m) {
  print_wrapped(plain(call_line(m)), "");
  if (const std::string d = description(m); !d.empty()) print_wrapped(plain(d), "  ");
  print_names("options", m.options, true);
  print_names("the table it returns", m.returns, false);
}

// The call line, shortened for listings.
std::string summary(const Method& m) {
  std::string s = plain(call_line(m));
  if (s.size() > kWidth - 2) s = s.substr(0, kWidth - 5) + "...";
  return s;
}

// ---- what an object offers --------------------------------------------------------------

// The documented functions of the table at idx, sorted by name.
std::vector<const Method*> documented(lua_State* L, int idx) {
  idx = lua_absindex(L, idx);
  std::vector<std::pair<std::string, const Method*>> found;
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_isfunction(L, -1))
      if (const Method* m = find_method(L, -1)) found.emplace_back(lua_tostring(L, -2), m);
    lua_pop(L, 1);
  }
  std::sort(found.begin(), found.end());
  std::vector<const Method*> out;
  for (const auto& [name, m] : found) out.push_back(m);
  return out;
}

void list(const std::vector<const Method*>& items) {
  for (const Method* m : items) std::printf("  %s\n", summary(*m).c_str());
}

// The fields documented for a type ("dda.RockMaterial").
Names fields_of(lua_State* L, const std::string& type) {
  for (const ApiSection& s : api_sections(L))
    if (s.owner == type) return s.fields;
  return {};
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
      "run at the next step (or clears the line), Ctrl-D leaves. Reference: docs/lua_api.md.\n\n",
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
  std::vector<std::pair<std::string, const Method*>> hits;
  for (const ApiSection& s : api_sections(L))
    for (const Method* m : s.methods)
      if (name == m->name) hits.emplace_back(call_line(*m), m);
  std::sort(hits.begin(), hits.end());
  if (hits.empty()) std::printf("no dda function is called '%s' (help() lists them)\n", name.c_str());
  for (const auto& [line, m] : hits) print_method(*m);
}

// ---- the reference -----------------------------------------------------------------

// A table cell: no line breaks, pipes escaped.
std::string markdown_cell(std::string text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

std::string names_table(const char* first, Names names, bool with_defaults) {
  std::string t = msg("| ", first, " | meaning |", with_defaults ? " default |" : "", "\n|---|---|",
                      with_defaults ? "---|" : "", "\n");
  for (const Name& n : names) {
    t += msg("| `", n.name, "` | ", markdown_cell(n.doc), " |");
    if (with_defaults) t += msg(" ", n.fallback ? markdown_cell(n.fallback) : std::string("required"), " |");
    t += "\n";
  }
  return t;
}

std::string method_markdown(const Method& m) {
  std::string s = msg("### `", call_line(m), "`\n\n");
  if (const std::string d = description(m); !d.empty()) s += d + "\n\n";
  if (m.options.data() == control_option_names().data())
    s += "Its options are the [controls](lua_api.md#controls).\n\n";
  else if (!m.options.empty())
    s += names_table("option", m.options, true) + "\n";
  if (!m.returns.empty()) s += "It returns a table:\n\n" + names_table("key", m.returns, false) + "\n";
  return s;
}

// What each type is, for its section's opening line.
struct TypeIntro {
  const char* type;
  const char* title;
  const char* intro;
};
constexpr TypeIntro kTypes[] = {
    {"dda", "The dda module", "`local dda = require \"dda\"` (also the global `dda` in `dda run` and the console)."},
    {"dda.Model", "dda.Model", "A model: `m = dda.model{...}`. Its methods build it, step it and read it."},
    {"dda.Block", "dda.Block", "One block (`m:block(id)`, `m:block_at(x, y)`, a block set's items)."},
    {"dda.BlockSet", "dda.BlockSet", "Blocks chosen together (`m:generate()`, `m:blocks{...}`); `#set`, `set[i]`."},
    {"dda.EdgeSet", "dda.EdgeSet", "Block edges chosen together (`m:edges{...}`, `hole:edges()`); `#set`, `set[i]`."},
    {"dda.RockMaterial", "dda.RockMaterial", "A rock material (`m:rock{...}`): fields read and written by name."},
    {"dda.JointMaterial", "dda.JointMaterial", "A joint material (`m:joint{...}`): fields read and written by name."},
    {"dda.Hole", "dda.Hole", "An excavation (`m:hole{...}`)."},
    {"dda.PointLoad", "dda.PointLoad", "A point load (`m:point_load{...}`)."},
    {"dda.Pressure", "dda.Pressure", "A pressure on edges (`edges:pressure(...)`)."},
    {"dda.Target", "dda.Target", "A prescribed motion (`m:target{...}`, `edges:target{...}`)."},
    {"dda.Boundary", "dda.Boundary",
     "A boundary on edges (`edges:viscous_boundary{...}`, `edges:spring_boundary{...}`, "
     "`edges:free_field{...}`)."},
    {"dda.Monitor", "dda.Monitor", "A followed material point (`m:monitor{...}`)."},
    {"dda.Frames", "dda.Frames", "A frame sequence (`m:frames{...}`)."},
    {"dda.Vtu", "dda.Vtu", "A ParaView series (`m:vtu{...}`)."},
};

const TypeIntro* intro_of(const std::string& owner) {
  for (const TypeIntro& t : kTypes)
    if (owner == t.type) return &t;
  return nullptr;
}

std::string methods_markdown(std::vector<const Method*> methods) {
  std::stable_sort(methods.begin(), methods.end(),
                   [](const Method* a, const Method* b) { return std::strcmp(a->name, b->name) < 0; });
  std::string text;
  for (const Method* m : methods) text += method_markdown(*m);
  return text;
}

std::string section_markdown(const ApiSection& s) {
  const TypeIntro* intro = intro_of(s.owner);
  std::string text = msg("## ", intro ? intro->title : s.owner.c_str(), "\n\n");
  if (intro) text += msg(intro->intro, "\n\n");
  if (!s.fields.empty()) text += names_table("field", s.fields, false) + "\n";
  return text + methods_markdown(s.methods);
}

// The model's methods of the given topics, a section each.
std::string topics_markdown(const ApiSection& model, std::initializer_list<const char*> topics) {
  std::string text;
  for (const char* topic : topics) {
    std::vector<const Method*> methods;
    for (std::size_t k = 0; k < model.methods.size(); ++k)
      if (model.topics[k] == topic) methods.push_back(model.methods[k]);
    text += msg("## ", topic, "\n\n", methods_markdown(methods));
  }
  return text;
}

constexpr const char* kGenerated =
    "<!-- Generated from the Lua binding's own tables (scripting/help.cpp, api_reference_pages); the test "
    "LuaApiReference.DocsAreTheBindingsOwn holds this file equal to them. Edit the tables, not this file. -->\n\n";

}  // namespace

std::vector<std::pair<std::string, std::string>> api_reference_pages(lua_State* L) {
  const std::vector<ApiSection> sections = api_sections(L);
  auto section = [&](const char* owner) {
    for (const ApiSection& s : sections)
      if (s.owner == owner) return section_markdown(s);
    return std::string();
  };
  std::string index =
      msg(kGenerated,
          "# Lua API reference\n\n"
          "Every function, option, field and default of the `dda` module, as `help()` prints them. How to use them: "
          "[scripting.md](scripting.md). The model's methods: building it, [lua_api_model.md](lua_api_model.md); "
          "running and reading it, [lua_api_run.md](lua_api_run.md); the objects they return, "
          "[lua_api_objects.md](lua_api_objects.md).\n\n",
          section("dda"),
          "## Constants\n\n"
          "| name | value |\n|---|---|\n"
          "| `dda.version` | the version, e.g. `\"",
          DDA_VERSION_TEXT,
          "\"` |\n"
          "| `dda.has_render` | whether this `dda` has the renderer (frames, plots) |\n"
          "| `dda.fields` | the monitor fields' names, in the order below |\n\n"
          "## Monitor fields\n\n"
          "What `m:monitor{fields = {...}}` records (and `monitor:value(name)` reads now).\n\n",
          names_table("field", field_names(), false),
          "\n## Controls\n\n"
          "The options of `dda.model{...}` and `m:controls{...}`: every control with its default. They may change "
          "between steps. A control set away from its default where the model in use does not read it "
          "(`rho_inf` without `integrator = \"generalized_alpha\"`, `contact_tolerance` under `\"holding\"`, "
          "`refactor_iterations` and `fill_ordering` under `solver = \"pcg\"`, a lumped or mixed `mesh_mass` or "
          "`mesh_preconditioner` without meshed blocks) stops the next step with why and the cure, rather than "
          "being ignored (`engine/world/inert_controls.hpp`).\n\n",
          controls_markdown_table());
  ApiSection model;
  for (const ApiSection& s : sections)
    if (s.owner == "dda.Model") model = s;
  const std::initializer_list<const char*> building_topics = {
      "Materials", "Geometry", "Blocks", "Edges", "Loads and fixed points", "Prescribed motion"};
  const std::initializer_list<const char*> running_topics = {"Running and reading", "Background runs", "Monitors",
                                                             "Frames", "ParaView files"};
  for (const std::string& topic : model.topics)
    DDA_ASSERT(std::count(building_topics.begin(), building_topics.end(), topic) +
                       std::count(running_topics.begin(), running_topics.end(), topic) ==
                   1,
               "a topic of the model's methods on no page of the reference (api_reference_pages)");
  std::string building = msg(kGenerated, "# Lua API reference: building a model\n\n", intro_of("dda.Model")->intro,
                             "\n\n", topics_markdown(model, building_topics));
  std::string running =
      msg(kGenerated, "# Lua API reference: running and reading a model\n\n", topics_markdown(model, running_topics));
  std::string objects = msg(kGenerated, "# Lua API reference: the objects\n\n");
  for (const TypeIntro& t : kTypes)
    if (std::strcmp(t.type, "dda") != 0 && std::strcmp(t.type, "dda.Model") != 0) objects += section(t.type);
  for (const ApiSection& s : sections)
    if (!intro_of(s.owner)) objects += section_markdown(s);
  return {{"lua_api.md", index},
          {"lua_api_model.md", building},
          {"lua_api_run.md", running},
          {"lua_api_objects.md", objects}};
}

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
    if (const Method* m = find_method(L, 1)) {
      print_method(*m);
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
    const std::string type = type_of(L, 1);
    const auto methods = documented(L, -1);
    if (!methods.empty()) {
      std::printf("%s methods:\n", type.c_str());
      list(methods);
    }
    if (const Names fields = fields_of(L, type); !fields.empty()) {
      std::printf("%s fields (read and written by name):\n", type.c_str());
      for (const Name& f : fields) print_wrapped(msg(f.name, ": ", plain(f.doc)), "  ");
    }
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
