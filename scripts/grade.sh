#!/usr/bin/env bash
# Grades the exercises, module by module: builds them in a scratch build and runs the
# graders (tests/grading/), one process per module with a time limit.
#
# Usage: scripts/grade.sh [--reference] [--timeout SECONDS] [--points N]
#   (also: ./scripts/dev.sh grade, make grade, make grade-reference)
#   --reference        grade the reference solutions (solutions/) instead of exercises
#   --timeout SECONDS  time limit per module (default 10)
#   --points N         points per module (default 10)
#   --expect MODE      exit 1 unless the scores are as expected: full, not-started (for CI
#                      and scripts/make-student-release.sh; see raylab-grade --help)
#
# Environment:
#   SUBMISSION=DIR     grade the NN_name.cpp files found in DIR (a student's unzipped
#                      hand-in, searched up to three folders deep) instead of exercises/.
#                      The working tree is not touched. A missing file, or one that does
#                      not compile, scores zero on its module with the compiler's message;
#                      the other modules are still graded.
#   GRADE_OUT=DIR      where the reports go (default build/grade/): summary.txt (the table
#                      and every failure), junit.xml, results.json (Gradescope), logs/,
#                      images/
#   GRADE_BUILD_DIR=DIR  the scratch build (default build-grade/); reused between runs, so
#                      grading a class rebuilds only the exercise files
#   GRADE_TIMEOUT=S, GRADE_POINTS=N  defaults for --timeout and --points
#
# Exit status: 0 when grading ran (whatever the scores), 1 when it could not (or when
# --expect was not met).
# Loop over a class:
#   for d in handins/*/; do SUBMISSION=$d GRADE_OUT=grades/$(basename "$d") make grade; done
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

usage() { sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; }

# ---- Arguments ------------------------------------------------------------------------

reference=0
timeout=${GRADE_TIMEOUT:-10}
points=${GRADE_POINTS:-10}
expect=''
while (($#)); do
    case $1 in
        --reference) reference=1 ;;
        --timeout) timeout=${2:?--timeout needs a value}; shift ;;
        --timeout=*) timeout=${1#*=} ;;
        --points) points=${2:?--points needs a value}; shift ;;
        --points=*) points=${1#*=} ;;
        --expect) expect=${2:?--expect needs a value}; shift ;;
        --expect=*) expect=${1#*=} ;;
        -h | --help) usage; exit 0 ;;
        *) usage >&2; die "unknown option '$1'" ;;
    esac
    shift
done

have cmake || die "cmake is missing: scripts/install-deps.sh build"
have ninja || die "ninja is missing: scripts/install-deps.sh build"

