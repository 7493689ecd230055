#!/usr/bin/env python3
"""The module tables of the docs list exactly the registry's modules, in order: README.md
(number, exercise file, handout) and docs/instructor-guide.md (number, ID, handout, the
module's functions). The registry is framework/include/raylab/modules.def; a module added
there and missing from a table, or a table row left behind, fails this check.

Usage: check_module_tables.py ROOT
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1])
registry = (root / "framework/include/raylab/modules.def").read_text()
modules = []  # (enum, ID, [functions])
for line in registry.splitlines():
    m = re.match(r'RAYLAB_MODULE\((\w+), "(\d\d_\w+)"', line)
    if m:
        modules.append((m.group(1), m.group(2), []))
    f = re.match(r"RAYLAB_FUNCTION\((\w+), (\w+)\)", line)
    if f:
        owner = next(mod for mod in modules if mod[0] == f.group(1))
        owner[2].append(f.group(2))
if not modules:
    sys.exit(f"FAIL: no RAYLAB_MODULE lines in {root}/framework/include/raylab/modules.def")

problems = []


def rows(path, pattern):
    """The table rows of path that match pattern, as match objects."""
    text = (root / path).read_text()
    return [m for m in (re.match(pattern, l) for l in text.splitlines()) if m]


# README.md: | N | name | `exercises/ID.cpp` | [ID](docs/handouts/ID.md) |
readme = rows("README.md",
              r"\| (\d+) \| [^|]+ \| `exercises/(\w+)\.cpp` \| \[(\w+)\]\(docs/handouts/(\w+)\.md\) \|")
got = [(int(m.group(1)), m.group(2), m.group(3), m.group(4)) for m in readme]
want = [(int(mid[:2]), mid, mid, mid) for _, mid, _ in modules]
if got != want:
    problems.append(f"README.md's module table {got} is not the registry's {want}")

# docs/instructor-guide.md: | N | `ID` | [NN](handouts/ID.md) | `f`, `g` |
guide = rows("docs/instructor-guide.md",
             r"\| (\d+) \| `(\w+)` \| \[\d+\]\(handouts/(\w+)\.md\) \| (.*) \|$")
got = [(int(m.group(1)), m.group(2), m.group(3), re.findall(r"`(\w+)`", m.group(4)))
       for m in guide]
want = [(int(mid[:2]), mid, mid, fns) for _, mid, fns in modules]
if got != want:
    problems.append(f"docs/instructor-guide.md's module table {got} is not the registry's {want}")

for p in problems:
    print("FAIL:", p)
if problems:
    sys.exit(1)
print(f"module tables match the registry: {len(modules)} modules")
