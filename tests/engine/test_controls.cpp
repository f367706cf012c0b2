// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// The table of controls (world/controls.hpp): the engine checks every control
// through it (docs/lua_api.md shows it: LuaApiReference.DocsAreTheBindingsOwn).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "world/controls.hpp"

using namespace dda;

namespace {

// A value just outside a control's range (below its minimum).
double below(const ControlRange& r) { return r.min_open ? r.min : r.min - 1; }

}  // namespace

TEST(Controls, NamesAreUniqueAndDefaultsPass) {
  const Controls defaults;
  for (const ControlSpec& s : control_specs()) {
    EXPECT_EQ(find_control(s.name), &s) << s.name;
    EXPECT_EQ(s.violated(defaults), nullptr) << s.name;
  }
}

// Each ranged control out of range stops the step with its name and rule.
TEST(Controls, EveryRangedControlIsCheckedByTheEngine) {
  int checked = 0;
  for (const ControlSpec& s : control_specs()) {
    if (s.type != ControlType::Number && s.type != ControlType::Integer) continue;
    Controls c;
    if (s.type == ControlType::Number)
      s.number(c) = below(s.range);
    else
      s.integer(c) = static_cast<int>(below(s.range));
    try {
      validate_controls(c);
      ADD_FAILURE() << s.name << ": no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("controls: ") + s.name + " " + s.range.rule), std::string::npos)
          << e.what();
    }
    ++checked;
  }
  EXPECT_GE(checked, 18);
}
