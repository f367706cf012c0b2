# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""The live view in a real browser: `dda run SCRIPT --live 0` serves a page
that headless Chromium (driven through chromedriver's WebDriver, plain HTTP
and JSON) loads during the run; a screenshot shows the frame and a monitor's
plot; the frame changes between two screenshots; a click on Pause stops the
step count and a click on Resume starts it again. Also, without a browser:
the page, the status and a frame over plain HTTP, and a refused port.
The first screenshot is kept as live_view.png in the scratch folder
(docs/figures/live_view.png is one).
Run: live_test.py path/to/dda   (exit 77, skipped, without chromium and chromedriver)"""
import base64
import json
import os
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
import zlib

from common import DDA, SOURCE, check, finish, scratch, write

d = scratch("live")

# A wall of bricks settling, paced to a twentieth of real time (light on the
# CPU: the test machine is shared), with a monitor for the plot.
write(os.path.join(d, "wall.lua"), """
package.path = "%s/scripts/bench/?.lua;%s/scripts/paper/?.lua;" .. package.path
local scenes = require "scenes"
local m = scenes.wall(4)
m:monitor{ name = "top", at = {2.25, 3.9}, fields = {"uy", "vy"} }
m:run{ time = 10, realtime = 0.05 }
""" % (SOURCE, SOURCE))


def start_dda(extra=()):
    p = subprocess.Popen([DDA, "run", "wall.lua", "--out", "out", "--live", "0", "--quiet"] + list(extra), cwd=d,
                         stderr=subprocess.PIPE, text=True)
    line = p.stderr.readline()
    m = re.search(r"live view at (http://127\.0\.0\.1:\d+/)", line)
    if not m:
        p.kill()
        p.wait()
        if "without the live view" in line:
            print("this dda was built without the live view: skipped")
            sys.exit(77)
        return p, None
    return p, m.group(1)


def get(url, data=None, timeout=30):
    req = urllib.request.Request(url, data=data, method="POST" if data is not None else "GET")
    with urllib.request.urlopen(req, timeout=timeout) as r:
        return r.status, dict(r.headers), r.read()


def stop(p):
    if p.poll() is None:
        p.send_signal(signal.SIGINT)
        try:
            p.wait(30)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait()


# ---- plain HTTP ---------------------------------------------------------------------------
dda, url = start_dda()
check(url is not None, "dda run --live 0 says where it serves")
if url is None:
    finish()
status, headers, body = get(url)
check(status == 200 and b"<title>dda live</title>" in body and b"EventSource" in body,
      "GET / is the page, with its script inline")
check(b"http://" not in body.replace(b"http://127", b"") and b"https://" not in body,
      "the page fetches nothing from elsewhere")
time.sleep(1.5)
status, _, body = get(url + "status")
s = json.loads(body)
check(s.get("state") == "running" and s.get("step", 0) > 0 and "profile" in s and "iterations" in s,
      "GET /status: running, with the step's profile and iterations", s)
status, headers, body = get(url + "frame.png?field=velocity&w=480&h=270")
check(status == 200 and body[:8] == b"\x89PNG\r\n\x1a\n" and int(headers.get("X-DDA-Step", -1)) >= 0,
      "GET /frame.png is a PNG of a step")
taken = subprocess.run([DDA, "run", "wall.lua", "--out", "out2", "--live", url.split(":")[2].rstrip("/")],
                       cwd=d, capture_output=True, text=True, timeout=60)
check(taken.returncode == 2 and "cannot serve the live view" in taken.stderr,
      "a port in use is refused, naming the cure", (taken.returncode, taken.stderr))
stop(dda)

# ---- the browser ----------------------------------------------------------------------------
chromium = shutil.which("chromium")
driver = shutil.which("chromedriver")
if not chromium or not driver:
    print("chromium and chromedriver are not installed: the browser checks are skipped")
    finish()


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def png_rgb(data):
    """(width, height, rows of RGB bytes) of an 8-bit RGB or RGBA PNG."""
    pos, chunks, idat = 8, {}, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            chunks["ihdr"] = body
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    w, h, depth, ctype = struct.unpack(">IIBB", chunks["ihdr"][:10])
    assert depth == 8 and ctype in (2, 6), (depth, ctype)
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line[i] for i in range(stride) if i % bpp < 3) if bpp == 4 else bytes(line))
        prev = line
    return w, h, rows


def region(img, rect):
    """The RGB pixels of an element's rectangle (CSS pixels = screenshot pixels here)."""
    w, h, rows = img
    x0, y0 = int(rect["x"]) + 2, int(rect["y"]) + 2
    x1, y1 = min(w, int(rect["x"] + rect["width"]) - 2), min(h, int(rect["y"] + rect["height"]) - 2)
    return [tuple(rows[y][3 * x:3 * x + 3]) for y in range(y0, y1) for x in range(x0, x1)]


