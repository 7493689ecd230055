#!/usr/bin/env bash
# ctest class/odd-names: hand-in folders named with a comma, a quote and a '|' keep one
# row each in class.csv (quoted as RFC 4180 says) and class.md ('|' escaped).
# Usage: check_odd_names.sh ROOT WORKDIR
set -euo pipefail
root=$1 work=$2
rm -rf "$work" && mkdir -p "$work/class/s1,comma \"quoted\"" "$work/class/s2|pipe"
"$root/scripts/grade-class.sh" "$work/class" --out "$work/out" >"$work/log" 2>&1 ||
    { cat "$work/log"; exit 1; }
python3 - "$work/out/class.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
names = sorted(r[0] for r in rows[1:])
assert names == ['s1,comma "quoted"', "s2|pipe"], names
assert all(len(r) == len(rows[0]) for r in rows), [len(r) for r in rows]
PY
grep -qF '| s2\|pipe |' "$work/out/class.md" || { echo "FAIL: '|' not escaped"; exit 1; }
echo PASS
