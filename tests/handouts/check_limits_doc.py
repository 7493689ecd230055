#!/usr/bin/env python3
"""docs/input.md's "Input limits" tables are the limits the code enforces.

  check_limits_doc.py ROOT

Each rule below names a row of the tables (its first cell), the source file and the
constant or literal that sets the limit there, and the words the row must then hold. A
limit changed in the code without the page, or the page without the code, fails; so does
a rule whose constant or row is gone (the rule must follow it).

Exits 0 when every row matches, 1 with one line per mismatch.
"""
import pathlib
import re
import sys

NUM = r"([0-9.e+-]+)"


def mib(v):
    return f"{v >> 20} MiB"


def kib(v):
    return f"{v >> 10} KiB"


def shifted(m):
    return int(m.group(1)) << int(m.group(2))


def g(k=1, cast=float):
    return lambda m: cast(m.group(k))


def num(x):
    """A limit as the page writes it: 1e6, 0.1, 179.9, 100."""
    x = float(x)
    if x >= 1e4 and x == 10 ** round(__import__("math").log10(x)):
        return f"1e{round(__import__('math').log10(x))}"
    return f"{x:g}"


INPUT_FILE = "framework/include/raylab/input_file.h"
CHECKS = "framework/include/raylab/input_checks.h"
RENDERER_H = "framework/include/raylab/renderer.h"
# (row's first cell, file, regex on the file, value from the match, text the row must hold)
RULES = [
    ("OBJ file", INPUT_FILE, r"kMaxObjBytes = std::size_t\((\d+)\) << (\d+)", shifted,
     lambda v: mib(v)),
    ("OBJ file", INPUT_FILE, r"kMaxObjLine = std::size_t\((\d+)\) << (\d+)", shifted,
     lambda v: f"one line at most {mib(v)}"),
    ("MTL file", INPUT_FILE, r"kMaxMtlBytes = std::size_t\((\d+)\) << (\d+)", shifted, mib),
    ("MTL file", INPUT_FILE, r"kMaxLine = (\d+);", g(1, int),
     lambda v: f"one line at most {v} bytes"),
    ("view file", INPUT_FILE, r"kMaxViewBytes = std::size_t\((\d+)\) << (\d+)", shifted, kib),
    ("view file", INPUT_FILE, r"kMaxLine = (\d+);", g(1, int),
     lambda v: f"one line at most {v} bytes"),
    ("coordinates", CHECKS, r"kMaxCoordinate = " + NUM + "f", g(), lambda v: f"+-{num(v)}"),
    ("MTL colours", CHECKS, r"kMaxIntensity = " + NUM + "f", g(), lambda v: f"[0, {num(v)}]"),
    ("`--fov`", CHECKS, r"kFovMin = " + NUM + "f;.*\n.*kFovMax = " + NUM + "f",
     lambda m: (float(m.group(1)), float(m.group(2))), lambda v: f"[{num(v[0])}, {num(v[1])}]"),
    ("`--eye`, `--lookat`, `--up`, `--light` position", CHECKS,
     r"kMaxCoordinate = " + NUM + "f", g(), lambda v: f"+-{num(v)}"),
    ("`--light` intensity", CHECKS, r"kMaxIntensity = " + NUM + "f", g(),
     lambda v: f"[0, {num(v)}]"),
    ("`--ambient`", CHECKS, r"kMaxAmbient = " + NUM + "f", g(), lambda v: f"[0, {num(v)}]"),
    ("`--exposure`", CHECKS, r"kMaxExposure = " + NUM + "f", g(),
     lambda v: f"[-{num(v)}, {num(v)}]"),
    ("`--width`, `--height`", RENDERER_H, r"kMaxImageSide = (\d+);", g(1, int),
     lambda v: f"1..{v} per side"),
    ("`--width`, `--height`", RENDERER_H, r"kMaxImagePixels = std::int64_t\{1\} << (\d+);",
     lambda m: 1 << int(m.group(1)), lambda v: f"{v >> 20} megapixels"),
    ("`--threads`", "framework/src/renderer.cpp", r"s\.threads < 0 \|\| s\.threads > (\d+)",
     g(1, int), lambda v: f"0..{v}"),
    ("`--spp`", CHECKS, r"kMaxSamplesPerSide = (\d+);", g(1, int), lambda v: f"n in 1..{v}"),
    ("`--light-size`", CHECKS, r"kMaxLightSize = " + NUM + "f", g(),
     lambda v: f"[0, {num(v)}]"),
    ("`--light-samples`", CHECKS, r"kMaxLightSamples = (\d+);", g(1, int),
     lambda v: f"1..{v}"),
    ("`--repeat`", "framework/src/options.cpp",
     r"o\.repeat = static_cast<int>\(parse_flag_whole\(flag, value\(\), (\d+), (\d+)\)\)",
     lambda m: (m.group(1), m.group(2)), lambda v: f"{v[0]}..{v[1]}"),
    ("`--seed` and other whole numbers", "framework/src/options.cpp",
     r"parse_flag_whole\(flag, text, -(\d+)LL, (\d+)LL\)", g(2, int),
     lambda v: f"+-{num(v)}"),
    ("`--window` (viewer)", "framework/viewer/viewer_options.cpp",
     r'parse_count\("--window", text\.substr\(0, x\), (\d+), (\d+)\);\n.*'
     r'parse_count\("--window", text\.substr\(x \+ 1\), (\d+), (\d+)\)',
     lambda m: m.groups(), lambda v: f"{v[0]}..{v[1]} x {v[2]}..{v[3]}"),
    ("`--image-scale` (viewer)", "framework/viewer/viewer_options.cpp",
     r"o\.image_scale = parse_count\(flag, value\(\), (\d+), (\d+)\)", lambda m: m.groups(),
     lambda v: f"{v[0]}..{v[1]}"),
    ("`--frames` (viewer)", "framework/viewer/viewer_options.cpp",
     r"o\.frames = parse_count\(flag, value\(\), (\d+), (\d+)\)", lambda m: m.groups(),
     lambda v: f"{v[0]}..{v[1]}"),
]


def rows(page):
    """First cell -> the rest of the row, for the tables of the Input limits section."""
    start = page.find("\n## Input limits\n")
    end = page.find("\n## ", start + 1)
    out = {}
    for line in page[start:end].split("\n"):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.startswith("|") and len(cells) >= 2:
            out[cells[0]] = " | ".join(cells[1:])
    return out if start >= 0 else {}


def main():
    if len(sys.argv) != 2:
        print("usage: check_limits_doc.py ROOT", file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
    doc = root / "docs" / "input.md"
    table = rows(doc.read_text(encoding="utf-8"))
    problems = []
    if not table:
        problems.append(f"{doc}: no '## Input limits' section with tables")
    for row, src, pattern, value, text in RULES:
        path = root / src
        if not path.is_file():
            problems.append(f"{src}: missing (the rule for '{row}' must follow the limit)")
            continue
        m = re.search(pattern, path.read_text(encoding="utf-8"))
        if not m:
            problems.append(f"{src}: no match for /{pattern}/ (the limit of '{row}' moved: "
                            "update check_limits_doc.py)")
            continue
        want = text(value(m))
        if row not in table:
            problems.append(f"{doc}: the Input limits tables have no row '{row}'")
        elif want not in table[row]:
            problems.append(f"{doc}: row '{row}' should say '{want}' ({src}): "
                            f"{table[row][:100]}")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
