# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""A run's traces: plain progress lines when the output is not a terminal
(as under CI or nohup), and the run log beside the outputs.
Run: runs_test.py path/to/dda"""
import os
import re

from common import check, finish, read, run, scratch, write

d = scratch("runs")
write(os.path.join(d, "fall.lua"), r"""
local dda = require "dda"
local m = dda.model{ gravity = {0, -9.81}, g1 = 1e-3, threads = 1 }
m:rock{ density = 1000, E = 1e9, nu = 0.2 }
m:add_block{ {0, 0}, {1, 0}, {1, 1}, {0, 1} }
m:run{ time = 0.2 }
print("done", m:steps())
""")
# DDA_PROGRESS_SECONDS=0: a line at each 5 % (the default is one every 10 s and one per 5 %, at most one a second).
r = run(["run", "fall.lua", "--out", "out", "--set", "unused=1"], d, env={"DDA_PROGRESS_SECONDS": "0"})
check(r.returncode == 0, "the run", r.stderr)
lines = [l for l in r.stderr.splitlines() if l.startswith("progress: ")]
check(len(lines) == 20, "20 progress lines, one per 5 %", r.stderr)
check(bool(lines) and re.match(r"progress: t = 0\.01 s / 0\.2 s \(5 %\) \| step 10 \| \d+ steps/s", lines[0]),
      "a line says t, the end, %, step, rate", lines[:1])
check("\r" not in r.stderr and "\033" not in r.stderr, "no terminal control characters in a file")
check(lines and "(100 %)" in lines[-1], "the last line at 100 %", lines[-1:])
r2 = run(["run", "fall.lua", "--out", "out", "--quiet"], d)
check("progress" not in r2.stderr, "--quiet: no progress lines", r2.stderr)

log = read(os.path.join(d, "out", "run.log"))
first = log.split("==== dda run")[1]
check(re.search(r"dda run fall.lua --out out --set unused=1", first) is not None, "the log has the command line", log)
check(re.search(r"version \S+, commit \S+, Lua 5\.4", first) is not None, "version and commit", first)
check("threads:" in first and "parameters (--set): unused=1" in first, "threads and parameters", first)
check(re.search(r"model: 1 blocks; controls: .*g1=0\.001.* threads=1", first) is not None, "the model's controls",
      first)
check("warning: --set unused=1 was never read" in first, "warnings go to the log", first)
check(re.search(r"end: exit status 0 \(ok\) after [\d.]+ s", first) is not None, "end and exit status", first)
check(re.match(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d  ==== dda run", log) is not None, "lines are time-stamped", log[:40])
check(log.count("==== dda run") == 2, "a second run appends its own block", log)

write(os.path.join(d, "bad.lua"), "local dda = require 'dda'\nlocal m = dda.model{}\nm:stpe(1)\n")
r = run(["run", "bad.lua", "--out", "out"], d)
log = read(os.path.join(d, "out", "run.log")).split("==== dda run")[-1]
check(r.returncode == 1 and "error: bad.lua:3:" in log and "end: exit status 1 (error)" in log,
      "a failing script: its error and exit status in the log", log)

# Results: a plain returned table is written; an object or a module returned is not; dda.result is strict.
write(os.path.join(d, "obj.lua"), "local t = setmetatable({a = 1}, {})\nreturn t\n")
r = run(["run", "obj.lua", "--out", "obj", "--quiet"], d)
check(r.returncode == 0 and not os.path.exists(os.path.join(d, "obj", "result.csv")),
      "a returned object (with a metatable) leaves no results and no error", r.stderr)
write(os.path.join(d, "nested.lua"), "return {a = 1, rows = {1, 2}}\n")
r = run(["run", "nested.lua", "--out", "nested", "--quiet"], d)
check(r.returncode == 0 and not os.path.exists(os.path.join(d, "nested", "result.csv")),
      "a returned table of non-scalars leaves no results", r.stderr)
write(os.path.join(d, "strict.lua"), "dda.result{a = 1, rows = {1, 2}}\n")
r = run(["run", "strict.lua", "--out", "strict", "--quiet"], d)
check(r.returncode == 1 and "strict.lua:1: dda.result: argument 1: result 'rows' must be a number" in r.stderr,
      "dda.result{} with a table value is an error naming the line", r.stderr)
write(os.path.join(d, "plain.lua"), "dda.result{b = 'x,y'}\nreturn {a = 1.5, ok = true}\n")
r = run(["run", "plain.lua", "--out", "plain", "--quiet"], d)
got = read(os.path.join(d, "plain", "result.csv")) if r.returncode == 0 else r.stderr
check(got == 'a,b,ok\n1.5,"x,y",true\n', "result.csv: sorted names, one row, quoted when needed", got)
finish()
