// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#include "core/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.hpp"

namespace dda {

namespace {

namespace fs = std::filesystem;

// A "Name:  1234 kB" field of /proc/self/status or /proc/meminfo, in bytes; -1 if absent.
double proc_field_bytes(const char* file, const std::string& name) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(name + ":", 0) == 0) {
      std::istringstream s(line.substr(name.size() + 1));
      double kb = -1;
      s >> kb;
      return kb >= 0 ? kb * 1024 : -1;
    }
  return -1;
}

double limit_headroom(int resource, double in_use) {
  rlimit r{};
  if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY || in_use < 0) return INFINITY;
  return std::max(0.0, static_cast<double>(r.rlim_cur) - in_use);
}

void take_least(MemoryHeadroom& least, double bytes, const std::string& limit) {
  if (bytes < least.bytes) least = {bytes, limit};
}

// ---- cgroups --------------------------------------------------------------------------

// A mounted hierarchy that holds the memory controller.
struct CgroupMount {
  fs::path point;  // where it is mounted
  fs::path root;   // the cgroup at its mount point (not "/" inside some containers)
  bool v2 = false;
};

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, sep);) parts.push_back(part);
  return parts;
}

// /proc/self/mountinfo: "id parent dev root point options [optional...] - fstype source super-options".
std::vector<CgroupMount> memory_mounts(const fs::path& root) {
  std::vector<CgroupMount> mounts;
  std::ifstream in(root / "proc/self/mountinfo");
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    const auto dash = std::find(w.begin(), w.end(), "-");
    if (w.size() < 5 || dash == w.end() || w.end() - dash < 4) continue;
    const std::string& type = dash[1];
    const std::vector<std::string> options = split(dash[3], ',');
    const bool v1_memory = type == "cgroup" && std::find(options.begin(), options.end(), "memory") != options.end();
    if (type == "cgroup2" || v1_memory) mounts.push_back({w[4], w[3], type == "cgroup2"});
  }
  return mounts;
}

// The process's cgroup in each hierarchy, from /proc/self/cgroup
// ("id:controllers:path"; v2: "0::path"): the v2 one and the v1 memory one.
void own_cgroups(const fs::path& root, std::string& v2, std::string& v1_memory) {
  std::ifstream in(root / "proc/self/cgroup");
  for (std::string line; std::getline(in, line);) {
    const auto a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    if (line.substr(0, a) == "0" && controllers.empty()) v2 = path;
    const std::vector<std::string> list = split(controllers, ',');
    if (std::find(list.begin(), list.end(), "memory") != list.end()) v1_memory = path;
  }
}

// A number in a cgroup file; -1 when absent or unlimited ("max", or v1's
// page-counter maximum, 2^63 rounded down to a page).
double cgroup_number(const fs::path& file) {
  std::ifstream in(file);
  std::string text;
  if (!(in >> text) || text == "max") return -1;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end != text.c_str() && v >= 0 && v < 0x1p62 ? v : -1;
}

// The reclaimable page cache of a cgroup's usage (memory.stat).
double inactive_file(const fs::path& stat, bool v2) {
  std::ifstream in(stat);
  const std::string key = v2 ? "inactive_file" : "total_inactive_file";
  for (std::string name; in >> name;) {
    double v = 0;
    if (!(in >> v)) break;
    if (name == key) return v;
  }
  return 0;
}

// The headroom of the cgroup at `dir` and of each one above it up to the
// mount point `top`.
void walk_up(const fs::path& root, const fs::path& top, fs::path dir, bool v2, MemoryHeadroom& least) {
  const char* limit_file = v2 ? "memory.max" : "memory.limit_in_bytes";
  const char* usage_file = v2 ? "memory.current" : "memory.usage_in_bytes";
  for (int depth = 0; depth < 64; ++depth) {
    const double limit = cgroup_number(dir / limit_file);
    if (limit >= 0) {
      double usage = cgroup_number(dir / usage_file);
      if (usage >= 0) usage = std::max(0.0, usage - inactive_file(dir / "memory.stat", v2));
      take_least(least, std::max(0.0, limit - std::max(usage, 0.0)),
                 msg("the cgroup limit of /", dir.lexically_relative(root).generic_string(), " (", limit_file, ")"));
    }
    if (dir == top || !dir.has_parent_path() || dir.parent_path() == dir) break;
    dir = dir.parent_path();
  }
}

}  // namespace

MemoryHeadroom cgroup_headroom(const fs::path& root) {
  MemoryHeadroom least;
  std::string v2_path, v1_path;
  own_cgroups(root, v2_path, v1_path);
  for (const CgroupMount& m : memory_mounts(root)) {
    const std::string& own = m.v2 ? v2_path : v1_path;
    if (own.empty()) continue;
    const fs::path top = (root / m.point.relative_path()).lexically_normal();
    // The cgroup's path is relative to the hierarchy's root; the mount shows
    // the part under the mount's own root.
    fs::path rel = fs::path(own).lexically_relative(m.root);
    if (rel.empty() || *rel.begin() == "..") rel = fs::path(own).relative_path();
    fs::path dir = (top / rel).lexically_normal();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) dir = top;  // not visible here: at least the mount's own limit
    walk_up(root, top, dir, m.v2, least);
  }
  return least;
}

namespace {
double g_own_limit = INFINITY;
}  // namespace

void set_own_memory_limit(double bytes) { g_own_limit = bytes; }

MemoryHeadroom memory_headroom() {
  MemoryHeadroom least = cgroup_headroom("/");
  const double total = proc_field_bytes("/proc/meminfo", "MemTotal");
  const double resident = proc_field_bytes("/proc/self/status", "VmRSS");
  if (total > 0 && resident >= 0) take_least(least, std::max(0.0, total - resident), "the machine's memory");
  take_least(least, limit_headroom(RLIMIT_AS, proc_field_bytes("/proc/self/status", "VmSize")), "ulimit -v");
  take_least(least, limit_headroom(RLIMIT_DATA, proc_field_bytes("/proc/self/status", "VmData")), "ulimit -d");
  if (g_own_limit < INFINITY)
    take_least(least, std::max(0.0, g_own_limit - std::max(resident, 0.0)), "the program's own limit");
  return least;
}

double memory_headroom_bytes() { return memory_headroom().bytes; }

void check_memory_need(double needed_bytes, const MemoryHeadroom& headroom, const std::string& what,
                       const std::string& detail, const std::string& cure) {
  if (!(needed_bytes > headroom.bytes)) return;
  auto gb = [](double b) {
    std::ostringstream s;
    s.precision(b < 1e10 ? 2 : 3);
    s << b / 1e9 << " GB";
    return s.str();
  };
  throw Error(msg(what, " needs about ", gb(needed_bytes), " of memory (", detail, "); this process can have about ",
                  gb(headroom.bytes), " (", headroom.limit, ", less what it uses): ", cure));
}

}  // namespace dda
