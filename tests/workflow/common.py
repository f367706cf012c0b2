# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""Shared by the workflow tests: the dda binary (argv[1]), scratch folders,
running dda, the console through a pty, and plain checks that print what
failed."""
import os
import pty
import resource
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time

DDA = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else "build/dda"
SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
failures = []
passes = []


def scratch(name):
    d = os.path.join(tempfile.gettempdir(), "dda-workflow-%s-%d" % (name, os.getpid()))
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    return d


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def read(path):
    with open(path) as f:
        return f.read()


def run(args, cwd, env=None, stdin=None, timeout=300):
    e = dict(os.environ)
    e.update(env or {})
    return subprocess.run([DDA] + args, cwd=cwd, env=e, input=stdin, capture_output=True, text=True,
                          timeout=timeout)


def file_size_limit(limit):
    """For subprocess's preexec_fn: files of at most `limit` bytes, SIGXFSZ ignored, so that
    write(2) writes what fits and then fails with EFBIG, as a disk filling up."""
    def pre():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))
    return pre


class Console:
    """`dda console [args]` on a pty, as a person at a terminal runs it."""

    def __init__(self, cwd, env, args=()):
        self.pid, self.fd = pty.fork()
        if self.pid == 0:
            os.chdir(cwd)
            os.environ.update(env)
            os.environ["TERM"] = "xterm"
            os.execv(DDA, [DDA, "console"] + list(args))
        self.out = b""

    def expect(self, text, timeout=20):
        """Reads until `text` appears after what was read so far; returns the text read."""
        start = len(self.out)
        end = time.time() + timeout
        while time.time() < end:
            if text.encode() in self.out[start:]:
                return self.out[start:].decode(errors="replace")
            r, _, _ = select.select([self.fd], [], [], 0.2)
            if r:
                try:
                    data = os.read(self.fd, 4096)
                except OSError:
                    break
                if not data:
                    break
                self.out += data
        return None

    def send(self, text):
        os.write(self.fd, text.encode())
        time.sleep(0.15)

    def wait(self, timeout=20):
        end = time.time() + timeout
        while time.time() < end:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid:
                return status
            try:
                select.select([self.fd], [], [], 0.2)
                os.read(self.fd, 4096)
            except OSError:
                pass
        os.kill(self.pid, signal.SIGKILL)
        return None


def check(ok, what, detail=""):
    if ok:
        passes.append(what)
        print("ok:", what)
    else:
        print("FAILED:", what, ("\n" + str(detail)) if detail else "")
        failures.append(what)


def finish():
    print("checks: %d ok, %d failed" % (len(passes), len(failures)))
    sys.exit(1 if failures else 0)
