#!/usr/bin/env bash
# ctest grading/mutants-build-error: check_mutants.sh on a list whose only mutant does not
# compile (selftest/) must fail and name it, though that mutant's expected verdict is zero.
# Usage: check_build_error.sh ROOT WORKDIR
set -uo pipefail
root=$1 work=$2 here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
status=0
"$here/check_mutants.sh" "$root" "$work" "$here/selftest/expected.txt" >"$work/check.log" 2>&1 ||
    status=$?
cat "$work/check.log"
if ((status == 0)); then
    echo "FAIL: check_mutants.sh passed a mutant that does not compile"
    exit 1
fi
if ! grep -q '^ERROR lambert_no_include.cpp: the mutant does not build' "$work/check.log"; then
    echo "FAIL: check_mutants.sh failed, but without naming the mutant that does not build"
    exit 1
fi
echo "ok: the mutant that does not build is an error of the check"
