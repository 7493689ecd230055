#!/usr/bin/env bash
# ctest grading/private-tests: the hidden tests of scripts/grade.sh --private DIR.
#  1. The reference, graded with a private seed (not the graders' default), gets full
#     marks, and the reports split them: every module with a "[private]" case has it in
#     the summary ("private tests: 1/1 passed") and in results.json (extra_data: public
#     and private points that add up to the module's score; 1 private case).
#  2. handins/public-view-only (a camera right only for the public DTU view; without
#     --private it scores 10, ctest grading/adversarial/public-view-only) loses exactly
#     its private points with the same seed: 0/1 private, full public points.
#  3. A hand-in that reaches for the seed (a header linked to it, an absolute #include, an
#     .incbin) scores zero on those modules, and the seed reaches no report or log.
# Usage: check_private.sh ROOT WORKDIR      (env GRADE_BUILD_DIR: the graders' build)
set -uo pipefail
root=$1 work=$2
rm -rf "$work" && mkdir -p "$work/private" "$work/handin"
echo 424242 >"$work/private/seed"
fail=0
if [[ ${RAYLAB_SANDBOX:-} == none ]] &&
    ! "${GRADE_BUILD_DIR:-$root/build-grade}/grading/raylab-sandbox" check; then
    echo "skipped: RAYLAB_SANDBOX=none needs Landlock, which this kernel lacks"; exit 77
fi

grade() {  # grade OUT ARGS...: grade.sh with the private seed
    local out=$1
    shift
    GRADE_OUT=$out "$root/scripts/grade.sh" --timeout 20 --private "$work/private" "$@" \
        >"$out.log" 2>&1 || { echo "FAIL: grade.sh $* failed"; tail -n 20 "$out.log"; exit 1; }
}

# The hand-in with its placeholder filled in (as handins/run-handins.sh does)
sed -e 's/namespace raylab::reference/namespace raylab::student/' \
    "$root/solutions/02_camera.cpp" >"$work/honest.cpp"
sed -e "/^\/\/ RAYLAB-HONEST-CODE 02_camera\$/{r $work/honest.cpp" -e 'd}' \
    "$root/tests/grading/handins/public-view-only/02_camera.cpp" >"$work/handin/02_camera.cpp"

grade "$work/reference" --reference
SUBMISSION=$work/handin grade "$work/handin-out"

mkdir -p "$work/thief"
ln -s "$work/private/seed" "$work/thief/seed.h"
printf '#include "seed.h"\n' >"$work/thief/03_plane.cpp"
printf '#include "%s"\n' "$work/private/seed" >"$work/thief/04_sphere.cpp"
printf 'asm(".incbin \\"%s\\"");\n' "$work/private/seed" >"$work/thief/05_triangle.cpp"
SUBMISSION=$work/thief grade "$work/thief-out"
for id in 03_plane 04_sphere 05_triangle; do
    grep -q "^$id .* 0\.00 / " "$work/thief-out/summary.txt" ||
        { echo "FAIL: the seed thief's $id did not score 0"; fail=1; }
done
if grep -rq 424242 "$work/thief-out" "$work/thief-out.log"; then
    echo "FAIL: the private seed reached $(grep -rl 424242 "$work/thief-out" "$work/thief-out.log")"
    fail=1
fi

python3 - "$work" <<'PY' || fail=1
import json, re, sys
work = sys.argv[1]
errors = []
def check(ok, what):
    if not ok: errors.append(what)
def parts(out):
    r = json.load(open(f"{work}/{out}/results.json"))
    return {t["number"]: t for t in r["tests"]}, r, open(f"{work}/{out}/summary.txt").read()

tests, r, summary = parts("reference")
check(r["score"] == sum(t["max_score"] for t in tests.values()),
      f"the reference scores {r['score']}, not full marks")
hidden = [m for m, t in tests.items() if t["extra_data"]["private_cases"] > 0]
check(len(hidden) >= 8, f"only {len(hidden)} modules have private cases: {hidden}")
for m in hidden:
    t, e = tests[m], tests[m]["extra_data"]
    check(e["private_cases"] == 1, f"{m}: {e['private_cases']} private cases, want 1")
    check(e["private_points"] > 0, f"reference {m}: no private points")
    check(abs(e["public_points"] + e["private_points"] - t["score"]) < 0.006,
          f"reference {m}: public + private points != score")
    check("private tests: 1/1 passed" in t["output"],
          f"reference {m}: results.json output lacks 'private tests: 1/1 passed'")
check(summary.count("private tests: 1/1 passed") == len(hidden),
      "the reference's summary.txt does not report each module's private test as passed")

ref_score, ref_max = r["score"], sum(t["max_score"] for t in tests.values())
tests, r, summary = parts("handin-out")
t, e = tests["02_camera"], tests["02_camera"]["extra_data"]
n = e["public_cases"] + e["private_cases"]
check(e["private_points"] == 0, f"public-view-only: {e['private_points']} private points")
check(abs(e["public_points"] - t["max_score"] * e["public_cases"] / n) < 0.006,
      f"public-view-only: public points {e['public_points']}, want all of them")
check(t["score"] < t["max_score"], f"public-view-only scores {t['score']}, full marks")
check(re.search(r"private tests: 0/1 passed", t["output"]) is not None,
      "public-view-only: the report does not say 'private tests: 0/1 passed'")
check("[private] a whole render of the DTU scene from a hidden viewpoint" in summary,
      "public-view-only: summary.txt does not name the failed private case")
print(f"reference: {ref_score}/{ref_max} ({len(hidden)} modules with a private case); "
      f"public-view-only 02_camera: {t['score']}/"
      f"{t['max_score']} (public {e['public_points']:.2f}, private {e['private_points']})")
for e in errors: print("FAIL:", e)
sys.exit(1 if errors else 0)
PY
exit $fail