class WebDriver:
    def __init__(self, port):
        self.base = "http://127.0.0.1:%d" % port
        self.sid = None

    def call(self, method, path, payload=None, timeout=120):
        data = json.dumps(payload).encode() if payload is not None else None
        req = urllib.request.Request(self.base + path, data=data, method=method,
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=timeout) as r:
                return json.loads(r.read())["value"]
        except urllib.error.HTTPError as e:  # chromedriver says why in its body
            raise RuntimeError("%s %s: HTTP %d: %s" % (method, path, e.code, e.read()[:600].decode(errors="replace")))

    def session(self, profile):
        args = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync",
                "--user-data-dir=" + profile, "--window-size=1280,900", "--force-device-scale-factor=1"]
        caps = {"capabilities": {"alwaysMatch": {"goog:chromeOptions": {"binary": chromium, "args": args}}}}
        self.sid = self.call("POST", "/session", caps)["sessionId"]

    def s(self, path):
        return "/session/%s%s" % (self.sid, path)

    def go(self, url):
        self.call("POST", self.s("/url"), {"url": url})

    def js(self, script):
        return self.call("POST", self.s("/execute/sync"), {"script": script, "args": []})

    def element(self, css):
        v = self.call("POST", self.s("/element"), {"using": "css selector", "value": css})
        return list(v.values())[0]

    def rect(self, css):
        return self.call("GET", self.s("/element/%s/rect" % self.element(css)))

    def click(self, css):
        self.call("POST", self.s("/element/%s/click" % self.element(css)), {})

    def screenshot(self):
        return base64.b64decode(self.call("GET", self.s("/screenshot")))

    def wait_for(self, script, timeout=90):
        end = time.time() + timeout
        while time.time() < end:
            if self.js(script):
                return True
            time.sleep(0.5)
        return False

    def quit(self):
        if self.sid:
            try:
                self.call("DELETE", self.s(""), timeout=30)
            except Exception:
                pass


dda, url = start_dda()
dport = free_port()
drv_proc = subprocess.Popen([driver, "--port=%d" % dport], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
profile = tempfile.mkdtemp(prefix="dda-live-chromium-")
wd = WebDriver(dport)
try:
    end = time.time() + 60
    while time.time() < end:
        try:
            wd.call("GET", "/status", timeout=5)
            break
        except Exception:
            time.sleep(0.5)
    wd.session(profile)
    wd.go(url + "?field=velocity")
    shown = wd.wait_for("return +(document.body.dataset.frames || 0) >= 1 && "
                        "[...document.querySelectorAll('canvas.plot')].some(c => +c.dataset.points >= 5)")
    check(shown, "the page shows a frame and a plot during the run")
    first = wd.screenshot()
    with open(os.path.join(d, "live_view.png"), "wb") as f:
        f.write(first)
    img = png_rgb(first)
    frame = region(img, wd.rect("#frame"))
    colours = len(set(frame))
    check(colours >= 30, "the screenshot's frame area holds a frame (%d colours)" % colours)
    plot = region(img, wd.rect("canvas.plot"))
    line = sum(1 for p in plot if abs(p[0] - 21) < 40 and abs(p[1] - 101) < 40 and abs(p[2] - 192) < 40)
    check(line >= 20, "the screenshot's plot area holds a plotted line (%d pixels)" % line)

    frames_before = wd.js("return +document.body.dataset.frames")
    changed = wd.wait_for("return +document.body.dataset.frames >= %d" % (frames_before + 2))
    second = png_rgb(wd.screenshot())
    check(changed and region(second, wd.rect("#frame")) != frame, "the frame changes between two screenshots")

    wd.click("#pause")
    paused = wd.wait_for("return document.getElementById('state').textContent == 'paused'", timeout=30)
    time.sleep(1.0)  # a status event or two after the pause
    s1 = wd.js("return document.getElementById('step').textContent")
    time.sleep(3.0)
    s2 = wd.js("return document.getElementById('step').textContent")
    check(paused and s1 == s2, "a click on Pause stops the step count (%s, then %s)" % (s1, s2))
    _, _, body = get(url + "status")
    check(json.loads(body).get("state") == "paused", "the run itself is paused")
    wd.click("#resume")
    moved = wd.wait_for("return +document.getElementById('step').textContent > %s" % s2, timeout=30)
    check(moved, "a click on Resume starts it again")
finally:
    wd.quit()
    drv_proc.terminate()
    try:
        drv_proc.wait(30)
    except subprocess.TimeoutExpired:
        drv_proc.kill()
    stop(dda)
    shutil.rmtree(profile, ignore_errors=True)
finish()
