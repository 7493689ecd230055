#!/usr/bin/env python3
"""Comments give the why in a clause; reference pages say what is. Neither cites an issue
or a review, and comments quote no timing: those belong in docs/decisions/.

  check_no_citations.py ROOT

Looks at the comments of the C++, shell, Python and CMake files under framework/,
solutions/, exercises/, engine/, grading/, bench/, tests/, scripts/ and fuzz/, and at the
reference pages (README.md, docs/*.md, docs/handouts/*.md and the hand-written head and
tail of the generated pages in bench/doc/; generated blocks are a run's record and are
skipped). docs/decisions/ is exempt: it is the record.

In comments: an issue ("issue 8", "#12"), a review ("review", "reviewer", an item code such
as "B5"), a timing ("51.7 ns", "13 %" or "2 minutes" where the comment speaks of speed,
"1.3x faster"), a date ("2026-11-26"). In reference pages: an issue, a review's finding, a
date.

Prints file:line: what: the line, one per hit, and exits 1 when there is any.
"""
import pathlib
import re
import sys

CODE_DIRS = ["framework", "solutions", "exercises", "engine", "grading", "bench", "tests",
             "scripts", "fuzz"]
SKIP_DIRS = {"data", "corpus", "crashes", "__pycache__"}
CPP = {".cpp", ".h", ".hpp", ".cc", ".inc", ".def", ".c"}
HASH = {".sh", ".py", ".cmake"}

ISSUE = re.compile(r"\b[Ii]ssues?\s+#?\d+|(?<![\w&/#])#\d+\b")
REVIEW_WORD = re.compile(r"\b[Rr]eview(s|ed|er|ers|ing)?\b")
# A review's item code: one capital of A-E and a number, as a word ("B5"), but not a
# compiler flag (-O2), a cache level (L2) or a key (F1)
REVIEW_CODE = re.compile(r"(?<![\w\-+./])[A-E]\d{1,2}(?![\w+.]| controls?)")
# Nanoseconds are always a measurement; milliseconds, minutes and percentages are one
# where the comment speaks of speed (a preview's budget of 100 ms or "64% of rays hit" is not)
TIMING = re.compile(r"\d(?:[\d,]*\d)?(?:\.\d+)?\s?ns\b"
                    r"|\d(?:\.\d+)?\s?(?:x|times)\s+(?:faster|slower)\b")
TIMING_IN_CONTEXT = re.compile(r"\d(?:[\d,]*\d)?(?:\.\d+)?\s?(?:us|µs|ms|%|minutes?|hours?)"
                               r"(?![\w])")
SPEED = re.compile(r"faster|slower|less time|more time|longer|took|measured|alternat|against|"
                   r"Cornell|frame|\bcosts?\b|\bspeed|\bCI\b|\bin CI|matrix takes",
                   re.IGNORECASE)
DATE = re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b")
DOC_REVIEW = re.compile(r"\b[Rr]eview(er)?(?:'s)?\s+(?:of|found|item|finding|[A-E]?\d)"
                        r"|\breviewer's\b|\bthe review\b")


