#!/usr/bin/env bash
# ctest class/gradescope-package: builds the autograder zip, lays out a scratch folder
# like /autograder (source/, submission/, results/), runs setup.sh (without installing
# packages) and run_autograder on a hand-in of the reference renamed into the student
# namespace with 06_point_light missing, and checks results.json.
# Usage: check_gradescope.sh ROOT WORKDIR
set -euo pipefail
root=$1 work=$2
rm -rf "$work" && mkdir -p "$work/ag/source" "$work/ag/submission"
"$root/scripts/make-gradescope.sh" "$work/pkg"
unzip -q "$work/pkg/autograder.zip" -d "$work/ag/source"
export AUTOGRADER_ROOT=$work/ag RAYLAB_SKIP_DEPS=1
bash "$work/ag/source/setup.sh" >"$work/setup.log" 2>&1 || { tail -n 30 "$work/setup.log"; exit 1; }
for f in "$root"/solutions/[0-9][0-9]_*.cpp; do
    [[ $(basename "$f") == 06_point_light.cpp ]] && continue
    sed 's/namespace raylab::reference/namespace raylab::student/' "$f" \
        >"$work/ag/submission/$(basename "$f")"
done
cp "$work/ag/source/run_autograder" "$work/ag/run_autograder"
"$work/ag/run_autograder" >"$work/run.log" 2>&1
results=$work/ag/results/results.json
jq . "$results" >/dev/null || { echo "FAIL: results.json is not JSON"; exit 1; }
score=$(jq '.score' "$results")
tests=$(jq '.tests | length' "$results")
light=$(jq '[.tests[] | select(.name | startswith("06_point_light")) | .score] | add' "$results")
echo "results.json: score $score, $tests tests, 06_point_light $light"
jq -r '.tests[] | "  \(.name): \(.score) / \(.max_score) \(.status)"' "$results"
[[ $score == 70 || $score == 70.0 ]] || { echo "FAIL: score $score, want 70"; exit 1; }
[[ $tests == 8 ]] || { echo "FAIL: $tests tests, want 8"; exit 1; }
jq -e '.tests | all(has("name") and has("score") and has("max_score"))' "$results" >/dev/null ||
    { echo "FAIL: a test lacks name, score or max_score"; exit 1; }
echo PASS
