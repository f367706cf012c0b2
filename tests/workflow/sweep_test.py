# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""dda sweep: a grid of 2 x 3 combinations run as separate processes, two at
a time; one fails on purpose. The summary table must hold one row per
combination with its status and what the run returned; --task runs one
combination (as a Slurm job array does) and --collect rebuilds the same table.
Run: sweep_test.py path/to/dda"""
import csv
import os
import shutil
import subprocess

from common import DDA, check, finish, read, run, scratch, write

SCRIPT = r"""
local dda = require "dda"
local a = dda.param("a", 1)
local b = dda.param("b", "x")
local offset = dda.param("offset", 0)
if a == 2 and b == "z" then error("this combination fails on purpose") end
local m = dda.model{ gravity = {0, -10}, g1 = 0.01 }
m:rock{ density = 1000, E = 1e9, nu = 0.2 }
m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }
local mon = m:monitor{ at = {0.5, 0.5}, fields = {"uy"} }
m:step(10 * a)
dda.result{ label = b .. "," .. a }            -- a comma: the CSV must quote it
return { drop = -mon:last("uy"), t = m:time(), steps = m:steps(), sum = a + offset }
"""

d = scratch("sweep")
write(os.path.join(d, "study.lua"), SCRIPT)
args = ["sweep", "study.lua", "--grid", "a=1,2", "--grid", "b=x,y,z", "--set", "offset=100", "--out", "runs"]
r = run(args + ["--jobs", "2"], d)
check(r.returncode == 1, "a failed run makes the sweep's exit status 1", (r.returncode, r.stdout, r.stderr))
summary = os.path.join(d, "runs", "summary.csv")
rows = list(csv.DictReader(open(summary))) if os.path.exists(summary) else []
check(len(rows) == 6, "one row per combination (6)", rows)
by = {(row["a"], row["b"]): row for row in rows}
check(by[("2", "z")]["status"] == "error" and by[("2", "z")]["exit_code"] == "1" and by[("2", "z")]["drop"] == "",
      "the failed run has a row with its status, no results", by.get(("2", "z")))
ok = [row for row in rows if row["status"] == "ok"]
check(len(ok) == 5, "the other 5 runs are ok", rows)
for row in ok:
    a = int(row["a"])
    t = float(row["t"])
    check(t > 0 and abs(float(row["drop"]) - 0.5 * 10 * t * t) < 1e-9 * t * t and row["steps"] == str(10 * a) and
          row["sum"] == str(a + 100) and row["label"] == "%s,%d" % (row["b"], a),
          "run a=%s b=%s: its returned drop 1/2 g t^2, steps, --set and dda.result values" % (row["a"], row["b"]),
          row)
check(list(rows[0].keys())[:6] == ["task", "status", "exit_code", "wall_s", "a", "b"], "columns", rows[0].keys())
check([(row["a"], row["b"]) for row in rows] == [(a, b) for a in "12" for b in "xyz"],
      "rows in task order, the last grid fastest")
for task in range(6):
    folder = os.path.join(d, "runs", "run_%03d" % task)
    log = read(os.path.join(folder, "run.log")) if os.path.exists(os.path.join(folder, "run.log")) else ""
    check(os.path.exists(os.path.join(folder, "output.txt")) and "==== dda run" in log and "end: exit status" in log,
          "run_%03d has its own output.txt and run.log" % task)
check("this combination fails on purpose" in read(os.path.join(d, "runs", "run_005", "output.txt")),
      "the failed run's message is in its output.txt")

# The Slurm way: each task on its own, then --collect.
for task in range(6):
    r = run(args + ["--task", str(task), "--out", "array"], d)
    check(r.returncode == (1 if task == 5 else 0), "--task %d exit status" % task, (r.returncode, r.stderr))
check(not os.path.exists(os.path.join(d, "array", "summary.csv")), "--task writes no summary (no races)")
r = run(args + ["--collect", "--out", "array"], d)
rows2 = list(csv.DictReader(open(os.path.join(d, "array", "summary.csv"))))
strip = lambda rs: [{k: v for k, v in row.items() if k != "wall_s"} for row in rs]
check(strip(rows2) == strip(rows), "--collect after --task runs gives the same table", (rows2, rows))

# A task that never ran is a row too.
os.remove(os.path.join(d, "array", "run_003", "status.txt"))
shutil.rmtree(os.path.join(d, "array", "run_004"))
run(args + ["--collect", "--out", "array"], d)
rows3 = list(csv.DictReader(open(os.path.join(d, "array", "summary.csv"))))
check(rows3[3]["status"] == "unfinished" and rows3[4]["status"] == "not run", "unfinished and missing runs have rows",
      rows3)

# Bad command lines.
r = run(["sweep", "study.lua", "--grid", "a=1,2", "--task", "7"], d)
check(r.returncode == 2 and "past the last combination" in r.stderr, "--task past the grid", r.stderr)
r = run(["sweep", "study.lua", "--grid", "a=1,2", "--set", "a=3"], d)
check(r.returncode == 2 and "both give 'a'" in r.stderr, "--set and --grid of the same name", r.stderr)
r = run(["sweep", "study.lua"], d)
check(r.returncode == 2 and "--grid" in r.stderr, "no grid", r.stderr)
r = run(["sweep", "study.lua", "--grid", "a=1,2", "--list"], d)
check(r.returncode == 0 and r.stdout.splitlines()[1].startswith("1 ") and "a=2" in r.stdout, "--list", r.stdout)
check(len(r.stderr.splitlines()) <= 2, "a command-line error prints one line of usage, not the help", r.stderr)
r = run(["sweep", "--help"], d)
check(r.returncode == 0 and "--grid" in r.stdout and "--jobs" in r.stdout, "dda sweep --help", r.stdout)

# A grid name the script never reads is refused before anything runs, with
# the names it does read (here the script reads a, b, offset).
r = run(["sweep", "study.lua", "--grid", "a=1,2", "--grid", "bb=x,y", "--out", "typo"], d)
check(r.returncode == 2 and "never reads a parameter 'bb'" in r.stderr and "did you mean 'b'" in r.stderr and
      "a, b, offset" in r.stderr, "a misspelt grid name is refused, naming the script's parameters", r.stderr)
check(not os.path.exists(os.path.join(d, "typo")), "... and nothing ran", os.listdir(d))
# A name read only after the first step (in a branch or at the end) is a
# string in the script: accepted.
write(os.path.join(d, "late.lua"), SCRIPT.replace("return {", "if dda.param('late', false) then a = a + 1 end\nreturn {"))
r = run(["sweep", "late.lua", "--grid", "late=true,false", "--out", "late"], d)
check(r.returncode == 0, "a name read after the first step is not refused", (r.stdout, r.stderr))
r = run(["run", "study.lua", "--list-params", "--set", "a=2"], d)
listed = [line.split("\t") for line in r.stdout.splitlines() if not line.startswith("#")]
check(r.returncode == 0 and listed == [["a", "1", "2"], ["b", "x", ""], ["offset", "0", ""]],
      "dda run --list-params: name, default, value given", (r.stdout, r.stderr))

# A result named like a grid parameter gets its own column NAME_result.
write(os.path.join(d, "clash.lua"), "local a = dda.param('a', 1)\nreturn { a = 10 * a, status = 'mine' }\n")
r = run(["sweep", "clash.lua", "--grid", "a=1,2", "--out", "clash"], d)
rows = list(csv.DictReader(open(os.path.join(d, "clash", "summary.csv"))))
check(r.returncode == 0 and [(row["a"], row["a_result"], row["status"], row["status_result"]) for row in rows] ==
      [("1", "10", "ok", "mine"), ("2", "20", "ok", "mine")] and "its column is 'a_result'" in r.stdout,
      "results named like a column are renamed NAME_result", (r.stdout, rows))

# The CPUs the process may use: its affinity, and SLURM_CPUS_PER_TASK when smaller.
cpus = len(os.sched_getaffinity(0))
r = run(["sweep", "clash.lua", "--grid", "a=1,2", "--jobs", "2", "--out", "jobs"], d)
log = read(os.path.join(d, "jobs", "run_000", "run.log"))
check("threads: %d (--threads); %d CPUs usable" % (max(1, cpus // 2), cpus) in log,
      "--jobs 2 gives each run half the usable CPUs", log)
r = run(["run", "clash.lua", "--out", "slurm"], d, env={"SLURM_CPUS_PER_TASK": "1"})
check("; 1 CPUs usable" in read(os.path.join(d, "slurm", "run.log")), "SLURM_CPUS_PER_TASK=1: one CPU usable",
      read(os.path.join(d, "slurm", "run.log")))
if shutil.which("taskset"):
    r = subprocess.run(["taskset", "-c", "0", DDA, "run", "clash.lua", "--out", "pinned"], cwd=d, capture_output=True)
    check("; 1 CPUs usable" in read(os.path.join(d, "pinned", "run.log")), "taskset -c 0: one CPU usable",
          read(os.path.join(d, "pinned", "run.log")))
finish()
