#!/usr/bin/env bash
# Runs raylab-render with the given arguments and checks that it fails with exit code 2 and a
# one-line error that contains EXPECTED. Usage: cli_checks.sh RENDER EXPECTED ARGS...
set -u
render=$1 expected=$2
shift 2
out=$("$render" "$@" 2>&1 >/dev/null)
rc=$?
echo "exit $rc: $out"
[ "$rc" -eq 2 ] || { echo "FAIL: expected exit code 2"; exit 1; }
[ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] || { echo "FAIL: expected one line"; exit 1; }
grep -qF -- "$expected" <<<"$out" || { echo "FAIL: expected '$expected'"; exit 1; }
