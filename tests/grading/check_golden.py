#!/usr/bin/env python3
"""ctest grading/golden-data-is-current: tests/data/golden/ is what the reference writes now.

Runs the graders with the reference and RAYLAB_GOLDEN_WRITE into a scratch folder (every
case, the hidden ones too: a hidden case that recorded golden data would fail there), then
compares with the committed folder: the same files, the text files line for line, the
images pixel for pixel within 1e-5 (relative above 1; the renderer's SIMD level may differ
between machines). No case name or file holds "[private]": a release ships this folder.
Usage: check_golden.py GRADING_TESTS GOLDEN_DIR SCRATCH
       check_golden.py --compare GOLDEN_DIR WRITTEN_DIR   (two folders already written,
       such as a release's, with the same rules)
"""
import os
import pathlib
import shutil
import struct
import subprocess
import sys

if sys.argv[1] == "--compare":
    golden, scratch = pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
else:
    binary, golden, scratch = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    shutil.rmtree(scratch, ignore_errors=True)
    scratch.mkdir(parents=True)
    env = dict(os.environ, RAYLAB_GRADE_IMPL="reference", RAYLAB_GOLDEN_WRITE=str(scratch))
    env.pop("RAYLAB_GRADE_ORACLE", None)
    run = subprocess.run([binary, "--no-colors"], env=env, capture_output=True, text=True)
    if run.returncode != 0:
        print(run.stdout[-4000:])
        sys.exit("the reference does not pass its graders, so no golden data was written")

REFRESH = "refresh it: ninja -C <build> raylab-update-golden"
problems = []


def read_pfm(path):
    data = path.read_bytes()
    parts, at = [], 0
    while len(parts) < 4:  # "PF", "W H" and the scale, each line ended by a newline
        end = data.index(b"\n", at)
        parts += data[at:end].split()
        at = end + 1
    width, height, scale = int(parts[1]), int(parts[2]), float(parts[3])
    fmt = ("<" if scale < 0 else ">") + "f" * (3 * width * height)
    return width, height, struct.unpack_from(fmt, data, at)


def compare_pfm(name, want, got):
    (w1, h1, a), (w2, h2, b) = read_pfm(want), read_pfm(got)
    if (w1, h1) != (w2, h2):
        return f"{name}: committed {w1} x {h1}, the reference writes {w2} x {h2}"
    worst = max((abs(x - y) / max(1.0, abs(y)) for x, y in zip(a, b)), default=0.0)
    return f"{name}: pixels differ by up to {worst:.3g}" if worst > 1e-5 else ""


def compare_txt(name, want, got):
    a, b = want.read_text().splitlines(), got.read_text().splitlines()
    keys = lambda lines: {l.split("\t")[0]: l for l in lines if l and not l.startswith("#")}
    ka, kb = keys(a), keys(b)
    for key in sorted(set(ka) | set(kb)):
        if key not in kb:
            return f"{name}: case '{key}' is committed, but no test makes it now"
        if key not in ka:
            return f"{name}: case '{key}' is missing from the committed data"
        if ka[key] != kb[key]:
            return f"{name}: case '{key}' differs:\n  committed: {ka[key]}\n  now:       {kb[key]}"
    return "" if a == b else f"{name}: the header or the order of the lines differs"


written = {p.name for p in scratch.iterdir()}
committed = {p.name for p in golden.iterdir()}
for name in sorted(committed - written):
    problems.append(f"{name} is committed, but the reference writes no such file")
for name in sorted(written - committed):
    problems.append(f"{name} is written by the reference, but not committed")
for name in sorted(written & committed):
    compare = compare_pfm if name.endswith(".pfm") else compare_txt
    why = compare(name, golden / name, scratch / name)
    if why:
        problems.append(why)
for name in sorted(written):
    if "private" in name or (name.endswith(".txt") and "[private]" in (scratch / name).read_text()):
        problems.append(f"{name}: holds a hidden case's data, which a release would ship")

if problems:
    print(f"tests/data/golden/ is not what the reference writes now ({REFRESH}):")
    for p in problems:
        print("  " + p)
    sys.exit(1)
print(f"tests/data/golden/: {len(written)} files, the same as the reference writes now")
