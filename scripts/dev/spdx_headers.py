#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# SPDX-FileCopyrightText: 2026 The dda maintainers
"""SPDX headers (REUSE specification 3.2) at the top of every tracked file that
can carry a comment: the licence and the copyright holder, in the file's own
comment syntax, after a shebang or a doctype. A file that already names its
licence keeps it; a missing copyright line is added beside it. Files that
cannot carry a header (data, images, generated reports, Markdown) are covered
by REUSE.toml instead. Idempotent: a second run changes nothing.

Run from anywhere:  python3 scripts/dev/spdx_headers.py [--check]
(--check changes nothing and exits 1 when a file lacks its header.)"""
import fnmatch
import os
import subprocess
import sys

LICENSE = "GPL-3.0-or-later"  # LICENSE's notice
HOLDER = "2026 The dda maintainers"  # LICENSE's copyright notice and REUSE.toml
# (comment start, comment end) by file name, first match wins.
SYNTAX = [
    ("*.cpp", "// ", ""), ("*.hpp", "// ", ""), ("*.h", "// ", ""), ("*.hpp.in", "// ", ""),
    ("*.lua", "-- ", ""),
    ("CMakeLists.txt", "# ", ""), ("*.cmake", "# ", ""),
    ("*.sh", "# ", ""), ("*.py", "# ", ""), (".ci/run", "# ", ""), (".githooks/*", "# ", ""),
    (".gitignore", "# ", ""), (".clang-format", "# ", ""), ("*.dict", "# ", ""),
    ("*.html", "<!-- ", " -->"),
]


def syntax(path):
    for pattern, start, end in SYNTAX:
        if fnmatch.fnmatch(path, pattern) or fnmatch.fnmatch(os.path.basename(path), pattern):
            return start, end
    return None


def add_header(text, start, end):
    lines = text.splitlines(keepends=True)
    licence = f"{start}SPDX-License-Identifier: {LICENSE}{end}\n"
    holder = f"{start}SPDX-FileCopyrightText: {HOLDER}{end}\n"
    head = lines[:6]
    has_licence = any("SPDX-License-Identifier:" in l for l in head)
    has_holder = any("SPDX-FileCopyrightText:" in l for l in head)
    if has_licence and has_holder:
        return text
    if has_licence:
        i = next(i for i, l in enumerate(head) if "SPDX-License-Identifier:" in l)
        lines.insert(i + 1, holder)
        return "".join(lines)
    # After a shebang or an HTML doctype (which must stay first).
    at = 1 if lines and (lines[0].startswith("#!") or lines[0].lower().startswith("<!doctype")) else 0
    lines[at:at] = [licence, holder]
    return "".join(lines)


def main():
    check = "--check" in sys.argv[1:]
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True, text=True,
                          cwd=os.path.dirname(os.path.abspath(__file__)), check=True).stdout.strip()
    files = subprocess.run(["git", "ls-files"], capture_output=True, text=True, cwd=root, check=True).stdout.split("\n")
    missing = []
    for path in filter(None, files):
        s = syntax(path)
        full = os.path.join(root, path)
        if s is None or os.path.islink(full) or not os.path.isfile(full):
            continue
        with open(full, encoding="utf-8", newline="") as f:
            text = f.read()
        new = add_header(text, *s)
        if new != text:
            missing.append(path)
            if not check:
                with open(full, "w", encoding="utf-8", newline="") as f:
                    f.write(new)
    verb = "lack" if check else "given"
    print(f"spdx_headers: {len(missing)} files {verb} their SPDX header" + (": " + ", ".join(missing) if check and missing else ""))
    return 1 if check and missing else 0


if __name__ == "__main__":
    sys.exit(main())
