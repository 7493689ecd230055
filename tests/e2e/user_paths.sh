#!/usr/bin/env bash
# The instructor's and the student's paths, end to end, as the docs tell them (run by
# `./scripts/dev.sh test`):
#   1. the instructor makes a student release (./scripts/dev.sh release: all its own checks)
#   2. in the release, as a student: the README's first command without a display
#      (./scripts/dev.sh run renders build/cornell.png), `grade` of the untouched stubs
#      (every module "not started"), `grade` of a correct hand-in (full marks)
#   3. the viewer's Run tests under Xvfb on a half-done exercises/ (some modules right,
#      one that does not compile, the rest stubs) gives the same table as `grade` on it
#   4. the release's Markdown links resolve (scripts/check-links.sh)
#   5. the instructor grades a generated class with ./scripts/dev.sh grade-class DIR --out X
#   6. the instructor guide's "Adding a module", followed in a scratch copy (add_module.sh)
# Each step prints its time. The Gradescope package runs in ctest class/gradescope-package.
#
# Usage: tests/e2e/user_paths.sh ROOT WORK
#   ROOT  the instructor's tree (with solutions/); WORK a scratch folder (emptied)
# Environment: RELEASE_BUILD_DIR=DIR, an existing Ninja build of ROOT that the release
# uses to write its golden data (CI passes build-ci/, already built).
set -euo pipefail
root=$(cd "$1" && pwd)
work=$2
# shellcheck source=../../scripts/lib/common.sh
source "$root/scripts/lib/common.sh"
rm -rf "$work" && mkdir -p "$work"
work=$(cd "$work" && pwd)
rel=$work/raylab check=$work/check
declare -a timings=()
t_step=$SECONDS
begin() { step "e2e: $*"; t_step=$SECONDS; label=$*; }
end() { timings+=("$(printf '%4d s  %s' $((SECONDS - t_step)) "$label")"); }
fail() { die "e2e: $*"; }

begin "dev.sh release (every check of the release)"
RELEASE_CHECK_DIR=$check "$root/scripts/dev.sh" release "$rel" >"$work/release.log" 2>&1 ||
    { tail -n 40 "$work/release.log"; fail "dev.sh release failed (log: $work/release.log)"; }
sed -n 's/^==> /    /p' "$work/release.log"
end

begin "the release's README, first command, without a display"
grep -q '^./scripts/dev.sh run ' "$rel/README.md" || fail "the release's README no longer starts with ./scripts/dev.sh run"
(cd "$rel" && env -u DISPLAY ./scripts/dev.sh run) >"$work/run.log" 2>&1 ||
    { cat "$work/run.log"; fail "./scripts/dev.sh run failed in the release"; }
