#!/usr/bin/env bash
# ctest class/grade-class: 20 generated hand-ins graded by scripts/grade-class.sh, and at the
# same time five of them (a copy) into another output folder: the two runs share the
# trusted build and the object cache, and give those five the same rows. A third run on an
# output folder in use must refuse. Each table must give every student the expected total
# and note (make_handins.py).
# Usage: check_class.sh ROOT WORKDIR [JOBS]
set -euo pipefail
root=$1 work=$2 jobs=${3:-2}
rm -rf "$work/class" "$work/class-b" "$work/class.expected.csv"
mkdir -p "$work/class-b"
python3 "$root/tests/class/make_handins.py" "$root" "$work/class"
few=(s01_correct s07_crlf s11_plane_broken s13_empty s16_all_stubs)
for student in "${few[@]}"; do cp -a "$work/class/$student" "$work/class-b/"; done

start=$(date +%s)
"$root/scripts/grade-class.sh" "$work/class" -j "$jobs" --out "$work/a" >"$work/a.log" 2>&1 &
a=$!
"$root/scripts/grade-class.sh" "$work/class-b" -j "$jobs" --out "$work/b" >"$work/b.log" 2>&1 &
b=$!
sleep 1
# A run on an output folder in use stops with a message instead of deleting its results
if "$root/scripts/grade-class.sh" "$work/class" --out "$work/a" >"$work/c.log" 2>&1; then
    echo "FAIL: a second run on $work/a did not stop"; fail=1
elif ! grep -q 'another grade-class run' "$work/c.log"; then
    echo "FAIL: the second run on $work/a gave no clear message:"; cat "$work/c.log"; fail=1
fi
wait $a || { echo "FAIL: run a failed"; cat "$work/a.log"; exit 1; }
wait $b || { echo "FAIL: run b failed"; cat "$work/b.log"; exit 1; }
echo "two runs (20 and ${#few[@]} hand-ins) at once, -j $jobs each: $(($(date +%s) - start)) s wall"

fail=${fail:-0}
for run in a b; do
    table=$work/$run/class.csv
    rows=20
    [[ $run == b ]] && rows=${#few[@]}
    [[ $(wc -l <"$table") -eq $((rows + 1)) ]] || { echo "FAIL: $table has not $rows rows"; fail=1; }
    # The column named "total" (one column per module comes before it)
    col=$(head -n 1 "$table" | tr ',' '\n' | grep -nx total | cut -d: -f1)
    [[ -n $col ]] || { echo "FAIL: $table has no total column"; fail=1; col=0; }
    while IFS=, read -r student want note; do
        [[ $run == a || " ${few[*]} " == *" $student "* ]] || continue
        row=$(grep "^$student," "$table") || { echo "FAIL: $student missing in $table"; fail=1; continue; }
        total=$(awk -F, -v c="$col" '{ print $c }' <<<"$row")
        case $want in
            any) ;;
            '<'*) awk -v t="$total" -v w="${want#<}" 'BEGIN { exit !(t < w) }' ||
                { echo "FAIL: $student: total $total, want $want"; fail=1; } ;;
            *) awk -v t="$total" -v w="$want" 'BEGIN { exit !(t == w) }' ||
                { echo "FAIL: $student: total $total, want $want ($row)"; fail=1; } ;;
        esac
        [[ -z $note || $row == *"$note"* ]] || { echo "FAIL: $student: no note '$note' ($row)"; fail=1; }
        for f in results.json junit.xml; do
            [[ -s $work/$run/students/$student/$f ]] || { echo "FAIL: no $f for $student"; fail=1; }
        done
    done <"$work/class.expected.csv"
done
for student in "${few[@]}"; do
    [[ $(grep "^$student," "$work/a/class.csv") == "$(grep "^$student," "$work/b/class.csv")" ]] ||
        { echo "FAIL: the two runs disagree on $student"; fail=1; }
done
cat "$work/a/class.md"
exit "$fail"
