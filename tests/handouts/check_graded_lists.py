#!/usr/bin/env python3
"""Each handout's "How you are graded" list must be the test cases of its grading suite, in
order (issue 7 item 9). Compares `raylab-grading-tests --list-test-cases --test-suite=ID`
with the "- " items of that section of docs/handouts/ID.md; --fix rewrites the lists.

The module IDs are the exercise files' names (exercises/NN_name.cpp).
Usage: check_graded_lists.py ROOT GRADING_TESTS [--fix]
"""
import pathlib
import re
import subprocess
import sys

root, binary = pathlib.Path(sys.argv[1]), sys.argv[2]
fix = "--fix" in sys.argv[3:]
ids = sorted(p.stem for p in (root / "exercises").glob("[0-9][0-9]_*.cpp"))


def test_cases(mid):
    out = subprocess.run([binary, "--list-test-cases", f"--test-suite={mid}"],
                         capture_output=True, text=True, check=True).stdout
    # Names sit between the two ===== rulers of doctest's listing
    parts = re.split(r"^=+$", out, flags=re.M)
    return [line for line in parts[1].splitlines() if line.strip()]


def graded_section(text):
    """(start, end) line indexes of the list items in the section."""
    lines = text.split("\n")
    head = next(i for i, l in enumerate(lines) if l.startswith("## How you are graded"))
    items = [i for i in range(head + 1, len(lines))
             if lines[i].startswith("- ") and not any(
                 lines[j].startswith("## ") for j in range(head + 1, i))]
    return lines, items


failures = 0
for mid in ids:
    handout = root / "docs" / "handouts" / f"{mid}.md"
    cases = test_cases(mid)
    lines, items = graded_section(handout.read_text())
    listed = [lines[i][2:] for i in items]
    missing = [c for c in cases if c not in listed]
    extra = [l for l in listed if l not in cases]
    if listed == cases:
        print(f"{mid}: {len(cases)} test cases, all listed in order")
        continue
    if fix:
        first, last = items[0], items[-1]
        lines[first:last + 1] = [f"- {c}" for c in cases]
        handout.write_text("\n".join(lines))
        print(f"{mid}: rewrote the list ({len(cases)} test cases)")
        continue
    failures += 1
    print(f"{mid}: the list in {handout.relative_to(root)} differs from the suite:")
    for c in missing:
        print(f"  not in the handout: {c}")
    for l in extra:
        print(f"  not a test case:    {l}")
    if not missing and not extra:
        print("  same cases, another order")
print(f"{len(ids)} handouts checked, {failures} differ"
      + ("" if not failures else
         " (fix: tests/handouts/check_graded_lists.py . build/tests/grading/raylab-grading-tests --fix)"))
sys.exit(1 if failures else 0)
