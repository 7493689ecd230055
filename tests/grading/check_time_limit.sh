#!/usr/bin/env bash
# ctest grading/time-limit-is-cpu-time: raylab-grade's module time limit counts CPU time,
# so that a busy machine does not fail honest code (at a load of 17 on 2 cores the
# reference's own 03_plane needed more than 30 s of clock time for its whole render), and
# the clock bounds code that only waits. A stand-in for raylab-grading-tests (one case per
# suite) waits 2 s in 01 (no CPU) and forever in 02; with --timeout 1, 01 must pass and 02
# must reach the clock limit (6 x 1 s) with a message that says so.
# Usage: check_time_limit.sh RAYLAB_GRADE ROOT WORKDIR
set -euo pipefail
grade=$1 root=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
mapfile -t modules < <(sed -n 's/^RAYLAB_MODULE([a-z_0-9]*, "\([0-9][0-9]_[a-z_0-9]*\)".*/\1/p' \
    "$root/framework/include/raylab/modules.def")
cat >"$work/fake-tests" <<FAKE
#!/usr/bin/env bash
case \$1 in
    --list-test-cases)
        for id in ${modules[*]}; do printf 'list\t%s\tthe case\n' "\$id" >>"\$RAYLAB_GRADE_LOG"; done ;;
    --test-suite=*)
        id=\${1#--test-suite=}
        case \$id in
            01_*) sleep 2 ;;
            02_*) exec sleep 1000 ;;
        esac
        printf 'case\t%s\tthe case\tpass\t\n' "\$id" >>"\$RAYLAB_GRADE_LOG" ;;
esac
FAKE
chmod +x "$work/fake-tests"
start=$SECONDS
"$grade" --tests "$work/fake-tests" --out "$work/out" --timeout 1 --points 10 \
    --label "a stand-in for the graders" >"$work/grade.log" 2>&1 || {
    cat "$work/grade.log"; echo "FAIL: raylab-grade failed"; exit 1; }
cat "$work/grade.log"
fail=0
grep -qE "^${modules[0]} +1/1 +10.00" "$work/out/summary.txt" ||
    { echo "FAIL: ${modules[0]} waited 2 s with no CPU time and did not pass"; fail=1; }
grep -qE "^${modules[1]} +0/1 .*no result after 6 s \(waiting or sleeping" "$work/out/summary.txt" ||
    { echo "FAIL: ${modules[1]} never answered and was not stopped by the clock"; fail=1; }
((SECONDS - start < 60)) || { echo "FAIL: took $((SECONDS - start)) s"; fail=1; }
exit "$fail"
