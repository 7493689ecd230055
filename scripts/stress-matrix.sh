#!/usr/bin/env bash
# Runs the numerical stress suite (tests/stress) under several compilers and optimisation
# levels, each in its own build folder, and fails if any configuration fails: the same
# pass/fail with GCC and clang, -O0/-O2/-O3 and -march=native.
#
#   scripts/stress-matrix.sh [--quick | --with-gcc-O0]
#
# The matrix, which `scripts/dev.sh test` (and so CI) runs: 5 configurations, only
# raylab-stress-tests and what it links built in each (and in clang++ -O2 the framework's
# and the engine's unit tests as well, in g++ -O2 -DRAYLAB_NO_SIMD the engine's):
#   g++     -O2 -DRAYLAB_NO_SIMD, -O3 -march=native
#   clang++ -O0, -O2, -O3 -march=native
# g++ -O0 is the sanitizer build of `scripts/dev.sh test` (Debug), which runs the suite on
# every engine version too; g++ -O3 is its strict build (Release); --with-gcc-O0 adds it here.
# RAYLAB_NO_SIMD builds the scalar twins of the SSE2 code (raylab/simd.h), which must give
# the same results. The builds for the baseline (-O0, -O2) also run the suite twice more,
# with RAYLAB_NO_AVX512=1 and with RAYLAB_NO_AVX2=1, on the reference engine's AVX2 and
# baseline versions (engine/src/engine_simd.h), which a processor with AVX-512 would not
# choose.
# Each is a unity build (RAYLAB_UNITY_BUILD: the framework's libraries and the stress suite
# in a few large files; the reference's modules and the framework's tests one file each),
# since what a configuration proves is how the compiler and its flags treat the numerics,
# not that each file compiles alone (the strict build of dev.sh test proves that).
# --quick: g++ -O2 -DRAYLAB_NO_SIMD and clang++ -O3 -march=native.
# Build folders: build-stress/<compiler>-<flags>. Uses ccache when it is installed;
# RAYLAB_STRESS_JOBS sets the build parallelism (default 2). Prints each configuration's
# time and compile count.
set -euo pipefail
cd "$(dirname "$0")/.."

configs=(
    "g++|-O2 -DRAYLAB_NO_SIMD"
    "g++|-O3 -march=native"
    "clang++|-O0"
    "clang++|-O2"
    "clang++|-O3 -march=native"
)
case "${1:-}" in
    "") ;;
    --quick) configs=("g++|-O2 -DRAYLAB_NO_SIMD" "clang++|-O3 -march=native") ;;
    --with-gcc-O0) configs=("g++|-O0" "${configs[@]}") ;;
    *)
        echo "usage: scripts/stress-matrix.sh [--quick | --with-gcc-O0]" >&2
        exit 2
        ;;
esac
jobs="${RAYLAB_STRESS_JOBS:-2}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi

mkdir -p build-stress
failed=()
for config in "${configs[@]}"; do
    cxx="${config%%|*}"
    flags="${config#*|}"
    if ! command -v "$cxx" >/dev/null; then
        echo "stress-matrix: $cxx not installed" >&2
        failed+=("$cxx $flags (compiler missing)")
        continue
    fi
    dir="build-stress/${cxx}${flags// /}"
    start=$SECONDS
    echo "== stress suite: $cxx $flags ($dir)"
    # clang++ -O2 builds and runs the framework's and the engine's unit tests too: the rest
    # of CI builds them with g++ only, and clang 14 refuses some C++17 that g++ takes. The
    # build without SIMD runs the engine's tests: its scalar twins (the hit point's shared
    # coordinates) are checked there, not by the stress suite
    targets=(raylab-stress-tests)
    if [[ "$cxx" == clang++ && "$flags" == "-O2" ]]; then
        targets+=(raylab-framework-tests raylab-engine-tests)
    elif [[ "$flags" == *RAYLAB_NO_SIMD* ]]; then
        targets+=(raylab-engine-tests)
    fi
    if ! cmake -S . -B "$dir" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" \
        -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="$flags" "${launcher[@]}" \
        -DRAYLAB_WITH_GUI=OFF -DRAYLAB_WERROR=ON -DRAYLAB_UNITY_BUILD=ON \
        >"$dir.configure.log" 2>&1 ||
        ! cmake --build "$dir" -j "$jobs" --target "${targets[@]}" \
            >"$dir.build.log" 2>&1; then
        echo "stress-matrix: build failed for $cxx $flags (see $dir.*.log)" >&2
        failed+=("$cxx $flags (build)")
        continue
    fi
    built=$SECONDS
    compiles=$(grep -c 'Building CXX object' "$dir.build.log" || true)
    if ! "$dir/tests/stress/raylab-stress-tests" --no-intro; then
        failed+=("$cxx $flags")
    fi
    if [[ " ${targets[*]} " == *" raylab-framework-tests "* ]]; then
        echo "== $cxx $flags, the framework's unit tests"
        if ! "$dir/tests/framework/raylab-framework-tests" --no-intro --minimal; then
            failed+=("$cxx $flags framework tests")
        fi
    fi
    if [[ " ${targets[*]} " == *" raylab-engine-tests "* ]]; then
        echo "== $cxx $flags, the engine's tests"
        if ! "$dir/engine/tests/raylab-engine-tests" --no-intro --minimal; then
            failed+=("$cxx $flags engine tests")
        fi
    fi
    # A build for the baseline carries the engine's AVX2 and AVX-512 versions too, and
    # this machine's processor chooses the widest it has: run again on the narrower ones
    if [[ "$flags" != *-march=native* && "$flags" != *RAYLAB_NO_SIMD* ]]; then
        for narrower in RAYLAB_NO_AVX512 RAYLAB_NO_AVX2; do
            echo "== $cxx $flags, the engine's narrower versions ($narrower=1)"
            if ! env "$narrower=1" "$dir/tests/stress/raylab-stress-tests" --no-intro; then
                failed+=("$cxx $flags $narrower=1")
            fi
        done
    fi
    echo "== $cxx $flags: build $((built - start)) s ($compiles compiles), tests $((SECONDS - built)) s"
done
if ((${#failed[@]})); then
    printf 'stress-matrix: FAILED: %s\n' "${failed[@]}" >&2
    exit 1
fi
echo "stress-matrix: all ${#configs[@]} configurations pass"
