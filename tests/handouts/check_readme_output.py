#!/usr/bin/env python3
"""The README's sample output of raylab-render is what raylab-render prints today.

README.md shows the command and the lines it prints under a marker comment:

    <!-- output of: raylab-render ARGS (checked by tests/handouts/check_readme_output.py) -->
    ```
    ...lines...
    ```

This script runs raylab-render with those ARGS (writing its image to a scratch folder)
and compares the lines. Counts of rays, tests and BVH nodes are deterministic and must
match exactly; only the time, the speed and the thread count (machine-dependent) are
free, and the "wrote" line is not shown in the README.

Usage: check_readme_output.py SOURCE_DIR RAYLAB_RENDER
Exit 1 with the differing lines when the README is stale; --fix rewrites the block.
"""
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile

MARKER = re.compile(
    r"<!-- output of: raylab-render (?P<args>.*?) "
    r"\(checked by tests/handouts/check_readme_output\.py\) -->\n```\n(?P<body>.*?)```",
    re.S)
# The machine-dependent parts of the "rendered ..." line
FREE = [
    (re.compile(r" in [0-9.]+ ms"), " in <t> ms"),
    (re.compile(r" on [0-9]+ threads?: [0-9.]+ Mrays/s"), " on <n> threads: <r> Mrays/s"),
]


def normalise(line):
    for pattern, replacement in FREE:
        line = pattern.sub(replacement, line)
    return line


def main():
    args = [a for a in sys.argv[1:] if a != "--fix"]
    fix = "--fix" in sys.argv[1:]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    readme = pathlib.Path(args[0]) / "README.md"
    render = str(pathlib.Path(args[1]).resolve())
    text = readme.read_text(encoding="utf-8")
    blocks = list(MARKER.finditer(text))
    if not blocks:
        print(f"{readme}: no '<!-- output of: raylab-render ... -->' block", file=sys.stderr)
        return 1
    stale = 0
    for block in reversed(blocks):
        with tempfile.TemporaryDirectory() as scratch:
            cmd = [render] + shlex.split(block["args"]) + ["--output", f"{scratch}/out.png"]
            run = subprocess.run(cmd, capture_output=True, text=True, timeout=600,
                                 cwd=scratch)
        if run.returncode != 0:
            print(f"{' '.join(cmd)} failed ({run.returncode}):\n{run.stderr}",
                  file=sys.stderr)
            return 1
        now = [l for l in run.stdout.splitlines() if not l.startswith("wrote ")]
        shown = block["body"].splitlines()
        if [normalise(l) for l in now] == [normalise(l) for l in shown]:
            continue
        stale += 1
        line = text.count("\n", 0, block.start()) + 1
        print(f"README.md:{line}: the output of raylab-render {block['args']} has changed:")
        for a, b in zip(shown + [""] * len(now), now + [""] * len(shown)):
            if normalise(a) != normalise(b):
                print(f"  README: {a}\n  today:  {b}")
        if fix:
            body = "\n".join(now) + "\n"
            text = text[:block.start("body")] + body + text[block.end("body"):]
    if fix and stale:
        readme.write_text(text, encoding="utf-8")
        print(f"rewrote {stale} block(s) in {readme}")
        return 0
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
