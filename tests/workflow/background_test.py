# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Background runs as a person uses them: the console through a pty stays up
while a run goes on (m:start), refuses changes while it runs, Ctrl-C at the
prompt pauses it (no step after), changes are taken while paused, m:resume()
goes on, Ctrl-C in m:wait() pauses it again, and a run's end is said at the
prompt. The console's live view sees the run and its Pause pauses it. In a
batch run a script that ends with a run still going waits for it, and a
background run's error fails the run.
Run: background_test.py path/to/dda"""
import json
import os
import re
import time
import urllib.request

from common import SOURCE, Console, check, finish, read, run, scratch, write

d = scratch("background")
env = {"DDA_HISTORY": ""}
paths = 'package.path = "%s/scripts/bench/?.lua;%s/scripts/paper/?.lua;" .. package.path' % (SOURCE, SOURCE)

c = Console(d, env)
check(c.expect("dda> ") is not None, "prompt on a pty")
c.send(paths + "\r")
c.send('scenes = require "scenes"; m = scenes.wall(4)\r')
check(c.expect("dda> ") is not None, "the wall is built")
c.send("m:start{ steps = 100000 }\r")
c.expect("dda> ")
c.send('print("alive", 1 + 1)\r')
check(c.expect("alive\t2", timeout=10) is not None, "the console answers while the run goes on")
c.send("print(m:running())\r")
check(c.expect("true\trunning") is not None, "m:running(): true, running")
c.send("m:gravity(0, -1)\r")
check(c.expect("m:pause() it first") is not None, "a change while it runs is refused, naming the cure")
c.expect("dda> ")
c.send("\x03")
check(c.expect("background run paused") is not None, "Ctrl-C at the prompt pauses the run")
c.send("print(m:running())\r")
check(c.expect("false\tpaused") is not None, "m:running(): false, paused")
c.send("s1 = m:steps()\r")
time.sleep(1.0)
c.send('print("same", m:steps() == s1)\r')
check(c.expect("same\ttrue") is not None, "no step is taken while paused")
c.send('m:gravity(0, -9.81); print("changed")\r')
check(c.expect("changed") is not None, "a change while paused is taken")
c.send("m:resume()\r")
c.expect("dda> ")
# Ctrl-C only once m:wait() runs (a loaded machine can take over a second to
# read the line; a Ctrl-C before it reaches the prompt instead). The marker is
# printed by the same line just before the wait; its echo does not hold it.
c.send('print("wait" .. "ing"); m:wait()\r')
c.expect("waiting")
time.sleep(0.5)
c.send("\x03")
check(c.expect("the background run is paused") is not None, "Ctrl-C in m:wait() pauses the run and ends the wait")
c.send("m:stop()\r")
c.expect("dda> ")
c.send("m:start{ steps = 5 }\r")
check(c.expect("background run finished", timeout=30) is not None, "the end of a run is said at the prompt")
c.send("\x04")
status = c.wait()
check(status is not None and os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0, "Ctrl-D leaves with exit 0",
      status)

# ---- the console's live view: its Pause acts on the background run ----------------------------
c = Console(d, env, ["--live", "0"])
said = c.expect("dda> ") or ""
if "without the live view" in said:
    print("this dda was built without the live view: its checks are skipped")
    c.wait()
else:
    m = re.search(r"live view at (http://127\.0\.0\.1:\d+/)", said)
    check(m is not None, "dda console --live 0 says where it serves", said)
    c.send(paths + "\r")
    c.send('scenes = require "scenes"; m = scenes.wall(4); m:start{ steps = 100000 }\r')
    c.expect("dda> ")
    time.sleep(1.0)
    if m:
        status = json.loads(urllib.request.urlopen(m.group(1) + "status", timeout=30).read())
        check(status.get("state") == "running" and status.get("background") is True,
              "the page sees the console's background run", status)
        req = urllib.request.Request(m.group(1) + "pause", data=b"", method="POST")
        answer = json.loads(urllib.request.urlopen(req, timeout=30).read())
        c.send("print(m:running())\r")
        check(answer.get("state") == "paused" and c.expect("false\tpaused") is not None,
              "the page's Pause pauses it as m:pause() does", answer)
    c.send("\x04")
    c.wait()

# ---- batch: the script ends with its run still going ------------------------------------------
write(os.path.join(d, "left_going.lua"), paths + """
local scenes = require "scenes"
local m = scenes.wall(4)
m:monitor{ name = "top", at = {2.25, 3.9}, fields = {"uy"} }
m:start{ steps = 40 }
""")
r = run(["run", "left_going.lua", "--quiet", "--out", "going"], d)
rows = read(os.path.join(d, "going", "top.csv")).splitlines() if r.returncode == 0 else []
check(r.returncode == 0 and len(rows) == 42, "the batch run waits for a run the script left going (41 rows)",
      (r.returncode, r.stderr, len(rows)))

write(os.path.join(d, "fails.lua"), paths + """
local scenes = require "scenes"
local m = scenes.wall(4)
m:edges{ on_segment = {-1, 0, -1, -1} }:pressure(function(t) if t > 0.005 then error("boom") end return 0 end)
m:start{ steps = 40 }
""")
r = run(["run", "fails.lua", "--quiet", "--out", "fails"], d)
check(r.returncode == 1 and "background run failed" in r.stderr and "boom" in r.stderr,
      "a background run's error fails the batch run", (r.returncode, r.stderr))
finish()
