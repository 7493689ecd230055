#!/usr/bin/env bash
# Grades the adversarial hand-ins in this folder with scripts/grade.sh and checks that
# each scores exactly what its own honest code earns, that the other modules are
# untouched, that nothing of the checkout changed and that no report is rewritten later.
#
# Usage: run-handins.sh BUILD_DIR [NAME...]     (ctest: grading/adversarial/NAME)
#
# Each folder NAME/ holds the files a cheating student would hand in and NAME/expect:
#   ID SCORE      module ID scores exactly SCORE (modules not listed: 0, file missing)
#   ID <SCORE     module ID scores less than SCORE
#   graded PATH   the report names PATH as the graded file
#   crlf          every file is handed in with CRLF line ends
#   settle        wait 3 s after grading, then check that no report changed (a process
#                 the hand-in left behind could rewrite them)
# In the files, "// RAYLAB-HONEST-CODE ID" stands for an honest implementation (the
# reference's code moved to namespace raylab::student), "@ROOT@" for the checkout and
# "@OUT@" for the hand-in's report folder: a student may know both (on Gradescope they
# are /autograder/source and /autograder/results).
set -euo pipefail
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ROOT=$(cd "$HERE/../../.." && pwd)
[[ -f $ROOT/solutions/01_pixel_loop.cpp ]] || { echo "needs solutions/"; exit 1; }
BUILD=$(cd "${1:?usage: run-handins.sh BUILD_DIR [NAME...]}" && pwd)
shift
names=("$@")
if ((${#names[@]} == 0)); then
    for d in "$HERE"/*/; do names+=("$(basename "$d")"); done
fi

WORK=$(mktemp -d "${TMPDIR:-/tmp}/raylab-handins.XXXXXX")
trap 'rm -rf "$WORK"' EXIT

# The source tree's fingerprint: nothing a hand-in does may change it
fingerprint() {
    (cd "$ROOT" && find scripts framework tests exercises solutions docs -type f \
        -print0 2>/dev/null | sort -z | xargs -0 sha1sum | sha1sum)
}

# Copies hand-in $1 to $2 with its placeholders filled in
materialize() {
    local src=$1 dst=$2 out=$3 f id
    cp -r "$src" "$dst"
    rm -f "$dst/expect"
    while IFS= read -r -d '' f; do
        while id=$(grep -o -m 1 '^// RAYLAB-HONEST-CODE [0-9a-z_]*' "$f" | cut -d' ' -f3) &&
            [[ -n $id ]]; do
            sed -e 's/namespace raylab::reference/namespace raylab::student/' \
                "$ROOT/solutions/$id.cpp" >"$WORK/honest.cpp"
            sed -i -e "/^\/\/ RAYLAB-HONEST-CODE $id\$/{r $WORK/honest.cpp" -e 'd}' "$f"
        done
        sed -i -e "s|@ROOT@|$ROOT|g" -e "s|@OUT@|$out|g" "$f"
        if grep -qx crlf "$src/expect"; then sed -i 's/$/\r/' "$f"; fi
    done < <(find "$dst" -type f -print0)
}

# The score of module $2 in the summary $1
score_of() { awk -v id="$2" '/^total/ { exit } $1 == id { print $3; exit }' "$1"; }

failed=0
before=$(fingerprint)
declare -A results=()
for name in "${names[@]}"; do
    [[ -f $HERE/$name/expect ]] || { echo "no hand-in $name"; failed=1; continue; }
    out=$WORK/out/$name
    materialize "$HERE/$name" "$WORK/$name" "$out"
    echo "==> $name"
    if ! SUBMISSION=$WORK/$name GRADE_OUT=$out GRADE_BUILD_DIR=$BUILD \
        "$ROOT/scripts/grade.sh" --timeout 8 >"$WORK/$name.log" 2>&1; then
        echo "FAIL $name: grade.sh failed"; tail -n 20 "$WORK/$name.log"; failed=1; continue
    fi
    summary=$out/summary.txt
    results[$name]=$(sha1sum <"$out/results.json")
    while read -r id want; do
        case $id in
            crlf | settle | '') continue ;;
            graded)
                grep -qF "graded file: $want" "$summary" ||
                    { echo "FAIL $name: the report does not name $want"; failed=1; }
                continue ;;
        esac
        got=$(score_of "$summary" "$id")
        if [[ $want == '<'* ]]; then
            awk -v g="$got" -v w="${want#<}" 'BEGIN { exit !(g < w) }' ||
                { echo "FAIL $name: $id scored $got, expected less than ${want#<}"; failed=1; }
        elif ! awk -v g="$got" -v w="$want" 'BEGIN { exit !(g == w) }'; then
            echo "FAIL $name: $id scored $got, expected $want"; failed=1
        fi
    done <"$HERE/$name/expect"
    # Every other module: missing from the hand-in, so 0
    for id in $(awk '/^total/ { exit } NR > 3 && $1 ~ /^[0-9][0-9]_[a-z_0-9]+$/ { print $1 }' "$summary"); do
        grep -q "^$id " "$HERE/$name/expect" && continue
        [[ $(score_of "$summary" "$id") == 0.00 ]] ||
            { echo "FAIL $name: $id (not handed in) scored $(score_of "$summary" "$id")"; failed=1; }
    done
    # Reports stay valid UTF-8 and never show the reference's source
    for f in results.json junit.xml summary.txt; do
        iconv -f UTF-8 -t UTF-8 "$out/$f" >/dev/null 2>&1 ||
            { echo "FAIL $name: $f is not valid UTF-8"; failed=1; }
    done
    if grep -q 'Precision Improvements\|namespace raylab::reference' "$out/results.json"; then
        echo "FAIL $name: the reference's source reached results.json"; failed=1
    fi
    grep -q $'\x1b' "$out/results.json" "$out/summary.txt" &&
        { echo "FAIL $name: a terminal escape reached the reports"; failed=1; }
    # What the student's code printed is kept, at most 1 MiB per worker
    for f in "$out"/logs/*.worker.log; do
        [[ ! -f $f || $(stat -c %s "$f") -le 1048576 ]] ||
            { echo "FAIL $name: $(basename "$f") holds more than 1 MiB"; failed=1; }
    done
    sed -n '4,12p' "$summary"
done

# A detached process could rewrite a report after its grade: wait, then compare
settle=0
for name in "${!results[@]}"; do grep -qx settle "$HERE/$name/expect" && settle=1; done
((settle)) && sleep 3
for name in "${!results[@]}"; do
    [[ $(sha1sum <"$WORK/out/$name/results.json") == "${results[$name]}" ]] ||
        { echo "FAIL $name: results.json changed after grading finished"; failed=1; }
done
[[ $(fingerprint) == "$before" ]] ||
    { echo "FAIL: the source tree changed while grading (see git status)"; failed=1; }
((failed == 0)) && echo "every hand-in scored what its own code earns"
exit "$failed"
