# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Outputs that cannot be redirected, clobber something else or be lost
(docs/robustness.md), each fault reproduced first: a symbolic link placed at
out/result.csv.part made dda write through it (overwriting the link's
target) and left result.csv a link to it; the rename replaced any target,
a device or a pipe included; .part files of killed runs stayed; a run
whose output folder could not take the results computed everything, then
lost the results; a monitor CSV on a full disk was left empty (0 bytes).
Run: safe_writes_test.py path/to/dda"""
import os
import stat
import subprocess
import time

from common import DDA, file_size_limit, check, finish, read, run, scratch, write

d = scratch("safe-writes")
write(os.path.join(d, "result.lua"), 'dda.result{ a = 1, b = "two" }\n')
MODEL = """
local m = dda.model{ g1 = 1e-4, gravity = {0, -9.81} }
local rock = m:rock{ density = 2000, E = 1e9, nu = 0.25 }
m:domain{ box = {0, 0, 1, 0.5}, rock = rock }
m:joint_set{ dip = 90, spacing = 0.5 }
m:generate()
"""

# ---- a symbolic link at PATH.part is removed, not written through -----------------------------
os.makedirs(os.path.join(d, "link"))
victim = os.path.join(d, "victim.txt")
write(victim, "not yours\n")
os.symlink(victim, os.path.join(d, "link", "result.csv.part"))
r = run(["run", "result.lua", "--out", "link", "--quiet"], d)
result = os.path.join(d, "link", "result.csv")
check(r.returncode == 0 and read(victim) == "not yours\n", "a link at result.csv.part: its target untouched",
      (r.returncode, r.stderr, read(victim)))
check(not os.path.islink(result) and read(result) == "a,b\n1,two\n" and not os.path.lexists(result + ".part"),
      "result.csv a regular file with the results, the link gone", os.listdir(os.path.join(d, "link")))

# ---- a target that is not a regular file is refused ----------------------------------------------
os.makedirs(os.path.join(d, "kinds"))
os.mkfifo(os.path.join(d, "kinds", "pipe.ckpt"))
os.makedirs(os.path.join(d, "kinds", "folder.ckpt"))
write(os.path.join(d, "save.lua"), MODEL + "m:save(arg[1])\n")
for name, words in [("pipe.ckpt", "it is a pipe (FIFO), not a regular file"), ("folder.ckpt", "it is a folder")]:
    r = run(["run", "save.lua", "--out", "kinds", "--quiet", "--", name], d)
    target = os.path.join(d, "kinds", name)
    check(r.returncode == 1 and ("cannot write 'kinds/%s': %s" % (name, words)) in r.stderr and "save.lua:7:" in r.stderr,
          "m:save onto %s: refused, naming the file, the cause and the line" % name, r.stderr)
    kept = stat.S_ISFIFO(os.lstat(target).st_mode) if name == "pipe.ckpt" else os.path.isdir(target)
    check(kept and not os.path.lexists(target + ".part"), "%s is still what it was, no .part left" % name)
r = run(["run", "save.lua", "--out", "kinds", "--quiet", "--", "/dev/null"], d)
check(r.returncode == 1 and "cannot write '/dev/null': it is a device, not a regular file" in r.stderr and
      stat.S_ISCHR(os.stat("/dev/null").st_mode), "m:save('/dev/null'): refused, the device left as it is", r.stderr)

# ---- stray .part files of a killed run are removed by the next run ---------------------------------
os.makedirs(os.path.join(d, "stray", "frames"))
old = time.time() - 3600
for f in ("plot.png.part", os.path.join("frames", "frame_00010.png.part")):
    write(os.path.join(d, "stray", f), "half a file")
    os.utime(os.path.join(d, "stray", f), (old, old))
write(os.path.join(d, "stray", "notes.part.txt"), "not ours")
r = run(["run", "result.lua", "--out", "stray", "--quiet"], d)
left = [f for root, _, files in os.walk(os.path.join(d, "stray")) for f in files if f.endswith(".part")]
check(r.returncode == 0 and not left and os.path.exists(os.path.join(d, "stray", "notes.part.txt")),
      "the .part files a killed run left are removed (and nothing else)", (left, r.stderr))
check("removed 2 unfinished file(s) an earlier run left" in read(os.path.join(d, "stray", "run.log")),
      "the run log names what was removed")

# ---- the output folder is checked before the run --------------------------------------------------
write(os.path.join(d, "a_file"), "x")
r = run(["run", "result.lua", "--out", "a_file/out", "--quiet"], d)
check(r.returncode == 1 and "the output folder 'a_file/out' cannot be used: cannot create it" in r.stderr and
      "give another with --out" in r.stderr, "an output folder that cannot be made: refused before the run",
      r.stderr)
r = run(["run", "result.lua", "--out", "/proc/self/fd", "--quiet"], d)
check(r.returncode == 1 and "cannot write in it" in r.stderr, "an output folder that cannot be written: refused",
      r.stderr)

# ---- results that cannot be written at the end go to stderr ------------------------------------------
write(os.path.join(d, "late.lua"), 'os.execute("mkdir -p " .. dda.out_dir() .. "/result.csv")\n'
      'dda.result{ ppv = 0.25, note = "kept" }\n')
r = run(["run", "late.lua", "--out", "late", "--quiet"], d)
check(r.returncode == 1 and "cannot write 'late/result.csv': it is a folder" in r.stderr and
      "the results are:\nnote,ppv\nkept,0.25\n" in r.stderr, "results that cannot be written are printed on stderr",
      r.stderr)


# ---- a monitor CSV whose header cannot be written is not left empty -----------------------------------
write(os.path.join(d, "mon.lua"), MODEL + 'm:monitor{ at = {0.25, 0.25}, name = "mon", fields = {"uy"} }\nm:run{ steps = 3 }\n')
os.makedirs(os.path.join(d, "full"))
p = subprocess.run([DDA, "run", "mon.lua", "--out", "full", "--quiet"], cwd=d, capture_output=True, text=True,
                   preexec_fn=file_size_limit(0), timeout=300)
check(p.returncode == 1 and "cannot write 'full/mon.csv': File too large" in p.stderr and
      not os.path.exists(os.path.join(d, "full", "mon.csv")), "a full disk at the CSV's header: no empty CSV left",
      (p.returncode, p.stderr, os.listdir(os.path.join(d, "full"))))

# ---- little space left: a warning before the run (root only: a small tmpfs) ----------------------------
if os.geteuid() == 0:
    mnt = os.path.join(d, "small")
    os.makedirs(mnt)
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=8m", "tmpfs", mnt]).returncode == 0:
        try:
            r = run(["run", "result.lua", "--out", "small", "--quiet"], d)
            check(r.returncode == 0 and "warning: the output folder 'small' has only" in r.stderr and
                  "outputs may not fit" in r.stderr, "an output folder with 8 MB free: a warning first", r.stderr)
        finally:
            subprocess.run(["umount", mnt])

finish()
