#!/usr/bin/env bash
# Grades a whole class: every hand-in folder of DIR (one folder per student) through
# scripts/grade.sh, N students at a time, and writes a class table.
#
# Usage: scripts/grade-class.sh DIR [-j N] [--out OUT] [--timeout S] [--points N]
#                               [--private DIR] [--trusted]
#   (also: ./scripts/dev.sh grade-class DIR [-j N] [--out OUT])
#   -j N          students graded at once (default 2)
#   --out OUT     where the results go (default build/class/<name of DIR>); removed and
#                 rewritten by each run
#   --timeout S, --points N, --private DIR, --trusted   passed to scripts/grade.sh
#
# Writes OUT/class.csv and OUT/class.md (student, points per module, total, notes), and per
# student OUT/students/NAME/{results.json,junit.xml,summary.txt,grade.log}. Every entry of
# DIR that is a folder, or a link, gets one row: a link is refused (a note says so), a
# name with a newline or another control character is shown escaped (\n). Every module
# short of full marks has its reason in the notes, in the words of summary.txt ("04_sphere
# missing", "03_plane did not compile", "05_triangle crashed with signal SIGSEGV",
# "06_point_light no answer in 10 s", "07_lambert NaN", "08_shadows wrong"), then the
# staging notes ("used sub/04_sphere.cpp", "ignored ...", "refused ..."). Points are
# rounded to two decimals, as the total is. One student's broken build, crash or hang
# never stops the others. Two runs with different OUT folders run side
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
        --timeout | --points | --private) grade_args+=("$1" "${2:?$1 needs a value}"); shift ;;
        --timeout=* | --points=* | --private=* | --trusted) grade_args+=("$1") ;;
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
# Every folder and link (a link is refused below), whatever its name
mapfile -d '' -t STUDENTS < <(find "$class" -mindepth 1 -maxdepth 1 \( -type d -o -type l \) \
    -printf '%f\0' | LC_ALL=C sort -z)
((${#STUDENTS[@]})) || die "$class has no hand-in folders"

# NAME as the table and the output folder show it: control characters escaped, one to
# one (a backslash is doubled, so no two names show alike: the name is also the output
# folder and the table's key)
shown() {
    local s=${1//\\/\\\\} out='' k c
    s=${s//$'\n'/\\n}
    s=${s//$'\t'/\\t}
    s=${s//$'\r'/\\r}
    for ((k = 0; k < ${#s}; k++)); do
        c=${s:k:1}
        if [[ $c == [$'\001'-$'\037'$'\177'] ]]; then
            out+=$(printf '\\x%02x' "'$c")
        else
            out+=$c
        fi
    done
    printf '%s' "$out"
}
declare -A SHOWN=()
for name in "${STUDENTS[@]}"; do
    SHOWN[$name]=$(shown "$name")
    [[ ${SHOWN[$name]} != . ]] || SHOWN[$name]='\x2e'
    [[ ${SHOWN[$name]} != .. ]] || SHOWN[$name]='\x2e\x2e'
done
# A spreadsheet runs a cell that starts with = + - @ (or a tab, a CR) as a formula
csv_cell() {
    local v=$1
    [[ $v == [=+@$'\t'$'\r'-]* ]] && v="'$v"
    if [[ $v == *[,\"]* || ${2:-} == quoted ]]; then printf '"%s"' "${v//\"/\"\"}"; else printf '%s' "$v"; fi
}

# Old results go (and the per-job builds of older versions of this script)
rm -rf "$out/students" "$out/class.csv" "$out/class.md" "$out/builds"
mkdir -p "$out/students"

# Grades student $1; never fails
grade_one() {
    local name=$1 dest=$out/students/${SHOWN[$1]}
    mkdir -p "$dest"
    if [[ -L $class/$name ]]; then
        # Another student's folder, or one outside the class: never graded in its place
        echo "refused: the hand-in is a symbolic link (to $(shown "$(readlink "$class/$name")")), not a folder" \
            >"$dest/failure.txt"
        return 0
    fi
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
            note "${SHOWN[${STUDENTS[i]}]}: done"
        done
    ) &
    pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid" || true; done

# Notes for one student: why each module lost points (the reports' words), then what
# staging noted (files used from folders, files ignored or refused)
student_notes() {
    local dest=$out/students/${SHOWN[$1]} notes=()
    [[ -f $dest/failure.txt ]] && notes+=("$(head -n 1 "$dest/failure.txt")")
    if [[ -f $dest/results.json ]]; then
        mapfile -t -O "${#notes[@]}" notes < <(jq -r '
            (.tests[] | select(.extra_data.reason != "") | "\(.number) \(.extra_data.reason)"),
            (.tests[] | (.output | capture("graded file: (?<f>[^\n]*/[^\n]*)").f // empty
                | "used \(.)")),
            (.tests[] | .extra_data.notes[]), (.extra_data.notes // [] | .[])' \
            "$dest/results.json" 2>/dev/null)
    elif [[ ! -f $dest/failure.txt ]]; then
        notes+=("no results")
    fi
    local IFS=';'
    printf '%s' "${notes[*]}" | sed 's/;/; /g'
}

# Points of module $2 in student $1's results.json (empty when there is none), rounded as
# the reports round them
points_of() {
    local results=$out/students/${SHOWN[$1]}/results.json
    [[ -f $results ]] || return 0
    jq -r --arg id "$2" \
        '[.tests[] | select(.name | startswith($id + ":")) | .score] | add // 0 |
         . * 100 | round / 100' "$results" || die "cannot read $results"
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
        total=$(awk -v a="$total" -v b="$p" 'BEGIN { printf "%.2f", a + b }')
    done
    notes=$(student_notes "$name")
    total=$(awk -v t="$total" 'BEGIN { print t + 0 }')
    shown_name=${SHOWN[$name]}
    {
        # Names and notes quoted (RFC 4180) and kept from a spreadsheet's formulas
        csv_cell "$shown_name"
        printf ',%s' "${row[@]}"
        # shellcheck disable=SC2128 # notes is a string here
        printf ',%s,%s\n' "$total" "$(csv_cell "$notes" quoted)"
    } >>"$csv"
    {
        printf '| %s |' "${shown_name//|/\\|}"
        printf ' %s |' "${row[@]}"
        printf ' %s | %s |\n' "$total" "${notes//|/\\|}"
    } >>"$md"
done
note "class table: $csv and $md"
note "each student's results.json, junit.xml and summary.txt: $out/students/"
