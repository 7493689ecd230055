#!/usr/bin/env bash
# Grades one hand-in, module by module. The student's files are staged in a private
# scratch folder outside the source tree, each compiled on its own (in a sandbox that sees
# only framework/include) and linked into one grading worker per module; the trusted
# graders (tests/grading/) call that worker and decide every score.
#
# Usage: scripts/grade.sh [--reference] [--timeout SECONDS] [--points N] [--expect MODE]
#                         [--private DIR]
#   (also: ./scripts/dev.sh grade, make grade, make grade-reference)
#   --reference        grade the reference solutions (solutions/) instead of exercises
#   --timeout SECONDS  limit per call to student code and for its start-up (default 10);
#                      a whole module stops after max(6 x SECONDS, 60 s) of wall time
#   --points N         points per module (default 10)
#   --expect MODE      exit 1 unless the scores are as expected: full, not-started (for CI
#                      and scripts/make-student-release.sh; see raylab-grade --help)
#   --private DIR      the instructor's private cases (hidden tests; never in a release)
#
# Environment:
#   SUBMISSION=DIR     grade the NN_name.cpp files found in DIR (a student's unzipped
#                      hand-in) instead of exercises/. For each module the shallowest
#                      NN_name.cpp up to two folders deep is used (the report names it);
#                      headers beside it are staged with it; CRLF line ends are accepted.
#                      A missing file, or one that does not compile or link, scores zero
#                      on its module with the compiler's message; the others are graded.
#   GRADE_OUT=DIR      where the reports go (default build/grade/): summary.txt, junit.xml,
#                      results.json (Gradescope), logs/, images/
#   GRADE_BUILD_DIR=DIR  the build of the trusted graders (default build-grade/), shared
#                      by concurrent runs (a lock serialises its updates)
#   GRADE_PRIVATE=DIR, GRADE_TIMEOUT=S, GRADE_POINTS=N  defaults for the options
#
# Several gradings may run at once (each has its own scratch folder; give each its own
# GRADE_OUT). Exit status: 0 when grading ran (whatever the scores), 1 when it could not
# (or when --expect was not met).
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

usage() { sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; }

# ---- Arguments ------------------------------------------------------------------------

