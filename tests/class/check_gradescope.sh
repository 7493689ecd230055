#!/usr/bin/env bash
# ctest class/gradescope-package: the Gradescope package as Gradescope uses it.
#  1. scripts/dev.sh gradescope FILE.zip --seed N writes that file (a zip with setup.sh and
#     run_autograder at its root), not a folder.
#  2. It is unzipped into a scratch folder laid out like /autograder (source/, submission/,
#     results/) and setup.sh runs there as it does on Gradescope (its package check finds
#     everything installed on this machine); afterwards the private seed is in private/seed,
#     closed to other users, and no longer under source/.
#  3. run_autograder grades a correct hand-in (the reference renamed into the student
#     namespace): full marks, the private tests included (so --private reached the graders);
#     then a broken one (06_point_light missing, 04_sphere not compiling): zero on those
#     two, full marks on the others.
#  4. Each results.json holds only the fields Gradescope documents, with valid values
#     (docs/instructor-guide.md, "The Gradescope package").
# Usage: check_gradescope.sh ROOT WORKDIR
set -euo pipefail
root=$1 work=$2
rm -rf "$work" && mkdir -p "$work/ag/source"
fail() { echo "FAIL: $*"; exit 1; }

RAYLAB_NO_INSTALL=1 "$root/scripts/dev.sh" gradescope "$work/pkg/autograder.zip" --seed 424242 \
    >"$work/make.log" 2>&1 || { cat "$work/make.log"; fail "dev.sh gradescope failed"; }
[[ -f $work/pkg/autograder.zip ]] || fail "dev.sh gradescope FILE.zip did not write the file FILE.zip"
listing=$(unzip -Z1 "$work/pkg/autograder.zip")
for f in setup.sh run_autograder private/seed raylab/scripts/grade.sh; do
    grep -qx "$f" <<<"$listing" || fail "the zip has no $f at its root"
done

grep -qx "raylab/.gradescope-trusted" <<<"$listing" && fail "a package made without --trusted is marked trusted"
RAYLAB_NO_INSTALL=1 "$root/scripts/dev.sh" gradescope "$work/pkg/trusted.zip" --seed 1 --trusted \
    >"$work/make-trusted.log" 2>&1 || { cat "$work/make-trusted.log"; fail "dev.sh gradescope --trusted failed"; }
unzip -Z1 "$work/pkg/trusted.zip" | grep -x "raylab/.gradescope-trusted" >/dev/null ||
    fail "dev.sh gradescope FILE.zip --trusted does not mark the package trusted"

unzip -q "$work/pkg/autograder.zip" -d "$work/ag/source"
export AUTOGRADER_ROOT=$work/ag
bash "$work/ag/source/setup.sh" >"$work/setup.log" 2>&1 || { tail -n 30 "$work/setup.log"; fail "setup.sh failed"; }
[[ $(cat "$work/ag/private/seed") == 424242 ]] || fail "private/seed does not hold the seed given"
[[ $(stat -c %a "$work/ag/private") == 700 && $(stat -c %a "$work/ag/private/seed") == 600 ]] ||
    fail "the seed is open to others: $(stat -c '%a %n' "$work/ag/private" "$work/ag/private/seed")"
[[ ! -e $work/ag/source/private ]] || fail "source/private/ is still there after setup.sh"
cp "$work/ag/source/run_autograder" "$work/ag/run_autograder"

# A container where neither bubblewrap nor Landlock can confine a hand-in's compile: setup.sh
# fails there and names the way out, unless the package was made with --trusted (root only:
# without namespaces grade.sh runs the student's code as nobody)
if ((EUID == 0)); then
    unconfined=(env RAYLAB_SANDBOX=none RAYLAB_LANDLOCK=off RAYLAB_SKIP_DEPS=1)
    if "${unconfined[@]}" bash "$work/ag/source/setup.sh" >"$work/setup-unconfined.log" 2>&1; then
        fail "setup.sh passed where no compile can be confined, in a package made without --trusted"
    fi
    grep -q "gradescope FILE.zip --trusted" "$work/setup-unconfined.log" ||
        { tail -n 5 "$work/setup-unconfined.log"; fail "setup.sh's refusal does not name --trusted"; }
    : >"$work/ag/source/raylab/.gradescope-trusted" # what make-gradescope.sh --trusted leaves
    "${unconfined[@]}" bash "$work/ag/source/setup.sh" >"$work/setup-trusted.log" 2>&1 ||
        { tail -n 20 "$work/setup-trusted.log"; fail "setup.sh of a --trusted package failed unconfined"; }
    rm "$work/ag/source/raylab/.gradescope-trusted"
fi

