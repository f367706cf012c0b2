// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Memory limits stated up front: what this process may still allocate, and
// a refusal, with the estimate, of work that would need more. The callers
// estimate their own needs (block cutting from the joint crossings, the
// first step from the blocks and vertices, meshes from their elements,
// ground motions from their samples, holes from their segments;
// docs/robustness.md).
#include <filesystem>
#include <string>

namespace dda {

// What this process may still allocate, and the limit that leaves the
// least: the least headroom of the machine's physical memory (MemTotal less
// this process's resident size), the address-space limit (ulimit -v, less
// the mapped size), the data limit (ulimit -d), and every memory cgroup the
// process is in (cgroup_headroom). bytes is +inf when none is known.
struct MemoryHeadroom {
  double bytes = 1.0 / 0.0;
  std::string limit = "no limit known";  // "ulimit -v", "the cgroup limit of /sys/fs/cgroup/...", ...
};
MemoryHeadroom memory_headroom();
double memory_headroom_bytes();  // memory_headroom().bytes
// A limit a program sets on itself, counted by memory_headroom() as "the
// program's own limit" (no user control: the fuzz targets stay under
// libFuzzer's RSS limit with it, and tests check refusals without
// allocating). +inf: none (the default).
void set_own_memory_limit(double bytes);

// The least headroom of the memory cgroups this process is in, as a batch
// system sets them (Slurm --mem, systemd scopes, containers): its own
// cgroup of each hierarchy, from /proc/self/cgroup, and every cgroup above
// it up to the hierarchy's mount (the lowest limit on the way binds), under
// cgroup v2 (memory.max less memory.current) and v1 (memory.limit_in_bytes
// less memory.usage_in_bytes), the usage less its inactive file cache
// (reclaimable: memory.stat). The hierarchies are found in
// /proc/self/mountinfo. `root` prefixes every path read: "/" in use, a fake
// tree in tests.
MemoryHeadroom cgroup_headroom(const std::filesystem::path& root = "/");

// Throws dda::Error "<what> needs about X GB of memory (<detail>); this
// process can have about Y GB (<the limit>): <cure>" when needed > headroom.
void check_memory_need(double needed_bytes, const MemoryHeadroom& headroom, const std::string& what,
                       const std::string& detail, const std::string& cure);

}  // namespace dda
