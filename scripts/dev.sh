#!/usr/bin/env bash
# raylab's front door: installs what is missing, builds, runs, tests. Works from any folder.
#
# Usage: scripts/dev.sh COMMAND [ARGS...]
#   run [FLAGS]        build the viewer and raylab-render only (Release, build/, warnings are
#                      not errors) and open the viewer on the Cornell box; without a display
#                      (or a viewer) render build/cornell.png with raylab-render instead.
#                      FLAGS go to the viewer or to raylab-render (e.g. --reference all)
#   test               everything CI checks, in build folders of its own: warnings as errors
#                      (build-ci/), clang-format, the build without the geometry engine
#                      (build-noengine/: its unit and stress tests, its images equal to
#                      build-ci/'s), an address and undefined-behaviour sanitizer
#                      build (build-asan/) running the unit tests, a few seconds of each fuzz
#                      target (build-fuzz/, when clang is installed), the users' paths end to
#                      end (tests/e2e/user_paths.sh: a student release and its checks, the
#                      student's first commands, grade and Run tests in it, grade-class),
#                      scripts/stress-matrix.sh (its five configurations, when it exists),
#                      then every test in build-ci/ (GUI tests under Xvfb); ends with each
#                      step's time and the slowest tests. Compiles through ccache, its cache
#                      in build-cache/
#   check              the edit loop's part of test: the strict build (build-ci/),
#                      clang-format and the unit tests in build-ci/ (ctest -L unit); the
#                      sanitizers, fuzzing, the end-to-end paths, the stress matrix and the
#                      grading and GUI tests are left to test
#   build              configure and build everything in build/ (Release)
#   grade [ARGS]       grade exercises (scripts/grade.sh [--timeout S] [--points N]
#                      [--expect full|not-started]); env SUBMISSION=DIR grades a hand-in,
#                      GRADE_OUT=DIR chooses where the reports go (default build/grade/)
#   grade-reference    grade the reference solutions (scripts/grade.sh --reference) [instructor]
#   grade-class DIR [-j N] [--out OUT]  grade every hand-in in DIR (scripts/grade-class.sh)
#   gradescope FILE.zip [--seed N] [--trusted]  make the Gradescope autograder package,
#                      with the private tests' seed N (scripts/make-gradescope.sh) [instructor]
#   release [OUT]      make the student release (scripts/make-student-release.sh) [instructor]
#   bench [ARGS]       build with Embree and run build/bench/raylab-bench ARGS [instructor]
#   bench --student [--quick]  time your plane, sphere and triangle tests and measure the
#                      error of their t against the reference's and the textbook's
#                      (build/bench/raylab-student-bench; --help lists its options)
#   fuzz [SECONDS]     run each fuzz target SECONDS (default 600) in build-fuzz/ (needs clang)
#   format             apply clang-format to the tracked C++ sources
#   clean              delete the build folders this script made (it lists them)
#   help               this text
#
# [instructor]: needs the instructor's tree (solutions/); a student release neither lists
# nor runs these.
#
# Each build folder is locked while a command uses it: a second dev.sh on the same folder
# waits and says so.
#
# Environment: RAYLAB_NO_INSTALL=1 skips the package check (non-Debian systems);
# CMAKE_ARGS="..." adds options to every configure; CI=true is honoured (nothing prompts);
# CCACHE_DIR chooses the cache of test and check (default build-cache/).
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"
CALLER_DIR=$PWD # `run` resolves relative paths in its flags from here
cd "$RAYLAB_ROOT"

BUILD_DIR=build      # the everyday build (Release, warnings are not errors)
CI_DIR=build-ci      # the strict build of `test` (warnings as errors), what CI checks
NOENGINE_DIR=build-noengine # test's strict build without the geometry engine
ASAN_DIR=build-asan  # the sanitizer build of `test` (same options as the asan preset)
FUZZ_DIR=build-fuzz  # libFuzzer targets (clang; fuzz/CMakeLists.txt)
MARKER=.raylab-build # in every folder configure() made: `clean` deletes only those
JOBS=$(nproc 2>/dev/null || echo 2)
# shellcheck source=lib/build.sh
source "$RAYLAB_ROOT/scripts/lib/build.sh"

