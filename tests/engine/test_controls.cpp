// The table of controls (world/controls.hpp): the engine checks every control
// through it, and docs/scripting.md shows it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "world/controls.hpp"

using namespace dda;

namespace {

std::filesystem::path source_dir() {
  if (const char* s = std::getenv("DDA_SOURCE_DIR")) return s;
  return DDA_SOURCE_DIR;
}

// The controls table of docs/scripting.md: from its header row to the first
// line that is not a table row.
std::string docs_controls_table() {
  std::ifstream in(source_dir() / "docs" / "scripting.md");
  std::string line, table;
  // Every table headed like the controls table is read: a second copy (a
  // paste in the wrong place) makes the test fail instead of going stale.
  bool inside = false;
  while (std::getline(in, line)) {
    if (line == "| option | default | meaning |") inside = true;
    if (!inside) continue;
    if (line.empty() || line[0] != '|') {
      inside = false;
      continue;
    }
    table += line + "\n";
  }
  return table;
}

// A value just outside a control's range (below its minimum).
double below(const ControlRange& r) { return r.min_open ? r.min : r.min - 1; }

}  // namespace

TEST(Controls, DocsTableIsTheTable) {
  const std::string generated = controls_markdown_table();
  EXPECT_EQ(docs_controls_table(), generated)
      << "docs/scripting.md's controls table differs from world/controls.cpp's; the table to paste:\n"
      << generated;
}

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
