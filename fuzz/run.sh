#!/usr/bin/env bash
# Runs the libFuzzer targets on copies of the seed corpus (docs/input.md, "Fuzzing";
# ./scripts/dev.sh fuzz SECONDS builds them and calls this).
# Usage: fuzz/run.sh BUILD_DIR SECONDS [TARGET...]   (targets: obj view options)
# Crashes land in BUILD_DIR/artifacts/; keep each as fuzz/crashes/TARGET-NAME and it is
# replayed by every later run. Exit status: non-zero when a target failed.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
build=$1 seconds=$2
shift 2
(($#)) || set -- obj view options
status=0
for t in "$@"; do
    work=$build/corpus-$t
    mkdir -p "$work" "$build/artifacts"
    cp -n "$here/corpus/$t/"* "$work/" 2>/dev/null || true
    # Every kept crash must now run cleanly
    for crash in "$here/crashes/$t-"*; do
        [[ -f $crash ]] || continue
        "$build/fuzz-$t" "$crash" >/dev/null 2>&1 || { echo "regression: $crash"; status=1; }
    done
    echo "fuzz-$t: ${seconds} s"
    "$build/fuzz-$t" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
        -artifact_prefix="$build/artifacts/$t-" -print_final_stats=1 "$work" \
        >"$build/fuzz-$t.log" 2>&1 || { tail -n 40 "$build/fuzz-$t.log"; status=1; }
    grep -E '^#[0-9]+.*DONE|stat::number_of_executed_units|cov:' "$build/fuzz-$t.log" | tail -n 2
done
exit "$status"
