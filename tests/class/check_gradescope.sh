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
# What to expect, from the registry: every module's points but 06_point_light's, one test
# per module
registry=$root/framework/include/raylab/modules.def
modules=$(grep -c '^RAYLAB_MODULE(' "$registry")
want=$(sed -n 's/^RAYLAB_MODULE([^"]*"\([0-9][0-9]_[a-z_0-9]*\)".*, *\([0-9.]*\))$/\1 \2/p' "$registry" |
    awk '$1 != "06_point_light" { s += $2 } END { print s }')
[[ $modules -gt 0 && -n $want ]] || { echo "FAIL: cannot read the modules of $registry"; exit 1; }
[[ $(jq --argjson w "$want" '.score == $w' "$results") == true ]] ||
    { echo "FAIL: score $score, want $want"; exit 1; }
[[ $tests == "$modules" ]] || { echo "FAIL: $tests tests, want $modules"; exit 1; }
jq -e '.tests | all(has("name") and has("score") and has("max_score"))' "$results" >/dev/null ||
    { echo "FAIL: a test lacks name, score or max_score"; exit 1; }
echo PASS
