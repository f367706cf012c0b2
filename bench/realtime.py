#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Which scenes run faster than real time on this machine: each scene runs
as a user runs it (dda run, its own defaults, or the settings given here to
keep it short), and its run log's "run:" lines (one per stepping call) give
the simulated time and the wall-clock time its steps took. Prints, per scene,
the blocks, the simulated seconds, the wall seconds and their ratio: above 1,
the scene runs faster than real time (realtime = 1 can pace it); below, the
fraction of real time it reaches (--realtime 1 then says it cannot keep up).

  bench/realtime.py build/dda [--threads N] [scene ...]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
# scene: (script, dda run arguments)
SCENES = {
    "free_fall": ("scripts/free_fall.lua", []),
    "incline": ("scripts/incline.lua", []),
    "integrator_contacts": ("scripts/integrator_contacts.lua", []),
    "jointed_slope": ("scripts/jointed_slope.lua", []),
    "earthquake_slope": ("scripts/earthquake_slope.lua", []),
    "rock_bar": ("scripts/rock_bar.lua", ["--set", "movie="]),
    "blast": ("scripts/paper/blast.lua", []),
}
RUN = re.compile(r"run: t = (\S+) -> (\S+) s, (\d+) steps in (\S+) s of wall clock")
BLOCKS = re.compile(r"model: (\d+) blocks")


def measure(dda, script, args, threads):
    with tempfile.TemporaryDirectory(prefix="dda-realtime-") as out:
        cmd = [dda, "run", os.path.join(SOURCE, script), "--out", out, "--quiet"] + args
        if threads is not None:
            cmd += ["--threads", str(threads)]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            return None, "exit %d: %s" % (r.returncode, r.stderr.strip().splitlines()[-1:] or "")
        log = open(os.path.join(out, "run.log")).read()
    sim = wall = 0.0
    steps = 0
    for t0, t1, n, w in RUN.findall(log):
        sim += float(t1) - float(t0)
        wall += float(w)
        steps += int(n)
    blocks = max([int(b) for b in BLOCKS.findall(log)] or [0])
    return (blocks, steps, sim, wall), None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dda")
    ap.add_argument("--threads", type=int)
    ap.add_argument("scenes", nargs="*", default=list(SCENES))
    a = ap.parse_args()
    print("%-20s %7s %7s %12s %10s %14s" % ("scene", "blocks", "steps", "simulated s", "wall s", "x real time"))
    for name in a.scenes:
        script, args = SCENES[name]
        got, why = measure(a.dda, script, args, a.threads)
        if not got:
            print("%-20s %s" % (name, why))
            continue
        blocks, steps, sim, wall = got
        ratio = sim / wall if wall > 0 else float("inf")
        print("%-20s %7d %7d %12.4g %10.3g %14.3g" % (name, blocks, steps, sim, wall, ratio), flush=True)


if __name__ == "__main__":
    sys.exit(main())
