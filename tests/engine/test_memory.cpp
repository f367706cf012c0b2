// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
// Memory limits as a cluster sets them (core/memory.hpp), read through the
// test seam: a fake tree of /proc/self/cgroup, /proc/self/mountinfo and the
// cgroup files under a temporary root. The headroom is the least of
// (limit − usage + inactive file cache) over the process's own cgroup and
// every one above it, in cgroup v2 and v1 (the exact arithmetic on the
// files' numbers, no tolerance), and names the cgroup that binds. And the
// estimates that refuse work before allocating: a mesh, a resampled record
// and a checkpoint's counts, against the program's own limit
// (set_own_memory_limit), each naming the control to change.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "../scenes.hpp"
#include "../source_dir.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "loading/ground_motion.hpp"
#include "world/world.hpp"

namespace dda {
namespace {

namespace fs = std::filesystem;

class FakeRoot {
 public:
  FakeRoot() : root_(fs::temp_directory_path() / ("dda_cgroup_test_" + std::to_string(::getpid()))) {
    fs::remove_all(root_);
    fs::create_directories(root_ / "proc/self");
  }
  ~FakeRoot() { fs::remove_all(root_); }
  void file(const std::string& path, const std::string& text) const {
    fs::create_directories((root_ / path).parent_path());
    std::ofstream(root_ / path) << text;
  }
  const fs::path& root() const { return root_; }

