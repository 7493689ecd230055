#!/usr/bin/env python3
"""The option table of docs/benchmarks.md is raylab-bench's --help, and stays so.

  check_bench_options.py ROOT BENCH

bench/doc/head.md (which bench/make-doc.sh copies to the top of docs/benchmarks.md) has a
table with one row per option, "| `--name ARG` | meaning (defaults) |". Every option that
`BENCH --help` lists has a row with the same argument name, and every row an option; where
both end in a parenthesised list of defaults with digits in it, the numbers are the same
(the table writes 400,000 where --help writes 400000, and leaves out "quick").

Exits 0 when they match, 1 with one line per difference.
"""
import pathlib
import re
import subprocess
import sys

# "  --name ARG   text" in --help; "| `--name ARG` | text |" in the table
HELP_OPTION = re.compile(r"^  (--[a-z][a-z0-9-]*)( [A-Za-z]+)?(?=\s|$)(.*)$")
TABLE_ROW = re.compile(r"^\| `(--[a-z][a-z0-9-]*)( [A-Za-z]+)?` \| (.*) \|$")


def numbers_in_defaults(text):
    """The numbers of a trailing "(...)" group, commas removed, or None."""
    m = re.search(r"\(([^()]*)\)\s*$", text.strip())
    if not m or not re.search(r"\d", m.group(1)):
        return None
    group = re.sub(r"(?<=\d),(?=\d{3}\b)", "", m.group(1))  # 400,000 -> 400000
    return re.findall(r"[0-9][0-9a-z.]*", group.replace(",", " ").replace("x", " x "))


def help_options(bench):
    out = subprocess.run([bench, "--help"], capture_output=True, text=True, check=True).stdout
    options = {}
    current = None
    for line in out.splitlines():
        m = HELP_OPTION.match(line)
        if m:
            current = m.group(1)
            options[current] = [(m.group(2) or "").strip(), m.group(3).strip()]
        elif current and line.startswith("    ") and line.strip():
            options[current][1] += " " + line.strip()
        else:
            current = None
    return options


def table_options(head):
    options = {}
    for line in head.read_text(encoding="utf-8").splitlines():
        m = TABLE_ROW.match(line)
        if m:
            options[m.group(1)] = [(m.group(2) or "").strip(), m.group(3).strip()]
    return options


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    root, bench = pathlib.Path(sys.argv[1]), sys.argv[2]
    head = root / "bench" / "doc" / "head.md"
    helped, tabled = help_options(bench), table_options(head)
    problems = []
    if not helped:
        problems.append(f"{bench} --help lists no option")
    for name, (arg, text) in helped.items():
        if name not in tabled:
            problems.append(f"{head}: no row for {name} (raylab-bench --help lists it)")
            continue
        if tabled[name][0] != arg:
            problems.append(f"{head}: {name} takes '{tabled[name][0]}' in the table, "
                            f"'{arg}' in --help")
        mine, theirs = numbers_in_defaults(tabled[name][1]), numbers_in_defaults(text)
        if mine is not None and theirs is not None and mine != theirs:
            problems.append(f"{head}: {name} defaults {mine} in the table, {theirs} in "
                            "--help")
    for name in tabled:
        if name not in helped:
            problems.append(f"{head}: row for {name}, which raylab-bench --help does not "
                            "list")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
