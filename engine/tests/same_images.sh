#!/usr/bin/env bash
# The images with and without the geometry engine, byte for byte: renders every sample
# scene with two raylab-render binaries, one of a build with the engine and one of a build
# with RAYLAB_WITH_ENGINE=OFF (the scene's queries then call the reference modules one
# primitive at a time), in every shading mode, with shadows, antialiasing and area
# lights, and compares the linear float images (PFM) and the 8-bit ones (PNG).
#
# Usage: same_images.sh WITH_ENGINE/raylab-render WITHOUT_ENGINE/raylab-render
set -euo pipefail
with=$1 without=$2
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
size=(--width 96 --height 72 --threads 2)
cases=(
    "--scene cornell"
    "--scene cornell --mode normals"
    "--scene cornell --mode depth"
    "--scene cornell --mode base --shadows off"
    "--scene cornell --spp 4 --light-size 0.3 --light-samples 4"
    "--scene cornell --spp 16 --aa adaptive --eye 0.9,0.9,0.9 --lookat -1,-1,-1"
    "--scene dtu"
    "--scene dtu --mode normals"
    "--scene dtu --spp 4 --light-size 0.5 --light-samples 2"
    "--scene blob"
    "--scene blob --mode normals"
    "--scene terrain"
    "--scene room"
    "--scene room --spp 4 --light-size 0.4"
)
failed=0
n=0
for c in "${cases[@]}"; do
    for ext in pfm png; do
        read -r -a args <<<"$c"
        "$with" "${args[@]}" "${size[@]}" --reference all --output "$out/a.$ext" >/dev/null
        "$without" "${args[@]}" "${size[@]}" --reference all --output "$out/b.$ext" >/dev/null
        if ! cmp -s "$out/a.$ext" "$out/b.$ext"; then
            echo "differs with and without the engine ($ext): $c" >&2
            failed=1
        fi
        n=$((n + 1))
    done
done
[[ $failed == 0 ]] || exit 1
echo "$n images the same byte for byte with and without the engine"
