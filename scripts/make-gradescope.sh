#!/usr/bin/env bash
# Builds the Gradescope autograder package: one zip file holding
#   setup.sh        run once, as root, when Gradescope builds the autograder's image (Ubuntu
#                   22.04, the default base image; Debian 12 works too): installs what grading
#                   needs (scripts/install-deps.sh grade: no graphical packages), moves the
#                   private seed out of the source folder into a folder only root can open,
#                   and builds the graders once, so that each submission only compiles the
#                   student's files
#   run_autograder  grades /autograder/submission with scripts/grade.sh --private (the hidden
#                   tests, with the seed) and writes /autograder/results/results.json
#                   (Gradescope's format: score, output, tests); whatever happens, it writes one
#   raylab/         this checkout's files (with solutions/: the package is for the
#                   instructor's Gradescope assignment only, never for students)
#   private/seed    the private tests' seed
#
# Usage: scripts/make-gradescope.sh FILE.zip [--seed N] [--trusted]
#                                                    (also: ./scripts/dev.sh gradescope)
#   --seed N   the seed of the private tests (a number, at most 18 digits); without it a
#              random one is drawn and printed. The same seed with scripts/grade.sh
#              --private DIR (DIR/seed holding it) gives the same grades on your machine.
#   --trusted  grade even where Gradescope's container can confine a hand-in's compile
#              neither with bubblewrap nor with Landlock (scripts/grade.sh --trusted); without
#              it setup.sh fails there and says so, rather than grade unconfined
# Upload FILE.zip as the assignment's autograder; students hand in the NN_name.cpp files
# (folders are fine: the shallowest copy of each file is graded).
#
# Both scripts take their root from AUTOGRADER_ROOT (default /autograder), so a test can run
# them in a scratch folder laid out like /autograder (tests/class/check_gradescope.sh);
# RAYLAB_SKIP_DEPS=1 makes setup.sh skip the package installation.
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

usage() { sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; }
out='' seed='' trusted=0
while (($#)); do
    case $1 in
        -h | --help) usage; exit 0 ;;
        --trusted) trusted=1 ;;
        --seed) (($# >= 2)) || die "--seed needs a number"; seed=$2; shift ;;
        --seed=*) seed=${1#*=} ;;
        -*) usage >&2; die "unknown option '$1'" ;;
        *) [[ -z $out ]] || die "one output file only, got '$out' and '$1'"; out=$1 ;;
    esac
    shift
done
[[ -n $out ]] || { usage >&2; die "usage: scripts/make-gradescope.sh FILE.zip [--seed N] [--trusted]"; }
[[ $out == *.zip ]] || die "the package is a zip file: name it FILE.zip, not '$out'"
[[ ! -d $out ]] || die "$out is a folder: name the zip file to write"
if [[ -z $seed ]]; then
    seed=$(od -An -N6 -tu8 /dev/urandom | tr -d ' ')
    random_seed=1
else
    [[ $seed =~ ^[0-9]{1,18}$ ]] || die "--seed takes a number of at most 18 digits, not '$seed'"
    random_seed=0
fi
have zip || die "zip is missing: scripts/install-deps.sh libs"
[[ -f $RAYLAB_ROOT/solutions/01_pixel_loop.cpp ]] ||
    die "this tree has no solutions/: the package can only be made from the instructor's tree"
dir=$(dirname "$out")
mkdir -p "$dir"
file=$(cd "$dir" && pwd)/$(basename "$out")
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT

step "Copying the tracked files of $RAYLAB_ROOT"
mkdir -p "$stage/raylab"
if git -C "$RAYLAB_ROOT" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git -C "$RAYLAB_ROOT" ls-files -z --cached --others --exclude-standard |
        (cd "$RAYLAB_ROOT" && xargs -0 tar -cf - --no-recursion --ignore-failed-read) |
        tar -xf - -C "$stage/raylab"
else
    (cd "$RAYLAB_ROOT" && find . -path './build*' -prune -o -type f -print0 |
        xargs -0 tar -cf - --no-recursion) | tar -xf - -C "$stage/raylab"
fi
[[ -f $stage/raylab/scripts/grade.sh ]] || die "the copy has no scripts/grade.sh"
mkdir -p "$stage/private"
printf '%s\n' "$seed" >"$stage/private/seed"
((trusted)) && : >"$stage/raylab/.gradescope-trusted"

cat >"$stage/setup.sh" <<'SH'
#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image.
set -euo pipefail
ROOT=${AUTOGRADER_ROOT:-/autograder}
SRC=$ROOT/source/raylab
# The private seed leaves source/ for a folder only its owner (root) can open: the
# student's compiler and program never run as root
install -d -m 700 "$ROOT/private"
if [[ -f $ROOT/source/private/seed ]]; then
    mv "$ROOT/source/private/seed" "$ROOT/private/seed"
    rmdir "$ROOT/source/private"
fi
chmod 600 "$ROOT/private/seed"
if [[ ${RAYLAB_SKIP_DEPS:-0} != 1 ]]; then
    bash "$SRC/scripts/install-deps.sh" grade
fi
# Build the graders once (in source/raylab/build-grade/, where grade.sh builds them in a
# tree) on the untouched stubs: each submission then compiles only its own files
mkdir -p "$ROOT/stubs"
cp "$SRC"/exercises/[0-9][0-9]_*.cpp "$ROOT/stubs/"
# The stubs are graded as a submission is, so a container that cannot confine a hand-in's
# compile fails here, where the instructor reads the log, not at each student's upload
trusted=()
[[ -f $SRC/.gradescope-trusted ]] && trusted=(--trusted)
SUBMISSION=$ROOT/stubs GRADE_OUT=$ROOT/setup-grade GRADE_BUILD_DIR=$SRC/build-grade \
    bash "$SRC/scripts/grade.sh" --expect not-started "${trusted[@]}" </dev/null || {
    echo "setup.sh: grading the untouched stubs failed (above). Where it says that this" \
        "container can confine a hand-in's compile neither with bubblewrap nor with Landlock," \
        "make the package again with 'dev.sh gradescope FILE.zip --trusted' to grade there" \
        "anyway (the instructor guide, 'The Gradescope package')" >&2
    exit 1
}
SH

cat >"$stage/run_autograder" <<'SH'
#!/usr/bin/env bash
# Gradescope runs this for each submission: grades ROOT/submission with the private tests,
# writes ROOT/results/results.json. Whatever happens, results.json is written.
set -uo pipefail
ROOT=${AUTOGRADER_ROOT:-/autograder}
SRC=$ROOT/source/raylab
mkdir -p "$ROOT/results"
trusted=()
[[ -f $SRC/.gradescope-trusted ]] && trusted=(--trusted)
SUBMISSION=$ROOT/submission GRADE_OUT=$ROOT/results/grade GRADE_BUILD_DIR=$SRC/build-grade \
    bash "$SRC/scripts/grade.sh" --private "$ROOT/private" "${trusted[@]}" </dev/null \
    >"$ROOT/results/grade.log" 2>&1
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
SH
chmod +x "$stage/setup.sh" "$stage/run_autograder"

step "Writing $file"
(cd "$stage" && zip -qr "$stage/package.zip" setup.sh run_autograder raylab private)
mv "$stage/package.zip" "$file"
note "$(du -h "$file" | cut -f1) $file: upload it as the assignment's autograder"
if ((random_seed)); then
    note "private seed $seed (drawn now; keep it to grade the same private tests elsewhere:" \
        "scripts/grade.sh --private DIR with DIR/seed holding it, or make the next package" \
        "with --seed $seed)"
else
    note "private seed: the one given (--seed)"
fi
