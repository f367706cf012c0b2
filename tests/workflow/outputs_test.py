# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Outputs that cannot be lost quietly. Each fault
was reproduced first: before, a full disk truncated the monitor CSV, left a
torn last row and the run exited 0; os.exit() with frames still queued lost
frames, crashed (SIGSEGV, the font cache destroyed under the frame-writer
thread) or hung.

A full disk three ways: a CSV that is /dev/full (nothing can be written);
a file-size limit (RLIMIT_FSIZE, SIGXFSZ ignored: write(2) writes what fits,
then fails with EFBIG, as a disk filling in the middle of a row); and, when
run as root, a 64 KiB tmpfs that fills during the run.
Run: outputs_test.py path/to/dda"""
import os
import shutil
import signal
import subprocess

from common import DDA, file_size_limit, SOURCE, check, finish, read, run, scratch, write

MODEL = """
local m = dda.model{ plane = 'stress', g1 = 1e-4, gravity = {0, -9.81} }
local rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }
local joint = m:joint{ friction = 30 }
m:domain{ box = {0, 0, 1, 0.5}, rock = rock }
m:joint_set{ dip = 90, spacing = 0.5, joint = joint }
m:generate()
"""
MONITOR = MODEL + """
m:monitor{ at = {0.25, 0.25}, name = "mon", fields = {"uy", "vy", "sxx"} }
m:run{ steps = STEPS }
print("done")
"""
d = scratch("outputs")
write(os.path.join(d, "mon.lua"), MONITOR.replace("STEPS", "20"))
write(os.path.join(d, "long.lua"), MONITOR.replace("STEPS", "2000"))


def complete_rows(text, fields):
    """Every line ends with a newline and has the header's number of fields."""
    lines = text.split("\n")
    return lines[-1] == "" and all(len(l.split(",")) == fields for l in lines[:-1])


# ---- the monitor CSV is /dev/full ----------------------------------------------------------
os.makedirs(os.path.join(d, "full"))
os.symlink("/dev/full", os.path.join(d, "full", "mon.csv"))
r = run(["run", "mon.lua", "--out", "full", "--quiet"], d)
check(r.returncode == 1, "CSV on /dev/full: exit status 1 (was 0)", r.returncode)
check("cannot write 'full/mon.csv': No space left on device" in r.stderr and "mon.lua:" in r.stderr,
      "the error names the file, the cause and the script line", r.stderr)
check("done" not in r.stdout, "the script stopped at the failing write", r.stdout)

# ---- the disk fills in the middle of the run (a file-size limit) -------------------------
p = subprocess.run([DDA, "run", "long.lua", "--out", "lim", "--quiet"], cwd=d, capture_output=True, text=True,
                   preexec_fn=file_size_limit(20000), timeout=300)
csv = read(os.path.join(d, "lim", "mon.csv"))
check(p.returncode == 1, "file-size limit reached mid-run: exit status 1", (p.returncode, p.stderr))
check("monitor 'mon': cannot write 'lim/mon.csv': File too large" in p.stderr and "long.lua:" in p.stderr,
      "the error names the monitor, the file, the cause and the line", p.stderr)
check(complete_rows(csv, 5) and csv.count("\n") > 100, "every row before the failure is complete (no torn row)",
      csv[-200:])

# ---- a small tmpfs that fills (root only: mount) ------------------------------------------
if os.geteuid() == 0:
    mnt = os.path.join(d, "tmpfs")
    os.makedirs(mnt)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", mnt]).returncode == 0:
        try:
            r = run(["run", "long.lua", "--out", "tmpfs", "--quiet"], d)
            csv = read(os.path.join(mnt, "mon.csv"))
            check(r.returncode == 1 and "No space left on device" in r.stderr, "tmpfs full: exit 1, ENOSPC named",
                  (r.returncode, r.stderr))
            check(complete_rows(csv, 5), "tmpfs full: every row written is complete", csv[-200:])
        finally:
            subprocess.run(["umount", mnt])

# ---- the script's printed output on a full disk ------------------------------------------
with open("/dev/full", "w") as full:
    p = subprocess.run([DDA, "run", "mon.lua", "--out", "o", "--quiet"], cwd=d, stdout=full, stderr=subprocess.PIPE,
                       text=True, timeout=300)
check(p.returncode == 1 and "cannot write the standard output" in p.stderr, "stdout on /dev/full: exit 1",
      (p.returncode, p.stderr))

# ---- the run log cannot be written ---------------------------------------------------------
os.makedirs(os.path.join(d, "log"))
os.symlink("/dev/full", os.path.join(d, "log", "run.log"))
r = run(["run", "mon.lua", "--out", "log", "--quiet"], d)
check(r.returncode == 1 and "run log: cannot write 'log/run.log'" in r.stderr, "run log on /dev/full: exit 1",
      (r.returncode, r.stderr))
check(complete_rows(read(os.path.join(d, "log", "mon.csv")), 5), "the run went on: its CSV is complete")

# ---- frames and plots: a PNG that cannot be written (a file-size limit) --------------------
write(os.path.join(d, "plot.lua"), 'dda.plot{ series = {{ name = "a", x = {0, 1}, y = {0, 1} }}, file = "p.png" }\n')
p = subprocess.run([DDA, "run", "plot.lua", "--out", "pfull", "--quiet"], cwd=d, capture_output=True, text=True,
                   preexec_fn=file_size_limit(4096), timeout=300)
