# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Frames from the command line: --frames FROM:TO:EVERY takes a window of
steps, and --movie makes a movie when ffmpeg is on the PATH; without ffmpeg
the run still succeeds and says why there is no movie.
Run: frames_test.py path/to/dda"""
import os
import shutil

from common import SOURCE, check, finish, run, scratch

d = scratch("frames")
script = os.path.join(SOURCE, "scripts", "free_fall.lua")
common = ["--quiet", "--set", "t_end=0.5", "--frame-field", "velocity", "--frame-size", "320x240"]

r = run(["run", script, "--out", "window", "--frames", "10:30:5"] + common, d)
files = sorted(os.listdir(os.path.join(d, "window", "frames"))) if r.returncode == 0 else []
check(files == ["velocity_%05d.png" % i for i in range(5)], "--frames 10:30:5: steps 10, 15, 20, 25, 30", (r.stderr, files))
r = run(["run", script, "--out", "view", "--frames", "50", "--frame-view", "-1,-2,2,1.5"] + common, d)
check(r.returncode == 0 and len(os.listdir(os.path.join(d, "view", "frames"))) == 2, "--frame-view", r.stderr)
r = run(["run", script, "--out", "bad", "--frame-view", "2,0,1,1"] + common, d)
check(r.returncode == 2 and "--frame-view needs" in r.stderr, "a view with X2 < X1 is refused", r.stderr)
r = run(["run", script, "--out", "bad", "--frames", "30:10:5"] + common, d)
check(r.returncode == 2 and "FROM:TO:EVERY" in r.stderr, "a window that ends before it starts is refused", r.stderr)

# No ffmpeg on the PATH: frames, a warning, exit 0.
r = run(["run", script, "--out", "noffmpeg", "--frames", "5", "--movie", "fall.mp4"] + common, d,
        env={"PATH": "/nonexistent"})
check(r.returncode == 0 and "ffmpeg is not on the PATH" in r.stderr, "without ffmpeg: a warning, exit 0", r.stderr)
check(not os.path.exists(os.path.join(d, "noffmpeg", "fall.mp4")) and
      len(os.listdir(os.path.join(d, "noffmpeg", "frames"))) == 11, "without ffmpeg: the 11 frames, no movie")

if shutil.which("ffmpeg"):
    r = run(["run", script, "--out", "movie", "--frames", "5", "--movie", "fall.mp4"] + common, d)
    movie = os.path.join(d, "movie", "fall.mp4")
    check(r.returncode == 0 and os.path.exists(movie) and os.path.getsize(movie) > 1000, "with ffmpeg: the movie",
          r.stderr)
    check(not [f for f in os.listdir(os.path.join(d, "movie")) if f.startswith(".part")], "no partial movie left")
    probe = shutil.which("ffprobe")
    if probe:
        import subprocess
        out = subprocess.run([probe, "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                              "stream=nb_read_frames,width,height", "-of", "csv=p=0", movie],
                             capture_output=True, text=True).stdout.strip()
        check(out == "320,240,11", "the movie has the 11 frames at 320x240", out)
else:
    print("ffmpeg is not on the PATH: the movie itself is not checked (WITH_FFMPEG=1 scripts/setup.sh installs it)")
finish()
