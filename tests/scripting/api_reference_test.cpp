// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The Lua API's documentation cannot drift from the binding: the reference
// (docs/lua_api*.md) is generated from the tables that register each
// function, its options, the keys it returns and the types' fields, and
// these tests hold the binding to those tables:
//  - each page of the reference equals what the tables generate;
//  - every documented option is accepted, and an undocumented one refused;
//  - every documented field of an object reads and writes, and no other;
//  - every table a function returns has exactly its documented keys;
//  - every `dda.name` and `m:name` the other docs and the README cite exists.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include "lua_state_test.hpp"
#include "script_helpers.hpp"
#include "scripting.hpp"
#include "wrap.hpp"

using namespace dda::script;
using dda::msg;

namespace {

// A model with one object of each type the API has.
const char* kObjects =
    "m = dda.model{ gravity = {0, -9.81}, g1 = 1e-3 }\n"
    "rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }\n"
    "joint = m:joint{ friction = 30 }\n"
    "base = m:add_block{ {-1, -1}, {2, -1}, {2, 0}, {-1, 0} }\n"
    "base:fix()\n"
    "b = m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }\n"
    "blocks = m:blocks()\n"
    "edges = m:edges{ block = b }\n"
    "monitor = m:monitor{ at = {0.5, 0.5}, fields = {'vx', 'vy'}, csv = false }\n"
    "load = m:point_load{ at = {0.5, 0.5}, fx = 1 }\n"
    "pressure = m:edges{ on_segment = {0, 1, 1, 1} }:pressure(1)\n"
    "target = m:target{ at = {0.2, 0.2}, displacement = {0, 0} }\n"
    "boundary = m:edges{ on_segment = {1, 0, 1, 1} }:spring_boundary{ p = 1 }\n"
    "vtu = m:vtu{}\n"
    "if dda.has_render then frames = m:frames{ every = 1000 } end\n"
    // The geometry calls need a model whose blocks are not generated yet.
    "g = dda.model{}\n"
    "g:rock{ density = 2000, E = 1e9, nu = 0.25 }\n"
    "g:domain{ box = {0, 0, 4, 4} }\n"
    "hole = g:hole{ box = {1, 1, 2, 2} }\n";

// The global a type's methods are called on.
const std::map<std::string, std::string> kSelf = {
    {"dda", "dda"},           {"dda.Model", "m"},           {"dda.Block", "b"},        {"dda.BlockSet", "blocks"},
    {"dda.EdgeSet", "edges"}, {"dda.Monitor", "monitor"},   {"dda.PointLoad", "load"}, {"dda.Pressure", "pressure"},
    {"dda.Target", "target"}, {"dda.Boundary", "boundary"}, {"dda.Vtu", "vtu"},        {"dda.Frames", "frames"},
    {"dda.Hole", "hole"}};
// Model methods that build geometry (the model g, not generated yet).
const std::set<std::string> kGeometry = {"domain", "hole", "region", "joint_set", "joint_line", "generate"};

class LuaApiReference : public dda::test::LuaStateTest {
 protected:
  void SetUp() override {
    out_ = std::make_unique<dda::test::TempDir>(::testing::UnitTest::GetInstance()->current_test_info()->name());
    Session s;
    s.out_dir = out_->path;
    start(std::move(s));
  }
  // The error of calling owner's method with the options table `options`
  // (Lua source), "" when the call succeeds.
  std::string call_error(const std::string& owner, const Method& m, const std::string& options) {
    std::string self = kSelf.at(owner);
    if (owner == "dda.Model" && kGeometry.count(m.name)) self = "g";
    const std::string call =
        self == "dda" ? msg("dda.", m.name, "(", options, ")") : msg(self, ".", m.name, "(", self, ", ", options, ")");
    std::string error;
    return run_string(L, call, "probe", error) ? std::string() : error;
  }
  std::unique_ptr<dda::test::TempDir> out_;
};

// Each page of the reference is what the binding's tables generate. When it
// is not, the generated page is written beside the test binary, to copy.
TEST_F(LuaApiReference, DocsAreTheBindingsOwn) {
  for (const auto& [file, text] : api_reference_pages(L)) {
    const std::string docs = dda::test::read_file(dda::test::source_dir() / "docs" / file);
    if (docs == text) continue;
    const auto generated = std::filesystem::read_symlink("/proc/self/exe").parent_path() / file;
    std::ofstream(generated) << text;
    ADD_FAILURE() << "docs/" << file
                  << " differs from the binding's tables (scripting/help.cpp); the generated page: " << generated
                  << "\n  cp " << generated << " " << (dda::test::source_dir() / "docs" / file);
  }
}

// Every documented option is accepted (a call given it alone fails, if it
// does, for another reason than an unknown option), and an undocumented one
// is refused as unknown.
TEST_F(LuaApiReference, EveryDocumentedOptionIsAcceptedAndNoOther) {
  run(kObjects);
  int probed = 0;
  for (const ApiSection& section : api_sections(L)) {
    if (std::none_of(section.methods.begin(), section.methods.end(),
                     [](const Method* m) { return !m->options.empty(); }))
      continue;
    if (!kSelf.count(section.owner)) {
      ADD_FAILURE() << "no object of type " << section.owner << " to probe: add one to kObjects and kSelf";
      continue;
    }
    if (section.owner == "dda.Frames" && !lua_getglobal(L, "frames")) {
      lua_pop(L, 1);
      continue;  // built without the renderer
    }
    lua_settop(L, 0);
    for (const Method* m : section.methods) {
      if (m->options.empty()) continue;
      const std::string unknown = call_error(section.owner, *m, "{ zz_undocumented = 1 }");
      EXPECT_NE(unknown.find("unknown option 'zz_undocumented'"), std::string::npos)
          << section.owner << " " << m->name << ": " << unknown;
      for (const Name& o : m->options) {
        const std::string e = call_error(section.owner, *m, msg("{ ", o.name, " = function() end }"));
        EXPECT_EQ(e.find("unknown option"), std::string::npos) << section.owner << " " << m->name << ": " << e;
        ++probed;
      }
    }
  }
  EXPECT_GT(probed, 100);
}

// A material's documented fields read (a number) and write (its own value
// back); another name is neither.
TEST_F(LuaApiReference, EveryDocumentedFieldReadsAndWritesAndNoOther) {
  run(kObjects);
  const std::map<std::string, std::string> objects = {{"dda.RockMaterial", "rock"}, {"dda.JointMaterial", "joint"}};
  int fields = 0;
  for (const ApiSection& section : api_sections(L)) {
    if (section.fields.empty()) continue;
    ASSERT_TRUE(objects.count(section.owner)) << section.owner << " has fields: add an object of it here";
    const std::string x = objects.at(section.owner);
    for (const Name& f : section.fields) {
      run(msg("assert(type(", x, ".", f.name, ") == 'number', '", f.name, "')"));
      if (std::string(f.name) != "id" && std::string(f.name) != "density")
        run(msg(x, ".", f.name, " = ", x, ".", f.name));
      ++fields;
    }
    EXPECT_NE(error_of(msg("local v = ", x, ".zz_undocumented")).find("has no method or field 'zz_undocumented'"),
              std::string::npos);
    EXPECT_NE(error_of(msg(x, ".zz_undocumented = 1")).find("unknown field 'zz_undocumented'"), std::string::npos);
  }
  EXPECT_EQ(fields, 11);
}

// The keys of every table a function returns are its documented ones. A
// function documented with returned keys needs a call here.
TEST_F(LuaApiReference, EveryReturnedTableHasItsDocumentedKeys) {
  run(kObjects);
  run("m:step(2)\n");
  const std::map<std::string, std::string> calls = {
      {"stats", "m:stats()"},
      {"energy", "m:energy()"},
      {"totals", "m:totals()"},
      {"contacts", "m:contacts()[1]"},
      {"contact_summary", "m:contact_summary()"},
      {"settle", "m:settle{}"},
      {"generate",
       "select(2, (function() local q = dda.model{} q:rock{ density = 1, E = 1, nu = 0 } "
       "q:domain{ box = {0, 0, 2, 2} } q:joint_set{ dip = 0, spacing = 1 } return q:generate() end)())"},
      {"ground_motion", "dda.ground_motion{ samples = {{0, 0}, {0.01, 1}, {0.02, 0}}, unit = 'm/s2' }"}};
  for (const ApiSection& section : api_sections(L))
    for (const Method* m : section.methods) {
      if (m->returns.empty()) continue;
      const auto call = calls.find(m->name);
      if (call == calls.end()) {
        ADD_FAILURE() << section.owner << " " << m->name << " documents the keys it returns: add a call here";
        continue;
      }
      run("keys = {} for k in pairs(" + call->second + ") do keys[#keys + 1] = k end table.sort(keys)");
      std::set<std::string> got, documented;
      lua_getglobal(L, "keys");
      for (lua_Integer i = 1; i <= static_cast<lua_Integer>(lua_rawlen(L, -1)); ++i) {
        lua_rawgeti(L, -1, i);
        got.insert(lua_tostring(L, -1));
        lua_pop(L, 1);
      }
      lua_pop(L, 1);
      for (const Name& n : m->returns) documented.insert(n.name);
      EXPECT_EQ(got, documented) << section.owner << " " << m->name;
    }
}

// `dda.name` and `m:name` in the README and the docs name functions that
// exist (the reference pages are generated; the rest is written by hand).
TEST_F(LuaApiReference, FunctionsTheDocsCiteExist) {
  std::set<std::string> module = {"version", "fields", "has_render"}, model;
  for (const ApiSection& s : api_sections(L))
    for (const Method* m : s.methods) {
      if (s.owner == "dda") module.insert(m->name);
      if (s.owner == "dda.Model") model.insert(m->name);
    }
  std::vector<std::filesystem::path> files = {dda::test::source_dir() / "README.md"};
  for (const auto& e : std::filesystem::directory_iterator(dda::test::source_dir() / "docs"))
    if (e.path().extension() == ".md" && e.path().filename().string().rfind("lua_api", 0) != 0)
      files.push_back(e.path());
  const std::regex cited(R"((dda\.|\bm:)([a-z_]+)\b)");
  int checked = 0;
  for (const auto& f : files) {
    const std::string text = dda::test::read_file(f);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), cited); it != std::sregex_iterator(); ++it) {
      const std::string kind = (*it)[1], name = (*it)[2];
      const std::string after = text.substr(it->position() + it->length(), 5);
      if (after.rfind("` →", 0) == 0 || after.rfind("<", 0) == 0) continue;  // Tab completion: a prefix
      const bool exists = (kind == "dda." ? module : model).count(name) > 0;
      EXPECT_TRUE(exists) << f.filename().string() << " cites " << kind << name << ", which the API does not have";
      ++checked;
    }
  }
  EXPECT_GT(checked, 50);
}

}  // namespace
