# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Smaller faults, each reproduced first: an empty
--threads taken as 0; an unusable frames folder with --frames (or
on_error = "continue") stopping the run although a failing frame is to be
reported and the run to go on; a bytecode script and a memory error with
no file; "never read" warnings after a script failed early; blast.lua
looping forever on --set line_step=0 and failing inside math.abs on
t_end=0.
Run: faults_test.py path/to/dda"""
import os
import resource
import subprocess

from common import DDA, SOURCE, check, finish, read, run, scratch, write

d = scratch("faults")
MODEL = """
local m = dda.model{ plane = 'stress', g1 = 1e-4, gravity = {0, -9.81} }
local rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }
m:domain{ box = {0, 0, 1, 0.5}, rock = rock }
m:generate()
"""
write(os.path.join(d, "model.lua"), MODEL + "m:run{ steps = 4 }\nprint('ran')\n")

r = run(["run", "model.lua", "--threads", ""], d)
check(r.returncode == 2 and "--threads needs a whole number" in r.stderr, "--threads '': a usage error (was 0)",
      (r.returncode, r.stderr[:200]))

# ---- an unusable frames folder: reported, the run goes on ---------------------------------
os.makedirs(os.path.join(d, "fo"))
write(os.path.join(d, "fo", "frames"), "a file where the folder should be")
r = run(["run", "model.lua", "--out", "fo", "--frames", "2", "--quiet"], d)
check(r.returncode == 0 and "ran" in r.stdout, "--frames into an unusable folder: the run goes on (was: stopped)",
      (r.returncode, r.stderr))
check("cannot create the folder 'fo/frames'" in r.stderr and "the run goes on" in r.stderr,
      "... with a warning naming the folder", r.stderr)
write(os.path.join(d, "cont.lua"), MODEL + """
local f = m:frames{ folder = "frames", every = 2, on_error = "continue" }
m:run{ steps = 4 }
print("active", f:active())
""")
r = run(["run", "cont.lua", "--out", "fo", "--quiet"], d)
check(r.returncode == 0 and "active\tfalse\tframe sequence: cannot create the folder" in r.stdout,
      "m:frames{on_error = 'continue'} into an unusable folder: off, the run goes on (was: raised)",
      (r.returncode, r.stdout, r.stderr))
write(os.path.join(d, "stop.lua"), MODEL + 'm:frames{ folder = "frames", every = 2 }\n')
r = run(["run", "stop.lua", "--out", "fo", "--quiet"], d)
check(r.returncode == 1 and "stop.lua:6:" in r.stderr and "cannot create the folder" in r.stderr,
      "on_error = 'stop' (the default) still stops, naming the line", r.stderr)

# ---- messages with the file -----------------------------------------------------------------
write(os.path.join(d, "dump.lua"),
      "local f = io.open('code.luac', 'wb') f:write(string.dump(function() print(1) end)) f:close()\n")
run(["run", "dump.lua", "--quiet"], d)
r = run(["run", "code.luac", "--quiet"], d)
check(r.returncode == 1 and "code.luac: binary chunks (precompiled bytecode) are refused" in r.stderr,
      "a bytecode script: refused naming the file", r.stderr)

write(os.path.join(d, "mem.lua"), "local t = {}\nfor i = 1, 1e9 do t[i] = string.rep('x', 1000) .. i end\n")


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))


p = subprocess.run([DDA, "run", "mem.lua", "--quiet"], cwd=d, capture_output=True, text=True, timeout=120,
                   preexec_fn=limit_memory)
check(p.returncode == 1 and "mem.lua: not enough memory" in p.stderr, "not enough memory: names the script",
      (p.returncode, p.stderr))

write(os.path.join(d, "early.lua"), "error('stops at once')\nlocal n = dda.param('n', 1)\n")
r = run(["run", "early.lua", "--set", "n=3", "--quiet"], d)
check(r.returncode == 1 and "never read" not in r.stderr, "no 'never read' warning when the script failed early",
      r.stderr)
write(os.path.join(d, "typo.lua"), "local n = dda.param('n', 1)\n")
r = run(["run", "typo.lua", "--set", "nn=3", "--quiet"], d)
check(r.returncode == 0 and "--set nn=3 was never read" in r.stderr, "a real typo is still reported", r.stderr)

# ---- blast.lua's parameters ---------------------------------------------------------------
blast = os.path.join(SOURCE, "scripts", "paper", "blast.lua")
for bad in ["line_step=0", "t_end=0", "spacing=-1", "frames=-1"]:
    try:
        r = run(["run", blast, "--set", bad, "--quiet", "--out", "b"], d, timeout=60)
        name = bad.split("=")[0]
        check(r.returncode == 1 and "--set " + bad + ": must be a number" in r.stderr and "blast.lua:" in r.stderr,
              "blast.lua --set %s: refused at once, naming it" % bad, r.stderr[-300:])
    except subprocess.TimeoutExpired:
        check(False, "blast.lua --set %s: refused at once (it ran on for 60 s)" % bad)

# ---- memory stated up front (Deliver 4) ------------------------------------------------------
# A 300 x 300 grid (90 000 blocks): the first step is estimated at 0.41 GB.
# Under an address-space limit (ulimit -v) it is refused before it starts,
# naming the estimate; with room for the estimate it runs, so the estimate
# is not below what the step takes. A domain whose cut alone would not fit
# is refused before cutting.
GRID = """
local n = dda.param("n", 300)
local m = dda.model{ plane = 'stress', g1 = 1e-4, gravity = {0, -9.81}, threads = 1 }
local rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }
m:domain{ box = {0, 0, n, n}, rock = rock }
m:joint_set{ dip = 0, spacing = 1 }
m:joint_set{ dip = 90, spacing = 1 }
local blocks = m:generate()
local f = io.open("/proc/self/status") local vm = f:read("a"):match("VmSize:%s*(%d+)") f:close()
print("generated", #blocks, "vmsize_kb", vm)
m:fix{0.5, 0.5}
m:step(1)
print("stepped")
"""
write(os.path.join(d, "grid.lua"), GRID)
r = run(["run", "grid.lua", "--quiet"], d)
vm_kb = int(r.stdout.split("vmsize_kb")[1].split()[0]) if "vmsize_kb" in r.stdout else 0
check(r.returncode == 0 and "stepped" in r.stdout and vm_kb > 0, "the 90 000-block grid runs unlimited", r.stderr)


def address_space(kb):
    def pre():
        resource.setrlimit(resource.RLIMIT_AS, (kb * 1024, kb * 1024))
    return pre


p = subprocess.run([DDA, "run", "grid.lua", "--quiet"], cwd=d, capture_output=True, text=True, timeout=300,
                   preexec_fn=address_space(vm_kb + 150 * 1024))
check(p.returncode == 1 and "generated\t90000" in p.stdout and
      "m:step: the model's first step needs about 0.41 GB of memory (90000 blocks with 360000 vertices)" in p.stderr,
      "150 MB of room: the first step is refused with its estimate", (p.returncode, p.stderr))
p = subprocess.run([DDA, "run", "grid.lua", "--quiet"], cwd=d, capture_output=True, text=True, timeout=300,
                   preexec_fn=address_space(vm_kb + 500 * 1024))
check(p.returncode == 0 and "stepped" in p.stdout, "500 MB of room (more than the 0.41 GB estimate): it runs",
      (p.returncode, p.stderr))
p = subprocess.run([DDA, "run", "grid.lua", "--set", "n=2000", "--quiet"], cwd=d, capture_output=True, text=True,
                   timeout=300, preexec_fn=address_space(vm_kb + 500 * 1024))
check(p.returncode == 1 and "m:generate: cutting the domain needs about 4" in p.stderr and "4004001 joint crossings"
      in p.stderr, "a cut that cannot fit is refused before cutting, with its estimate", (p.returncode, p.stderr))

finish()
