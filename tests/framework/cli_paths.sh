#!/usr/bin/env bash
# raylab-render's paths that the bad-input table cannot see (it reads stderr only).
# Usage: cli_paths.sh RENDER CASE
#   wrote-name   an output name with ESC and BEL: written, and "wrote NAME" escaped
#   write-fails  a PNG and a PFM write that fail (file size limit): exit 2, the reason
#   budget       a render above the 1e10-ray budget prints its estimate first, and
#                Ctrl+C (SIGINT) stops it: exit 130, no file
#   progress     on a terminal the progress line shows the fraction done and time left
set -u
render=$(realpath "$1") case_name=$2
T=$(mktemp -d "${TMPDIR:-/tmp}/raylab-cli.XXXXXX")
trap 'rm -rf "$T"' EXIT
cd "$T" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
has_control() { LC_ALL=C grep -q $'[\x01-\x08\x0b-\x1f\x7f]' "$1"; }

case $case_name in
wrote-name)
    name=$'a\e[31m\a.png'
    "$render" --width 8 --height 8 --output "$name" > out.txt 2> err.txt ||
        fail "render failed: $(cat err.txt)"
    [ -f "$name" ] || fail "no file '$name'"
    has_control out.txt && fail "control characters on stdout: $(cat -v out.txt)"
    grep -qF 'wrote a\x1b[31m\x07.png' out.txt || fail "no escaped 'wrote': $(cat out.txt)"
    ;;
write-fails)
    for ext in png pfm; do
        # A 1-block file size limit: the write fails with EFBIG (SIGXFSZ ignored)
        (trap '' XFSZ; ulimit -f 1; exec "$render" --width 200 --height 200 --output "big.$ext") \
            > out.txt 2> err.txt
        code=$?
        [ "$code" = 2 ] || fail "$ext: exit $code, expected 2 ($(cat out.txt err.txt))"
        grep -q "cannot write ${ext^^} 'big.$ext': File too large" err.txt ||
            fail "$ext: no reason: $(cat err.txt)"
        grep -q '^wrote' out.txt && fail "$ext: says 'wrote' after a failed write"
    done
    ;;
budget)
    # Job control: the background render gets SIGINT as from a terminal's Ctrl+C
    set -m
    "$render" --width 4096 --height 4096 --spp 1024 --output never.png > out.txt 2> err.txt &
    pid=$!
    for _ in $(seq 600); do grep -q '^note: this render casts' out.txt && break; sleep 0.1; done
    grep -q '^note: this render casts up to 3.4e+10 rays' out.txt ||
        { kill -KILL $pid; fail "no estimate before rendering: $(cat out.txt)"; }
    kill -INT $pid
    wait $pid
    code=$?
    [ "$code" = 130 ] || fail "exit $code after Ctrl+C, expected 130"
    grep -q 'interrupted (Ctrl+C): nothing written' err.txt || fail "$(cat err.txt)"
    [ -e never.png ] && fail "an interrupted render wrote its file"
    # Below the budget: no note
    "$render" --width 64 --height 48 --output small.png > out.txt || fail "small render"
    grep -q '^note: this render casts' out.txt && fail "a note below the budget"
    ;;
progress)
    command -v script > /dev/null || { echo "SKIP: script not installed"; exit 77; }
    # Ctrl+C after 10 s: the line shows within a fraction of a second, and a sanitizer
    # build would take many minutes for the whole frame
    script -qec "timeout --preserve-status -s INT 10 '$render' --width 1024 --height 1024 \
        --spp 64 --output p.png" typescript > /dev/null
    code=$?
    [ "$code" = 0 ] || [ "$code" = 130 ] ||
        fail "render on a terminal: exit $code, expected 0 or 130: $(cat -v typescript)"
    grep -qa 'rendering 1024x1024, [0-9]* s left *[0-9]*%' typescript ||
        fail "no fraction and time left: $(cat -v typescript | tail -c 300)"
    ;;
*) fail "unknown case $case_name" ;;
esac
echo "ok: $case_name"
