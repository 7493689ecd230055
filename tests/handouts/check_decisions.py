#!/usr/bin/env python3
"""docs/decisions/ is a numbered set of dated records and README.md is its index.

  check_decisions.py ROOT

Every record is docs/decisions/NNNN-title.md (four digits, numbers unique and without
gaps from 0001), starts with "# NNNN: title", has a date line (YYYY-MM-DD. Status: ...)
and the sections Context, Choice and Measurement; the index's table lists each record
once, by its file, with the record's own title and date, and nothing else.

Exits 0 when the folder has that form, 1 with one line per problem.
"""
import pathlib
import re
import sys


def main():
    if len(sys.argv) != 2:
        print("usage: check_decisions.py ROOT", file=sys.stderr)
        return 2
    folder = pathlib.Path(sys.argv[1]) / "docs" / "decisions"
    problems = []
    records = {}
    for p in sorted(folder.glob("*.md")):
        if p.name == "README.md":
            continue
        m = re.fullmatch(r"(\d{4})-[a-z0-9-]+\.md", p.name)
        if not m:
            problems.append(f"{p}: not named NNNN-title.md (lower case, hyphens)")
            continue
        text = p.read_text(encoding="utf-8")
        head = re.match(r"# (\d{4}): (.+)\n\n(\d{4}-\d\d-\d\d)\. Status: [^\n]+\n", text)
        if not head or head.group(1) != m.group(1):
            problems.append(f"{p}: does not start with '# {m.group(1)}: title', a blank line "
                            "and 'YYYY-MM-DD. Status: ...'")
            continue
        for section in ("Context", "Choice", "Measurement"):
            if not re.search(rf"^## {section}\b", text, re.M):
                problems.append(f"{p}: no '## {section}' section")
        records[p.name] = (int(m.group(1)), head.group(2), head.group(3))
    numbers = sorted(n for n, _, _ in records.values())
    if numbers != list(range(1, len(numbers) + 1)):
        problems.append(f"{folder}: record numbers {numbers} are not 1..{len(numbers)}, each once")
    index = (folder / "README.md").read_text(encoding="utf-8")
    listed = {}
    for line in index.split("\n"):
        m = re.match(r"\| \[(\d{4})\]\(([^)]+)\) \| (.+?) \| (\d{4}-\d\d-\d\d) \|$", line)
        if m:
            if m.group(2) in listed:
                problems.append(f"{folder}/README.md: {m.group(2)} listed twice")
            listed[m.group(2)] = (int(m.group(1)), m.group(3), m.group(4))
    for name, rec in records.items():
        if name not in listed:
            problems.append(f"{folder}/README.md: no line for {name}")
        elif listed[name] != rec:
            problems.append(f"{folder}/README.md: the line for {name} says {listed[name]}, "
                            f"the record {rec}")
    for name in listed:
        if name not in records:
            problems.append(f"{folder}/README.md: lists {name}, which is not a record here")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
