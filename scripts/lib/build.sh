# shellcheck shell=bash
# Build-folder helpers for scripts/dev.sh (sourced after common.sh, never run).
# Needs: RAYLAB_ROOT, JOBS, MARKER; provides lock, configure, compile, has_target,
# check_grade_args.

# lock DIR: hold an exclusive lock on the build folder DIR until this script exits, so two
# runs never write the same ninja log; a second run waits and says so
declare -A LOCKED=()
lock() {
    local dir=$1 fd
    [[ -n ${LOCKED[$dir]:-} ]] && return 0
    have flock || return 0
    mkdir -p "$dir"
    exec {fd}>>"$dir/.raylab-lock"
    if ! flock -n "$fd"; then
        note "another dev.sh is using $dir/; waiting for it to finish ..."
        flock "$fd"
    fi
    LOCKED[$dir]=$fd
}

# configure DIR [CMAKE OPTIONS...]: Ninja for a new folder when there is ninja; an existing
# folder keeps the generator it was made with
configure() {
    local dir=$1
    shift
    lock "$dir"
    : >"$dir/$MARKER"
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
    lock "$dir"
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

# check_grade_args ARGS...: the options scripts/grade.sh takes, checked before any build
check_grade_args() {
    while (($#)); do
        case $1 in
            --timeout)
                [[ ${2:-} =~ ^[0-9]+([.][0-9]+)?$ && ! ${2:-} =~ ^0+([.]0+)?$ ]] ||
                    die "grade: --timeout needs a positive number of seconds, got '${2:-}'"
                shift ;;
            --points)
                [[ ${2:-} =~ ^[0-9]+([.][0-9]+)?$ ]] ||
                    die "grade: --points needs a number, got '${2:-}'"
                shift ;;
            --expect)
                [[ ${2:-} == full || ${2:-} == not-started ]] ||
                    die "grade: --expect needs full or not-started, got '${2:-}'"
                shift ;;
            --private)
                [[ -d ${2:-} ]] || die "grade: --private needs a folder, got '${2:-}'"
                shift ;;
            --reference | --trusted) ;;
            *) die "grade: unknown argument '$1' (--timeout S, --points N, --expect full|not-started, --private DIR, --trusted)" ;;
        esac
        shift
    done
}
