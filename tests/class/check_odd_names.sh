#!/usr/bin/env bash
# ctest class/odd-names: every entry of a class folder gets exactly one row. Names with a
# comma, a quote and a '|' are quoted (RFC 4180) or escaped ('|' in class.md); a name with
# a newline is graded and shown as "\n"; a student folder that is a symbolic link (to
# another student's) and a hand-in whose file links to another student's are refused
# with a note, never given that student's marks.
# Usage: check_odd_names.sh ROOT WORKDIR
set -euo pipefail
root=$1 work=$2
if [[ ${RAYLAB_SANDBOX:-} == none ]] &&
    ! "${GRADE_BUILD_DIR:-$root/build-grade}/grading/raylab-sandbox" check; then
    echo "skipped: RAYLAB_SANDBOX=none needs Landlock, which this kernel lacks"; exit 77
fi
rm -rf "$work" && mkdir -p "$work/class/s1,comma \"quoted\"" "$work/class/s2|pipe" \
    "$work/class/s3"$'\n'"newline" "$work/class/s5_copier"
sed 's/namespace raylab::reference/namespace raylab::student/' "$root/solutions/03_plane.cpp" \
    >"$work/class/s3"$'\n'"newline/03_plane.cpp"
cp "$work/class/s3"$'\n'"newline/03_plane.cpp" "$work/class/s2|pipe/"
ln -s "s2|pipe" "$work/class/s4_link"
# Two names that once showed alike (a control character was shown as "?"): each keeps
# its own points; and a name a spreadsheet would run as a formula
mkdir -p "$work/class/s6a?b" "$work/class/s6a"$'\x01'"b" "$work/class/=s7"
cp "$work/class/s2|pipe/03_plane.cpp" "$work/class/s6a"$'\x01'"b/"
ln -s "../s2|pipe/03_plane.cpp" "$work/class/s5_copier/03_plane.cpp"
"$root/scripts/grade-class.sh" "$work/class" --out "$work/out" >"$work/log" 2>&1 ||
    { cat "$work/log"; exit 1; }
cat "$work/out/class.md"
python3 - "$work/out/class.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head, rows = rows[0], {r[0]: r for r in rows[1:]}
want = ["'=s7", 's1,comma "quoted"', "s2|pipe", "s3\\nnewline", "s4_link", "s5_copier",
        "s6a?b", "s6a\\x01b"]
assert sorted(rows) == want, sorted(rows)
assert all(len(r) == len(head) for r in rows.values()), [len(r) for r in rows.values()]
total, notes = head.index("total"), head.index("notes")
def check(name, points, note):
    r = rows[name]
    assert float(r[total]) == points, (name, r[total], points)
    assert note in r[notes], (name, r[notes], note)
check("s2|pipe", 10, "01_pixel_loop missing")
check("s3\\nnewline", 10, "04_sphere missing")
check("s4_link", 0, "refused: the hand-in is a symbolic link")
check("s5_copier", 0, "03_plane refused")
check("s5_copier", 0, "refused 03_plane.cpp: a symbolic link")
check("s6a?b", 0, "03_plane missing")
check("s6a\\x01b", 10, "04_sphere missing")
check("'=s7", 0, "03_plane missing")
PY
grep -qF '| s2\|pipe |' "$work/out/class.md" || { echo "FAIL: '|' not escaped"; exit 1; }
echo PASS
