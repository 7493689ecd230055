#!/usr/bin/env bash
# Grades one hand-in, module by module. The student's files are staged in a private
# scratch folder outside the source tree, each compiled on its own (in a sandbox that sees
# only framework/include) and linked into one grading worker per module; the trusted
# graders (tests/grading/) call that worker and decide every score.
#
# Usage: scripts/grade.sh [--reference] [--timeout SECONDS] [--points N] [--expect MODE]
#                         [--private DIR] [--trusted]
#   (also: ./scripts/dev.sh grade, make grade, make grade-reference)
#   --reference        grade the reference solutions (solutions/) instead of exercises
#   --timeout SECONDS  CPU time limit per module (default 10; its clock time may be 6 times
#                      that, so that a busy machine does not fail honest code)
#   --points N         points per module (default 10)
#   --expect MODE      exit 1 unless the scores are as expected: full, not-started (for CI
#                      and scripts/make-student-release.sh; see raylab-grade --help)
#   --private DIR      the instructor's private cases (hidden tests; never in a release).
#                      Never inside the hand-in; no student compile or process can read it
#   --trusted          grade a SUBMISSION even where the hand-in's compile cannot be
#                      confined (no bubblewrap, no Landlock): for hand-ins you trust only
#
# Environment:
#   SUBMISSION=DIR     grade the NN_name.cpp files found in DIR (a student's unzipped
#                      hand-in) instead of exercises/ (DIR may be a link to the folder).
#                      For each module the shallowest NN_name.cpp up to two folders deep
#                      is used (the report names it, and any other copy it ignored); the
#                      .h/.hpp headers beside it are staged with it; CRLF line ends are
#                      accepted. Only regular files are taken, never through a link, at
#                      most 1 MiB each and 8 MiB in all: a link, FIFO, device or socket is
#                      refused with a note naming it. A missing file, or one that does not
#                      compile or link, scores zero on its module with the reason; the
#                      others are graded.
#   GRADE_OUT=DIR      where the reports go (default build/grade/): summary.txt, junit.xml,
#                      results.json (Gradescope), logs/, images/
#   GRADE_BUILD_DIR=DIR  the build of the trusted graders (default build-grade/), shared
#                      by concurrent runs (a lock serialises its updates)
#   GRADE_PRIVATE=DIR, GRADE_TIMEOUT=S, GRADE_POINTS=N  defaults for the options
#   GRADE_COMPILE_MEMORY_MB=N  address space of the sandboxed compiler (default 2048; it
#                      also gets 120 s of CPU and writes 64 MiB at most)
#   RAYLAB_SANDBOX=none  compile and run the hand-in without bubblewrap, as happens where
#                      it cannot start: the compile is then confined with Landlock to /usr,
#                      the public headers and the staged hand-in (without Landlock a
#                      SUBMISSION needs --trusted); as root the compiler and worker run as
#                      nobody, solutions/, the graders' build and --private DIR are closed
#                      to other users (chmod go-rwx), and nobody's SysV IPC objects are
#                      removed after grading
#   RAYLAB_LANDLOCK=off  do not use Landlock (to see what a machine without it does)
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
# Address space of the sandboxed compiler, in MiB (a 64 MiB object file at most)
COMPILE_MEMORY_MB=${GRADE_COMPILE_MEMORY_MB:-2048}
points=${GRADE_POINTS:-10}
private=${GRADE_PRIVATE:-}
expect=''
trusted=0
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
        --trusted) trusted=1 ;;
        -h | --help) usage; exit 0 ;;
        *) usage >&2; die "unknown option '$1'" ;;
    esac
    shift
done

# Checked before anything is built
[[ $timeout =~ ^[0-9]{1,4}(\.[0-9]+)?$ && $timeout != 0 && ! $timeout =~ ^0+(\.0*)?$ ]] ||
    die "--timeout needs a positive number of seconds (at most 9999), not '$timeout'"