def cpp_comments(text):
    """(line, comment text) of every // and /* */ comment, strings and chars skipped."""
    out = []
    i, n, line = 0, len(text), 1
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append((line, text[i + 2:j]))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j
            for k, part in enumerate(text[i + 2:j].split("\n")):
                out.append((line + k, part))
            line += text.count("\n", i, j)
            i = j + 2
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^()\\ ]{0,16})\(', text[i:])
            if not m:
                i += 1
                continue
            end = text.find(")" + m.group(1) + '"', i)
            end = n if end < 0 else end
            line += text.count("\n", i, end)
            i = end + len(m.group(1)) + 2
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator 1'000
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            i = j + 1
        else:
            i += 1
    return out


def hash_comments(text):
    """(line, comment) of '#' comments: a line starting with '#', or ' #' after code."""
    out = []
    for k, l in enumerate(text.split("\n"), 1):
        s = l.lstrip()
        if s.startswith("#!") and k == 1:
            continue
        if s.startswith("#"):
            out.append((k, s[1:]))
            continue
        m = re.search(r"\s#\s", l)
        if m and l.count('"', 0, m.start()) % 2 == 0 and l.count("'", 0, m.start()) % 2 == 0:
            out.append((k, l[m.end():]))
    return out


def code_files(root):
    for d in CODE_DIRS:
        base = root / d
        if not base.is_dir():
            continue
        for p in sorted(base.rglob("*")):
            rel = p.relative_to(root)
            if p.resolve() == pathlib.Path(__file__).resolve():
                continue  # its own patterns and examples
            if not p.is_file() or SKIP_DIRS & set(rel.parts[:-1]):
                continue
            if p.suffix in CPP or p.suffix in HASH or p.name == "CMakeLists.txt" or \
                    (p.suffix == "" and p.read_bytes()[:2] == b"#!"):
                yield p


def check_code(root, hits):
    for p in code_files(root):
        try:
            text = p.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        comments = cpp_comments(text) if p.suffix in CPP else hash_comments(text)
        for line, c in comments:
            unquoted = re.sub(r'"[^"]*"|`[^`]*`', '""', c)  # "Material #25" is a name
            checks = [("issue", ISSUE), ("review", REVIEW_WORD), ("review item", REVIEW_CODE),
                      ("timing", TIMING), ("date", DATE)]
            if SPEED.search(c) and "as if" not in c:  # a test's hypothetical, not a measurement
                checks.append(("timing", TIMING_IN_CONTEXT))
            for what, rx in checks:
                m = rx.search(unquoted)
                if m:
                    hits.append(f"{p.relative_to(root)}:{line}: {what} '{m.group(0)}': "
                                f"{c.strip()[:120]}")


def reference_pages(root):
    pages = [root / "README.md"] + sorted((root / "docs").glob("*.md")) + \
        sorted((root / "docs" / "handouts").glob("*.md")) + \
        sorted((root / "bench" / "doc").glob("*.md"))
    # benchmarks.md and sampling-benchmarks.md are head + a run + tail: their hand-written
    # parts are bench/doc/'s files, checked above, and the run is a run's record
    generated = {root / "docs" / "benchmarks.md", root / "docs" / "sampling-benchmarks.md"}
    return [p for p in pages if p.is_file() and p not in generated]


def check_docs(root, hits):
    for p in reference_pages(root):
        skipping = False
        for k, l in enumerate(p.read_text(encoding="utf-8").split("\n"), 1):
            # a block a script writes (viewer-timing.sh's table): its stamp is a run's
            if re.search(r"<!--.*begin \(generated", l):
                skipping = True
            if re.search(r"<!--.*: end -->", l):
                skipping = False
            if skipping:
                continue
            for what, rx in (("issue", ISSUE), ("review", DOC_REVIEW),
                             ("review item", REVIEW_CODE), ("date", DATE)):
                # not inside link targets or quoted names (`Material #25`)
                m = rx.search(re.sub(r"\]\([^)]*\)|`[^`]*`", "]()", l))
                if m:
                    hits.append(f"{p.relative_to(root)}:{k}: {what} '{m.group(0)}': "
                                f"{l.strip()[:120]}")


def main():
    if len(sys.argv) != 2:
        print("usage: check_no_citations.py ROOT", file=sys.stderr)
        return 2
    root = pathlib.Path(sys.argv[1])
    hits = []
    check_code(root, hits)
    check_docs(root, hits)
    for h in hits:
        print(h)
    if hits:
        print(f"check_no_citations: {len(hits)} comments or reference lines cite an issue, a "
              "review, a timing or a date: give the why in a clause and move the history to a "
              "record in docs/decisions/")
    return 1 if hits else 0


if __name__ == "__main__":
    sys.exit(main())
