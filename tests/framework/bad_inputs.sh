#!/usr/bin/env bash
# Runs the bad-input table (bad_inputs.tsv): every case through its entry point, checking
# the exit code, that the last line of stderr holds the expected fragment, and that no
# control character reaches the terminal.
#
# Usage: bad_inputs.sh RENDER INPUT_CHECK TABLE [--record]
#   RENDER       raylab-render
#   INPUT_CHECK  raylab-input-check (the viewer's --load-view and flags, without a window)
#   --record     print "id<TAB>exit<TAB>last stderr line" for every case and check nothing
#                (to compare the behaviour of two builds)
#
# Table: one case a line, tab-separated: ID, ENTRY, EXIT, FRAGMENT ("-": none), INPUT.
#   ENTRY render  INPUT is raylab-render's arguments (shell words; @T@ is a scratch folder
#                 with the fixtures below, @D@ the folder of this script's data)
#         obj     INPUT is OBJ text (echo -e escapes: \n \r \xHH \e; "|||" starts the text of @T@/m.mtl),
#                 loaded with raylab-render --scene @T@/case.obj
#         view    INPUT is view-file text (the same escapes), loaded as --load-view would
#         viewer  INPUT is the viewer's arguments (shell words)
#   root-only cases are marked ENTRY render!: skipped when running as root (root reads
#   files whatever their mode).
set -u
render=$(realpath "$1") check=$(realpath "$2") table=$3 mode=${4:-check}
data=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/data
T=$(mktemp -d "${TMPDIR:-/tmp}/raylab-bad.XXXXXX")
trap 'chmod -R u+rwx "$T" 2>/dev/null; rm -rf "$T"' EXIT

# Fixtures that cannot live in git: FIFOs, devices, folders, unreadable and large files
mkfifo "$T/fifo.obj" "$T/fifo.view" "$T/fifo.mtl" "$T/fifo.png"
ln -s /dev/full "$T/full.png"
ln -s "$T/no/such/x.png" "$T/dangling.png"
mkdir -p "$T/dir.obj" "$T/ro" "$T/dir.png"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/ok.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/unreadable.obj"
chmod 000 "$T/unreadable.obj"
chmod 555 "$T/ro"
ln -s /dev/zero "$T/zero.obj"
ln -s /dev/null "$T/null.obj"
printf 'mtllib fifo.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/fifo-mtl.obj"
printf 'mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/zero-mtl.obj"
printf 'mtllib dir.obj\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/dir-mtl.obj"
printf 'mtllib ok.obj\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$T/obj-mtl.obj"
head -c 5000 /dev/zero | tr '\0' x | sed 's/^/# /' >"$T/long.view"
{ printf 'eye 0 0 3\nlookat 0 0 0\nup 0 1 0\nfov 40\n'; head -c 70000 /dev/zero | tr '\0' '#'; } \
    >"$T/big.view"
{ printf 'v 0 0 0\n'; head -c 5000000 /dev/zero | tr '\0' '1'; printf '\n'; } >"$T/longline.obj"
printf 'eye 0 0 3\nlookat 0 0 0\nup 0 1 0\nfov 40\n' >"$T/ok.view"

failed=0 ran=0 skipped=0
while IFS=$'\t' read -r id entry want fragment input || [[ -n $id ]]; do
    [[ -z $id || $id == \#* ]] && continue
    if [[ $entry == *! ]]; then
        entry=${entry%!}
        if ((EUID == 0)); then skipped=$((skipped + 1)); continue; fi
    fi
    input=${input//@T@/$T}
    fragment=${fragment//@T@/$T}
    input=${input//@D@/$data}
    out=$T/out.png
    case $entry in
        render) eval "args=($input)"; cmd=("$render" --width 8 --height 8 --output "$out" "${args[@]}") ;;
        obj)
            printf '%b' "${input%%|||*}" >"$T/case.obj"
            [[ $input == *'|||'* ]] && printf '%b' "${input#*|||}" >"$T/m.mtl"
            cmd=("$render" --width 8 --height 8 --output "$out" --scene "$T/case.obj") ;;
        view) printf '%b' "$input" >"$T/case.view"; cmd=("$check" view "$T/case.view") ;;
        viewer) eval "args=($input)"; cmd=("$check" viewer "${args[@]}") ;;
        *) echo "$id: unknown entry '$entry'"; failed=$((failed + 1)); continue ;;
    esac
    ran=$((ran + 1))
    err=$(cd "$T" && timeout 20 "${cmd[@]}" 2>&1 >/dev/null </dev/null)
    rc=$?
    last=$(printf '%s\n' "$err" | tail -n 1)
    rm -f "$T/case.obj" "$T/m.mtl" "$T/case.view" "$out"
    if [[ $mode == --record ]]; then
        printf '%s\t%s\t%s\n' "$id" "$rc" "$(printf '%s' "$last" | LC_ALL=C tr -c '[:print:]' '?')"
        continue
    fi
    problem=''
    [[ $rc == "$want" ]] || problem="exit $rc, expected $want"
    [[ $fragment == - || $last == *"$fragment"* ]] || problem+="${problem:+; }message lacks '$fragment'"
    if printf '%s' "$err" | LC_ALL=C grep -q $'[\x01-\x08\x0b-\x1f\x7f]'; then
        problem+="${problem:+; }control characters on stderr"
    fi
    if [[ -n $problem ]]; then
        failed=$((failed + 1))
        printf 'FAIL %s (%s): %s\n    stderr: %s\n' "$id" "$entry" "$problem" "$last"
    fi
done <"$table"
[[ $mode == --record ]] && exit 0
echo "bad inputs: $ran cases run, $skipped skipped (root), $failed failed"
((failed == 0 && ran > 0))
