// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Helpers for the scripting tests: locating the dda executable, running it,
// reading CSV files, temporary folders.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../source_dir.hpp"

namespace dda::test {

inline std::filesystem::path source_dir() {
  if (const char* s = std::getenv("DDA_SOURCE_DIR")) return s;
  return DDA_SOURCE_DIR;
}

// build/dda: DDA_EXE, else beside the test executable's folder (build/tests/..).
inline std::filesystem::path dda_exe() {
  if (const char* s = std::getenv("DDA_EXE")) return s;
  const auto self = std::filesystem::read_symlink("/proc/self/exe");
  return self.parent_path().parent_path() / "dda";
}

// A fresh folder under the system temp dir, removed at the end of the test.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& name) {
    path = std::filesystem::temp_directory_path() / ("dda-scripting-" + name + "-" + std::to_string(getpid()));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::filesystem::path operator/(const std::string& f) const { return path / f; }
};

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

inline std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs `dda <args>` in `cwd` (stdin from /dev/null unless input_file given).
inline RunResult run_dda(const std::string& args, const std::filesystem::path& cwd,
                         const std::filesystem::path& input_file = "/dev/null") {
  const auto out = cwd / "stdout.txt", err = cwd / "stderr.txt";
  const std::string cmd = "cd " + quote(cwd.string()) + " && " + quote(dda_exe().string()) + " " + args + " <" +
                          quote(input_file.string()) + " >" + quote(out.string()) + " 2>" + quote(err.string());
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  bool complete = true;  // every row has as many fields as the header, file ends with '\n'
  int column(const std::string& name) const {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
};

inline std::vector<std::string> split(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string item;
  while (std::getline(s, item, sep)) out.push_back(item);
  if (!line.empty() && line.back() == sep) out.push_back("");
  return out;
}

inline Csv read_csv(const std::filesystem::path& p) {
  Csv csv;
  const std::string text = read_file(p);
  if (!text.empty() && text.back() != '\n') csv.complete = false;
  std::stringstream s(text);
  std::string line;
  bool first = true;
  while (std::getline(s, line)) {
    const auto f = split(line);
    if (first) {
      csv.header = f;
      first = false;
      continue;
    }
    if (f.size() != csv.header.size()) csv.complete = false;
    std::vector<double> row;
    for (const auto& x : f) {
      char* end = nullptr;
      row.push_back(std::strtod(x.c_str(), &end));
      if (end == x.c_str() || *end != '\0') csv.complete = false;
    }
    csv.rows.push_back(row);
  }
  return csv;
}

}  // namespace dda::test