# grade NAME: run_autograder on submission/, its results.json kept as NAME.json
grade() {
    rm -rf "$work/ag/results"
    (cd "$work/ag" && ./run_autograder) >"$work/$1.log" 2>&1 || fail "run_autograder exited non-zero ($1)"
    cp "$work/ag/results/results.json" "$work/$1.json"
}
rename() { sed 's/namespace raylab::reference/namespace raylab::student/' "$1" >"$2"; }

mkdir -p "$work/ag/submission"
for f in "$root"/solutions/[0-9][0-9]_*.cpp; do rename "$f" "$work/ag/submission/$(basename "$f")"; done
grade correct
rm -rf "$work/ag/submission" && mkdir -p "$work/ag/submission/my folder"
for f in "$root"/solutions/[0-9][0-9]_*.cpp; do
    case $(basename "$f") in
        06_point_light.cpp) ;;
        04_sphere.cpp) { rename "$f" /dev/stdout; echo 'this line does not compile'; } \
            >"$work/ag/submission/my folder/04_sphere.cpp" ;;
        *) rename "$f" "$work/ag/submission/my folder/$(basename "$f")" ;;
    esac
done
grade broken

python3 - "$work" "$root/framework/include/raylab/modules.def" <<'PY'
import json, re, sys
work, registry = sys.argv[1], sys.argv[2]
modules = re.findall(r'^RAYLAB_MODULE\([^"]*"(\d\d_[a-z_0-9]+)"', open(registry).read(), re.M)
errors = []
def check(ok, what):
    if not ok: errors.append(what)

# The fields of Gradescope's autograder specification (results.json), and their values
TOP = {"score", "execution_time", "output", "output_format", "test_output_format",
       "test_name_format", "visibility", "stdout_visibility", "extra_data", "tests",
       "leaderboard"}
TEST = {"score", "max_score", "status", "name", "name_format", "number", "output",
        "output_format", "tags", "visibility", "extra_data"}
VISIBILITY = {"hidden", "after_due_date", "after_published", "visible"}
def number(x): return isinstance(x, (int, float)) and not isinstance(x, bool) and x == x

def validate(name):
    r = json.load(open(f"{work}/{name}.json"))
    check(isinstance(r, dict), f"{name}: results.json is not an object")
    check(set(r) <= TOP, f"{name}: fields Gradescope does not document: {set(r) - TOP}")
    check(number(r.get("score")), f"{name}: score is not a number")
    check(isinstance(r.get("output", ""), str), f"{name}: output is not text")
    for key in ("visibility", "stdout_visibility"):
        check(r.get(key, "visible") in VISIBILITY, f"{name}: {key} {r.get(key)!r}")
    tests = r.get("tests", [])
    check(isinstance(tests, list) and len(tests) == len(modules),
          f"{name}: {len(tests)} tests, want one per module ({len(modules)})")
    for t in tests:
        n = t.get("name", "?")
        check(set(t) <= TEST, f"{name}/{n}: fields Gradescope does not document: {set(t) - TEST}")
        check(number(t.get("score")) and number(t.get("max_score")), f"{name}/{n}: score or max_score not a number")
        check(0 <= t["score"] <= t["max_score"], f"{name}/{n}: score {t['score']} outside [0, {t['max_score']}]")
        check(t.get("status", "passed") in ("passed", "failed"), f"{name}/{n}: status {t.get('status')!r}")
        check(t.get("visibility", "visible") in VISIBILITY, f"{name}/{n}: visibility {t.get('visibility')!r}")
        check(isinstance(t.get("output", ""), str) and isinstance(t.get("number", ""), str),
              f"{name}/{n}: output or number is not text")
        check(isinstance(t.get("extra_data", {}), dict), f"{name}/{n}: extra_data is not an object")
    check(abs(r["score"] - sum(t["score"] for t in tests)) < 1e-6,
          f"{name}: score {r['score']} is not the sum of the tests'")
    return r, {t["number"]: t for t in tests}

r, tests = validate("correct")
full = sum(t["max_score"] for t in tests.values())
check(abs(r["score"] - full) < 1e-6, f"correct hand-in: {r['score']} of {full}")
private = [m for m, t in tests.items() if t.get("extra_data", {}).get("private_cases", 0) > 0]
check(len(private) > 0, "correct hand-in: no module ran a private test (--private not passed?)")
for m in private:
    check("private tests: 1/1 passed" in tests[m]["output"], f"correct hand-in {m}: private test not passed")

r, tests = validate("broken")
for m, t in tests.items():
    want = 0 if m in ("04_sphere", "06_point_light") else t["max_score"]
    check(abs(t["score"] - want) < 1e-6, f"broken hand-in {m}: {t['score']}, want {want}")
check("does not compile" in tests["04_sphere"]["output"], "broken hand-in: 04_sphere's output does not say it does not compile")
print("\n".join(f"FAIL: {e}" for e in errors) or
      f"results.json of both hand-ins valid; correct {full}/{full}, broken {r['score']}/{full}")
sys.exit(1 if errors else 0)
PY
echo PASS
