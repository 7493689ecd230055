#!/usr/bin/env bash
# raylab's front door: installs what is missing, builds, runs, tests. Works from any folder.
#
# Usage: scripts/dev.sh COMMAND [ARGS...]
#   run [FLAGS]        build (Release, build/) and open the viewer on the Cornell box; without a
#                      display (or a viewer) render build/cornell.png with raylab-render instead.
#                      FLAGS go to the viewer or to raylab-render (e.g. --reference all)
#   test               everything CI checks: warnings as errors, clang-format, an address and
#                      undefined-behaviour sanitizer build (build-asan/) running the unit tests,
#                      then every test in build/ (GUI tests under Xvfb)
#   build              configure and build build/ (Release)
#   grade [ARGS]       grade exercises (scripts/grade.sh); env SUBMISSION=DIR grades a hand-in,
#                      GRADE_OUT=DIR chooses where the reports go (default build/grade/)
#   grade-reference    grade the reference solutions (scripts/grade.sh --reference)
#   release [OUT]      make the student release (scripts/make-student-release.sh)
#   bench [ARGS]       build with Embree and run build/bench/raylab-bench ARGS
#   format             apply clang-format to the tracked C++ sources
#   clean              delete the build folders (build/ and every build-*/)
#   help               this text
#
# Environment: RAYLAB_NO_INSTALL=1 skips the package check (non-Debian systems);
# CMAKE_ARGS="..." adds options to every configure; CI=true is honoured (nothing prompts).
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"
CALLER_DIR=$PWD # `run` resolves relative paths in its flags from here
cd "$RAYLAB_ROOT"

BUILD_DIR=build      # the everyday build (Release), also tested by `test`
ASAN_DIR=build-asan  # the sanitizer build of `test` (same options as the asan preset)
JOBS=$(nproc 2>/dev/null || echo 2)

usage() { sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; }

# ---- Helpers ---------------------------------------------------------------------------

# Install the package groups named (see scripts/install-deps.sh)
install_deps() {
    if [[ ${RAYLAB_NO_INSTALL:-} == 1 ]]; then
        step "Skipping the package check (RAYLAB_NO_INSTALL=1)"
        return
    fi
    "$RAYLAB_ROOT/scripts/install-deps.sh" "$@"
}

# configure DIR [CMAKE OPTIONS...]: Ninja for a new folder when there is ninja; an existing
# folder keeps the generator it was made with
configure() {
    local dir=$1
    shift
    local gen=()
    if [[ ! -f $dir/CMakeCache.txt ]] && have ninja; then gen=(-G Ninja); fi
    local extra=()
    if [[ -n ${CMAKE_ARGS:-} ]]; then read -r -a extra <<<"$CMAKE_ARGS"; fi
    step "Configuring $dir/ ($*)"
    mkdir -p "$dir"
    local log=$dir/raylab-configure.log
    cmake -S "$RAYLAB_ROOT" -B "$dir" "${gen[@]}" "$@" "${extra[@]}" >"$log" 2>&1 || {
        cat "$log" >&2
        die "configuring $dir/ failed (log above)"
    }
    # The project's own messages and CMake's warnings; the rest stays in the log
    grep -E '^(-- raylab|CMake (Warning|Deprecation))' "$log" | sed 's/^/    /' || true
}

# compile DIR [TARGET...]
compile() {
    local dir=$1
    shift
    local targets=()
    (($#)) && targets=(--target "$@")
    step "Building $dir/${1:+ (target $*)} with $JOBS jobs"
    local t0=$SECONDS
    cmake --build "$dir" -j "$JOBS" "${targets[@]}" || die "building $dir/ failed (errors above)"
    note "built in $((SECONDS - t0)) s"
}

# Does the build folder DIR know the target NAME?
has_target() {
    local dir=$1 name=$2
    if [[ -f $dir/build.ninja ]]; then
        ninja -C "$dir" -t query "$name" >/dev/null 2>&1
    else
        make -C "$dir" -n "$name" >/dev/null 2>&1
    fi
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

cmd_build() {
    install_deps build libs
    configure "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
    compile "$BUILD_DIR"
}

cmd_run() {
    cmd_build
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

cmd_test() {
    install_deps build libs gui format
    local t0=$SECONDS

    # Warnings as errors, GUI included
    configure "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WERROR=ON
    compile "$BUILD_DIR"

    cmd_format_check

    # Address and undefined-behaviour sanitizers on the unit tests (no GUI: Mesa leaks)
    configure "$ASAN_DIR" -DCMAKE_BUILD_TYPE=Debug -DRAYLAB_SANITIZE=ON -DRAYLAB_WITH_GUI=OFF \
        -DRAYLAB_WERROR=ON
    compile "$ASAN_DIR"
    local select=(-L unit) count
    count=$(cd "$ASAN_DIR" && ctest -N -L unit | sed -n 's/^Total Tests: //p')
    if [[ ${count:-0} == 0 ]]; then
        note "no test carries the label 'unit': running every test not labelled 'gui'"
        select=(-LE gui)
    fi
    step "Unit tests under the sanitizers (ctest ${select[*]} in $ASAN_DIR/)"
    ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0} \
        UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
        run_ctest "$ASAN_DIR" "${select[@]}" || die "sanitizer tests failed (output above)"

    # Last, so that the output ends with ctest's summary
    step "All tests in $BUILD_DIR/ (ctest; $((SECONDS - t0)) s so far)"
    run_ctest "$BUILD_DIR"
}

cmd_grade() {
    install_deps build libs
    run_script scripts/grade.sh "$@"
}

cmd_release() {
    install_deps build libs
    run_script scripts/make-student-release.sh "$@"
}

cmd_bench() {
    install_deps build libs bench
    configure "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WITH_EMBREE=ON
    has_target "$BUILD_DIR" raylab-bench ||
        die "there is no raylab-bench target yet (bench/CMakeLists.txt does not define it)"
    compile "$BUILD_DIR" raylab-bench
    step "Running $BUILD_DIR/bench/raylab-bench $*"
    "$BUILD_DIR/bench/raylab-bench" "$@"
}

cmd_format() {
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

cmd_clean() {
    step "Deleting build/ and build-*/ (all generated; .gitignore lists them)"
    local d
    for d in build build-*/; do
        [[ -d $d ]] || continue
        rm -rf "${d%/}"
        note "deleted ${d%/}/"
    done
}

# ---- Dispatch --------------------------------------------------------------------------

command=${1:-help}
(($#)) && shift
case $command in
    run) cmd_run "$@" ;;
    test) cmd_test "$@" ;;
    build) cmd_build "$@" ;;
    grade) cmd_grade "$@" ;;
    grade-reference) cmd_grade --reference "$@" ;;
    release) cmd_release "$@" ;;
    bench) cmd_bench "$@" ;;
    format) cmd_format "$@" ;;
    clean) cmd_clean ;;
    help | -h | --help) usage ;;
    *)
        usage >&2
        die "unknown command '$command'"
        ;;
esac