check(p.returncode == 1 and "cannot write 'pfull/p.png': File too large" in p.stderr and
      not os.path.exists(os.path.join(d, "pfull", "p.png")) and not os.path.exists(os.path.join(d, "pfull", "p.png.part")),
      "plot PNG on a full disk: exit 1, the file named, no half PNG", (p.returncode, p.stderr))

# ---- VTU files on a full disk (a file-size limit the run log fits under, a VTU file does not) ----
write(os.path.join(d, "vtu.lua"), MODEL + "m:run{ steps = 10 }\n")
p = subprocess.run([DDA, "run", "vtu.lua", "--out", "vfull", "--quiet", "--vtu", "5"], cwd=d, capture_output=True,
                   text=True, preexec_fn=file_size_limit(2000), timeout=300)
check(p.returncode == 1 and "cannot write 'vfull/vtu/" in p.stderr and "File too large" in p.stderr,
      "VTU on a full disk: exit 1, the file named", (p.returncode, p.stderr))

# ---- sweep records and tables that cannot be written ------------------------------------------------
write(os.path.join(d, "sw.lua"), 'local a = dda.param("a", 1)\ndda.result{ a = a }\n')
# (a folder that is not empty: the sweep removes an old record before the run)
os.makedirs(os.path.join(d, "swo", "run_001", "status.txt", "x"))
r = run(["sweep", "sw.lua", "--grid", "a=1,2", "--out", "swo"], d)
check(r.returncode == 1 and "cannot write 'swo/run_001/status.txt': it is a folder" in r.stderr,
      "a sweep whose run record cannot be written: exit 1, the file named (was: 0)", (r.returncode, r.stderr))
shutil.rmtree(os.path.join(d, "swo", "run_001", "status.txt"))
os.remove(os.path.join(d, "swo", "summary.csv"))
os.makedirs(os.path.join(d, "swo", "summary.csv", "x"))
r = run(["sweep", "sw.lua", "--grid", "a=1,2", "--out", "swo"], d)
check(r.returncode == 1 and "cannot write 'swo/summary.csv': it is a folder" in r.stderr,
      "a sweep table that cannot be written: exit 1, the file named", (r.returncode, r.stderr))

# ---- a paper script's own CSV (io.open) on a full disk ---------------------------------------
os.makedirs(os.path.join(d, "bg"))
os.symlink("/dev/full", os.path.join(d, "bg", "blast_geometry.csv"))
r = run(["run", os.path.join(SOURCE, "scripts", "paper", "blast_geometry.lua"), "--out", "bg", "--quiet", "--set",
         "check_step=false"], d)
check(r.returncode == 1 and "blast_geometry.lua:" in r.stderr and
      "cannot write bg/blast_geometry.csv: No space left on device" in r.stderr,
      "blast_geometry.lua's CSV on a full disk: exit 1 naming the file (was: 0)", (r.returncode, r.stderr))

# ---- killed in the middle: every row complete ---------------------------------------------
import time
for sig in (signal.SIGTERM, signal.SIGKILL):
    out = "kill%d" % sig
    p = subprocess.Popen([DDA, "run", "long.lua", "--out", out, "--quiet"], cwd=d, stdout=subprocess.DEVNULL,
                         stderr=subprocess.DEVNULL)
    csv_path = os.path.join(d, out, "mon.csv")
    end = time.time() + 30
    while time.time() < end and (not os.path.exists(csv_path) or os.path.getsize(csv_path) < 2000):
        time.sleep(0.05)
    p.send_signal(sig)
    p.wait(timeout=60)
    csv = read(csv_path)
    check(complete_rows(csv, 5) and csv.count("\n") > 10, "killed by signal %d mid-run: every row complete" % sig,
          csv[-200:])

# ---- os.exit() with frames still queued, many times ----------------------------------------
EXIT = MODEL + "m:run{ steps = 12 }\nos.exit(CODE)\n"
write(os.path.join(d, "exit.lua"), EXIT.replace("CODE", "true"))
write(os.path.join(d, "exit3.lua"), EXIT.replace("CODE", "3"))
bad = []
for i in range(30):
    out = "x%d" % i
    try:
        r = run(["run", "exit.lua", "--out", out, "--quiet", "--frames", "1", "--frame-size", "320x180"], d, timeout=60)
    except subprocess.TimeoutExpired:
        bad.append((i, "hung"))
        continue
    pngs = [n for n in os.listdir(os.path.join(d, out, "frames")) if n.endswith(".png")]
    if r.returncode != 0 or len(pngs) != 13:
        bad.append((i, r.returncode, len(pngs), r.stderr[-300:]))
check(not bad, "os.exit(true) with frames queued, 30 runs: exit 0, all 13 frames, no crash or hang", bad)
r = run(["run", "exit3.lua", "--out", "x3", "--quiet", "--frames", "1", "--frame-size", "320x180"], d, timeout=60)
check(r.returncode == 3, "os.exit(3): exit status 3", r.returncode)
check("end: exit status 3" in read(os.path.join(d, "x3", "run.log")), "the run log records how os.exit ended it")

finish()