# The header above; in a student release without the [instructor] commands
usage() {
    local text
    text=$(sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0")
    if is_instructor_tree; then
        printf '%s\n' "$text"
        return
    fi
    # A command's entry runs from its line ("  name ...") to the next entry; drop the
    # entries marked [instructor] and the note about them
    printf '%s\n' "$text" | awk '
        function flush() { if (entry !~ /\[instructor\]/) printf "%s", entry; entry = "" }
        entry != "" && /^    / { entry = entry $0 "\n"; next }
        { flush() }
        /^  [a-z]/ { entry = $0 "\n"; next }
        /^\[instructor\]/ { skip = 1 }
        skip && /^$/ { skip = 0; next }
        skip { next }
        { print }
        END { flush() }'
}

# The instructor's tree holds the reference's source; a student release does not
is_instructor_tree() { [[ -f $RAYLAB_ROOT/solutions/01_pixel_loop.cpp ]]; }

# instructor_only COMMAND: refuse COMMAND in a student release
instructor_only() {
    is_instructor_tree ||
        die "'$1' is an instructor's command: this copy has no solutions/ (a student release)"
}

# ---- Helpers ---------------------------------------------------------------------------

# Install the package groups named (see scripts/install-deps.sh)
install_deps() {
    if [[ ${RAYLAB_NO_INSTALL:-} == 1 ]]; then
        step "Skipping the package check (RAYLAB_NO_INSTALL=1)"
        return
    fi
    "$RAYLAB_ROOT/scripts/install-deps.sh" "$@"
}

# Is FLAG among the remaining arguments (as FLAG or FLAG=...)?
has_flag() {
    local flag=$1
    shift
    local a
    for a in "$@"; do [[ $a == "$flag" || $a == "$flag="* ]] && return 0; done
    return 1
}

# The value of the last FLAG VALUE (or FLAG=VALUE) among the remaining arguments
flag_value() {
    local flag=$1 value=''
    shift
    while (($#)); do
        case $1 in
            "$flag") value=${2:-}; shift ;;
            "$flag="*) value=${1#*=} ;;
        esac
        shift
    done
    printf '%s' "$value"
}

# The tracked C++ sources, NUL-separated (a release without git: every source outside builds)
cxx_sources() {
    if git -C "$RAYLAB_ROOT" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
        git -C "$RAYLAB_ROOT" ls-files -z -- '*.cpp' '*.h' '*.hpp' '*.inc'
    else
        find . -path './build*' -prune -o -type f \
            \( -name '*.cpp' -o -name '*.h' -o -name '*.hpp' -o -name '*.inc' \) -printf '%P\0'
    fi
}

# A script of a colleague that may not exist yet: run it, or say so
run_script() {
    local script=$1
    shift
    [[ -x $script || -f $script ]] ||
        die "$script does not exist yet (it belongs to the grading tools); nothing to run"
    step "Running $script $*"
    bash "$script" "$@"
}

# ---- Commands --------------------------------------------------------------------------

# no_args COMMAND ARGS...: the command takes no arguments
no_args() {
    local command=$1
    shift
    (($# == 0)) || die "'$command' takes no arguments, got: $* (see scripts/dev.sh help)"
}

# The everyday build: never -Werror, so a half-written exercise still builds
configure_everyday() {
    configure "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WERROR=OFF
}

cmd_build() {
    no_args build "$@"
    install_deps build libs
    configure_everyday
    compile "$BUILD_DIR"
}

cmd_run() {
    install_deps build libs
    configure_everyday
    # Only what the first picture needs: raylab-render, and the viewer when there is a
    # display to show it on
    local targets=(raylab-render)
    if [[ -n ${DISPLAY:-} ]] && has_target "$BUILD_DIR" raylab-viewer; then
        targets+=(raylab-viewer)
    fi
    compile "$BUILD_DIR" "${targets[@]}"
    local viewer=$RAYLAB_ROOT/$BUILD_DIR/framework/viewer/raylab
    local render=$RAYLAB_ROOT/$BUILD_DIR/framework/raylab-render
    local scene=()
    has_flag --scene "$@" || scene=(--scene cornell)
    cd "$CALLER_DIR"
    if [[ -n ${DISPLAY:-} && -x $viewer ]]; then
        step "Starting the viewer: $BUILD_DIR/framework/viewer/raylab ${scene[*]} $*"
        exec "$viewer" "${scene[@]}" "$@"
    fi
    if [[ -z ${DISPLAY:-} ]]; then
        step "No display (\$DISPLAY is not set), so no viewer: rendering a PNG with raylab-render"
    else
        step "No viewer in $BUILD_DIR/framework/viewer/ (RAYLAB_WITH_GUI=OFF?): rendering a PNG"
    fi
    local output=()
    has_flag --output "$@" || output=(--output "$RAYLAB_ROOT/$BUILD_DIR/cornell.png")
    "$render" "${scene[@]}" "${output[@]}" "$@" || die "raylab-render failed"
    local out
    out=$(flag_value --output "${output[@]}" "$@")
    [[ $out == /* ]] || out=$CALLER_DIR/$out
    step "Wrote $out"
}

cmd_format_check() {
    step "Checking the C++ style (clang-format --dry-run --Werror)"
    have clang-format || die "clang-format is missing: scripts/install-deps.sh format"
    local bad=() f n=0
    while IFS= read -r -d '' f; do
        n=$((n + 1))
        clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
    done < <(cxx_sources)
    if ((${#bad[@]})); then
        printf '    not formatted: %s\n' "${bad[@]}" >&2
        die "${#bad[@]} of $n files are not clang-formatted. Fix them with:
       scripts/dev.sh format     (or: clang-format -i ${bad[*]})"
    fi
    note "$n files formatted"
}

# ctest in DIR with the remaining options; fails if no test ran
run_ctest() {
    local dir=$1
    shift
    (cd "$dir" && ctest --output-on-failure -j "$JOBS" --no-tests=error "$@")
}

# fuzz_run SECONDS: build the fuzz targets with clang and run each SECONDS
fuzz_run() {
    local seconds=$1
    lock "$FUZZ_DIR"
    if [[ ! -f $FUZZ_DIR/CMakeCache.txt ]]; then
        step "Configuring $FUZZ_DIR/ (clang, libFuzzer, ASan, UBSan)"
        : >"$FUZZ_DIR/$MARKER"
        CC=clang CXX=clang++ cmake -S fuzz -B "$FUZZ_DIR" -G Ninja -DRAYLAB_UNITY_BUILD=ON \
            >"$FUZZ_DIR/configure.log" 2>&1 ||
            { cat "$FUZZ_DIR/configure.log" >&2; die "configuring $FUZZ_DIR/ failed"; }
    fi
    compile "$FUZZ_DIR" fuzz-obj fuzz-view fuzz-options
    step "Fuzzing each target for $seconds s (fuzz/run.sh; crashes in $FUZZ_DIR/artifacts/)"
    fuzz/run.sh "$FUZZ_DIR" "$seconds" || die "a fuzz target failed (output above)"
}

cmd_fuzz() {
    local seconds=${1:-600}
    (($# <= 1)) || die "'fuzz' takes at most one argument (SECONDS), got: $*"
    [[ $seconds =~ ^[1-9][0-9]{0,5}$ ]] || die "fuzz: '$seconds' is not a number of seconds"
    install_deps build libs fuzz
    have clang++ || die "fuzzing needs clang: scripts/install-deps.sh fuzz"
    fuzz_run "$seconds"
}

# ccache for every compile of test and check, also in the folders their scripts configure
# (the student release, the add-module copy, the Gradescope package, the stress matrix):
# CMake takes the launcher from the environment when it configures a new folder. The cache
# is build-cache/ of this tree, paths in it relative to the build folder (base_dir), so a
# build of the same sources laid out the same way hits it, in this run or the next
use_ccache() {
    if ! have ccache; then
        warn "ccache is missing: every build compiles from scratch (scripts/install-deps.sh test)"
        return
    fi
    export CCACHE_DIR=${CCACHE_DIR:-$RAYLAB_ROOT/build-cache}
    export CCACHE_BASEDIR=$RAYLAB_ROOT
    # A fresh clone or copy has just written its files: trust the content hash alone
    export CCACHE_SLOPPINESS=include_file_ctime,include_file_mtime
    # -Werror changes no object, only whether a warning fails: the graders' and the
    # release's everyday builds take the strict build's objects. The strict build is the
    # first compile of every run (test, check), so each source it meets was compiled
    # strictly before any other build could store it with a warning
    export CCACHE_IGNOREOPTIONS=-Werror
    export CMAKE_CXX_COMPILER_LAUNCHER=${CMAKE_CXX_COMPILER_LAUNCHER:-ccache}
    export CMAKE_C_COMPILER_LAUNCHER=${CMAKE_C_COMPILER_LAUNCHER:-ccache}
    mkdir -p "$CCACHE_DIR"
    if [[ $CCACHE_DIR == "$RAYLAB_ROOT/build-cache" ]]; then : >"$CCACHE_DIR/$MARKER"; fi
    CCACHE_BEFORE=$(ccache_counts)
    note "ccache: $CCACHE_DIR/"
}

# "HITS MISSES" of the cache so far
ccache_counts() {
    ccache --print-stats 2>/dev/null | awk -F'\t' '
        $1 == "direct_cache_hit" || $1 == "preprocessed_cache_hit" { hit += $2 }
        $1 == "cache_miss" { miss += $2 }
        END { print hit + 0, miss + 0 }'
}

# timed LABEL COMMAND...: run COMMAND, keep its time for times_table
declare -a STEP_TIMES=()
timed() {
    local label=$1 t=$SECONDS rc=0
    shift
    "$@" || rc=$?
    record_time $((SECONDS - t)) "$label"
    return "$rc"
}

# record_time SECONDS LABEL: one row of the table times_table prints
record_time() {
    STEP_TIMES+=("$(printf '%5d s  %s' "$1" "$2")")
}

# Each step's time, ccache's hits and ctest's slowest tests in DIR
times_table() {
    local dir=$1 total=$2
    step "Times (on $JOBS cores; $(uptime | sed 's/.*load average/load average/'))"
    printf '    %s\n' "${STEP_TIMES[@]}"
    printf '    %5d s  in all\n' "$total"
    if [[ -n ${CCACHE_BEFORE:-} ]]; then
        local before after
        read -r -a before <<<"$CCACHE_BEFORE"
        read -r -a after <<<"$(ccache_counts)"
        note "ccache: $((after[0] - before[0])) compiles from the cache," \
            "$((after[1] - before[1])) compiled"
    fi
    local cost=$dir/Testing/Temporary/CTestCostData.txt
    if [[ -f $cost ]]; then
        note "slowest tests in $dir/:"
        awk '/^---/ { exit }
            { t = $NF; name = $0; sub(/ [0-9]+ [0-9.eE+-]+$/, "", name)
              printf "%9.1f s  %s\n", t, name }' "$cost" | sort -rn | sed -n '1,8s/^/    /p'
    fi
}

cmd_test() {
    no_args test "$@"
    install_deps build libs gui format test fuzz
    local t0=$SECONDS
    use_ccache

    # Warnings as errors, GUI included, in a folder of its own (build/ stays lenient)
    timed "strict build ($CI_DIR/)" build_ci

    timed "clang-format check" cmd_format_check

    # The engine is one CMake line away: without it the same images, the same tests
    timed "without the engine ($NOENGINE_DIR/)" without_engine

    # Address and undefined-behaviour sanitizers on the unit tests (no GUI: Mesa leaks); the
    # libraries and the stress suite as unity builds (RAYLAB_UNITY_BUILD), since the strict
    # build compiles every file alone
    timed "sanitizer build ($ASAN_DIR/)" build_asan
    local select=(-L unit) count
    count=$(cd "$ASAN_DIR" && ctest -N -L unit | sed -n 's/^Total Tests: //p')
    if [[ ${count:-0} == 0 ]]; then
        note "no test carries the label 'unit': running every test not labelled 'gui'"
        select=(-LE gui)
    fi
    # The suites again on the engine's narrower versions (*-versions) run in the strict
    # build's ctest; under the sanitizers the stress suite runs on those versions
    # (stress_narrower below)
    select+=(-E 'engine-[a-z0-9]+-versions$')
    step "Unit tests under the sanitizers (ctest ${select[*]} in $ASAN_DIR/)"
    ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0} \
        UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
        timed "unit tests under the sanitizers" run_ctest "$ASAN_DIR" "${select[@]}" ||
        die "sanitizer tests failed (output above)"
    timed "stress suite on the engine's narrower versions ($ASAN_DIR/)" stress_narrower

    # A few seconds of each fuzz target, replaying every crash kept in fuzz/crashes/
    if have clang++; then
        timed "fuzzing ($FUZZ_DIR/: build, 5 s a target)" fuzz_run 5
    else
        warn "clang++ is missing: the fuzz targets did not run (scripts/install-deps.sh fuzz)"
    fi
    # The numerical stress matrix (its five configurations; g++ -O0 is the sanitizer build
    # above) compiles on both cores while the users' paths below, which mostly grade one
    # hand-in at a time, leave one idle: the two run at once, the matrix's output kept in a
    # file and printed once both are done
    local matrix_log=$CI_DIR/stress-matrix.log matrix_pid='' matrix_t0=$SECONDS
    if [[ -f scripts/stress-matrix.sh ]]; then
        step "The numerical stress matrix (scripts/stress-matrix.sh), beside the users'" \
            "paths; its output: $matrix_log"
        bash scripts/stress-matrix.sh >"$matrix_log" 2>&1 &
        matrix_pid=$!
    fi
    # What instructors and students run, end to end: the release and its own checks, the
    # README's first command in it, grade, the viewer's Run tests, grade-class. The release
    # writes its golden data with the build above
    if [[ -f tests/e2e/user_paths.sh ]]; then
        step "The users' paths end to end (tests/e2e/user_paths.sh, in $CI_DIR/e2e/)"
        RELEASE_BUILD_DIR=$RAYLAB_ROOT/$CI_DIR timed "users' paths (tests/e2e/user_paths.sh)" \
            bash tests/e2e/user_paths.sh "$RAYLAB_ROOT" "$RAYLAB_ROOT/$CI_DIR/e2e" || {
            [[ -z $matrix_pid ]] || pkill -TERM -P "$matrix_pid" 2>/dev/null || true
            die "tests/e2e/user_paths.sh failed (output above)"
        }
    fi
    if [[ -n $matrix_pid ]]; then
        local matrix_status=0
        wait "$matrix_pid" || matrix_status=$?
        step "The numerical stress matrix's output ($matrix_log)"
        cat "$matrix_log"
        record_time $((SECONDS - matrix_t0)) \
            "stress matrix (scripts/stress-matrix.sh), from its start beside the users' paths"
        ((matrix_status == 0)) || die "scripts/stress-matrix.sh failed (output above)"
    fi

    # Last, so that the output ends with ctest's summary
    step "All tests in $CI_DIR/ (ctest; $((SECONDS - t0)) s so far)"
    timed "all tests in $CI_DIR/ (ctest)" run_ctest "$CI_DIR"
    times_table "$CI_DIR" $((SECONDS - t0))
}

# The stress suite of the sanitizer build again on the engine's AVX2 and baseline versions,
# which a processor with AVX-512 or AVX2 does not choose by itself: with the ctest run above,
# this is the stress matrix's g++ -O0 configuration (scripts/stress-matrix.sh)
stress_narrower() {
    local suite=$ASAN_DIR/tests/stress/raylab-stress-tests narrower
    [[ -x $suite ]] || return 0 # a student release: no reference, no stress suite
    for narrower in RAYLAB_NO_AVX512 RAYLAB_NO_AVX2; do
        step "The stress suite under the sanitizers with $narrower=1"
        env "$narrower=1" ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}" \
            UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}" \
            "$suite" --no-intro || die "the stress suite failed with $narrower=1 (output above)"
    done
}

# The strict build: what test builds first and CI checks
build_ci() {
    configure "$CI_DIR" -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WERROR=ON
    compile "$CI_DIR"
}

# The build without the geometry engine (RAYLAB_WITH_ENGINE=OFF), the strict build's flags
# otherwise, so that ccache serves every compile the engine does not change: its unit and
# stress tests pass, and raylab-render's images equal the strict build's byte for byte
without_engine() {
    [[ -d engine ]] || return 0 # a student release: the engine is in the compiled reference
    configure "$NOENGINE_DIR" -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WERROR=ON \
        -DRAYLAB_WITH_ENGINE=OFF
    compile "$NOENGINE_DIR" raylab-render raylab-framework-tests raylab-stress-tests
    step "Unit and stress tests without the engine ($NOENGINE_DIR/)"
    "$NOENGINE_DIR/tests/framework/raylab-framework-tests" --no-intro --minimal ||
        die "the framework's tests failed without the engine (output above)"
    "$NOENGINE_DIR/tests/stress/raylab-stress-tests" --no-intro --minimal ||
        die "the stress suite failed without the engine (output above)"
    step "Images with and without the engine (engine/tests/same_images.sh)"
    bash engine/tests/same_images.sh "$CI_DIR/framework/raylab-render" \
        "$NOENGINE_DIR/framework/raylab-render" ||
        die "the images differ without the engine (output above)"
}

# The sanitizer build (the asan preset's options)
build_asan() {
    # Without the benchmarks: their checks are of tables and rounds, and run in build-ci/
    configure "$ASAN_DIR" -DCMAKE_BUILD_TYPE=Debug -DRAYLAB_SANITIZE=ON -DRAYLAB_WITH_GUI=OFF \
        -DRAYLAB_WERROR=ON -DRAYLAB_UNITY_BUILD=ON -DRAYLAB_WITH_BENCH=OFF
    compile "$ASAN_DIR"
}

cmd_check() {
    no_args check "$@"
    install_deps build libs format test
    local t0=$SECONDS
    use_ccache
    timed "strict build ($CI_DIR/)" build_ci
    timed "clang-format check" cmd_format_check
    step "Unit tests (ctest -L unit in $CI_DIR/)"
    timed "unit tests in $CI_DIR/ (ctest -L unit)" run_ctest "$CI_DIR" -L unit
    times_table "$CI_DIR" $((SECONDS - t0))
    note "the sanitizers, fuzzing, the end-to-end paths, the stress matrix, grading and the" \
        "GUI tests run in ./scripts/dev.sh test"
}

cmd_grade() {
    check_grade_args "$@"
    install_deps build libs
    run_script scripts/grade.sh "$@"
}

cmd_grade_class() {
    (($# >= 1)) || die "grade-class needs the folder of hand-ins: grade-class DIR [-j N] [--out OUT]"
    local dir=$1
    [[ -d $dir ]] || die "grade-class: '$dir' is not a folder"
    # The options of scripts/grade-class.sh, checked before any build
    local rest=("${@:2}")
    while ((${#rest[@]})); do
        case ${rest[0]} in
            -j) [[ ${rest[1]:-} =~ ^[1-9][0-9]{0,2}$ ]] ||
                die "grade-class: -j needs N from 1 to 999, got '${rest[1]:-}'"
                rest=("${rest[@]:2}") ;;
            --out | --private)
                [[ -n ${rest[1]:-} ]] || die "grade-class: ${rest[0]} needs a folder"
                rest=("${rest[@]:2}") ;;
            --timeout | --points)
                check_grade_args "${rest[0]}" "${rest[1]:-}"
                rest=("${rest[@]:2}") ;;
            --trusted) rest=("${rest[@]:1}") ;;
            *) die "grade-class takes DIR [-j N] [--out OUT] [--timeout S] [--points N] [--private DIR] [--trusted], got: ${*:2}" ;;
        esac
    done
    install_deps build libs
    run_script scripts/grade-class.sh "$@"
}

cmd_gradescope() {
    (($# >= 1 && $# <= 4)) ||
        die "gradescope takes the zip file to write and its options: gradescope FILE.zip [--seed N] [--trusted]"
    install_deps build libs
    run_script scripts/make-gradescope.sh "$@"
}

cmd_release() {
    (($# <= 1)) || die "release takes at most one argument (OUT), got: $*"
    install_deps build libs
    run_script scripts/make-student-release.sh "$@"
}

cmd_bench() {
    if [[ ${1:-} == --student ]]; then
        shift
        cmd_student_bench "$@"
        return
    fi
    instructor_only bench
    install_deps build libs bench
    configure "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WITH_EMBREE=ON
    has_target "$BUILD_DIR" raylab-bench ||
        die "there is no raylab-bench target yet (bench/CMakeLists.txt does not define it)"
    compile "$BUILD_DIR" raylab-bench
    step "Running $BUILD_DIR/bench/raylab-bench $*"
    "$BUILD_DIR/bench/raylab-bench" "$@"
}

# The student's own tests against the reference's: also in a student release, which ships
# the student bench's sources and the compiled reference
cmd_student_bench() {
    install_deps build libs
    configure_everyday
    has_target "$BUILD_DIR" raylab-student-bench ||
        die "there is no raylab-student-bench target (it needs bench/ and the reference:" \
            "solutions/ or reference/libraylab_reference.a)"
    compile "$BUILD_DIR" raylab-student-bench
    step "Running $BUILD_DIR/bench/raylab-student-bench $*"
    "$BUILD_DIR/bench/raylab-student-bench" "$@"
}

cmd_format() {
    no_args format "$@"
    install_deps format
    step "Formatting the tracked C++ sources (clang-format -i)"
    local changed=0 n=0 f
    while IFS= read -r -d '' f; do
        n=$((n + 1))
        if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
            clang-format -i "$f"
            note "formatted $f"
            changed=$((changed + 1))
        fi
    done < <(cxx_sources)
    note "$changed of $n files changed"
}

# Did this project make the folder DIR? (configure's marker, or a CMake cache of this tree)
made_here() {
    local dir=$1 home
    [[ -f $dir/$MARKER ]] && return 0
    home=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$dir/CMakeCache.txt" 2>/dev/null)
    [[ -n $home && ($home == "$RAYLAB_ROOT" || $home == "$RAYLAB_ROOT"/*) ]]
}

cmd_clean() {
    no_args clean "$@"
    local d deleted=0
    for d in build build-*/; do
        d=${d%/}
        [[ -d $d && ! -L $d ]] || continue
        if ! made_here "$d"; then
            note "kept $d/ (not made by raylab's build: no $MARKER and no CMake cache of this tree)"
            continue
        fi
        lock "$d"
        step "Deleting $d/ ($(du -sh "$d" 2>/dev/null | cut -f1))"
        rm -rf "$d"
        deleted=$((deleted + 1))
    done
    note "deleted $deleted build folder(s)"
}

# ---- Dispatch --------------------------------------------------------------------------

command=${1:-help}
(($#)) && shift
case $command in
    run) cmd_run "$@" ;;
    test) cmd_test "$@" ;;
    check) cmd_check "$@" ;;
    build) cmd_build "$@" ;;
    grade) cmd_grade "$@" ;;
    grade-reference) instructor_only "$command"; cmd_grade --reference "$@" ;;
    grade-class) cmd_grade_class "$@" ;;
    gradescope) instructor_only "$command"; cmd_gradescope "$@" ;;
    release) instructor_only "$command"; cmd_release "$@" ;;
    bench) cmd_bench "$@" ;;
    fuzz) cmd_fuzz "$@" ;;
    format) cmd_format "$@" ;;
    clean) cmd_clean "$@" ;;
    help | -h | --help) no_args help "$@"; usage ;;
    *)
        usage >&2
        die "unknown command '$command'"
        ;;
esac
