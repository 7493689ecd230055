#!/usr/bin/env bash
# Regenerate the expected images of the handouts (docs/images/handouts/) with the reference
# solutions, so that every picture in docs/handouts/ is what `raylab-render --reference all`
# draws today.
#
# Usage: scripts/render-handout-images.sh [--list] [RAYLAB_RENDER]
#   RAYLAB_RENDER  path to a raylab-render built with solutions/ (default: builds one in
#                  build-docs/, headless, with Ninja when it is installed)
#   --list         print the commands instead of running them
#
# The renders are deterministic (one ray per pixel centre, or seeded samples), so running the script
# again changes no file unless a reference module, a scene or the tone mapping changed.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$root/docs/images/handouts"

list=false
render=""
for arg in "$@"; do
    case $arg in
        -h | --help) sed -n '2,/^[^#]/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0 ;;
        --list) list=true ;;
        -*) echo "error: unknown option $arg" >&2; exit 1 ;;
        *) render=$arg ;;
    esac
done
render=${render:-${RAYLAB_RENDER:-}}

# The images: file name, then the flags after `raylab-render --reference all`
images=(
    "01_pixel_loop.png   --scene cornell --mode base --width 400 --height 400"
    "02_camera.png       --scene dtu --mode base --width 480 --height 360"
    "02_camera_fov90.png --scene dtu --mode base --width 480 --height 360 --fov 90"
    "03_plane.png        --scene dtu --mode depth --width 480 --height 360"
    "04_sphere.png       --scene dtu --mode normals --width 480 --height 360"
    "05_triangle.png     --scene cornell --mode normals --width 400 --height 400"
    "06_point_light.png  --scene dtu --mode lambert --shadows off --width 480 --height 360"
    "07_lambert.png      --scene cornell --mode lambert --shadows off --width 400 --height 400"
    "08_shadows.png      --scene cornell --mode lambert --shadows on --width 400 --height 400"
    "08_shadows_dtu.png  --scene dtu --mode lambert --shadows on --width 480 --height 360"
    "09_one_sample.png   --scene dtu --width 240 --height 180"
    "09_antialiasing.png --scene dtu --width 240 --height 180 --spp 16 --aa stratified"
    "09_adaptive.png     --scene dtu --width 240 --height 180 --spp 16 --aa adaptive"
    "10_area_light.png   --scene cornell --width 400 --height 400 --light-size 0.4 --light-samples 64"
    "10_area_light_dtu.png --scene dtu --width 480 --height 360 --light-size 1.5 --light-samples 64"
)

if $list; then
    for entry in "${images[@]}"; do
        read -r file flags <<<"$entry"
        echo "raylab-render --reference all $flags --output docs/images/handouts/$file"
    done
    exit 0
fi

# A raylab-render that has the reference modules
if [[ -z $render ]]; then
    build="$root/build-docs"
    generator=()
    if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
    echo "==> Building raylab-render in $build"
    cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
        -DRAYLAB_WITH_GUI=OFF -DRAYLAB_BUILD_TESTS=OFF >/dev/null
    cmake --build "$build" --target raylab-render -j "${RAYLAB_JOBS:-2}" >/dev/null
    render="$build/framework/raylab-render"
fi
[[ -x $render ]] || { echo "error: $render is not an executable raylab-render" >&2; exit 1; }

mkdir -p "$out"
echo "==> Rendering the handout images into ${out#"$root"/}"
for entry in "${images[@]}"; do
    read -r file flags <<<"$entry"
    # shellcheck disable=SC2086 # flags are words on purpose
    "$render" --reference all $flags --output "$out/$file" >/dev/null
    echo "    $file  ($flags)"
done
