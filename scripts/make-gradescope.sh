#!/usr/bin/env bash
# Builds a Gradescope autograder package (issue 7 item 7): OUT/autograder.zip with
#   setup.sh        run once when Gradescope builds the image: installs the Debian packages
#                   (scripts/install-deps.sh build libs) and builds the grader once, so each
#                   submission only compiles the student's files
#   run_autograder  grades /autograder/submission with scripts/grade.sh and writes
#                   /autograder/results/results.json (Gradescope's format: score, output, tests)
#   raylab/         this checkout's tracked files (with solutions/: the package is for the
#                   instructor's Gradescope assignment only, never for students)
#
# Usage: scripts/make-gradescope.sh OUT   (also: ./scripts/dev.sh gradescope OUT)
# Upload OUT/autograder.zip as the assignment's autograder; students hand in the
# NN_name.cpp files (folders are fine: the shallowest copy of each file is graded).
#
# Both scripts take their root from AUTOGRADER_ROOT (default /autograder), so a test can run
# them in a scratch folder laid out like /autograder (tests/class/check_gradescope.sh);
# RAYLAB_SKIP_DEPS=1 makes setup.sh skip the package installation.
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

[[ $# -eq 1 && $1 != -* ]] || {
    sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0" >&2
    die "usage: scripts/make-gradescope.sh OUT"
}
have zip || die "zip is missing: apt-get install zip"
mkdir -p "$1"
out=$(cd "$1" && pwd)
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT

step "Copying the tracked files of $RAYLAB_ROOT"
mkdir -p "$stage/raylab"
git -C "$RAYLAB_ROOT" ls-files -z --cached --others --exclude-standard |
    (cd "$RAYLAB_ROOT" && xargs -0 tar -cf - --no-recursion --ignore-failed-read) |
    tar -xf - -C "$stage/raylab"
[[ -f $stage/raylab/scripts/grade.sh ]] || die "the copy has no scripts/grade.sh"

cat >"$stage/setup.sh" <<'EOF'
#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder image.
set -euo pipefail
ROOT=${AUTOGRADER_ROOT:-/autograder}
SRC=$ROOT/source/raylab
if [[ ${RAYLAB_SKIP_DEPS:-0} != 1 ]]; then
    export DEBIAN_FRONTEND=noninteractive
    apt-get update
    apt-get install -y --no-install-recommends jq
    bash "$SRC/scripts/install-deps.sh" build libs
fi
# Build the grader once on the untouched stubs: each submission then compiles its own files
mkdir -p "$ROOT/stubs"
cp "$SRC"/exercises/[0-9][0-9]_*.cpp "$ROOT/stubs/"
SUBMISSION=$ROOT/stubs GRADE_OUT=$ROOT/setup-grade GRADE_BUILD_DIR=$ROOT/build-grade \
    bash "$SRC/scripts/grade.sh"
EOF

cat >"$stage/run_autograder" <<'EOF'
#!/usr/bin/env bash
# Gradescope runs this for each submission: grades ROOT/submission, writes
# ROOT/results/results.json. Whatever happens, results.json is written.
set -uo pipefail
ROOT=${AUTOGRADER_ROOT:-/autograder}
SRC=$ROOT/source/raylab
mkdir -p "$ROOT/results"
SUBMISSION=$ROOT/submission GRADE_OUT=$ROOT/results/grade GRADE_BUILD_DIR=$ROOT/build-grade \
    bash "$SRC/scripts/grade.sh" >"$ROOT/results/grade.log" 2>&1
status=$?
if ((status == 0)) && [[ -s $ROOT/results/grade/results.json ]]; then
    cp "$ROOT/results/grade/results.json" "$ROOT/results/results.json"
else
    # Grading could not run: score 0, and the log's tail for the student and instructor
    tail -n 40 "$ROOT/results/grade.log" |
        jq -Rs '{score: 0, output: ("Grading could not run:\n" + .), tests: []}' \
            >"$ROOT/results/results.json" 2>/dev/null ||
        printf '{"score": 0, "output": "Grading could not run", "tests": []}\n' \
            >"$ROOT/results/results.json"
fi
cat "$ROOT/results/grade/summary.txt" 2>/dev/null || tail -n 40 "$ROOT/results/grade.log"
EOF
chmod +x "$stage/setup.sh" "$stage/run_autograder"

step "Writing $out/autograder.zip"
rm -f "$out/autograder.zip"
(cd "$stage" && zip -qr "$out/autograder.zip" setup.sh run_autograder raylab)
note "$(du -h "$out/autograder.zip" | cut -f1) $out/autograder.zip: upload it as the autograder"
