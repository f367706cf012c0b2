# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""The console driven as a person would: through a pty (readline: Ctrl-C at
the prompt, Ctrl-D inside a statement, Tab completion, saved history) and
through piped input (input ending inside a statement). Each fault was
reproduced first: before, EOF at a continuation line aborted (Lua PANIC,
exit 134, the model lost) and Ctrl-C at the prompt killed the console.
Run: console_test.py path/to/dda"""
import os
import time

from common import Console, check, finish, read, run, scratch, write


d = scratch("console")
hist = os.path.join(d, "history")
env = {"DDA_HISTORY": hist}
write(os.path.join(d, "zzfile_for_completion.txt"), "x")

# ---- piped input that ends inside a statement --------------------------------------------
r = run(["console"], d, stdin="m = dda.model{}\nprint('model', m ~= nil)\nfor i = 1, 3 do\n  print(i)\n", env=env)
check(r.returncode == 0, "piped EOF inside a statement: exit 0 (was 134, Lua PANIC)", r.returncode)
check("PANIC" not in r.stderr, "no Lua PANIC", r.stderr)
check("'end' expected" in r.stderr and "unfinished statement" in r.stderr,
      "the unfinished statement is reported", r.stderr)
check("model\ttrue" in r.stdout, "statements before it ran", r.stdout)

# ---- a terminal ----------------------------------------------------------------------------
c = Console(d, env)
check(c.expect("dda> ") is not None, "prompt on a pty")
c.send("x = 41\r")
c.expect("dda> ")
c.send("unfinished_line_text")
c.send("\x03")  # Ctrl-C at the prompt
check(c.expect("dda> ") is not None, "Ctrl-C at the prompt: a fresh prompt (was: the console killed)")
c.send("print(x + 1)\r")
got = c.expect("dda> ")
check(got is not None and "42" in got and "unfinished_line_text" not in got.split("print")[-1],
      "the console and its state survive Ctrl-C; the line was cleared", got)
c.send("for i = 1, 2 do\r")
check(c.expect("...> ") is not None, "continuation prompt")
c.send("\x03")  # Ctrl-C at the continuation prompt drops the statement
c.send("print('after ctrl-c')\r")
got = c.expect("dda> ")
check(got is not None and "after ctrl-c" in got, "Ctrl-C at a continuation line drops the statement", got)
c.send("m = dda.model{}\r")
c.expect("dda> ")
c.send("for i = 1, 2 do\r")
c.expect("...> ")
c.send("\x04")  # Ctrl-D inside the statement
got = c.expect("dda> ")
check(got is not None and "unfinished statement" in got, "Ctrl-D at a continuation line reports it", got)
c.send("print(m)\r")
got = c.expect("dda> ")
check(got is not None and "dda.Model" in got, "the model is still alive after Ctrl-D in a statement", got)

# completion: Lua names, never file names
c.send("m:contact_s\t")
got = c.expect("m:contact_summary(", timeout=5)
check(got is not None, "Tab completes a method (m:contact_s -> m:contact_summary()", c.out[-200:])
c.send("\x15")  # Ctrl-U: clear the line
c.send("dda.mo\t")
check(c.expect("dda.model(", timeout=5) is not None, "Tab completes a module field (dda.mo -> dda.model()")
c.send("\x15")
c.send("zzfile_for\t")
time.sleep(0.5)
got = c.expect("zzfile_for_completion", timeout=1)
check(got is None, "Tab does not complete file names")
c.send("\x15")
c.send("pri\t")
check(c.expect("print(", timeout=5) is not None, "Tab completes a global (pri -> print()")
c.send("\x15")

# tables print as tables; help
c.send("{1, 2, name = 'x', nested = {a = {b = {c = {d = 1}}}}}\r")
got = c.expect("dda> ")
check(got is not None and '{1, 2, name = "x", nested = {a = {b = {...}}}}' in got,
      "a table prints as a table, nesting bounded", got)
c.send("help(m.step)\r")
got = c.expect("dda> ")
check(got is not None and "m:step([n = 1])" in got, "help(m.step) prints its documentation", got)
c.send("help()\r")
got = c.expect("dda> ")
check(got is not None and "dda.model{" in got and "m:run{" in got, "help() lists the API", got)
c.send("help(m)\r")
got = c.expect("dda> ")
check(got is not None and "dda.Model methods" in got and "m:contacts" in got, "help(m) lists the model's methods",
      got)
c.send("\x04")  # Ctrl-D at the prompt leaves
status = c.wait()
check(status is not None and os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0, "Ctrl-D leaves with exit 0",
      status)

# history: saved, and there in the next session
h = read(hist) if os.path.exists(hist) else ""
check("x = 41" in h and "print(x + 1)" in h, "history saved to $DDA_HISTORY", h)
c = Console(d, env)
c.expect("dda> ")
c.send("\x1b[A")  # up arrow twice: the last line but one of the previous session, help()
c.send("\x1b[A")
c.send("\r")
got = c.expect("dda> ", timeout=10)
check(got is not None and "help(f)" in got and "m:run{" in got, "the previous session's history is there (up arrow)",
      c.out[-300:])
c.send("\x15\x04")
c.wait()
finish()
