#!/usr/bin/env bash
# ctest grading/mutants: each honest mistake in this folder fails the test case that names
# it (or scores 0), each correct alternative scores full marks (expected.txt). Each file is
# graded alone through scripts/grade.sh as the only file of a hand-in; one build of the
# graders (env GRADE_BUILD_DIR, default WORKDIR/build). A mutant that does not build is an
# error of this check, whatever its expected verdict: a zero from a compile error says
# nothing about the graders (the Lambert mutant once scored zero only because it missed
# an #include). EXPECTED names another list, whose files lie beside it (the self-test).
# The file name "@stub" stands for the module's stub with its RAYLAB_STUB lines deleted:
# the stub's own placeholder answers handed in as work, which must score 0.
# Usage: check_mutants.sh ROOT WORKDIR [EXPECTED]
set -uo pipefail
root=$1 work=$2
expected=${3:-$(cd "$(dirname "$0")" && pwd)/expected.txt}
here=$(cd "$(dirname "$expected")" && pwd)
mkdir -p "$work"
fail=0
while IFS='|' read -r file module want; do
    [[ -z $file || $file == \#* ]] && continue
    rm -rf "$work/handin" "$work/out" && mkdir -p "$work/handin"
    if [[ $file == @stub ]]; then
        stub=$root/tests/grading/stubs/$module.cpp
        [[ -f $stub ]] || stub=$root/exercises/$module.cpp
        grep -v 'RAYLAB_STUB(' "$stub" >"$work/handin/$module.cpp"
        file=@stub-$module
    else
        cp "$here/$file" "$work/handin/$module.cpp"
    fi
    SUBMISSION=$work/handin GRADE_OUT=$work/out GRADE_BUILD_DIR=${GRADE_BUILD_DIR:-$work/build} \
        "$root/scripts/grade.sh" >"$work/$file.log" 2>&1 || { echo "FAIL $file: grade.sh failed"; fail=1; continue; }
    verdict=$(python3 - "$work/out" "$module" <<'PY'
import json, sys, xml.etree.ElementTree as ET
out, module = sys.argv[1], sys.argv[2]
m = [m for m in json.load(open(f"{out}/cases.json")) if m["id"] == module][0]
if m["status"] == "build error" or m["build_error"]:
    print("BUILD|" + (m["first_failure"] or m["build_error"].splitlines()[0]))
    sys.exit()
r = json.load(open(f"{out}/results.json"))
t = [t for t in r["tests"] if t["name"].startswith(module + ":")][0]
failed = [c.get("name") for c in ET.parse(f"{out}/junit.xml").iter("testcase")
          if c.get("classname") == module and (c.find("failure") is not None or c.find("error") is not None)]
print(f'{t["score"]}/{t["max_score"]}|' + "|".join(failed))
PY
)
    score=${verdict%%|*} failed=${verdict#*|}
    if [[ $score == BUILD ]]; then
        echo "ERROR $file: the mutant does not build, so its verdict says nothing: $failed"
        fail=1
        continue
    fi
    case $want in
        zero) ok=$([[ ${score%%/*} == 0 || ${score%%/*} == 0.0 ]] && echo 1 || echo 0) ;;
        full) ok=$([[ -z $failed ]] && echo 1 || echo 0) ;;
        *) ok=$([[ "|$failed" == *"|$want"* ]] && echo 1 || echo 0) ;;
    esac
    printf '%-32s %-6s %-10s want %-45s failed: %s\n' "$file" "$([[ $ok == 1 ]] && echo ok || echo FAIL)" "$score" "$want" "${failed:-none}"
    [[ $ok == 1 ]] || fail=1
done <"$expected"
exit $fail