[[ $(head -c 8 "$rel/build/cornell.png" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]] ||
    fail "dev.sh run wrote no PNG at build/cornell.png"
note "build/cornell.png written ($(du -k "$rel/build/cornell.png" | cut -f1) KiB)"
end

# The graders that the release's check built (in its copy of the release) serve every
# grading below, the viewer's Run tests included
export GRADE_BUILD_DIR=$check/raylab/build-grade
grade() {  # grade NAME [ARGS...]: ./scripts/dev.sh grade in the release, reports in WORK/NAME
    local name=$1
    shift
    (cd "$rel" && GRADE_OUT=$work/$name ./scripts/dev.sh grade "$@") >"$work/$name.log" 2>&1 ||
        { cat "$work/$name.log"; fail "grade $name failed"; }
    sed -n '/^raylab grade:/,/^total/p' "$work/$name.log" | sed 's/^/    /'
}

begin "grade of the untouched stubs"
grade stubs --expect not-started
end

begin "grade of a correct hand-in"
mkdir -p "$work/correct"
for f in "$root"/solutions/[0-9][0-9]_*.cpp; do
    sed 's/namespace raylab::reference/namespace raylab::student/' "$f" >"$work/correct/$(basename "$f")"
done
SUBMISSION=$work/correct grade correct --expect full
end

begin "the viewer's Run tests against grade, on a half-done exercises/"
# The student's viewer: what ./scripts/dev.sh run builds when there is a display
ninja -C "$rel/build" raylab-viewer >"$work/viewer-build.log" 2>&1 ||
    { tail -n 40 "$work/viewer-build.log"; fail "the release's viewer does not build"; }
viewer=$rel/build/framework/viewer/raylab
[[ -x $viewer ]] || fail "the release's build/ has no viewer ($viewer)"
have xvfb-run || fail "xvfb-run is missing (scripts/install-deps.sh gui)"
# Modules 01-03 right, 04 does not compile, the rest untouched
for id in 01_pixel_loop 02_camera 03_plane; do cp "$work/correct/$id.cpp" "$rel/exercises/"; done
echo 'this line does not compile' >>"$rel/exercises/04_sphere.cpp"
grade half
# The viewer: Run tests at start, quit once they are done
xvfb-run -a -s '-screen 0 1280x800x24' "$viewer" --width 64 --height 48 --run-tests \
    --frames 2 >"$work/viewer.log" 2>&1 || { cat "$work/viewer.log"; fail "the viewer failed"; }
python3 - "$work/half/cases.json" "$work/viewer.log" <<'PY' || fail "the viewer's Run tests and grade differ (above)"
import json, re, sys
cases, log = sys.argv[1], open(sys.argv[2]).read()
# grade's words, as the viewer's panel puts them (viewer/grader.cpp)
want = {}
for m in json.load(open(cases)):
    s = m["status"]
    want[m["id"]] = f"{m['passed']}/{len(m['cases'])} passed" if s in ("passed", "failed") else s
block = log.split("graders of the student's code", 1)
if len(block) < 2:
    sys.exit("the viewer logged no results of Run tests:\n" + log[-2000:])
got = dict(re.findall(r"^\s+(\d\d_[a-z_0-9]+)\s+(.*?)\s+\(the viewer runs", block[1], re.M))
print(f"    {'module':<16}{'grade':<30}viewer Run tests")
for mid in want:
    print(f"    {mid:<16}{want[mid]:<30}{got.get(mid, '(none)')}")
bad = [m for m in want if got.get(m) != want[m]]
sys.exit(f"differ: {bad}" if bad else 0)
PY
kinds=$(python3 -c 'import json,sys; print(", ".join(sorted({m["status"] for m in json.load(open(sys.argv[1]))})))' "$work/half/cases.json")
[[ $kinds == *passed* && $kinds == *"not started"* && $(tr -cd , <<<"$kinds") == ,,* ]] ||
    fail "the half-done exercises gave only: $kinds (want passed, not started and a third)"
note "same table; statuses compared: $kinds"
end

begin "the release's link check"
bash "$rel/scripts/check-links.sh" "$rel" | sed 's/^/    /'
end

begin "dev.sh grade-class on a generated class, --out"
python3 "$root/tests/class/make_handins.py" "$root" "$work/class" >/dev/null
# Three of the twenty students keep it short
keep=$(cd "$work/class" && ls | sort | head -n 3)
for d in "$work/class"/*; do grep -qxF "$(basename "$d")" <<<"$keep" || rm -rf "$d"; done
GRADE_BUILD_DIR=${RELEASE_BUILD_DIR:-$root/build-grade} RAYLAB_NO_INSTALL=1 \
    "$root/scripts/dev.sh" grade-class "$work/class" --out "$work/class-out" \
    >"$work/class.log" 2>&1 || { tail -n 30 "$work/class.log"; fail "dev.sh grade-class DIR --out X failed"; }
[[ -s $work/class-out/class.csv ]] || fail "grade-class wrote no $work/class-out/class.csv"
rows=$(($(wc -l <"$work/class-out/class.csv") - 1))
((rows == 3)) || fail "class.csv has $rows rows, want 3"
sed 's/^/    /' "$work/class-out/class.csv"
end

begin "the instructor guide's \"Adding a module\" in a scratch copy (tests/e2e/add_module.sh)"
bash "$root/tests/e2e/add_module.sh" "$root" "$work/add-module" 2>&1 | sed 's/^/    /'
end

step "e2e: every step passed"
printf '    %s\n' "${timings[@]}"
