#!/usr/bin/env python3
"""No shell script under `set -o pipefail` pipes a command into a reader that may stop early.

  check_pipefail_grep.py ROOT

`grep -q` (and `grep -m N`, `head`) exits at its first match; the command writing into the
pipe then dies of SIGPIPE, and under pipefail the whole pipeline fails although the match
was found: `cmd | grep -q x || fail` fails at random, more often the longer cmd's output.
Write `cmd | grep x >/dev/null`, which reads to the end, or test a variable instead.

A line counts when it pipes into `grep -q`, `grep -m` or `head` outside a command
substitution: `$(cmd | head -n 1)` is left out, since its status is seldom looked at (an
assignment's is, under set -e: keep such output small). Prints file:line for each hit;
exits 1 if there is any.
"""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(sys.argv[1])
EARLY = re.compile(r"\|\s*(grep\s+-[A-Za-z]*[qm]|head\b)")


def tracked_scripts():
    out = subprocess.run(["git", "-C", str(ROOT), "ls-files", "*.sh", "fuzz/*", "scripts/*",
                          ".ci/*"], capture_output=True, text=True)
    names = out.stdout.split() if out.returncode == 0 else []
    if not names:  # not a git tree (a student release): every .sh file
        names = [str(p.relative_to(ROOT)) for p in ROOT.rglob("*.sh")
                 if not p.relative_to(ROOT).parts[0].startswith("build")]
    return sorted(set(names))


def in_text_substitution(line, at):
    """The pipe at `at` is inside a $( ... ) that opens on this line."""
    depth = 0
    for k in range(at - 1, -1, -1):
        if line.startswith(")", k):
            depth += 1
        elif line.startswith("$(", k):
            if depth == 0:
                return True
            depth -= 1
    return False


hits = []
for name in tracked_scripts():
    path = ROOT / name
    if not path.is_file():
        continue
    try:
        text = path.read_text()
    except UnicodeDecodeError:
        continue
    if not text.startswith("#!") or "bash" not in text.split("\n", 1)[0]:
        continue
    if "pipefail" not in text:
        continue
    for n, line in enumerate(text.split("\n"), 1):
        code = line.split(" #", 1)[0]
        if code.lstrip().startswith("#"):
            continue
        for m in EARLY.finditer(code):
            if not in_text_substitution(code, m.start()):
                hits.append(f"{name}:{n}: {line.strip()}")
print("\n".join(hits) if hits else "no pipeline under pipefail ends in a reader that stops early")
sys.exit(1 if hits else 0)
