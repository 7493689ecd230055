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
#   link PATH TARGET  PATH in the hand-in is a symbolic link to TARGET
#   fifo PATH     PATH in the hand-in is a FIFO
#   big PATH KIB  PATH in the hand-in is a regular file of KIB KiB (a comment)
#   note TEXT     the summary names TEXT (a note, a reason)
#   absent REGEX  no line of summary.txt matches REGEX (student text posing as the grader's)
#   via-link      SUBMISSION is a symbolic link to the hand-in's folder
#   ipc           grading leaves no new 256 MiB SysV shared-memory segment behind (the
#                 size the hand-in asks for: other programs on the machine use SysV IPC too)
#   noleftover    no process of the sandbox's uid (nobody) whose program was deleted (a
#                 worker of a finished grading: grade.sh removes its scratch folder) is
#                 left once grading returns
#   size BYTES    results.json, junit.xml and summary.txt hold at most BYTES each
#   unconfined    without namespaces and without Landlock, grade.sh refuses the hand-in
#                 unless --trusted; graded then with --trusted
# Every hand-in is graded with a secret the grader can read and the student must never
# see: a file (@SECRET@, world-readable), a copy of solutions/ in another world-readable
# checkout (@OTHER@), the grader's environment and its standard input. No report may
# contain the secret, nor the first line of /etc/shadow.
# In the files, "// RAYLAB-HONEST-CODE ID" stands for an honest implementation (the
# reference's code moved to namespace raylab::student), "@ROOT@" for the checkout and
# "@OUT@" for the hand-in's report folder: a student may know both (on Gradescope they
# are /autograder/source and /autograder/results); "@SECRET@" and "@OTHER@" as above.
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

# Without namespaces grade.sh needs Landlock to grade a hand-in: where the kernel has
# none, this mode cannot run here (ctest: skipped)
if [[ ${RAYLAB_SANDBOX:-} == none ]] && ! "$BUILD/grading/raylab-sandbox" check; then
    echo "skipped: RAYLAB_SANDBOX=none needs Landlock, which this kernel lacks"; exit 77
fi
WORK=$(mktemp -d "${TMPDIR:-/tmp}/raylab-handins.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
chmod 755 "$WORK"
SECRET=RAYLAB-SECRET-$(od -An -N8 -tx8 /dev/urandom | tr -d ' ')
mkdir -p "$WORK/secret" "$WORK/other"
printf '%s\n' "$SECRET" >"$WORK/secret/secret.txt"
cp -r "$ROOT/solutions" "$WORK/other/solutions"
chmod -R a+rX "$WORK/secret" "$WORK/other"
shadow=$(head -n 1 /etc/shadow 2>/dev/null || true)

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
        sed -i -e "s|@ROOT@|$ROOT|g" -e "s|@OUT@|$out|g" -e "s|@SECRET@|$WORK/secret/secret.txt|g" \
            -e "s|@OTHER@|$WORK/other|g" "$f"
        if grep -qx crlf "$src/expect"; then sed -i 's/$/\r/' "$f"; fi
    done < <(find "$dst" -type f -print0)
    local kind path arg
    while read -r kind path arg; do
        arg=${arg//@ROOT@/$ROOT}
        arg=${arg//@SECRET@/$WORK/secret/secret.txt}
        arg=${arg//@OTHER@/$WORK/other}
        case $kind in
            link) mkdir -p "$(dirname "$dst/$path")"; ln -s "$arg" "$dst/$path" ;;
            fifo) mkdir -p "$(dirname "$dst/$path")"; mkfifo "$dst/$path" ;;
            big) head -c $((arg * 1024)) /dev/zero | tr '\0' '/' >"$dst/$path" ;;
        esac
    done <"$src/expect"
}

# Processes of nobody running a deleted program: workers that outlived their grading
leftovers() {
    local p exe
    for p in $(pgrep -u 65534 2>/dev/null || true); do
        exe=$(readlink "/proc/$p/exe" 2>/dev/null) || continue
        [[ $exe == *' (deleted)' ]] && echo "$p $exe"
    done
    return 0
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
    submission=$WORK/$name
    if grep -qx via-link "$HERE/$name/expect"; then
        ln -s "$WORK/$name" "$WORK/$name.link"
        submission=$WORK/$name.link
    fi
    ipc_before=$(ipcs -m 2>/dev/null | awk '$5 == 268435456' | wc -l)
    extra=() envs=()
    if grep -qx unconfined "$HERE/$name/expect"; then
        if SUBMISSION=$submission GRADE_OUT=$out GRADE_BUILD_DIR=$BUILD RAYLAB_SANDBOX=none \
            RAYLAB_LANDLOCK=off "$ROOT/scripts/grade.sh" </dev/null >"$WORK/$name.refused" 2>&1 ||
            ! grep -q 'pass --trusted' "$WORK/$name.refused"; then
            echo "FAIL $name: graded without confinement and without --trusted"; failed=1
        fi
        extra=(--trusted) envs=(RAYLAB_SANDBOX=none RAYLAB_LANDLOCK=off)
    fi
    if ! printf '%s\n' "$SECRET" | SUBMISSION=$submission GRADE_OUT=$out GRADE_BUILD_DIR=$BUILD \
        RAYLAB_HANDIN_SECRET=$SECRET env "${envs[@]}" \
        "$ROOT/scripts/grade.sh" --timeout 8 "${extra[@]}" >"$WORK/$name.log" 2>&1; then
        echo "FAIL $name: grade.sh failed"; tail -n 20 "$WORK/$name.log"; failed=1; continue
    fi
    summary=$out/summary.txt
    results[$name]=$(sha1sum <"$out/results.json")
    while read -r id want; do
        case $id in
            crlf | settle | via-link | unconfined | link | fifo | big | '') continue ;;
            noleftover)
                left=$(leftovers)
                [[ -z $left ]] ||
                    { echo "FAIL $name: processes of nobody outlived grading: $left"; failed=1; }
                continue ;;
            size)
                for f in results.json junit.xml summary.txt; do
                    [[ $(stat -c %s "$out/$f") -le $want ]] ||
                        { echo "FAIL $name: $f holds more than $want bytes"; failed=1; }
                done
                continue ;;
            ipc)
                [[ $(ipcs -m 2>/dev/null | awk '$5 == 268435456' | wc -l) == "$ipc_before" ]] ||
                    { echo "FAIL $name: a SysV shared-memory segment was left behind"; ipcs -m; failed=1; }
                continue ;;
            note)
                grep -qF -- "$want" "$summary" ||
                    { echo "FAIL $name: the summary does not say: $want"; failed=1; }
                continue ;;
            absent)
                ! grep -qE -- "$want" "$summary" ||
                    { echo "FAIL $name: summary.txt has a line matching $want"; failed=1; }
                continue ;;
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
    # Nothing from outside the hand-in reaches a report or a log
    if grep -rqF -- "$SECRET" "$out" || { [[ -n $shadow ]] && grep -rqF -- "$shadow" "$out"; }; then
        echo "FAIL $name: the secret reached $(grep -rlF -- "$SECRET" "$out" | head -n 3)"; failed=1
    fi
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