[[ $points =~ ^[0-9]{1,6}(\.[0-9]+)?$ ]] || die "--points needs a number, not '$points'"
[[ -z $expect || $expect =~ ^(full|not-started|faults)$ ]] ||
    die "--expect takes full, not-started or faults, not '$expect'"
[[ -z $private || -d $private ]] || die "--private $private is not a folder"
[[ $COMPILE_MEMORY_MB =~ ^[1-9][0-9]{2,5}$ ]] ||
    die "GRADE_COMPILE_MEMORY_MB needs a number of MiB (at least 100), not '$COMPILE_MEMORY_MB'"

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
    # A link to the hand-in's folder (the instructor's choice, not the student's) is
    # resolved: the hand-in is the folder it names
    SOURCE=$(cd -P "$SOURCE" && pwd)
    label="submission $SOURCE"
    if [[ -n $private ]]; then
        p=$(cd -P "$private" && pwd)
        [[ $p/ != "$SOURCE"/* && $SOURCE/ != "$p"/* ]] ||
            die "--private $private and the hand-in $SOURCE must not contain each other"
    fi
else
    SOURCE=$RAYLAB_ROOT/exercises
    label="exercises/ ($SOURCE)"
fi

# A private scratch folder per run: staged files, objects, workers. Its name says nothing
# about grading: the sandbox's process list shows the worker's path
SCRATCH=$(mktemp -d)
trap 'rm -rf "$SCRATCH"' EXIT
mkdir -p "$SCRATCH/stage" "$SCRATCH/obj" "$SCRATCH/out" "$SCRATCH/workers" "$OUT"
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
    targets=(raylab-grading-tests raylab-grade raylab-sandbox raylab_worker_main raylab_core)
    ((reference)) && targets+=(raylab-worker-reference)
    ninja -C "$BUILD" "${targets[@]}" >"$BUILD/build.log" 2>&1 || { tail -n 40 "$BUILD/build.log"; exit 1; }
    # The stubs' objects, for the modules a worker does not take from the hand-in
    # shellcheck disable=SC1091
    source "$BUILD/grading/worker-toolchain.sh"
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
source "$BUILD/grading/worker-toolchain.sh"
CXX=$(readlink -f "$CXX") # /usr/bin/c++ leads through /etc/alternatives, outside the sandbox

declare -A error=() # module -> file with the reason it scores zero
declare -A used=()  # module -> the hand-in's file that was graded
notes=()            # ID<TAB>text: what the student should know (ID "-": the hand-in)
# Text for the terminal: control characters, the C1 controls (U+009B is a CSI), the line
# and paragraph separators and the bidirectional controls as \u{hex}, as in the reports
shown_safe() {
    # shellcheck disable=SC2016 # a perl program
    perl -MEncode -ne 'my $t = decode("UTF-8", $_);
        $t =~ s/([\x00-\x08\x0b-\x1f\x7f-\x9f\x{2028}\x{2029}\x{200e}\x{200f}\x{202a}-\x{202e}\x{2066}-\x{2069}\x{feff}])/sprintf("\\u{%x}", ord $1)/ge;
        print encode("UTF-8", $t)'
}
zero() {
    error[$1]=$OUT/build-errors/$1.txt
    printf '%s\n' "$2" >"${error[$1]}"
    note "$1: scores zero: $(head -n 1 "${error[$1]}" | shown_safe)"
}
# At most 8 KB of a log, read from a file (never a pipe that could SIGPIPE its writer)
capped() { head -c 8000 "$1" | sed -e "s|$SCRATCH/stage/[^/]*/||g" -e 's|/hand-in/||g'; }
# The compiler's lines about the hand-in's own files (the staged folder $2), indented, at
# most 60 of 300 characters each; every other line (about a system header, or a file
# outside the hand-in that a hostile #include named, with its contents) is only counted
quoted() {
    local own
    own=$(cd "$2" && find . -maxdepth 1 -type f -printf '%f/')
    sed -e "s|$SCRATCH/stage/[^/]*/||g" -e 's|/hand-in/||g' "$1" | awk -v files="$own" '
        function show(s) { if (shown < 60) { print "    " substr(s, 1, 300); shown++ } else hidden++ }
        BEGIN { n = split(files, f, "/"); for (i = 1; i <= n; i++) if (f[i] != "") own[f[i]] = 1 }
        {
            line = $0; sub(/^In file included from /, "", line); sub(/^ +from /, "", line)
            name = line; sub(/:.*/, "", name)
            # a source excerpt or caret line belongs to the diagnostic above it
            if ($0 ~ /^ *[0-9]* *[|]/ || $0 ~ /^ +[+~^]/) { if (keep) show($0); else hidden++; next }
            keep = (name in own) && line ~ /^[^:]+:/
            if (keep) show($0); else hidden++
        }
        END { if (hidden) printf "    (%d more lines of compiler output not shown: not about the hand-in'"'"'s own files, or past the first 60)\n", hidden }'
}

# ---- The sandbox: bubblewrap, or Landlock without namespaces -----------------------------

# bubblewrap with a user namespace (the hand-in's compiler then runs as nobody inside it);
# where the kernel refuses one (a chroot, some containers) but we are root, the other
# namespaces without it and with every capability dropped (as the worker's sandbox does,
# grading/worker_client.cpp)
sandbox=none
namespaces=()
# RAYLAB_SANDBOX=none (as for the worker, worker_client.cpp) grades without namespaces, as
# where bubblewrap cannot start (Docker's default profile)
for try in "--unshare-all --uid 65534 --gid 65534" \
    "--unshare-pid --unshare-net --unshare-ipc --unshare-uts --unshare-cgroup-try --cap-drop ALL"; do
    [[ ${RAYLAB_SANDBOX:-auto} != none ]] || break
    [[ $try == --unshare-all* || $EUID == 0 ]] || continue
    read -ra namespaces <<<"$try"
    if bwrap "${namespaces[@]}" --die-with-parent --ro-bind /usr /usr --symlink usr/lib /lib \
        --symlink usr/lib64 /lib64 --symlink usr/bin /bin /usr/bin/true 2>/dev/null; then
        sandbox=bwrap
        break
    fi
done
# Without namespaces the compile is confined by Landlock and the worker by seccomp; where
# either is missing, nothing keeps a hostile hand-in's compile from reading any file its
# user may read, and a SUBMISSION is graded only when the instructor says it is trusted
landlock=0
[[ ${RAYLAB_LANDLOCK:-auto} == off ]] || ! "$SANDBOX" check || landlock=1
if [[ $sandbox == none && -n $SOURCE && $SOURCE != "$RAYLAB_ROOT/exercises" ]]; then
    missing=()
    ((landlock)) || missing+=("Landlock (Linux 5.13 or later, enabled)")
    [[ $LIBS == *-lseccomp* ]] || missing+=("libseccomp (scripts/install-deps.sh libs)")
    if ((${#missing[@]})); then
        msg="bubblewrap cannot start here and this machine lacks ${missing[*]}: a hand-in's compile could read any file its user can read"
        ((trusted)) || die "$msg. Not grading an untrusted hand-in; pass --trusted to grade it anyway"
        warn "$msg (graded anyway: --trusted)"
    fi
fi
if [[ $sandbox == none && $EUID == 0 ]]; then
    note "no namespaces here: the hand-in's compiler and worker run as nobody$( ((landlock)) && echo ', the compiler and the worker confined by Landlock')"
fi

# Runs COMMAND... where it sees /usr, the public headers (at /raylab/include), the folder
# $1 read-only (at /hand-in) and $2 read-write (at /out): in bubblewrap, or else under
# Landlock (as nobody when root). Standard input is /dev/null: a compile that reads
# "/dev/stdin" gets nothing, and never what the grader's terminal types
contained() {
    local ro=$1 rw=$2
    shift 2
    if [[ $sandbox == bwrap ]]; then
        bwrap "${namespaces[@]}" --die-with-parent --new-session --ro-bind /usr /usr \
            --symlink usr/lib /lib --symlink usr/lib64 /lib64 --symlink usr/bin /bin \
            --ro-bind-try /etc/ld.so.cache /etc/ld.so.cache --tmpfs /tmp \
            --ro-bind "$INCLUDE" /raylab/include --ro-bind "$ro" /hand-in \
            --bind "$rw" /out --chdir /hand-in --clearenv --setenv PATH /usr/bin \
            --setenv TMPDIR /out "$@" </dev/null
    else
        local confine=() user=()
        ((landlock)) && confine=("$SANDBOX" run --ro /usr --ro /etc/ld.so.cache \
            --ro "$SCRATCH/include" --ro "$ro" --rw "$rw" --)
        if ((EUID == 0)); then
            chmod 755 "$SCRATCH" "$(dirname "$rw")"
            chmod -R a+rX "$SCRATCH/include" "$ro"
            chown 65534:65534 "$rw"
            user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
        fi
        (cd "$ro" && env -i PATH=/usr/bin HOME=/ TMPDIR="$rw" "${user[@]}" "${confine[@]}" \
            "$@" </dev/null)
    fi
}

# ---- Staging: each module's file and the headers beside it ------------------------------

if [[ -n $SOURCE ]]; then
    step "Staging the exercise files of the $label"
    # raylab-sandbox stage opens nothing through a link and takes regular files only (see
    # grading/sandbox_main.cpp); in bubblewrap it sees the hand-in and the stage only
    if [[ $sandbox == bwrap ]]; then
        stage=(bwrap "${namespaces[@]}" --die-with-parent --new-session --ro-bind /usr /usr
            --symlink usr/lib /lib --symlink usr/lib64 /lib64 --ro-bind "$SANDBOX" /stage-tool
            --ro-bind-try /etc/ld.so.cache /etc/ld.so.cache --ro-bind "$SOURCE" /hand-in
            --bind "$SCRATCH/stage" /stage --clearenv /stage-tool stage /hand-in /stage)
    else
        stage=("$SANDBOX" stage "$SOURCE" "$SCRATCH/stage")
    fi
    "${stage[@]}" "${MODULES[@]}" </dev/null >"$SCRATCH/staged.tsv" 2>"$SCRATCH/stage.log" ||
        die "staging the hand-in failed: $(head -c 2000 "$SCRATCH/stage.log")"
    while IFS=$'\t' read -r kind id text; do
        case $kind in
            used) used[$id]=$text ;;
            missing) zero "$id" "$text" ;;
            note) notes+=("$id"$'\t'"$text"); note "${id/#-/hand-in}: $text" ;;
        esac
    done <"$SCRATCH/staged.tsv"
fi

# ---- Compiling and linking one worker per module ----------------------------------------

# Compiles $1 (a staged file) to $2, contained (above): no path leads to solutions/ or
# any other file outside /usr, the public headers and the staged folder. The compiler
# gets the limits of a worker too: an endless #include "/dev/zero" or a huge array would
# otherwise take all the grading machine's memory or disk for the 120 s of its time limit
compile() {
    local src=$1 obj=$2 dir out
    dir=$(dirname "$src")
    ulimit -v $((COMPILE_MEMORY_MB * 1024)) -f $((64 * 1024)) -t 120 -c 0
    out=$SCRATCH/out/$(basename "$obj" .o)
    rm -rf "$out" && mkdir -p "$out"
    if [[ $sandbox == bwrap ]]; then
        # shellcheck disable=SC2086
        contained "$dir" "$out" timeout 120 "$CXX" $CXXFLAGS -I/raylab/include \
            -MD -MF /out/out.d -c "/hand-in/$(basename "$src")" -o /out/out.o || return
        sed -e 's|/hand-in/|@HANDIN@/|g' -e 's|/raylab/include/|@INCLUDE@/|g' "$out/out.d" >"$obj.d"
    else
        # No namespaces: a copy of the headers, so that no relative path from the include
        # folder reaches solutions/
        [[ -d $SCRATCH/include ]] || cp -r "$INCLUDE" "$SCRATCH/include"
        # shellcheck disable=SC2086
        contained "$dir" "$out" timeout 120 "$CXX" $CXXFLAGS -I"$SCRATCH/include" \
            -MD -MF "$out/out.d" -c "$src" -o "$out/out.o" || return
        sed -e "s|$dir/|@HANDIN@/|g" -e "s|$SCRATCH/include/|@INCLUDE@/|g" "$out/out.d" >"$obj.d"
    fi
    cp "$out/out.o" "$obj"
}

# Without namespaces a root grader closes solutions/, its own build and the private
# cases to other users: the hand-in's compiler and worker run as nobody, and must not
# read the reference's source or objects, nor the secret seed
if [[ $sandbox == none && $EUID == 0 ]]; then
    for d in "$RAYLAB_ROOT/solutions" "$BUILD" ${private:+"$private"}; do
        if [[ -d $d && -n $(find "$d" -maxdepth 0 -perm /o=rwx) ]]; then
            chmod go-rwx "$d"
            note "no namespaces here: $d is now closed to other users (chmod go-rwx)"
        fi
    done
fi

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
TOOL_KEY=$({ "$CXX" --version; printf '%s\n' "$CXXFLAGS" "$sandbox" "compiled-as-nobody-when-root" "$landlock"; hash_files "$INCLUDE"; } | key_of)
LINK_KEY=$({ sha256sum "$BUILD"/stub-objects/*.o "$WORKER_MAIN" "$CORE" | cut -d' ' -f1
    printf '%s\n' "$LIBS" "$TOOL_KEY"; } | key_of)

# Copies cache entry $1 to $2 (true when there is one)
from_cache() { [[ -s $CACHE/$1 ]] && touch "$CACHE/$1" && cp "$CACHE/$1" "$2"; }
# Stores $2 as cache entry $1 (atomically: several gradings share the cache)
to_cache() { cp "$2" "$CACHE/$1.$$" && mv -f "$CACHE/$1.$$" "$CACHE/$1"; }

# compile (in a subshell: its limits stay there), through the cache. Only a compile that
# read nothing but the staged files, the public headers and the compiler's own headers is
# stored: its object is exactly the one a new compile would make
compile_cached() {
    local key dir=${1%/*}
    key=$({ echo "$TOOL_KEY"; hash_files "$dir"; } | key_of).o
    from_cache "$key" "$2" && return 0
    (compile "$1" "$2") || return
    # An asm statement may read a file (.incbin, also spelt ".inc" "bin" or pasted
    # together by a macro): never cached, like #embed
    grep -rqE 'asm|incbin|embed|##' "$dir" && return 0
    tr ' \\' '\n\n' <"$2.d" | grep -v -e '^$' -e ':$' -e '^@HANDIN@/' -e '^@INCLUDE@/' \
        -e '^/usr/include/' -e '^/usr/lib/gcc/' | grep . >/dev/null && return 0
    to_cache "$key" "$2"
}

# Every symbol the worker's libraries and trusted objects define or look up: a hand-in
# object that defines one too (of any kind: a weak object, a GNU unique global) would take
# its place for code that runs before the sandbox is complete, such as the seccomp
# filter's own setup. Names are compared, not kinds
LIBRARY_SYMBOLS=$SCRATCH/library-symbols
{
    for l in c.so.6 m.so.6 stdc++.so gcc_s.so.1 seccomp.so tinyobjloader.so; do
        f=$(readlink -f "$("$CXX" -print-file-name="lib$l")")
        [[ -f $f ]] && nm -D "$f" 2>/dev/null
    done
    nm -g --defined-only "$CORE" "$WORKER_MAIN" 2>/dev/null
} | awk '{ n = $NF; sub(/@.*/, "", n); if (n != "" && n !~ /:$/) print n }' |
    LC_ALL=C sort -u >"$LIBRARY_SYMBOLS"
[[ $(wc -l <"$LIBRARY_SYMBOLS") -gt 1000 ]] || die "could not list the worker's library symbols (nm)"

# The first directive in the staged files of folder $1 that names a file outside it:
# #include, #include_next, #import, #embed, __has_include(_next), __has_embed, #pragma GCC
# dependency (also through _Pragma), with an absolute name, a ".." or a computed one.
# Prints "FILE:LINE" (after comments are removed and digraphs and trigraphs read as #)
outside_names() {
    # shellcheck disable=SC2016 # a perl program
    (cd "$1" && find . -maxdepth 1 -type f -printf '%f\0' | LC_ALL=C sort -z |
        xargs -0 -r perl -0777 -ne '
            my $t = $_;
            $t =~ s/\r//g;
            $t =~ s{/\*(.*?)\*/}{my $c = $1; " " . ("\n" x ($c =~ tr/\n//))}gse;
            $t =~ s{//[^\n]*}{}g;
            $t =~ s/\\\n/ /g;
            $t =~ s/%:|\?\?=/#/g;
            my $n = 0;
            for my $line (split /\n/, $t, -1) {
                $n++;
                my @args;
                push @args, $1 if $line =~ /^\s*#\s*(?:include|include_next|import|embed)\b\s*(.*)/;
                push @args, $1 while $line =~ /__has_(?:include|include_next|embed)\s*\(\s*([^)]*)/g;
                my $bad = $line =~ /^\s*#\s*pragma\s+GCC\s+dependency\b/ ||
                    $line =~ /_Pragma\s*\(.*dependency/;
                for my $a (@args) {
                    my ($p) = $a =~ /^(?:"([^"]*)"|<([^>]*)>)/ ? ($1 // $2) : (undef);
                    $bad ||= !defined $p || $p =~ m{^/} || $p =~ m{(^|/)\.\.(/|$)};
                }
                if ($bad) { print "$ARGV:$n\n"; exit 0; }
            }') | sed -n 1p
}

declare -A compiled=() # module -> its object, compiled and checked
# The functions object $1 calls but does not define; and those it defines
calls() { nm -u --format=posix "$1" | awk '{ print $1 }' | sort -u; }
defines() { nm --defined-only --format=posix "$1" | awk '$2 ~ /^[TWtwVv]$/ { print $1 }' | sort -u; }

# Links worker $2 of module $1 from object $3 and, for the other modules, the stubs
# ($4 = stubs) or ($4 = own) the hand-in's own objects of the modules it calls, directly
# or through another (a module built on the student's earlier modules gets the student's
# code for them, as in the viewer); a module it does not call stays a stub, so that its
# static initializers do not run in this module's worker
link_cached() {
    local id=$1 worker=$2 obj=$3 mode=$4 key other others=() grown=1
    declare -A own=([$id]=1)
    while [[ $mode == own ]] && ((grown)); do
        grown=0
        for other in "${!own[@]}"; do cat "${compiled[$other]}.calls"; done | sort -u >"$obj.all-calls"
        for other in "${MODULES[@]}"; do
            [[ -n ${own[$other]:-} || -z ${compiled[$other]:-} ]] && continue
            if comm -12 "${compiled[$other]}.defines" "$obj.all-calls" | grep . >/dev/null; then
                own[$other]=1 grown=1
            fi
        done
    done
    for other in "${MODULES[@]}"; do
        [[ $other == "$id" ]] && continue
        if [[ -n ${own[$other]:-} ]]; then
            others+=("${compiled[$other]}")
        else
            others+=("$BUILD/stub-objects/$other.o")
        fi
    done
    key=$({ echo "$LINK_KEY worker-main-first $id"; cat "$obj" "${others[@]}" | sha256sum; } | key_of).worker
    from_cache "$key" "$worker" && return 0
    # shellcheck disable=SC2086
    # The worker's own objects first: of the template and inline code that both they and
    # the hand-in emit, the linker keeps the first copy, so the code that installs the
    # sandbox runs the grader's copy
    "$CXX" -o "$worker" -Wl,--whole-archive "$WORKER_MAIN" -Wl,--no-whole-archive "$obj" \
        "${others[@]}" "$CORE" $LIBS && to_cache "$key" "$worker"
}

if ((reference)); then
    for id in "${MODULES[@]}"; do
        cp "$BUILD/grading/raylab-worker-reference" "$SCRATCH/workers/$id"
    done
else
    step "Compiling each exercise file on its own and linking its worker"
    for id in "${MODULES[@]}"; do
        [[ -n ${error[$id]:-} ]] && continue
        obj=$SCRATCH/obj/$id.o
        log=$SCRATCH/obj/$id.log
        # A file named by an absolute path or one with "..": without namespaces, Landlock
        # refuses to open an outside file that exists while a missing one is merely not
        # found, so even __has_include would tell the student whether a path exists.
        # Computed names (a macro) are refused too: the name is only known after expansion
        where=$(outside_names "$SCRATCH/stage/$id") || true
        if [[ -n $where ]]; then
            zero "$id" "$where: only the hand-in's own files and the public headers may be included, by a plain relative name (no absolute path, no \"..\", no macro)"
            continue
        fi
        # shellcheck disable=SC2086
        status=0
        compile_cached "$SCRATCH/stage/$id/$id.cpp" "$obj" >"$log" 2>&1 || status=$?
        if ((status != 0)); then
            quoted "$log" "$SCRATCH/stage/$id" >"$log.quoted"
            first=$(grep -m 1 -E 'error|out of memory|memory exhausted' "$log.quoted") ||
                if grep -q '^{standard input}: Assembler messages' "$log"; then
                    first="the assembler stopped: an asm statement (.incbin of a file outside the hand-in?)"
                else
                    first="the compiler stopped (status $status) without a message about the hand-in's files"
                fi
            first=${first#"    "}
            if grep -q -E 'out of memory|memory exhausted|File size limit' "$log" ||
                ((status == 124 || status > 128)); then
                first="$first (the compiler's limits: $COMPILE_MEMORY_MB MiB of memory, 120 s, a 64 MiB object)"
            fi
            zero "$id" "$id.cpp does not compile: $first
$(cat "$log.quoted")"
            continue
        fi
        # The reference is never part of a hand-in: defined, included or called
        refs=$(nm -C "$obj" | grep -o 'raylab::reference::[a-z_0-9]*' | sort -u | paste -sd ' ') || true
        if [[ -n $refs ]]; then
            zero "$id" "$id.cpp refers to the reference solution ($refs), which is not allowed"
            continue
        fi
        # Nothing of the hand-in may run before the worker's seccomp filter (a constructor
        # of priority 101 in worker_main.cpp): no constructor priorities (GNU ld sorts any
        # .init_array.SUFFIX, ".init_array.00001x" too, by the number it starts with), no
        # code in .init or .preinit_array, no ifunc resolvers (they run while the loader
        # relocates), and no definition of a C-level or C++ runtime symbol (malloc,
        # operator new, std::...): the shared libraries' own initializers, which run before
        # the worker's, would call the hand-in's copy
        early=$({
            readelf -SW "$obj" | sed -n 's/^ *\[ *[0-9]*\] \([^ ]*\).*/\1/p' |
                grep -E '^(\.rela)?\.(preinit_array|init|ctors|dtors|init_array\..*|ctors\..*|preinit_array\..*)$'
            readelf -sW "$obj" | awk '$4 == "IFUNC" { print "ifunc " $8 }'
            # C-level names: no function, nothing weak or unique (a C++ file's own
            # functions are mangled; its global variables may stay, unless a library
            # knows their name). Mangled names a library knows too: only the weak
            # template and inline definitions of the standard library, glm and the
            # framework's headers, which every file that uses them emits (COMDAT)
            nm -g --defined-only "$obj" | awk 'NF == 3 { print $3, $2 }' | LC_ALL=C sort -u |
                LC_ALL=C join -a 1 -o 0,1.2,2.1 -e - - "$LIBRARY_SYMBOLS" | awk '
                    $1 == "DW.ref.__gxx_personality_v0" && $2 == "V" { next }
                    $1 !~ /^_Z/ && ($2 ~ /^[TtWwVvuiI]$/ || $3 != "-") { print "symbol " $1; next }
                    $1 ~ /^_Z/ && $3 != "-" && !($2 ~ /^[WVu]$/ &&
                        $1 ~ /^_Z(T[VIS]|GV|TH|TW)?Z?N?K?(St|Sa|Sb|Ss|Si|So|Sd|9__gnu_cxx|3glm|6raylab)/) {
                        print "symbol " $1 }' | c++filt
            nm -g --defined-only "$obj" | awk 'NF == 3 && ($3 ~ /^_Z(nw|na|dl|da)/ ||
                ($2 !~ /^[WVu]$/ && $3 ~ /^_Z(N|NK)?(St|Sa|Sb|Ss|Si|So|Sd|N9__gnu_cxx|N10__cxxabiv1)/)) {
                    print "symbol " $3 }' | c++filt
        } | sort -u | paste -sd ' ') || true
        if [[ -n $early ]]; then
            zero "$id" "$id.cpp has code that would run before the grader's sandbox is complete ($early): constructor priorities, .init sections, ifuncs and definitions of C library or C++ runtime functions are not allowed"
            continue
        fi
        compiled[$id]=$obj
        calls "$obj" >"$obj.calls"
        defines "$obj" >"$obj.defines"
    done
    for id in "${MODULES[@]}"; do
        [[ -n ${compiled[$id]:-} ]] || continue
        log=$SCRATCH/obj/$id.log
        # With the hand-in's other modules; where they clash (a function defined in two
        # files), with the stubs
        link_cached "$id" "$SCRATCH/workers/$id" "${compiled[$id]}" own >"$log" 2>&1 && continue
        if ! link_cached "$id" "$SCRATCH/workers/$id" "${compiled[$id]}" stubs >"$log" 2>&1; then
            zero "$id" "$id.cpp does not link with the framework (is a function missing, defined with another signature, or defined twice?)
$(capped "$log" | grep -e 'undefined reference' -e 'multiple definition' -e 'error' | head -n 20 | sed 's/^/    /')"
        fi
    done
fi
# Without namespaces the worker runs as nobody, under Landlock where the kernel has it
# (worker_client.cpp): a copy of raylab-sandbox outside the closed build folder
if [[ $sandbox == none ]] && ((landlock)); then
    cp "$SANDBOX" "$SCRATCH/raylab-sandbox"
    export RAYLAB_WORKER_LANDLOCK=$SCRATCH/raylab-sandbox
fi
chmod -R a+rX "$SCRATCH" # a worker without namespaces runs as nobody

# ---- Grading ---------------------------------------------------------------------------

args=(--tests "$BUILD/tests/grading/raylab-grading-tests" --out "$OUT" --timeout "$timeout"
    --points "$points" --label "$label" --workers "$SCRATCH/workers")
((reference)) && args+=(--reference)
[[ -n $expect ]] && args+=(--expect "$expect")
[[ -n $private ]] && args+=(--private "$private")
for id in "${!error[@]}"; do args+=(--module-error "$id=${error[$id]}"); done
for id in "${!used[@]}"; do args+=(--source "$id=${used[$id]}"); done
for n in "${notes[@]}"; do args+=(--note "${n%%$'\t'*}=${n#*$'\t'}"); done

step "Grading, one process per module (time limit ${timeout} s each)"
status=0
"$BUILD/grading/raylab-grade" "${args[@]}" || status=$?
# Without an IPC namespace, SysV objects a worker made as nobody would outlive it (the
# worker's seccomp filter refuses them; this is the second line)
if [[ $sandbox == none && $EUID == 0 ]] && have ipcs && have ipcrm; then
    for kind in m s q; do
        ipcs -"$kind" 2>/dev/null | awk '$3 == "nobody" && $2 ~ /^[0-9]+$/ { print $2 }' |
            while read -r ipc; do ipcrm -"$kind" "$ipc" 2>/dev/null || true; done
    done
fi
exit "$status"
