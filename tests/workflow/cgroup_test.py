# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Memory limits as a cluster sets them, with a real cgroup (root only; skipped,
exit 77, where none can be made): dda runs in a memory cgroup of its own made
below the one this test runs in (v1's memory hierarchy, or v2 where it has
the memory controller), limited to 250 MB; a model whose first step the
estimate puts at about 0.4 GB is refused before it starts, naming that
cgroup (was: under v1 the limit was not read, and the system killed the run
part way, with no message). The fake cgroup trees of
tests/engine/test_memory.cpp check the reading itself.
Run: cgroup_test.py path/to/dda"""
import os
import subprocess
import sys

from common import DDA, check, finish, scratch, write

LIMIT = 250 * 1000 * 1000


def memory_cgroup():
    """(folder of this process's memory cgroup, its limit file), or None."""
    own_v1 = own_v2 = None
    for line in open("/proc/self/cgroup"):
        hid, controllers, path = line.rstrip("\n").split(":", 2)
        if "memory" in controllers.split(","):
            own_v1 = path
        if hid == "0" and controllers == "":
            own_v2 = path
    for line in open("/proc/self/mountinfo"):
        w = line.split()
        dash = w.index("-")
        fstype, options = w[dash + 1], w[dash + 3].split(",")
        root, point = w[3], w[4]
        if fstype == "cgroup" and "memory" in options and own_v1:
            return os.path.join(point, os.path.relpath(own_v1, root)), "memory.limit_in_bytes"
        if fstype == "cgroup2" and own_v2:
            folder = os.path.join(point, os.path.relpath(own_v2, root))
            controllers = os.path.join(folder, "cgroup.subtree_control")
            if os.path.exists(controllers) and "memory" in open(controllers).read().split():
                return folder, "memory.max"
    return None


found = memory_cgroup() if os.geteuid() == 0 else None
if not found:
    print("skipped: not root, or no memory cgroup to make one below")
    sys.exit(77)
parent, limit_file = found
cg = os.path.join(parent, "dda-test-%d" % os.getpid())
try:
    os.mkdir(cg)
    write(os.path.join(cg, limit_file), str(LIMIT))
except OSError as e:
    print("skipped: cannot make a limited cgroup in %s: %s" % (parent, e))
    sys.exit(77)

d = scratch("cgroup")
# 300 x 300 blocks of 0.25 m: the first step's estimate is about 0.4 GB (the
# cut's, about 0.1 GB, fits).
write(os.path.join(d, "big.lua"), """
local m = dda.model{ g1 = 1e-4 }
local rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }
m:domain{ box = {0, 0, 75, 75}, rock = rock }
m:joint_set{ dip = 0, spacing = 0.25 }
m:joint_set{ dip = 90, spacing = 0.25 }
m:generate()
m:step()
""")
try:
    p = subprocess.run(["sh", "-c", 'echo $$ > "$0/cgroup.procs" && exec "$@"', cg, DDA, "run", "big.lua", "--out",
                        "o", "--quiet", "--threads", "1"], cwd=d, capture_output=True, text=True, timeout=600)
    shown = "/" + os.path.relpath(cg, "/")
    check(p.returncode == 1 and "the model's first step needs about" in p.stderr and
          ("(the cgroup limit of %s (%s), less what it uses)" % (shown, limit_file)) in p.stderr,
          "a model too big for its 250 MB cgroup: refused before the first step, naming the cgroup",
          (p.returncode, p.stderr[-600:]))
finally:
    os.rmdir(cg)
finish()
