# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Checkpoint and restart as a user meets them: `dda run --checkpoint-every`,
`dda run --restart FILE` (a fresh process, 1 or 2 threads) and
m:save / dda.load continue with the state hash of the straight run (the
reference; no tolerance: the hashes are equal) on the bar, a blast and a
block sliding down an incline; monitor files continue; wrong, truncated and
damaged files and a restart of another model are refused with a message.
Run: restart_test.py path/to/dda"""
import os
import re
import signal
import subprocess

from common import DDA, SOURCE, check, finish, read, run, scratch, write

d = scratch("restart")
# Each scene steps `steps` (or runs to `time`) and prints its hash. A monitor
# records every 3 steps.
write(os.path.join(d, "scene.lua"), r"""
local dda = require "dda"
package.path = package.path .. ";" .. dda.param("source", ".") .. "/scripts/bench/?.lua"
local scenes = require "scenes"
local name, threads = dda.param("scene", "bar"), dda.param("threads", 1)
local m, probe
if name == "bar" then
  m = scenes.bar(threads)
  probe = m:monitor{ at = {0.55, 0.05}, fields = {"sxx", "vx"}, name = "probe", every = 3 }
  m:monitor{ at = {0.35, 0.05}, fields = {"vx"}, csv = false }
elseif name == "blast" then
  m = scenes.blast(4, threads)
  probe = m:monitor{ at = {0, -10}, fields = {"ux", "uy"}, name = "probe", every = 3 }
else  -- a block sliding down a 30 degree incline, phi = 20 degrees
  local alpha = math.rad(30)
  m = dda.model{ gravity = {0, -9.81}, g1 = 1e-3, g2 = 0.01, threads = threads }
  local rock = m:rock{ density = 2600, E = 5e9, nu = 0.25 }
  local joint = m:joint{ friction = 20 }
  local s, n = {math.cos(alpha), math.sin(alpha)}, {-math.sin(alpha), math.cos(alpha)}
  m:add_block{ {0, 0}, {0, -1}, {4 * s[1], -1}, {4 * s[1], 4 * s[2]}, rock = rock, joint = joint }:fix()
  local function at(d, h) return {d * s[1] + h * n[1], d * s[2] + h * n[2]} end
  m:add_block{ at(3, 1e-6), at(3.5, 1e-6), at(3.5, 0.500001), at(3, 0.500001), rock = rock, joint = joint }
  probe = m:monitor{ at = at(3.25, 0.25), fields = {"x", "vx"}, name = "probe", every = 3 }
