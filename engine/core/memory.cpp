#include "core/memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace dda {

namespace {

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

// A number in a cgroup v2 file ("max" or absent: -1).
double cgroup_value(const char* name) {
  std::ifstream in(std::string("/sys/fs/cgroup/") + name);
  std::string text;
  if (!(in >> text) || text == "max") return -1;
  return std::strtod(text.c_str(), nullptr);
}

double limit_headroom(int resource, double in_use) {
  rlimit r{};
  if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY || in_use < 0) return INFINITY;
  return std::max(0.0, static_cast<double>(r.rlim_cur) - in_use);
}

}  // namespace

double memory_headroom_bytes() {
  double headroom = INFINITY;
  const double total = proc_field_bytes("/proc/meminfo", "MemTotal");
  const double resident = proc_field_bytes("/proc/self/status", "VmRSS");
  if (total > 0 && resident >= 0) headroom = std::min(headroom, std::max(0.0, total - resident));
  headroom = std::min(headroom, limit_headroom(RLIMIT_AS, proc_field_bytes("/proc/self/status", "VmSize")));
  headroom = std::min(headroom, limit_headroom(RLIMIT_DATA, proc_field_bytes("/proc/self/status", "VmData")));
  const double cg_max = cgroup_value("memory.max"), cg_now = cgroup_value("memory.current");
  if (cg_max > 0 && cg_now >= 0) headroom = std::min(headroom, std::max(0.0, cg_max - cg_now));
  return headroom;
}

void check_memory_need(double needed_bytes, double headroom_bytes, const std::string& what, const std::string& detail,
                       const std::string& cure) {
  if (!(needed_bytes > headroom_bytes)) return;
  auto gb = [](double b) {
    std::ostringstream s;
    s.precision(b < 1e10 ? 2 : 3);
    s << b / 1e9 << " GB";
    return s.str();
  };
  throw Error(msg(what, " needs about ", gb(needed_bytes), " of memory (", detail, "); this process can have about ",
                  gb(headroom_bytes),
                  " (the machine's memory, ulimit -v and the cgroup limit, less what it uses): ", cure));
}

}  // namespace dda
