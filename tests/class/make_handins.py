#!/usr/bin/env python3
"""Writes 20 hand-in folders shaped like a real class into OUT, and OUT.expected.csv:
student, expected total (or "<100" where only an upper bound is certain), note to expect.

Correct modules are copies of solutions/ renamed into namespace raylab::student; the rest
are stubs (exercises/), broken files, missing files, nested folders, CRLF and helper headers.

Usage: make_handins.py ROOT OUT   (ROOT: the repository, holding solutions/ and exercises/)
"""
import pathlib
import shutil
import sys

ROOT, OUT = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
MODULES = sorted(p.stem for p in (ROOT / "exercises").glob("[0-9][0-9]_*.cpp"))
N = len(MODULES)


def points(modules):
    """The total of a hand-in with this many modules right (10 points each)."""
    return str(10 * modules)


def correct(mid):
    text = (ROOT / "solutions" / f"{mid}.cpp").read_text()
    return text.replace("namespace raylab::reference", "namespace raylab::student")


def stub(mid):
    return (ROOT / "exercises" / f"{mid}.cpp").read_text()


def broken(mid):
    return correct(mid).replace("{", "{ this does not compile;", 1)


def always_false_shadow():
    text = stub("08_shadows")
    head = text[: text.index("namespace raylab::student")]
    return head + (
        "namespace raylab::student {\n"
        "bool in_shadow(const Occluder&, const Vec3&, const Vec3&, const LightSample&) {\n"
        "    return false;\n}\n}  // namespace raylab::student\n")


def write(student, files):
    folder = OUT / student
    folder.mkdir(parents=True)
    for rel, text in files.items():
        path = folder / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(text.encode() if isinstance(text, str) else text)


def everything(make=correct, prefix=""):
    return {f"{prefix}{m}.cpp": make(m) for m in MODULES}


expected = []  # (student, total, note)
for i in range(1, 6):
    write(f"s{i:02d}_correct", everything())
    expected.append((f"s{i:02d}_correct", points(N), ""))
write("s06_nested", everything(prefix="handin/src/"))
expected.append(("s06_nested", points(N), "used handin/src/04_sphere.cpp"))
write("s07_crlf", {f"{m}.cpp": correct(m).replace("\n", "\r\n") for m in MODULES})
expected.append(("s07_crlf", points(N), ""))
files = everything()
files["04_sphere.cpp"] = files["04_sphere.cpp"].replace(
    '#include "raylab/contract.h"', '#include "raylab/contract.h"\n#include "sphere_util.h"')
files["sphere_util.h"] = "#pragma once\n// A helper header a student keeps beside the exercise\n"
write("s08_helper_header", files)
expected.append(("s08_helper_header", points(N), ""))  # the header beside it is staged
write("s09_first_half", {f"{m}.cpp": correct(m) for m in MODULES[:4]})
expected.append(("s09_first_half", points(4), "05_triangle missing"))
write("s10_half_stubs", {f"{m}.cpp": (correct(m) if k < 4 else stub(m))
                         for k, m in enumerate(MODULES)})
expected.append(("s10_half_stubs", points(4), "05_triangle not started"))
files = everything()
files["03_plane.cpp"] = broken("03_plane")
write("s11_plane_broken", files)
expected.append(("s11_plane_broken", points(N - 1), "03_plane did not compile"))
write("s12_all_broken", everything(make=broken))
expected.append(("s12_all_broken", points(0), "01_pixel_loop did not compile"))
(OUT / "s13_empty").mkdir(parents=True)
expected.append(("s13_empty", points(0), "01_pixel_loop missing"))
files = everything()
files["08_shadows.cpp"] = always_false_shadow()
write("s14_never_shadowed", files)
expected.append(("s14_never_shadowed", points(N - 1), "08_shadows wrong"))  # a constant earns nothing
files = everything()
files["deep/old/04_sphere.cpp"] = broken("04_sphere")  # the shallowest file wins
write("s15_two_copies", files)
expected.append(("s15_two_copies", points(N), "ignored deep/old/04_sphere.cpp"))
write("s16_all_stubs", everything(make=stub))
expected.append(("s16_all_stubs", points(0), "01_pixel_loop not started"))
files = everything()
files["07_lambert.cpp"] = broken("07_lambert")
files["08_shadows.cpp"] = broken("08_shadows")
write("s17_last_two_broken", files)
expected.append(("s17_last_two_broken", points(N - 2), "08_shadows did not compile"))
write("s18_nested_crlf", {f"ex/{m}.cpp": correct(m).replace("\n", "\r\n") for m in MODULES})
expected.append(("s18_nested_crlf", points(N), "used ex/01_pixel_loop.cpp"))
write("s19_only_camera", {"02_camera.cpp": correct("02_camera")})
expected.append(("s19_only_camera", points(1), "01_pixel_loop missing"))
files = everything()
del files["05_triangle.cpp"]
files["sub/05_triangle.cpp"] = correct("05_triangle")
write("s20_one_nested", files)
expected.append(("s20_one_nested", points(N), "used sub/05_triangle.cpp"))

with open(f"{OUT}.expected.csv", "w") as f:
    for row in expected:
        f.write(",".join(row) + "\n")
print(f"{len(expected)} hand-ins in {OUT}")
