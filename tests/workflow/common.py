"""Shared by the workflow tests: the dda binary (argv[1]), scratch folders,
running dda, and plain checks that print what failed."""
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile

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