# Absolute path of $1, relative to where we were started
absolute() { [[ $1 == /* ]] && printf '%s' "$1" || printf '%s/%s' "$PWD" "$1"; }

OUT=$(absolute "${GRADE_OUT:-$RAYLAB_ROOT/build/grade}")
BUILD=$(absolute "${GRADE_BUILD_DIR:-$RAYLAB_ROOT/build-grade}")
STAGE=$BUILD/submission # the exercise files this build compiles
MODULES=(01_pixel_loop 02_camera 03_plane 04_sphere 05_triangle 06_point_light 07_lambert
    08_shadows)
# The untouched stubs stand in for a module that is missing or does not build: a student
# release ships them in tests/grading/stubs/; here exercises/ holds them
FALLBACK=$RAYLAB_ROOT/tests/grading/stubs
[[ -d $FALLBACK ]] || FALLBACK=$RAYLAB_ROOT/exercises

if ((reference)); then
    [[ -f $RAYLAB_ROOT/solutions/01_pixel_loop.cpp ]] ||
        die "there are no reference solutions (solutions/) in this copy, so --reference cannot run"
    [[ -z ${SUBMISSION:-} ]] || warn "--reference grades solutions/; SUBMISSION is ignored"
    SOURCE=$RAYLAB_ROOT/exercises
    label="reference solutions (solutions/)"
elif [[ -n ${SUBMISSION:-} ]]; then
    SOURCE=$(absolute "$SUBMISSION")
    [[ -d $SOURCE ]] || die "SUBMISSION=$SUBMISSION is not a folder"
    label="submission $SOURCE"
else
    SOURCE=$RAYLAB_ROOT/exercises
    label="exercises/ ($SOURCE)"
fi

mkdir -p "$OUT" "$STAGE"
rm -rf "$OUT/logs" "$OUT/images" "$OUT/build-errors"
mkdir -p "$OUT/logs" "$OUT/build-errors"
declare -A error=() # module -> file with the reason it scores zero

# Replaces module $1 by its stub, with reason $2 (a file's contents or a line)
fall_back() {
    local id=$1
    cp "$FALLBACK/$id.cpp" "$STAGE/$id.cpp"
    error[$id]=$OUT/build-errors/$id.txt
    printf '%s\n' "$2" >"${error[$id]}"
    note "$id: scores zero: $(head -n 1 "${error[$id]}")"
}

# ---- The submission's files -----------------------------------------------------------

step "Collecting the exercise files of the $label"
for id in "${MODULES[@]}"; do
    # The shallowest NN_name.cpp in the submission
    found=$(find "$SOURCE" -maxdepth 3 -name "$id.cpp" -type f -printf '%d %p\n' 2>/dev/null |
        sort -n | head -n 1 | cut -d' ' -f2-)
    if [[ -z $found ]]; then
        fall_back "$id" "$id.cpp is missing from $SOURCE"
        continue
    fi
    # Copy only when changed: an unchanged file keeps its object in the scratch build
    cmp -s "$found" "$STAGE/$id.cpp" || cp "$found" "$STAGE/$id.cpp"
done

# ---- Scratch build ---------------------------------------------------------------------

configured=$(sed -n 's/^RAYLAB_EXERCISES_DIR:PATH=//p' "$BUILD/CMakeCache.txt" 2>/dev/null || true)
if [[ $configured != "$STAGE" || ! -f $BUILD/build.ninja ]]; then
    step "Configuring the scratch build $BUILD/"
    cmake -S "$RAYLAB_ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release \
        -DRAYLAB_WITH_GUI=OFF -DRAYLAB_WERROR=OFF -DRAYLAB_EXERCISES_DIR="$STAGE" >"$OUT/logs/configure.log" 2>&1 ||
        die "configuring $BUILD/ failed: see $OUT/logs/configure.log"
fi

# The compiler's messages without ninja's noise and the scratch folder's path
compiler_message() {
    grep -v -e '^\[[0-9]*/[0-9]*\]' -e '^FAILED: ' -e '^ninja: ' -e ' -c /' "$1" |
        sed "s|$STAGE/||g" | head -n 60
}

step "Compiling each exercise file on its own"
for id in "${MODULES[@]}"; do
    [[ -n ${error[$id]:-} ]] && continue
    object=$(ninja -C "$BUILD" -t targets all | grep -o "^[^:]*submission/$id\.cpp\.o" | head -n 1)
    [[ -n $object ]] || die "the scratch build has no object for $id.cpp"
    log=$OUT/logs/compile-$id.log
    if ! ninja -C "$BUILD" "$object" >"$log" 2>&1; then
        message=$(compiler_message "$log")
        fall_back "$id" "$id.cpp does not compile: $(grep -m 1 'error' <<<"$message")
$message"
        continue
    fi
    # Grading must see the student's own code, not a call into the reference
    calls=$(nm -C "$BUILD/$object" 2>/dev/null | grep -o 'U raylab::reference::[a-z_]*' |
        sed 's/^U //' | sort -u | paste -sd ' ' || true)
    if [[ -n $calls ]]; then
        fall_back "$id" "$id.cpp calls the reference solution ($calls), which is not allowed"
    fi
done

# Which module a student function belongs to
module_of() {
    case $1 in
        image_plane_point | render_tile) echo 01_pixel_loop ;;
        camera_frame | camera_constant | camera_ray) echo 02_camera ;;
        intersect_plane) echo 03_plane ;;
        intersect_sphere) echo 04_sphere ;;
        intersect_triangle) echo 05_triangle ;;
        sample_point_light | intensity_from_power) echo 06_point_light ;;
        lambert) echo 07_lambert ;;
        in_shadow) echo 08_shadows ;;
    esac
}

step "Building the graders"
for attempt in 1 2 3; do
    log=$OUT/logs/build.log
    if ninja -C "$BUILD" raylab-grading-tests raylab-grade >"$log" 2>&1; then
        break
    fi
    # A link error: blame the modules it names (a function defined with another
    # signature, or twice), put their stubs in and try again
    blamed=()
    while read -r fn; do
        m=$(module_of "$fn")
        [[ -n $m ]] && blamed+=("$m")
    done < <(grep -o "undefined reference to \`raylab::student::[a-z_]*" "$log" |
        sed 's/.*:://' | sort -u)
    while read -r m; do
        blamed+=("$m")
    done < <(grep -e 'multiple definition' "$log" | grep -o '0[1-8]_[a-z_]*\.cpp' |
        sed 's/\.cpp$//' | sort -u)
    progress=0
    for m in $(printf '%s\n' "${blamed[@]}" | sort -u); do
        [[ -n ${error[$m]:-} ]] && continue
        message=$(grep -e 'undefined reference' -e 'multiple definition' "$log" |
            sed -e "s|$STAGE/||g" -e 's|^/usr/bin/ld: ||' | sort -u | head -n 20)
        fall_back "$m" "$m.cpp does not link with the framework (is a function missing, defined with another signature, or defined twice?): $(head -n 1 <<<"$message")
$message"
        progress=1
    done
    ((progress)) || die "building the graders failed: see $log
$(compiler_message "$log" | head -n 30)"
done

# ---- Grading ---------------------------------------------------------------------------

args=(--tests "$BUILD/tests/grading/raylab-grading-tests" --out "$OUT" --timeout "$timeout"
    --points "$points" --label "$label")
((reference)) && args+=(--reference)
[[ -n $expect ]] && args+=(--expect "$expect")
for id in "${!error[@]}"; do args+=(--module-error "$id=${error[$id]}"); done

step "Grading, one process per module (time limit ${timeout} s each)"
"$BUILD/tests/grading/raylab-grade" "${args[@]}"
