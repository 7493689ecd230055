#!/usr/bin/env bash
# Writes the student release of raylab and checks it.
#
# Usage: scripts/make-student-release.sh [OUT]      (also: make release OUT=DIR)
#   OUT defaults to build/student-release/raylab. An existing OUT is replaced only if it
#   is an earlier release (it holds .raylab-release).
#
# The release is this tree without what students must not have or cannot build: solutions/
# and engine/ (the reference and its fast path), bench/ but for the student bench's sources
# (raylab-student-bench, which measures the student's tests beside the compiled reference;
# its formulations and ray sets ship compiled, as reference/libraylab_bench_kernels.a, since
# they hold working sphere and triangle tests) and tests/stress/ (they measure the
# reference), tests/e2e/ (it makes a release), the graders' mutants, the hostile hand-ins
# and the class tests (near-copies of the reference or copies of it), the
# instructor guide, the benchmark notes (with the sampling benchmark's plots and CSV) and
# the decision records (the reference's history); a link to one of those in a page the
# release keeps becomes plain text. In their place it gets:
#   README.md             the students' README (scripts/release/README.md)
#   reference/libraylab_reference.a
#                         the reference compiled (no source): stubs fall back to it, the
#                         compare view, heat map and inspector show it, --reference works.
#                         Built here by the instructor's toolchain: the release's platform
#                         is this machine's (the course's is Debian 12 x86_64, g++ 12);
#                         rebuild the release on each platform you support
#   tests/data/golden/    the reference's answers to every grading case, written now by the
#                         reference, so that the graders work without solutions/
#   tests/grading/stubs/  the untouched exercise files, which scripts/grade.sh compiles in
#                         place of a hand-in's missing or broken file
# Then it checks the release in a scratch folder: every relative Markdown link resolves
# (scripts/check-links.sh), every stub has its TODO(student) steps, it configures and
# builds with warnings as errors, starts the viewer under Xvfb (when the viewer and
# xvfb-run exist) and compares its picture with the reference's, and grades the untouched exercises with
# scripts/grade.sh, which must find every module not started.
#
# Environment: RELEASE_BUILD_DIR=DIR, the build of this tree that writes the golden data
# (default build-student-release/; an existing Ninja build of this tree is used with its
# options, so CI's own build serves); RELEASE_KEEP_CHECK=1 keeps the scratch check folder;
# RELEASE_CHECK_DIR=DIR makes the checks in DIR (new or empty) and keeps it, with the copy
# of the release they build and grade (DIR/raylab: build/, build-grade/); CMAKE_ARGS="..."
# adds options to every configure (as in scripts/dev.sh).
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

