#!/usr/bin/env bash
# Grades a whole class: every hand-in folder of DIR (one folder per student) through
# scripts/grade.sh, N students at a time, and writes a class table.
#
# Usage: scripts/grade-class.sh DIR [-j N] [--out OUT] [--timeout S] [--points N]
#   (also: ./scripts/dev.sh grade-class DIR [-j N])
#   -j N          students graded at once (default 2)
#   --out OUT     where the results go (default build/class/<name of DIR>); removed and
#                 rewritten by each run
#   --timeout S, --points N   passed to scripts/grade.sh
#
# Writes OUT/class.csv and OUT/class.md (student, points per module, total, notes such as
# "used sub/dir/04_sphere.cpp" or "04_sphere did not compile"), and per student
# OUT/students/NAME/{results.json,junit.xml,summary.txt,grade.log}. One student's broken
# build, crash or hang never stops the others. Two runs with different OUT folders run side
# by side; a second run on the same OUT stops at once with a message (a lock on OUT).
#
# Environment: GRADE_BUILD_DIR=DIR, the build of the trusted graders shared by every job
# and run (default build-grade/, as scripts/grade.sh). Files that are byte for byte the
# same (untouched stubs, a regrade of the same class) are compiled once: see grade.sh.
set -euo pipefail
# shellcheck source=lib/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib/common.sh"

usage() { sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; }

jobs=2
out=''
class=''
grade_args=()
while (($#)); do
    case $1 in
        -j) jobs=${2:?-j needs a value}; shift ;;
        -j*) jobs=${1#-j} ;;
        --out) out=${2:?--out needs a value}; shift ;;
        --out=*) out=${1#*=} ;;
        --timeout | --points) grade_args+=("$1" "${2:?$1 needs a value}"); shift ;;
        --timeout=* | --points=*) grade_args+=("$1") ;;
        -h | --help) usage; exit 0 ;;
        -*) usage >&2; die "unknown option '$1'" ;;
        *) [[ -z $class ]] || die "one class folder only (got '$class' and '$1')"; class=$1 ;;
    esac
    shift
done
[[ -n $class ]] || { usage >&2; die "which class folder?"; }
[[ -d $class ]] || die "$class is not a folder"
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "-j needs a positive number, not '$jobs'"
have jq || die "jq is missing (it reads each student's results.json): scripts/install-deps.sh libs"
class=$(cd "$class" && pwd)
out=${out:-$RAYLAB_ROOT/build/class/$(basename "$class")}
mkdir -p "$out"
out=$(cd "$out" && pwd)

# One run per output folder at a time: a second one would delete the first one's results
exec 9>"$out/.lock"
flock -n 9 || die "another grade-class run is writing $out; wait for it or use --out"

# The modules, from the registry (as scripts/grade.sh)
mapfile -t MODULES < <(sed -n 's/^RAYLAB_MODULE([a-z_0-9]*, "\([0-9][0-9]_[a-z_0-9]*\)".*/\1/p' \
    "$RAYLAB_ROOT/framework/include/raylab/modules.def")
((${#MODULES[@]})) || die "no modules in framework/include/raylab/modules.def"
build=${GRADE_BUILD_DIR:-$RAYLAB_ROOT/build-grade}
mapfile -t STUDENTS < <(find "$class" -mindepth 1 -maxdepth 1 -type d -printf '%f\n' | sort)
((${#STUDENTS[@]})) || die "$class has no hand-in folders"

# Old results go (and the per-job builds of older versions of this script)
rm -rf "$out/students" "$out/class.csv" "$out/class.md" "$out/builds"
mkdir -p "$out/students"

# Grades student $1; never fails
grade_one() {
    local name=$1 dest=$out/students/$1
    mkdir -p "$dest"
    if ! SUBMISSION="$class/$name" GRADE_OUT="$dest" GRADE_BUILD_DIR="$build" \
        "$RAYLAB_ROOT/scripts/grade.sh" "${grade_args[@]}" </dev/null >"$dest/grade.log" 2>&1; then
        echo "grade.sh failed: $(grep -m 1 'error' "$dest/grade.log" || tail -n 1 "$dest/grade.log")" \
            >"$dest/failure.txt"
    fi
    rm -rf "$dest/images" # large, and the table does not need them
}

# Job k grades students k, k+N, k+2N, ... one after the other
step "Grading ${#STUDENTS[@]} hand-ins of $class, $jobs at a time"
pids=()
for ((k = 0; k < jobs; k++)); do
    (
        for ((i = k; i < ${#STUDENTS[@]}; i += jobs)); do
            grade_one "${STUDENTS[i]}"
            note "${STUDENTS[i]}: done"
        done
    ) &
    pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid" || true; done

# Notes for one student: nested files used, modules that scored zero without running
student_notes() {
    local name=$1 dest=$out/students/$1 id found rel first
    local notes=()
    for id in "${MODULES[@]}"; do
        found=$(find "$class/$name" -maxdepth 3 -name "$id.cpp" -type f -printf '%d %P\n' \
            2>/dev/null | sort -n | head -n 1 | cut -d' ' -f2-)
        [[ -n $found && $found == */* ]] && notes+=("used $found")
        if [[ -f $dest/build-errors/$id.txt ]]; then
            first=$(head -n 1 "$dest/build-errors/$id.txt")
            case $first in
                *"is missing"*) notes+=("$id missing") ;;
                *"does not compile"*) notes+=("$id did not compile") ;;
                *"does not link"*) notes+=("$id did not link") ;;
                *) notes+=("$id: ${first:0:80}") ;;
            esac
        fi
    done
    [[ -f $dest/failure.txt ]] && notes+=("$(head -n 1 "$dest/failure.txt")")
    [[ -f $dest/results.json ]] || notes+=("no results")
    local IFS=';'
    printf '%s' "${notes[*]}" | sed 's/;/; /g'
}

# Points of module $2 in student $1's results.json (empty when there is none)
points_of() {
    local results=$out/students/$1/results.json
    [[ -f $results ]] || return 0
    jq -r --arg id "$2" \
        '[.tests[] | select(.name | startswith($id + ":")) | .score] | add // 0' "$results" ||
        die "cannot read $results"
}

step "Writing the class table"
csv=$out/class.csv md=$out/class.md
{
    printf 'student'
    printf ',%s' "${MODULES[@]}"
    printf ',total,notes\n'
} >"$csv"
{
    printf '| student |'
    printf ' %s |' "${MODULES[@]}"
    printf ' total | notes |\n|---|'
    printf -- '---:|%.0s' "${MODULES[@]}"
    printf -- '---:|---|\n'
} >"$md"
for name in "${STUDENTS[@]}"; do
    row=() total=0
    for id in "${MODULES[@]}"; do
        p=$(points_of "$name" "$id")
        p=${p:-0}
        row+=("$p")
        total=$(awk -v a="$total" -v b="$p" 'BEGIN { print a + b }')
    done
    notes=$(student_notes "$name")
    {
        # A folder name with a comma or a quote is quoted (RFC 4180)
        if [[ $name == *[,\"]* ]]; then printf '"%s"' "${name//\"/\"\"}"; else printf '%s' "$name"; fi
        printf ',%s' "${row[@]}"
        printf ',%s,"%s"\n' "$total" "${notes//\"/\"\"}"
    } >>"$csv"
    {
        printf '| %s |' "${name//|/\\|}"
        printf ' %s |' "${row[@]}"
        printf ' %s | %s |\n' "$total" "${notes//|/\\|}"
    } >>"$md"
done
note "class table: $csv and $md"
note "each student's results.json, junit.xml and summary.txt: $out/students/"
