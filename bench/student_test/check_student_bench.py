#!/usr/bin/env python3
"""ctest bench/student-*: runs a student bench built on a known student and checks its
tables (no timing is asserted, only that ns/test are positive numbers).

Usage: check_student_bench.py reference|textbook BENCH
  reference: the reference renamed into the student's namespace. Every "yours" row must
             equal the reference's row in every column but the timings.
  textbook:  the textbook float sphere (b^2 - c) and float Moeller-Trumbore, and a plane
             stub. The plane must say "not started"; "yours" must equal the textbook row
             of the same formulation and show more error than the reference far away;
             the float triangle test must leak through shared edges, the reference not.
  endless:   a plane test that never returns: with --module-timeout 2 the bench must
             stop with exit 3 and name exercises/03_plane.cpp.
"""
import re
import subprocess
import sys

TIMING = {"ns/test", "x ref"}


def fail(message, output=None):
    if output is not None:
        sys.stderr.write(output)
    sys.exit(f"check_student_bench: {message}")


def sections(text):
    """{"Ray-plane": [table, ...], ...}; a table is a list of {header: cell} rows."""
    out, name, table = {}, None, None
    for line in text.splitlines():
        m = re.match(r"## (Ray-\w+)", line)
        if m:
            name, table = m.group(1), None
            out[name] = []
            continue
        if name is None or not line.startswith("|"):
            table = None
            continue
        cells = [c.strip() for c in line.strip("|").split("|")]
        if table is None:
            table = {"headers": cells, "rows": []}
            out[name].append(table)
        elif not set(cells[0]) <= set("-: "):
            table["rows"].append(dict(zip(table["headers"], cells)))
    return out


def number(cell):
    return float("inf") if cell == "inf" else float(cell)


def groups(table):
    """Rows by ray set: {(rays, D): {kernel: row}}"""
    g = {}
    for row in table["rows"]:
        g.setdefault((row["rays"], row["D"]), {})[row["kernel"]] = row
    return g


def accuracy(row):
    return {k: v for k, v in row.items() if k not in TIMING and k != "kernel"}


def check_common(tables, output):
    for name, ts in tables.items():
        for t in ts:
            for key, rows in groups(t).items():
                if "yours" not in rows or "reference" not in rows:
                    fail(f"{name} {key}: no 'yours' or 'reference' row", output)
                hits = {r["truth hits"] for r in rows.values()}
                if len(hits) != 1:
                    fail(f"{name} {key}: the kernels disagree on the truth: {hits}", output)
                for r in rows.values():
                    if not number(r["ns/test"]) > 0:
                        fail(f"{name} {key} {r['kernel']}: ns/test {r['ns/test']}", output)
                    if "missed" in r and int(r["missed"]) > int(r["truth hits"]):
                        fail(f"{name} {key} {r['kernel']}: more misses than hits", output)


def main():
    mode, bench = sys.argv[1], sys.argv[2]
    if mode == "endless":
        run = subprocess.run([bench, "--quick", "--module-timeout", "2"],
                             capture_output=True, text=True, timeout=60)
        if run.returncode != 3 or "exercises/03_plane.cpp has run for 2 s" not in run.stderr:
            fail(f"an endless plane test: exit {run.returncode}, stderr {run.stderr!r}")
        print("check_student_bench endless: stopped and named the module")
        return
    run = subprocess.run([bench, "--quick", "--repeats", "1"], capture_output=True,
                         text=True, timeout=600)
    output = run.stdout + run.stderr
    if run.returncode != 0:
        fail(f"{bench} exited with {run.returncode}", output)
    tables = sections(run.stdout)
    check_common(tables, output)
    if mode == "reference":
        for name in ("Ray-plane", "Ray-sphere", "Ray-triangle"):
            if not tables.get(name):
                fail(f"no {name} table: the reference as the student was skipped", output)
            for t in tables[name]:
                for key, rows in groups(t).items():
                    if accuracy(rows["yours"]) != accuracy(rows["reference"]):
                        fail(f"{name} {key}: the same code measures differently:\n"
                             f"  yours     {rows['yours']}\n  reference {rows['reference']}",
                             output)
    elif mode == "textbook":
        if tables.get("Ray-plane") or \
                "Not started: exercises/03_plane.cpp" not in run.stdout:
            fail("the stub plane was not reported as not started", output)
        pairs = {"Ray-sphere": "textbook float (b^2 - c)",
                 "Ray-triangle": "Moeller-Trumbore float"}
        for name, textbook in pairs.items():
            if not tables.get(name):
                fail(f"no {name} table", output)
            main_table = groups(tables[name][0])
            for key, rows in main_table.items():
                if accuracy(rows["yours"]) != accuracy(rows[textbook]):
                    fail(f"{name} {key}: yours is the textbook formulation but measures "
                         f"differently:\n  yours    {rows['yours']}\n"
                         f"  textbook {rows[textbook]}", output)
            # The largest distance of the random rays: more error than the reference's
            far = max((k for k in main_table if k[0] == "random"), key=lambda k: float(k[1]))
            yours, ref = main_table[far]["yours"], main_table[far]["reference"]
            wrong = lambda r: int(r["missed"]) + int(r["false hits"])  # noqa: E731
            if not (wrong(yours) > wrong(ref) or
                    number(yours["p99 ulps"]) > 4 * number(ref["p99 ulps"])):
                fail(f"{name} {far}: the float textbook test shows no more error than "
                     f"the reference:\n  yours     {yours}\n  reference {ref}", output)
        shared = groups(tables["Ray-triangle"][1])
        leaks = lambda kernel: sum(  # noqa: E731
            int(rows[kernel]["hit none (leak)"]) for rows in shared.values())
        if not (leaks("yours") > 0 and leaks("reference") == 0):
            fail(f"shared edges and vertices: yours leaks {leaks('yours')} rays, the "
                 f"reference {leaks('reference')} (want > 0 and 0)", output)
    else:
        fail(f"unknown mode {mode}")
    print(f"check_student_bench {mode}: the tables of {bench} are consistent")


if __name__ == "__main__":
    main()