usage() { sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; }
case ${1:-} in -h | --help) usage; exit 0 ;; esac
(($# <= 1)) || { usage >&2; die "too many arguments"; }

absolute() { [[ $1 == /* ]] && printf '%s' "$1" || printf '%s/%s' "$PWD" "$1"; }
OUT=$(absolute "${1:-$RAYLAB_ROOT/build/student-release/raylab}")
BUILD=$(absolute "${RELEASE_BUILD_DIR:-$RAYLAB_ROOT/build-student-release}")
# The modules, from the registry (as scripts/grade.sh)
mapfile -t MODULES < <(sed -n 's/^RAYLAB_MODULE([a-z_0-9]*, "\([0-9][0-9]_[a-z_0-9]*\)".*/\1/p' \
    "$RAYLAB_ROOT/framework/include/raylab/modules.def")
((${#MODULES[@]})) || die "no modules in framework/include/raylab/modules.def"
t0=$SECONDS
extra=()
if [[ -n ${CMAKE_ARGS:-} ]]; then read -r -a extra <<<"$CMAKE_ARGS"; fi

have cmake || die "cmake is missing: scripts/install-deps.sh build"
have ninja || die "ninja is missing: scripts/install-deps.sh build"
[[ -f $RAYLAB_ROOT/solutions/01_pixel_loop.cpp ]] ||
    die "this tree has no solutions/: a release can only be made from the instructor's tree"
case $OUT in
    "$RAYLAB_ROOT" | "$RAYLAB_ROOT/" | /) die "OUT must not be $OUT" ;;
esac
if [[ -e $OUT ]]; then
    [[ -f $OUT/.raylab-release ]] ||
        die "$OUT exists and is not an earlier raylab release: choose another OUT"
    rm -rf "$OUT"
fi

# ---- The exercise files must be the untouched stubs -----------------------------------

step "Checking that exercises/ holds the stubs"
for id in "${MODULES[@]}"; do
    grep -q "RAYLAB_STUB(\"$id\")" "$RAYLAB_ROOT/exercises/$id.cpp" ||
        die "exercises/$id.cpp does not call RAYLAB_STUB: is a solution in exercises/?"
    if grep -q 'raylab::reference' "$RAYLAB_ROOT/exercises/$id.cpp"; then
        die "exercises/$id.cpp mentions raylab::reference"
    fi
done

# ---- Copy ------------------------------------------------------------------------------

# What never goes to students
excluded() {
    case $1 in
        bench/CMakeLists.txt | bench/student_bench.cpp | bench/kernels.h | bench/kernel_cases.h | \
            bench/report.h | bench/rng.h | bench/student_cases.h) return 1 ;;
        solutions/* | engine/* | bench/* | tests/stress/* | tests/e2e/* | docs/instructor-guide.md | \
            tests/grading/mutants/* | tests/grading/handins/* | tests/class/* | \
            docs/benchmarks.md | docs/sampling-benchmarks.md | docs/images/sampling-benchmark* | \
            docs/data/* | docs/decisions/* | \
            tests/data/golden/* | build*/* | scripts/release/* | README.md) return 0 ;;
    esac
    return 1
}

step "Copying the release to $OUT/"
mkdir -p "$OUT"
if git -C "$RAYLAB_ROOT" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    list_files() { git -C "$RAYLAB_ROOT" ls-files; }
    commit=$(git -C "$RAYLAB_ROOT" rev-parse --short HEAD)
    git -C "$RAYLAB_ROOT" diff --quiet HEAD -- . 2>/dev/null || commit="$commit + local changes"
else
    list_files() { (cd "$RAYLAB_ROOT" && find . -path './build*' -prune -o -type f -printf '%P\n'); }
    commit=unknown
fi
count=0
while IFS= read -r f; do
    excluded "$f" && continue
    [[ -f $RAYLAB_ROOT/$f ]] || continue # deleted but not yet committed
    mkdir -p "$OUT/$(dirname "$f")"
    cp -p "$RAYLAB_ROOT/$f" "$OUT/$f"
    count=$((count + 1))
done < <(list_files)
mkdir -p "$OUT/tests/grading/stubs" "$OUT/tests/data/golden"
cp "$RAYLAB_ROOT"/exercises/*.cpp "$OUT/tests/grading/stubs/"
cp "$RAYLAB_ROOT/scripts/release/README.md" "$OUT/README.md"
printf 'raylab student release of %s, made %s\n' "$commit" "$(date -u +%Y-%m-%dT%H:%MZ)" \
    >"$OUT/.raylab-release"
note "$count files; no solutions/, engine/, bench/ (but the student bench), tests/stress/," \
    "decision records or instructor guide"

# A page copied to the release may link a page that stays behind (architecture.md links
# benchmarks.md): such a link becomes its plain text, so that both trees' links resolve.
# A link that resolves in neither tree is left for Check 0 to report
step "Unlinking the pages the release leaves out"
(cd "$OUT" && find . -name '*.md' -print0 | RAYLAB_ROOT=$RAYLAB_ROOT perl -0 -ne '
    use File::Basename; use File::Spec;
    chomp(my $md = $_); $md =~ s{^\./}{};
    open(my $in, "<", $md) or die "$md: $!"; local $/; my $text = <$in>; close $in;
    my $dir = dirname($md); my $n = 0;
    $text =~ s{(!?)\[([^\[\]\n]*)\]\(([^)#\s]+)(#[^)]*)?\)}{
        my ($img, $label, $target, $anchor) = ($1, $2, $3, $4 // "");
        my $path = File::Spec->canonpath("$dir/$target"); 1 while $path =~ s{(^|/)(?!\.\./)[^/]+/\.\.(/|$)}{$1};
        if ($target !~ /^[a-z]+:/ && !-e $path && -e "$ENV{RAYLAB_ROOT}/$path") {
            $n++; print "    $md: $target (not in the release): now plain text\n"; $label;
        } else { "$img\[$label\]($target$anchor)" }
    }ge;
    if ($n) { open(my $out, ">", $md) or die "$md: $!"; print $out $text; close $out; }
') || die "unlinking the pages left out failed"

# ---- Golden data, written by the reference -----------------------------------------------

step "Writing the golden data with the reference (build in $BUILD/)"
mkdir -p "$BUILD"
if [[ -f $BUILD/CMakeCache.txt ]]; then
    # An existing Ninja build of this tree (CI passes its own) keeps its options; it must
    # build the stubs of exercises/
    cached() { sed -n "s/^$1:[A-Z]*=//p" "$BUILD/CMakeCache.txt"; }
    [[ $(realpath -m "$(cached CMAKE_HOME_DIRECTORY)") == "$(realpath "$RAYLAB_ROOT")" &&
        $(realpath -m "$(cached RAYLAB_EXERCISES_DIR)") == "$(realpath "$RAYLAB_ROOT/exercises")" &&
        -f $BUILD/build.ninja ]] ||
        die "RELEASE_BUILD_DIR=$BUILD is not a Ninja build of this tree's exercises/"
else
    cmake -S "$RAYLAB_ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WITH_GUI=OFF \
        -DRAYLAB_EXERCISES_DIR="$RAYLAB_ROOT/exercises" "${extra[@]}" \
        >"$BUILD/release-configure.log" 2>&1 ||
        die "configuring $BUILD/ failed: see $BUILD/release-configure.log"
fi
ninja -C "$BUILD" raylab-grading-tests raylab-worker raylab-worker-reference \
    >"$BUILD/release-build.log" 2>&1 ||
    die "building the graders failed: see $BUILD/release-build.log"
RAYLAB_GRADE_IMPL=reference RAYLAB_GOLDEN_WRITE="$OUT/tests/data/golden" \
    "$BUILD/tests/grading/raylab-grading-tests" --no-colors >"$BUILD/release-golden.log" 2>&1 ||
    die "the reference fails its own graders: see $BUILD/release-golden.log"
grep '^\[raylab\] wrote' "$BUILD/release-golden.log" | sed 's/^\[raylab\] /    /'
# ---- The reference, compiled ------------------------------------------------------------

step "Building the reference library (raylab_reference) for the release"
mkdir -p "$OUT/reference"
if ninja -C "$BUILD" -t targets all 2>/dev/null | grep '^raylab_reference:' >/dev/null; then
    ninja -C "$BUILD" raylab_reference raylab-render >"$BUILD/release-reference.log" 2>&1 ||
        die "building raylab_reference failed: see $BUILD/release-reference.log"
    lib=$(find "$BUILD" -name libraylab_reference.a -print -quit)
    [[ -n $lib ]] || die "raylab_reference built no libraylab_reference.a"
    cp "$lib" "$OUT/reference/libraylab_reference.a"
    note "reference/libraylab_reference.a ($(du -k "$lib" | cut -f1) KiB," \
        "$(uname -m), $(c++ --version | head -n 1))"
else
    die "this tree has no raylab_reference target (framework/CMakeLists.txt): cannot ship" \
        "the compiled reference"
fi
# The student bench's formulations and ray sets, compiled: its sources hold working tests
if ninja -C "$BUILD" -t targets all 2>/dev/null | grep '^raylab_bench_kernels:' >/dev/null; then
    ninja -C "$BUILD" raylab_bench_kernels >>"$BUILD/release-reference.log" 2>&1 ||
        die "building raylab_bench_kernels failed: see $BUILD/release-reference.log"
    lib=$(find "$BUILD" -name libraylab_bench_kernels.a -print -quit)
    [[ -n $lib ]] || die "raylab_bench_kernels built no libraylab_bench_kernels.a"
    cp "$lib" "$OUT/reference/libraylab_bench_kernels.a"
    note "reference/libraylab_bench_kernels.a ($(du -k "$lib" | cut -f1) KiB)"
fi

# Images within the tolerance the graders use: compilers differ in their last bits
if ! python3 "$RAYLAB_ROOT/tests/grading/check_golden.py" --compare \
    "$RAYLAB_ROOT/tests/data/golden" "$OUT/tests/data/golden" >/dev/null; then
    warn "tests/data/golden/ in this tree differs from what the reference writes now;" \
        "refresh it: ninja -C <build> raylab-update-golden"
fi

# ---- Check the release -------------------------------------------------------------------

[[ ! -e $OUT/solutions ]] || die "the release holds solutions/"
src=$(find "$OUT/reference" -type f ! -name libraylab_reference.a ! -name libraylab_bench_kernels.a)
[[ -z $src ]] || die "reference/ holds more than the library: $src"
leaks=$(grep -rl 'raylab::reference::[a-z_]*(' "$OUT/exercises" "$OUT/grading" "$OUT/tests/grading" || true)
[[ -z $leaks ]] || die "these release files call the reference: $leaks"
# No working intersection test in source: the bench's formulations, the graders' mutants
# and the hostile hand-ins (near-copies of the reference) stay in the instructor's tree
for f in bench/kernels.cpp bench/kernel_cases.cpp bench/student_cases.cpp bench/student_test \
    tests/grading/mutants tests/grading/handins tests/class; do
    [[ ! -e $OUT/$f ]] || die "the release holds $f, which holds working intersection tests"
done

if [[ -n ${RELEASE_CHECK_DIR:-} ]]; then
    CHECK=$(absolute "$RELEASE_CHECK_DIR")
    mkdir -p "$CHECK"
    [[ -z $(ls -A "$CHECK") ]] || die "RELEASE_CHECK_DIR=$CHECK is not empty"
else
    CHECK=$(mktemp -d "${TMPDIR:-/tmp}/raylab-release-check.XXXXXX")
    cleanup() { [[ ${RELEASE_KEEP_CHECK:-} == 1 ]] || rm -rf "$CHECK"; }
    trap cleanup EXIT
fi

step "Check 0: links and stubs"
bash "$RAYLAB_ROOT/scripts/check-links.sh" "$OUT" | sed 's/^/    /' ||
    die "the release's Markdown has broken links (above)"
for id in "${MODULES[@]}"; do
    grep -q "TODO(student)" "$OUT/exercises/$id.cpp" ||
        die "exercises/$id.cpp has no TODO(student) step: grep -rn \"TODO(student)\" fails"
done
for f in "$OUT"/README.md "$OUT"/docs/handouts/*.md; do
    if grep -n 'instructor-guide\|benchmarks\.md\|solutions/' "$f"; then
        die "$f mentions what the release does not hold (above)"
    fi
done
listed=$(bash "$OUT/scripts/dev.sh" help | grep -E '^  (bench|grade-reference|gradescope|release)( |$)' |
    grep -v '^  bench --student ') &&
    die "the release's dev.sh help lists instructor commands: $listed"
note "links resolve, every stub lists its TODO(student) steps, dev.sh help lists no" \
    "instructor command"

# The checks build and grade a copy of the release, with their build folders inside it as a
# student's are (build/, build-grade/), and leave OUT as it is handed out. ccache (dev.sh
# test) keys compiles on paths relative to the build folder, so this tree's builds serve them
COPY=$CHECK/raylab
cp -a "$OUT" "$COPY"
step "Check 1: the release builds (warnings as errors) in $COPY/build"
cmake -S "$COPY" -B "$COPY/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYLAB_WERROR=ON \
    "${extra[@]}" >"$CHECK/configure.log" 2>&1 || {
    cat "$CHECK/configure.log" >&2
    die "the release does not configure"
}
grep -E '^-- raylab' "$CHECK/configure.log" | sed 's/^/    /' || true
ninja -C "$COPY/build" >"$CHECK/build.log" 2>&1 || {
    tail -n 40 "$CHECK/build.log" >&2
    die "the release does not build"
}
note "built"

step "Check 2: the viewer starts"
viewer=$COPY/build/framework/viewer/raylab
if [[ ! -x $viewer ]]; then
    note "SKIPPED: no viewer was built (RAYLAB_WITH_GUI needs libglfw3-dev and libimgui-dev)"
elif ! have xvfb-run; then
    note "SKIPPED: xvfb-run is missing (scripts/install-deps.sh gui)"
else
    # The first run from the stubs alone must show the reference's Cornell box, lit and
    # shadowed: the window's image region against the instructor build's raylab-render
    shot=(--width 320 --height 240)
    "$BUILD/framework/raylab-render" "${shot[@]}" --output "$CHECK/reference.png" \
        >/dev/null || die "raylab-render of the instructor build failed"
    xvfb-run -a -s '-screen 0 1280x800x24' "$viewer" "${shot[@]}" --image-scale 1 \
        --window 1000x600 --frames 3 --screenshot "$CHECK/viewer.png" \
        >"$CHECK/viewer.log" 2>&1 || {
        cat "$CHECK/viewer.log" >&2
        die "the viewer of the release does not start"
    }
    [[ -s $CHECK/viewer.png ]] || die "the viewer wrote no screenshot"
    n='\([0-9]*\)'
    crop=$(sed -n "s/.*image at $n,$n size ${n}x$n.*/\\1,\\2,\\3,\\4/p" "$CHECK/viewer.log")
    "$COPY/build/tests/gui/raylab-png-diff" "$CHECK/viewer.png" "$CHECK/reference.png" \
        --crop "$crop" --tolerance 2 >"$CHECK/viewer-diff.log" 2>&1 || {
        cat "$CHECK/viewer-diff.log" >&2
        die "the release's first picture is not the reference's Cornell box"
    }
    note "the viewer's first picture from the stubs equals the reference's (Xvfb)"
fi

step "Check 3: the graders run on the untouched exercises and score zero"
GRADE_OUT=$CHECK/grade GRADE_BUILD_DIR=$COPY/build-grade SUBMISSION='' \
    bash "$COPY/scripts/grade.sh" --expect not-started >"$CHECK/grade.log" 2>&1 || {
    cat "$CHECK/grade.log" >&2
    die "the graders of the release did not score the stubs zero"
}
sed -n '/^raylab grade:/,/^total/p' "$CHECK/grade.log" | sed 's/^/    /'

step "Student release ready in $OUT/ ($((SECONDS - t0)) s)"
note "from $commit; hand it out as it is, e.g. tar -C $(dirname "$OUT") -czf raylab.tar.gz $(basename "$OUT")"
