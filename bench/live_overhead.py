#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""What watching a run costs it: the same `dda run` side by side, A B A B,
plain (A) and with --live served to a client that asks what the page asks
at its fastest (B): the status events, and a 960x540 frame as soon as the
last one arrived, at most FPS a second. Prints each run's wall-clock
and CPU seconds (user + system: on a machine whose cores are all busy, the
CPU the live view takes is what it takes from the run), the frames the
client got, and the medians of the pairs' ratios B / A (1.05 would be a run
5 % slower).

  bench/live_overhead.py build/dda scripts/rock_bar.lua [--pairs 5] [--fps 10] [--field sigma_xx] [-- --set t_end=6e-3]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request


def client(url, fps, field, stop, counts):
    def events():
        try:
            with urllib.request.urlopen(url + "events", timeout=600) as r:
                while not stop.is_set() and r.readline():
                    counts["events"] += 1
        except Exception:
            pass

    threading.Thread(target=events, daemon=True).start()
    while not stop.is_set():
        began = time.monotonic()
        try:
            with urllib.request.urlopen(url + "frame.png?field=%s&w=960&h=540" % field, timeout=60) as r:
                r.read()
                counts["frames"] += 1
        except Exception:
            pass
        time.sleep(max(0.0, 1.0 / fps - (time.monotonic() - began)))


def one_run(dda, script, out, live, fps, field, extra):
    cmd = [dda, "run", script, "--out", out, "--quiet"] + (["--live", "0"] if live else []) + extra
    counts = {"frames": 0, "events": 0}
    stop = threading.Event()
    began = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if live:
        m = re.search(r"live view at (\S+)", p.stderr.readline())
        if not m:
            sys.exit("dda did not say where it serves the live view")
        threading.Thread(target=client, args=(m.group(1), fps, field, stop, counts), daemon=True).start()
    p.stderr.read()
    _, status, usage = os.wait4(p.pid, 0)
    wall = time.monotonic() - began
    stop.set()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit("%s failed with exit status %d" % (" ".join(cmd), os.waitstatus_to_exitcode(status)))
    return wall, usage.ru_utime + usage.ru_stime, counts


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dda")
    ap.add_argument("script")
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--fps", type=float, default=10)
    ap.add_argument("--field", default="sigma_xx")
    argv = sys.argv[1:]
    cut = argv.index("--") if "--" in argv else len(argv)
    a = ap.parse_args(argv[:cut])
    a.extra = argv[cut + 1:]  # more dda run arguments, after --
    ratios = []
    with tempfile.TemporaryDirectory(prefix="dda-live-overhead-") as out:
        one_run(a.dda, a.script, out, False, a.fps, a.field, a.extra)  # warm-up: caches, files
        print("%4s %9s %9s %7s   %9s %9s %7s %7s" %
              ("pair", "wall A", "wall B", "B/A", "cpu A", "cpu B", "B/A", "frames"))
        cpu_ratios = []
        for i in range(a.pairs):
            wall_a, cpu_a, _ = one_run(a.dda, a.script, out, False, a.fps, a.field, a.extra)
            wall_b, cpu_b, counts = one_run(a.dda, a.script, out, True, a.fps, a.field, a.extra)
            ratios.append(wall_b / wall_a)
            cpu_ratios.append(cpu_b / cpu_a)
            print("%4d %8.2fs %8.2fs %7.3f   %8.2fs %8.2fs %7.3f %7d" %
                  (i + 1, wall_a, wall_b, wall_b / wall_a, cpu_a, cpu_b, cpu_b / cpu_a, counts["frames"]), flush=True)
    print("median B/A: wall %.3f (%.3f .. %.3f), cpu %.3f (%.3f .. %.3f)" %
          (statistics.median(ratios), min(ratios), max(ratios), statistics.median(cpu_ratios), min(cpu_ratios),
           max(cpu_ratios)))


if __name__ == "__main__":
    main()