reference=0
timeout=${GRADE_TIMEOUT:-10}
points=${GRADE_POINTS:-10}
private=${GRADE_PRIVATE:-}
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
        --private) private=${2:?--private needs a value}; shift ;;
        --private=*) private=${1#*=} ;;
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
[[ -z $private ]] || private=$(absolute "$private")
# The modules, from the registry
mapfile -t MODULES < <(sed -n 's/^RAYLAB_MODULE([a-z_0-9]*, "\([0-9][0-9]_[a-z_0-9]*\)".*/\1/p' \
    "$RAYLAB_ROOT/framework/include/raylab/modules.def")
((${#MODULES[@]})) || die "no modules in framework/include/raylab/modules.def"
# The untouched stubs stand in for a module that is missing or does not build: a student
# release ships them in tests/grading/stubs/; here exercises/ holds them
FALLBACK=$RAYLAB_ROOT/tests/grading/stubs
[[ -d $FALLBACK ]] || FALLBACK=$RAYLAB_ROOT/exercises

if ((reference)); then
    [[ -f $RAYLAB_ROOT/solutions/01_pixel_loop.cpp ]] ||
        die "there are no reference solutions (solutions/) in this copy, so --reference cannot run"
    [[ -z ${SUBMISSION:-} ]] || warn "--reference grades solutions/; SUBMISSION is ignored"
    SOURCE=''
    label="reference solutions (solutions/)"
elif [[ -n ${SUBMISSION:-} ]]; then
    SOURCE=$(absolute "$SUBMISSION")
    [[ -d $SOURCE ]] || die "SUBMISSION=$SUBMISSION is not a folder"
    label="submission $SOURCE"
else
    SOURCE=$RAYLAB_ROOT/exercises
    label="exercises/ ($SOURCE)"
fi

# A private scratch folder per run: staged files, objects, workers. Its name says nothing
# about grading: the sandbox's process list shows the worker's path
SCRATCH=$(mktemp -d)
trap 'rm -rf "$SCRATCH"' EXIT
mkdir -p "$SCRATCH/stage" "$SCRATCH/obj" "$SCRATCH/workers" "$OUT"
rm -rf "$OUT/logs" "$OUT/images" "$OUT/build-errors" "$OUT/results.json" "$OUT/junit.xml" \
    "$OUT/summary.txt"
mkdir -p "$OUT/logs" "$OUT/build-errors"

# ---- The trusted graders (shared build, locked) ----------------------------------------

step "Building the trusted graders in $BUILD/"
mkdir -p "$BUILD"
(
    flock 9
    if [[ ! -f $BUILD/build.ninja ]]; then
        cmake -S "$RAYLAB_ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release \
            -DRAYLAB_WITH_GUI=OFF -DRAYLAB_WERROR=OFF -DRAYLAB_EXERCISES_DIR="$FALLBACK" \
            >"$BUILD/configure.log" 2>&1 || { cat "$BUILD/configure.log"; exit 1; }
    fi
    targets=(raylab-grading-tests raylab-grade raylab_worker_main raylab_core)
    ((reference)) && targets+=(raylab-worker-reference)
    ninja -C "$BUILD" "${targets[@]}" >"$BUILD/build.log" 2>&1 || { tail -n 40 "$BUILD/build.log"; exit 1; }
    # The stubs' objects, for the modules a worker does not take from the hand-in
    # shellcheck disable=SC1091
    source "$BUILD/tests/grading/worker-toolchain.sh"
    mkdir -p "$BUILD/stub-objects"
    for id in "${MODULES[@]}"; do
        o=$BUILD/stub-objects/$id.o
        if [[ ! -f $o || $FALLBACK/$id.cpp -nt $o ]]; then
            # shellcheck disable=SC2086
            $CXX $CXXFLAGS -I"$INCLUDE" -c "$FALLBACK/$id.cpp" -o "$o.tmp" && mv "$o.tmp" "$o"
        fi
    done
) 9>"$BUILD/.grade.lock" || die "building the graders failed (see $BUILD/build.log)"
# shellcheck disable=SC1091
source "$BUILD/tests/grading/worker-toolchain.sh"
CXX=$(readlink -f "$CXX") # /usr/bin/c++ leads through /etc/alternatives, outside the sandbox

declare -A error=() # module -> file with the reason it scores zero
declare -A used=()  # module -> the hand-in's file that was graded
zero() {
    error[$1]=$OUT/build-errors/$1.txt
    printf '%s\n' "$2" >"${error[$1]}"
    note "$1: scores zero: $(head -n 1 "${error[$1]}")"
}
# At most 8 KB of a log, read from a file (never a pipe that could SIGPIPE its writer)
capped() { head -c 8000 "$1" | sed -e "s|$SCRATCH/stage/[^/]*/||g" -e 's|/hand-in/||g'; }

# ---- Staging: each module's file and the headers beside it ------------------------------

if [[ -n $SOURCE ]]; then
    step "Staging the exercise files of the $label"
    for id in "${MODULES[@]}"; do
        # The shallowest NN_name.cpp, at most two folders deep; ties by name
        found=$(find "$SOURCE" -maxdepth 3 -name "$id.cpp" -type f -printf '%d\t%p\n' \
            2>/dev/null | sort -t$'\t' -k1,1n -k2,2 | head -n 1 | cut -f2-) || true
        if [[ -z $found ]]; then
            zero "$id" "$id.cpp is missing from the hand-in"
            continue
        fi
        used[$id]=${found#"$SOURCE"/}
        dir=$SCRATCH/stage/$id
        mkdir -p "$dir"
        # Helper headers beside the file; CRLF line ends become LF
        for f in "$found" "$(dirname "$found")"/*.h "$(dirname "$found")"/*.hpp; do
            [[ -f $f ]] && sed 's/\r$//' "$f" >"$dir/$(basename "$f")"
        done
    done
fi

# ---- Compiling and linking one worker per module ----------------------------------------

# bubblewrap with a user namespace; where the kernel refuses one (a chroot, some containers)
# but we are root, the other namespaces without it and with every capability dropped (as
# the worker's sandbox does, tests/grading/worker_client.cpp)
sandbox=none
namespaces=()
for try in "--unshare-all" \
    "--unshare-pid --unshare-net --unshare-ipc --unshare-uts --unshare-cgroup-try --cap-drop ALL"; do
    [[ $try == --unshare-all || $EUID == 0 ]] || continue
    read -ra namespaces <<<"$try"
    if bwrap "${namespaces[@]}" --die-with-parent --ro-bind /usr /usr --symlink usr/lib /lib \
        --symlink usr/lib64 /lib64 --symlink usr/bin /bin /usr/bin/true 2>/dev/null; then
        sandbox=bwrap
        break
    fi
done

# Compiles $1 (a staged file) to $2: in a sandbox that sees /usr, framework/include and
# the staged folder only, so that no path leads to solutions/
compile() {
    local src=$1 obj=$2 dir
    dir=$(dirname "$src")
    if [[ $sandbox == bwrap ]]; then
        bwrap "${namespaces[@]}" --die-with-parent --new-session --ro-bind /usr /usr \
            --symlink usr/lib /lib --symlink usr/lib64 /lib64 --symlink usr/bin /bin \
            --ro-bind-try /etc/ld.so.cache /etc/ld.so.cache --proc /proc --dev /dev \
            --tmpfs /tmp --ro-bind "$INCLUDE" /raylab/include --ro-bind "$dir" /hand-in \
            --bind "$(dirname "$obj")" /out --chdir /hand-in --clearenv \
            --setenv PATH /usr/bin \
            timeout 120 "$CXX" $CXXFLAGS -I/raylab/include -c "/hand-in/$(basename "$src")" \
            -o "/out/$(basename "$obj")"
    else
        # No namespaces: a copy of the headers, so that no relative path from the include
        # folder reaches solutions/ (an absolute path still would: the nm check remains)
        [[ -d $SCRATCH/include ]] || cp -r "$INCLUDE" "$SCRATCH/include"
        (cd "$dir" && timeout 120 env -i PATH=/usr/bin "$CXX" $CXXFLAGS -I"$SCRATCH/include" \
            -c "$src" -o "$obj")
    fi
}

# Files that are byte for byte the same (the untouched stubs of a class, a regrade) are
# compiled and linked once. The key of an object hashes the compiler, its flags, the
# sandbox, the framework headers and every staged file of the module; the key of a worker
# hashes its object and everything linked with it. Only this script writes the cache (the
# sandboxed compiler writes to the scratch folder), and entries unused for 30 days go.
CACHE=$BUILD/object-cache
mkdir -p "$CACHE"
find "$CACHE" -type f -mtime +30 -delete 2>/dev/null || true
hash_files() { (cd "$1" && find . -type f -print0 | LC_ALL=C sort -z | xargs -0 -r sha256sum); }
key_of() { sha256sum | cut -d' ' -f1; }
TOOL_KEY=$({ "$CXX" --version; printf '%s\n' "$CXXFLAGS" "$sandbox"; hash_files "$INCLUDE"; } | key_of)
LINK_KEY=$({ sha256sum "$BUILD"/stub-objects/*.o "$WORKER_MAIN" "$CORE" | cut -d' ' -f1
    printf '%s\n' "$LIBS" "$TOOL_KEY"; } | key_of)

# Copies cache entry $1 to $2 (true when there is one)
from_cache() { [[ -s $CACHE/$1 ]] && touch "$CACHE/$1" && cp "$CACHE/$1" "$2"; }
# Stores $2 as cache entry $1 (atomically: several gradings share the cache)
to_cache() { cp "$2" "$CACHE/$1.$$" && mv -f "$CACHE/$1.$$" "$CACHE/$1"; }

# compile, through the cache
compile_cached() {
    local key
    key=$({ echo "$TOOL_KEY"; hash_files "$(dirname "$1")"; } | key_of).o
    from_cache "$key" "$2" && return 0
    compile "$1" "$2" && to_cache "$key" "$2"
}

# Links worker $2 of module $1 from object $3 and the stubs of the other modules
link_cached() {
    local id=$1 worker=$2 obj=$3 key other stubs=()
    key=$({ echo "$LINK_KEY $id"; sha256sum <"$obj"; } | key_of).worker
    from_cache "$key" "$worker" && return 0
    for other in "${MODULES[@]}"; do
        [[ $other == "$id" ]] || stubs+=("$BUILD/stub-objects/$other.o")
    done
    # shellcheck disable=SC2086
    "$CXX" -o "$worker" "$obj" "${stubs[@]}" "$WORKER_MAIN" "$CORE" $LIBS && to_cache "$key" "$worker"
}

if ((reference)); then
    for id in "${MODULES[@]}"; do
        ln -s "$BUILD/tests/grading/raylab-worker-reference" "$SCRATCH/workers/$id"
    done
else
    step "Compiling each exercise file on its own and linking its worker"
    for id in "${MODULES[@]}"; do
        [[ -n ${error[$id]:-} ]] && continue
        obj=$SCRATCH/obj/$id.o
        log=$SCRATCH/obj/$id.log
        # shellcheck disable=SC2086
        if ! compile_cached "$SCRATCH/stage/$id/$id.cpp" "$obj" >"$log" 2>&1; then
            zero "$id" "$id.cpp does not compile: $(capped "$log" | grep -m 1 'error')
$(capped "$log")"
            continue
        fi
        # The reference is never part of a hand-in: defined, included or called
        refs=$(nm -C "$obj" | grep -o 'raylab::reference::[a-z_0-9]*' | sort -u | paste -sd ' ') || true
        if [[ -n $refs ]]; then
            zero "$id" "$id.cpp refers to the reference solution ($refs), which is not allowed"
            continue
        fi
        # Nothing of the hand-in may run before the worker's seccomp filter (a constructor
        # of priority 101 in worker_main.cpp): no constructor priorities, no code in .init
        # or .preinit_array, no ifunc resolvers (they run while the loader relocates)
        early=$({
            readelf -SW "$obj" | sed -n 's/^ *\[ *[0-9]*\] \([^ ]*\).*/\1/p' |
                grep -E '^(\.rela)?\.(preinit_array|init|ctors|init_array\.[0-9]+|ctors\.[0-9]+)$'
            readelf -sW "$obj" | awk '$4 == "IFUNC" { print "ifunc " $8 }'
        } | sort -u | paste -sd ' ') || true
        if [[ -n $early ]]; then
            zero "$id" "$id.cpp has code that would run before the grader's sandbox is complete ($early): constructor priorities, .init sections and ifuncs are not allowed"
            continue
        fi
        if ! link_cached "$id" "$SCRATCH/workers/$id" "$obj" >"$log" 2>&1; then
            zero "$id" "$id.cpp does not link with the framework (is a function missing, defined with another signature, or defined twice?)
$(capped "$log" | grep -e 'undefined reference' -e 'multiple definition' -e 'error' | head -n 20)"
        fi
    done
    chmod -R a+rX "$SCRATCH"
fi

# ---- Grading ---------------------------------------------------------------------------

args=(--tests "$BUILD/tests/grading/raylab-grading-tests" --out "$OUT" --timeout "$timeout"
    --points "$points" --label "$label" --workers "$SCRATCH/workers")
((reference)) && args+=(--reference)
[[ -n $expect ]] && args+=(--expect "$expect")
[[ -n $private ]] && args+=(--private "$private")
for id in "${!error[@]}"; do args+=(--module-error "$id=${error[$id]}"); done
for id in "${!used[@]}"; do args+=(--source "$id=${used[$id]}"); done

step "Grading, one process per module (${timeout} s per call to student code)"
"$BUILD/tests/grading/raylab-grade" "${args[@]}"
