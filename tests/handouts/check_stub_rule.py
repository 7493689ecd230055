#!/usr/bin/env python3
"""One rule for RAYLAB_STUB: every place that tells the student when to delete the marker
(README.md, scripts/release/README.md, each handout, each exercise file's header) says it
in the same words, once.

Usage: check_stub_rule.py ROOT
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1])
RULE = ("Delete a function's RAYLAB_STUB line when you start on that function: while a "
        "module's functions still call it, the viewer runs the reference for that module "
        "and the graders report it as not started.")

files = [root / "README.md", root / "scripts/release/README.md"]
files += sorted((root / "docs/handouts").glob("[0-9][0-9]_*.md"))
files += sorted((root / "exercises").glob("[0-9][0-9]_*.cpp"))
problems = []
for path in files:
    if not path.exists():
        continue
    text = path.read_text()
    if path.suffix == ".cpp":
        text = "\n".join(l[2:] if l.startswith("//") else "" for l in text.splitlines())
    # One line of prose: comment markers and Markdown's code marks and list layout gone
    prose = re.sub(r"\s+", " ", text.replace("`", "").replace("RAYLAB_STUB(...)", "RAYLAB_STUB"))
    said = re.findall(r"Delete [^.]*RAYLAB_STUB[^.]*\.(?: [^.]*not started\.)?", prose)
    if len(said) != 1 or said[0] != RULE:
        problems.append(f"{path.relative_to(root)}: {said or 'no rule for RAYLAB_STUB'}")
for p in problems:
    print("FAIL", p)
print(f"{len(files) - len(problems)} of {len(files)} files state the RAYLAB_STUB rule")
sys.exit(1 if problems else 0)