end
local t = dda.param("time", 0)
if t > 0 then m:run{ time = t } else m:step(dda.param("steps", 60)) end
print("hash " .. m:hash() .. " step " .. m:steps() .. " sliding " .. m:contact_summary().sliding)
local sum, series = 0, probe:series(name == "blast" and "uy" or "vx")
for _, v in ipairs(series) do sum = sum + v end
print(string.format("monitor %d rows, sum %.17g", #series, sum))
""")


def hash_of(r):
    m = re.search(r"hash (\w+) step (\d+) sliding (\d+)", r.stdout)
    return (m.group(1), int(m.group(2)), int(m.group(3))) if m else (None, None, None)


def dda(*args):
    return run(["run", "scene.lua", "--quiet", "--set", "source=" + SOURCE] + list(args), d)


cases = [("bar", ["--set", "steps=90", "--vtu", "10"], ["--set", "steps=50", "--vtu", "10"], "--checkpoint-every", "20"),
         ("blast", ["--set", "steps=60"], ["--set", "steps=35"], "--checkpoint-every", "15"),
         ("slope", ["--set", "time=0.4"], ["--set", "time=0.25"], "--checkpoint-every", "0.1s")]
for scene, full, part, every_opt, every in cases:
    out = "straight-" + scene
    r = dda("--set", "scene=" + scene, "--out", out, *full)
    straight, straight_out = hash_of(r), r.stdout
    check(r.returncode == 0 and straight[0], scene + ": the straight run", r.stderr)
    if scene == "slope":
        check(straight[2] > 0, "slope: the block slides (friction state is carried)", r.stdout)
    for threads in ("1", "2"):
        o = "cut-%s-%s" % (scene, threads)
        r = dda("--set", "scene=" + scene, "--out", o, every_opt, every, *part)
        ckpt = os.path.join(d, o, "checkpoint.ckpt")
        check(r.returncode == 0 and os.path.exists(ckpt) and not os.path.exists(ckpt + ".part"),
              "%s: a run that stops early leaves its last checkpoint (%s %s)" % (scene, every_opt, every), r.stderr)
        r = dda("--set", "scene=" + scene, "--out", o, "--restart", ckpt, "--set", "threads=" + threads, *full)
        check(r.returncode == 0 and hash_of(r) == straight,
              "%s: --restart in a fresh process, %s thread(s): the straight run's hash" % (scene, threads),
              "%s\n%s against %s" % (r.stderr, hash_of(r), straight))
        rows = re.search(r"monitor \d+ rows, sum \S+", r.stdout)
        check(rows and rows.group(0) in straight_out, "%s: the monitor's records in memory: the whole run's" % scene,
              r.stdout + straight_out)
        check(read(os.path.join(d, o, "probe.csv")) == read(os.path.join(d, out, "probe.csv")),
              "%s: the monitor file continues: the straight run's rows, none twice" % scene)
        if scene == "bar":
            vtu, vtu0 = os.path.join(d, o, "vtu"), os.path.join(d, out, "vtu")
            check(read(os.path.join(vtu, "blocks.pvd")) == read(os.path.join(vtu0, "blocks.pvd")) and
                  read(os.path.join(vtu, "contacts_00009.vtu")) == read(os.path.join(vtu0, "contacts_00009.vtu")),
                  "bar: the VTU series continues: the straight run's .pvd and files")
        log = read(os.path.join(d, o, "run.log")).split("==== dda run")[-1]
        check(re.search(r"restart: model 1 continues from \S+checkpoint.ckpt at step \d+", log) is not None,
              scene + ": the run log says where the restart continued", log)

# Ctrl-C: the run stops at a step boundary with a checkpoint (none was due yet), and
# --restart from it ends with the straight run's hash.
args = [DDA, "run", "scene.lua", "--set", "source=" + SOURCE, "--set", "scene=slope", "--set", "time=20"]
r = dda("--set", "scene=slope", "--set", "time=20", "--out", "int-straight")
straight = hash_of(r)
p = subprocess.Popen(args + ["--out", "int", "--checkpoint-every", "1000000"], cwd=d, stderr=subprocess.PIPE,
                     stdout=subprocess.PIPE, text=True, env=dict(os.environ, DDA_PROGRESS_SECONDS="0"))
line = p.stderr.readline()  # the first progress line: stepping has begun
p.send_signal(signal.SIGINT)
out, err = p.communicate(timeout=120)
ckpt = os.path.join(d, "int", "checkpoint.ckpt")
check(p.returncode == 130 and os.path.exists(ckpt), "Ctrl-C: exit 130 and a checkpoint", line + err)
r = dda("--set", "scene=slope", "--set", "time=20", "--out", "int", "--restart", ckpt)
check(r.returncode == 0 and hash_of(r) == straight, "--restart after Ctrl-C: the straight run's hash",
      "%s\n%s against %s" % (r.stderr, hash_of(r), straight))

# SIGTERM (what a batch queue sends before SIGKILL) as Ctrl-C: a final checkpoint,
# every file complete, exit 143; the restart ends with the straight run's hash
# (was: killed at once, no checkpoint).
p = subprocess.Popen(args + ["--out", "term", "--checkpoint-every", "1000000"], cwd=d, stderr=subprocess.PIPE,
                     stdout=subprocess.PIPE, text=True, env=dict(os.environ, DDA_PROGRESS_SECONDS="0"))
line = p.stderr.readline()
p.send_signal(signal.SIGTERM)
out, err = p.communicate(timeout=120)
ckpt = os.path.join(d, "term", "checkpoint.ckpt")
log = read(os.path.join(d, "term", "run.log"))
probe = read(os.path.join(d, "term", "probe.csv"))
check(p.returncode == 143 and os.path.exists(ckpt) and "terminated (SIGTERM)" in err,
      "SIGTERM: exit 143, a final checkpoint, the cause named", line + err)
check("end: exit status 143 (terminated)" in log and probe.endswith("\n") and
      not [f for f in os.listdir(os.path.join(d, "term")) if f.endswith(".part")],
      "SIGTERM: the run log closed, the monitor file complete, no .part left", log[-300:])
r = dda("--set", "scene=slope", "--set", "time=20", "--out", "term", "--restart", ckpt)
check(r.returncode == 0 and hash_of(r) == straight, "--restart after SIGTERM: the straight run's hash",
      "%s\n%s against %s" % (r.stderr, hash_of(r), straight))

# m:save and dda.load: in the same script (a branch point) and in a fresh process.
write(os.path.join(d, "branch.lua"), r"""
local dda = require "dda"
package.path = package.path .. ";" .. dda.param("source", ".") .. "/scripts/bench/?.lua"
local scenes = require "scenes"
local m = scenes.bar(1)
m:step(40)
print("saved " .. m:save("at40.ckpt"))
local copy = dda.load("at40.ckpt")
copy:controls{ threads = 2 }
m:step(30)
copy:step(30)
print("same " .. tostring(m:hash() == copy:hash()) .. " " .. copy:steps())
""")
r = run(["run", "branch.lua", "--quiet", "--out", "o", "--set", "source=" + SOURCE], d)
check(r.returncode == 0 and "same true 70" in r.stdout and os.path.exists(os.path.join(d, "o", "at40.ckpt")),
      "m:save into the output folder, dda.load of it in the same script: the same hash 30 steps on",
      r.stdout + r.stderr)
write(os.path.join(d, "resume.lua"), r"""
local dda = require "dda"
local m = dda.load(arg[1])
m:step(30)
print("hash " .. m:hash() .. " step " .. m:steps() .. " sliding 0")
""")
r = dda("--set", "scene=bar", "--out", "b70", "--set", "steps=70")
r2 = run(["run", "resume.lua", "--quiet", "--out", "o2", "--", os.path.join(d, "o", "at40.ckpt")], d)
check(r2.returncode == 0 and hash_of(r2)[0] == hash_of(r)[0] and hash_of(r2)[1] == 70,
      "dda.load in a fresh process continues as the straight run", r2.stdout + r2.stderr)

# A load given as a Lua function cannot travel: dda.load says so and keeps its last value.
write(os.path.join(d, "fn.lua"), r"""
local dda = require "dda"
local m = dda.model{ g1 = 1e-4, threads = 1 }
m:rock{ density = 2600, E = 5e9, nu = 0.25 }
local b = m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }
m:edges{ on_segment = {0, 0, 0, 1} }:pressure(function(t) return 1e5 * t end)
m:step(5)
m:save("fn.ckpt")
local again = dda.load("fn.ckpt")
again:step(2)
""")
r = run(["run", "fn.lua", "--quiet", "--out", "o"], d)
check(r.returncode == 0 and re.search(r"dda: warning: dda.load: pressure 1 was driven by a Lua function "
                                      r"\(function at fn.lua:6\).*keeps its last value", r.stderr) is not None,
      "dda.load warns of a load that was a Lua function, naming where it was", r.stderr)

# Wrong, truncated, damaged files; another model; bad options.
with open(os.path.join(d, "o", "at40.ckpt"), "rb") as f:
    good = f.read()
with open(os.path.join(d, "short.ckpt"), "wb") as f:
    f.write(good[: len(good) // 2])
damaged = bytearray(good)
damaged[len(good) // 3] ^= 0x40
with open(os.path.join(d, "damaged.ckpt"), "wb") as f:
    f.write(bytes(damaged))
for name, words in [("scene.lua", "is not a dda checkpoint"), ("short.ckpt", "is truncated"),
                    ("damaged.ckpt", "is damaged: its checksum does not match"),
                    ("missing.ckpt", "missing.ckpt': No such file or directory")]:
    r = dda("--set", "scene=bar", "--out", "bad", "--restart", name)
    check(r.returncode == 1 and ("dda: --restart: cannot read checkpoint" in r.stderr or
                                 "dda: --restart: checkpoint '%s'" % name in r.stderr) and words in r.stderr,
          "--restart %s: exit 1, \"%s\"" % (name, words), r.stderr)
r = dda("--set", "scene=blast", "--out", "bad", "--restart", os.path.join(d, "o", "at40.ckpt"))
check(r.returncode == 1 and "holds a model with 500 blocks; the script built model 1 with" in r.stderr,
      "--restart of another model: refused, saying what differs", r.stderr)
r = run(["run", "resume.lua", "--quiet", "--out", "o3", "--", os.path.join(d, "scene.lua")], d)
check(r.returncode == 1 and "resume.lua:3: dda.load: checkpoint '" in r.stderr and "is not a dda checkpoint" in r.stderr,
      "dda.load of a wrong file: an error naming the script line and the file", r.stderr)
write(os.path.join(d, "nowhere.lua"), "local m = dda.model{}\nm:save(arg[1] .. '/y.ckpt')\n")  # a file as folder
r = run(["run", "nowhere.lua", "--quiet", "--out", "o", "--", os.path.join(d, "scene.lua")], d)
check(r.returncode == 1 and "nowhere.lua:2: m:save: cannot write '%s/y.ckpt': Not a directory" % os.path.join(d, "scene.lua") in r.stderr,
      "m:save that cannot write: an error naming the file and the cause", r.stderr)
for bad in ["0", "x", "1.5", "-2s"]:
    r = dda("--checkpoint-every", bad)
    check(r.returncode == 2 and "--checkpoint-every needs N" in r.stderr, "--checkpoint-every %s: exit 2" % bad, r.stderr)
finish()