 private:
  fs::path root_;
};

constexpr const char* kV2Mount = "30 23 0:26 / /sys/fs/cgroup rw,nosuid - cgroup2 cgroup2 rw,nsdelegate\n";
constexpr const char* kV1Mounts =
    "31 23 0:28 / /sys/fs/cgroup tmpfs rw - tmpfs tmpfs rw,mode=755\n"
    "32 31 0:29 / /sys/fs/cgroup/cpu rw,relatime - cgroup cgroup rw,cpu\n"
    "35 31 0:32 / /sys/fs/cgroup/memory rw,relatime - cgroup cgroup rw,memory\n";

TEST(Memory, CgroupV2NestedLimitsTheLowestBinds) {
  // A Slurm-like tree: the job's step has no limit of its own, the job has
  // 2 GB of which 0.5 GB is used (0.1 GB of it inactive file cache), the
  // user slice above it 8 GB with 7.2 GB used.
  FakeRoot t;
  t.file("proc/self/mountinfo", std::string("22 1 8:1 / / rw - ext4 /dev/sda rw\n") + kV2Mount);
  t.file("proc/self/cgroup", "0::/user.slice/job_7/step_0\n");
  t.file("sys/fs/cgroup/user.slice/memory.max", "8000000000\n");
  t.file("sys/fs/cgroup/user.slice/memory.current", "7200000000\n");
  t.file("sys/fs/cgroup/user.slice/job_7/memory.max", "2000000000\n");
  t.file("sys/fs/cgroup/user.slice/job_7/memory.current", "500000000\n");
  t.file("sys/fs/cgroup/user.slice/job_7/memory.stat", "anon 400000000\nfile 100000000\ninactive_file 100000000\n");
  t.file("sys/fs/cgroup/user.slice/job_7/step_0/memory.max", "max\n");
  t.file("sys/fs/cgroup/user.slice/job_7/step_0/memory.current", "400000000\n");
  const MemoryHeadroom h = cgroup_headroom(t.root());
  EXPECT_EQ(h.bytes, 800e6);  // the slice: 8 GB − 7.2 GB, less than the job's 2 GB − 0.4 GB
  EXPECT_EQ(h.limit, "the cgroup limit of /sys/fs/cgroup/user.slice (memory.max)");
  t.file("sys/fs/cgroup/user.slice/memory.max", "max\n");
  const MemoryHeadroom job = cgroup_headroom(t.root());
  EXPECT_EQ(job.bytes, 1600e6);  // 2 GB − (0.5 GB − 0.1 GB of inactive cache)
  EXPECT_EQ(job.limit, "the cgroup limit of /sys/fs/cgroup/user.slice/job_7 (memory.max)");
}

TEST(Memory, CgroupV1MemoryHierarchyIsRead) {
  // Slurm --mem on a v1 cluster: the memory controller's own hierarchy.
  FakeRoot t;
  t.file("proc/self/mountinfo", kV1Mounts);
  t.file("proc/self/cgroup", "4:memory:/slurm/uid_1000/job_42\n3:cpu:/\n0::/\n");
  const std::string job = "sys/fs/cgroup/memory/slurm/uid_1000/job_42/";
  t.file(job + "memory.limit_in_bytes", "3000000000\n");
  t.file(job + "memory.usage_in_bytes", "1000000000\n");
  t.file(job + "memory.stat", "cache 300000000\ntotal_inactive_file 250000000\n");
  t.file("sys/fs/cgroup/memory/slurm/memory.limit_in_bytes", "9223372036854771712\n");  // v1's "unlimited"
  t.file("sys/fs/cgroup/memory/slurm/memory.usage_in_bytes", "5000000000\n");
  const MemoryHeadroom h = cgroup_headroom(t.root());
  EXPECT_EQ(h.bytes, 2250e6);  // 3 GB − (1 GB − 0.25 GB)
  EXPECT_EQ(h.limit, "the cgroup limit of /sys/fs/cgroup/memory/slurm/uid_1000/job_42 (memory.limit_in_bytes)");
}

TEST(Memory, ContainerMountShowsTheCgroupBelowItsRoot) {
  // Inside a container the hierarchy is mounted from the container's own
  // cgroup: /proc/self/cgroup names the full path, the mount shows the part
  // below its root.
  FakeRoot t;
  t.file("proc/self/mountinfo", "35 31 0:32 /docker/abc /sys/fs/cgroup/memory ro - cgroup cgroup rw,memory\n");
  t.file("proc/self/cgroup", "4:memory:/docker/abc/inner\n");
  t.file("sys/fs/cgroup/memory/inner/memory.limit_in_bytes", "1000000000\n");
  t.file("sys/fs/cgroup/memory/inner/memory.usage_in_bytes", "100000000\n");
  t.file("sys/fs/cgroup/memory/memory.limit_in_bytes", "600000000\n");
  t.file("sys/fs/cgroup/memory/memory.usage_in_bytes", "200000000\n");
  const MemoryHeadroom h = cgroup_headroom(t.root());
  EXPECT_EQ(h.bytes, 400e6);  // the container's own 0.6 GB − 0.2 GB
  EXPECT_EQ(h.limit, "the cgroup limit of /sys/fs/cgroup/memory (memory.limit_in_bytes)");
}

TEST(Memory, NoCgroupOrNoLimitIsNoLimit) {
  FakeRoot t;
  EXPECT_TRUE(std::isinf(cgroup_headroom(t.root()).bytes));
  t.file("proc/self/mountinfo", kV2Mount);
  t.file("proc/self/cgroup", "0::/a\n");
  t.file("sys/fs/cgroup/a/memory.max", "max\n");
  t.file("sys/fs/cgroup/a/memory.current", "12345\n");
  EXPECT_TRUE(std::isinf(cgroup_headroom(t.root()).bytes));
  // This machine's own tree reads without error (its numbers vary).
  EXPECT_GE(cgroup_headroom().bytes, 0.0);
}

// The program's own limit for the tests below, lifted at the end of each.
class OwnLimit {
 public:
  explicit OwnLimit(double bytes) { set_own_memory_limit(bytes); }
  ~OwnLimit() { set_own_memory_limit(INFINITY); }
};

void expect_error(const std::function<void()>& f, std::initializer_list<const char*> words) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    for (const char* w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

TEST(Memory, ATinyMeshSizeIsRefusedBeforeMeshingNamingIt) {
  // mesh_size 0.01 m on a 10 m square: 4 million elements, about 16 GB; was
  // a bare "not enough memory" after the mesher had run for a minute.
  const OwnLimit limit(2e9);
  World w;
  RockMaterial rock = test::granite();
  rock.mesh_size = 0.01;
  const int r = w.add_rock_material(rock);
  expect_error([&] { w.add_block(test::rectangle(0, 0, 10, 10), r); },
               {"meshing block", "about 4000000 elements at mesh_size 0.01 m", "the program's own limit",
                "give a larger mesh_size"});
  EXPECT_EQ(w.block_count(), 0u);
}

TEST(Memory, AResamplingThatCannotFitIsRefusedNamingDt) {
  // The bundled record (36.9 s) at dt = 1e-6 s: 3.7e7 samples, about 17 GB.
  const OwnLimit limit(2e9);
  const std::string record = std::string(DDA_SOURCE_DIR) + "/data/imperial_valley_1979_el_centro_array7_S50W.dat";
  expect_error([&] { GroundMotion::read_accelerogram(record, AccelerationUnit::CentimetrePerSecond2, 1e-6); },
               {"resampling to dt = 1e-06 s needs about 17 GB", "give a larger dt"});
  // A spacing so small that the count does not fit a number at all.
  expect_error(
      [&] {
        GroundMotion::from_samples({{0, 0}, {1e-300, 1}, {1, 0}}, 1e-310, "three rows");
      },
      {"three rows: resampling 1 s at dt = ", "give a larger dt"});
}

}  // namespace
}  // namespace dda
