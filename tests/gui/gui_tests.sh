#!/usr/bin/env bash
# GUI tests of the viewer under Xvfb (Mesa software GL), driven by ctest (LABELS gui).
#
#   gui_tests.sh CASE VIEWER RENDER PNG_DIFF WORKDIR
#
# Cases:
#   screenshot   the viewer's saved image equals raylab-render's for the same flags, and
#                the image region of its window screenshot matches within 2 of 255
#   keys         arrow keys walk, W moves the light, a drag orbits (read from --save-view)
#   focus        keys typed into a panel text field move nothing
#   run-tests    "Run tests" grades in child processes (a fake grader crashes in one
#                module) and --report writes the folder
#   small-panel  at 1024x640 and UI scale 1.5 the module rows stay on the first screen and
#                the image region still equals raylab-render's (no overlay)
#   first-screen at the default 1280x800, UI scale 1 and 1.5: the Modules section comes
#                first and ends within the window (no scrolling), the debug view opens
#                clear of the panel, the inspector shows the reference's ray
#   inspector    a pinned pixel in the box's shadow: with the shadow stub the student's
#                side is lit, the reference's shadow ray is blocked by a named triangle
#   debug-view   the 3D debug view draws the scene and the pinned pixel's rays
#   skip         shadows off, then on again: the second is the kept first frame (no
#                render); an exposure drag tone-maps again and renders nothing
#   repeat       --repeat 3 renders the same full frame three times (neither the kept
#                frame nor its camera hits answer) and logs the medians; the image is
#                raylab-render's
#   no-display   without DISPLAY: exit code 2 and a one-line message, no crash
# Exit 77 (ctest: skipped) when xvfb-run or xdotool is missing.
set -u
case_name=$1 viewer=$2 render=$3 png_diff=$4 work=$5
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
xvfb() { xvfb-run -a -s '-screen 0 1280x1024x24' "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
need() { command -v "$1" > /dev/null || { echo "SKIP: $1 not installed"; exit 77; }; }

# "panel: modules start at S, end at E, window H, scroll max M" as "S E H M"
n='\([0-9]*\)'
panel_line() {
    sed -n "s/.*modules start at $n, end at $n, window $n, scroll max $n.*/\\1 \\2 \\3 \\4/p" "$1"
}

# The value of KEY (eye, lookat, light) in a view file, as "x y z" (light: position)
field() { awk -v k="$2" '$1 == k { print $2, $3, $4; exit }' "$1"; }

# Starts the viewer in the background under one Xvfb, runs the xdotool steps in $1,
# quits with Ctrl+Q and waits; the view ends in view.txt, the output in out.txt
drive() {
    local steps=$1; shift
    xvfb bash -c '
        viewer=$1 steps=$2; shift 2
        "$viewer" --save-view view.txt "$@" > out.txt 2>&1 &
        pid=$!
        for _ in $(seq 600); do grep -q "^rendered" out.txt && break; sleep 0.1; done
        # "panel: widget NAME at X,Y size WxH" as "X Y W H"
        widget() {
            for _ in $(seq 100); do grep -q "widget $1 at" out.txt && break; sleep 0.1; done
            sed -n "s/^panel: widget $1 at \([0-9]*\),\([0-9]*\) size \([0-9]*\)x\([0-9]*\)$/\1 \2 \3 \4/p" out.txt
        }
        wid=$(xdotool search --sync --onlyvisible --name "^raylab - " | head -n 1)
        xdotool windowfocus --sync "$wid" 2> /dev/null || true
        eval "$steps"
        xdotool key --window "$wid" ctrl+q
        wait $pid' _ "$viewer" "$steps" "$@"
}

flags=(--scene cornell --width 320 --height 240 --eye 0.4,0.3,2.8 --fov 60)
case $case_name in
screenshot)
    need xvfb-run
    "$render" "${flags[@]}" --output render.png > render.txt ||
        fail "raylab-render failed"
    xvfb "$viewer" "${flags[@]}" --image-scale 1 --window 1000x600 --frames 3 \
        --screenshot shot.png --save-image saved.png > out.txt 2>&1 ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt
    # "screenshot shot.png: window 1000x600, image at X,Y size WxH"
    n='\([0-9]*\)'
    read -r x y w h < <(sed -n "s/.*image at $n,$n size ${n}x$n.*/\\1 \\2 \\3 \\4/p" \
        out.txt)
    [ "${w:-}" = 320 ] && [ "${h:-}" = 240 ] ||
        fail "image region not 320x240: '${x:-} ${y:-} ${w:-} ${h:-}'"
    "$png_diff" saved.png render.png --tolerance 0 ||
        fail "saved image differs from raylab-render"
    "$png_diff" shot.png render.png --crop "$x,$y,$w,$h" --tolerance 2 ||
        fail "window region differs from raylab-render"
    ;;
keys)
    need xvfb-run; need xdotool
    # Hold Up (walk), W (light forward), then drag right over the image (orbit)
    drive 'xdotool mousemove --window "$wid" 900 300
           xdotool keydown Up; sleep 0.4; xdotool keyup Up
           xdotool keydown w; sleep 0.4; xdotool keyup w
           xdotool mousedown 1
           for s in 1 2 3 4 5 6; do xdotool mousemove_relative 10 0; sleep 0.05; done
           xdotool mouseup 1; sleep 0.2' --width 160 --height 120 ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt view.txt
    read -r ex ey ez < <(field view.txt eye)
    read -r lx ly lz < <(field view.txt lookat)
    read -r px py pz < <(field view.txt light)
    # Start: eye (0,0,3), look-at 0, light (0,0.5,0.7). Walking moves the look-at to
    # z < 0 (the eye too, but the orbit then moves it); the orbit swings the eye
    # sideways at the same distance 3; W moves the light towards -z
    awk -v lz="$lz" 'BEGIN { exit !(lz < -0.01) }' ||
        fail "Up did not walk: lookat z = $lz"
    awk -v ex="$ex" 'BEGIN { exit !(ex > 0.01 || ex < -0.01) }' ||
        fail "drag did not orbit: eye x = $ex"
    awk -v ex="$ex" -v ey="$ey" -v ez="$ez" -v lx="$lx" -v ly="$ly" -v lz="$lz" \
        'BEGIN { d = sqrt((ex-lx)^2 + (ey-ly)^2 + (ez-lz)^2)
                 exit !(d > 2.999 && d < 3.001) }' ||
        fail "orbit changed the distance"
    awk -v pz="$pz" 'BEGIN { exit !(pz < 0.69) }' ||
        fail "W did not move the light: z = $pz"
    awk -v py="$py" 'BEGIN { exit !(py > 0.4999 && py < 0.5001) }' ||
        fail "W moved the light up"
    ;;
focus)
    need xvfb-run; need xdotool
    # Click into the OBJ path field (top of the panel), then hold Up and type "wasd"
    drive 'read -r x y _ < <(widget obj-path)
           xdotool mousemove --window "$wid" $((x + 20)) $((y + 8)) click 1; sleep 0.2
           xdotool keydown Up; sleep 0.4; xdotool keyup Up
           xdotool type --delay 50 wasd; sleep 0.2' --width 160 --height 120 ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt view.txt
    [ "$(field view.txt eye)" = "0 0 3" ] ||
        fail "keys moved the camera while a field had focus"
    [ "$(field view.txt light)" = "0 0.5 0.699999988" ] ||
        fail "keys moved the light while a field had focus: $(field view.txt light)"
    ;;
run-tests)
    need xvfb-run
    # A stand-in for raylab-grading-tests in the grade driver's protocol: 05_triangle's
    # worker crashes, every other module passes two cases of three
    cat > fake-grader.sh << 'SH'
#!/bin/sh
ids="01_pixel_loop 02_camera 03_plane 04_sphere 05_triangle 06_point_light 07_lambert 08_shadows 09_antialiasing 10_area_light"
case "$1" in
--list-test-cases) for id in $ids; do printf 'list\t%s\t%s\n' $id a $id b $id c; done > "$RAYLAB_GRADE_LOG";;
--test-suite=05_triangle) printf 'crash\t05_triangle\ta\tthe worker crashed (SIGSEGV, Segmentation fault)\n' > "$RAYLAB_GRADE_LOG";;
--test-suite=*) id=${1#--test-suite=}
    printf 'case\t%s\t%s\t%s\n' $id a pass $id b pass $id c fail > "$RAYLAB_GRADE_LOG";;
esac
SH
    chmod +x fake-grader.sh
    RAYLAB_GRADING_TESTS=$PWD/fake-grader.sh xvfb "$viewer" --width 64 --height 48 \
        --run-tests --frames 2 --report report > out.txt 2>&1 ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt
    grep -q "05_triangle  *crashed" out.txt || fail "no crash reported for 05_triangle"
    grep -q "04_sphere  *2/3 passed" out.txt || fail "no result for 04_sphere"
    for f in view.txt settings.txt image.png log.txt; do
        [ -s "report/$f" ] || fail "report/$f missing"
    done
    grep -q "raylab-render --scene cornell" report/settings.txt ||
        fail "no command in report"
    ;;
small-panel)
    need xvfb-run
    "$render" "${flags[@]}" --output render.png > render.txt ||
        fail "raylab-render failed"
    xvfb "$viewer" "${flags[@]}" --image-scale 1 --window 1024x640 --ui-scale 1.5 \
        --frames 3 --screenshot shot.png > out.txt 2>&1 ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt
    n='\([0-9]*\)'
    read -r x y w h < <(sed -n "s/.*image at $n,$n size ${n}x$n.*/\\1 \\2 \\3 \\4/p" \
        out.txt)
    [ "${w:-}" = 320 ] || fail "image region not 320 wide: '${w:-}'"
    "$png_diff" shot.png render.png --crop "$x,$y,$w,$h" --tolerance 2 ||
        fail "something covers the image (window region differs from raylab-render)"
    read -r top e ph s < <(panel_line out.txt)
    [ -n "${e:-}" ] || fail "no panel line"
    [ "$e" -le "$ph" ] || fail "module rows end at $e, below the window's $ph"
    ;;
first-screen)
    need xvfb-run
    for scale in 1 1.5; do
        xvfb "$viewer" --ui-scale "$scale" --pin 400,300 --student camera --debug-view \
            --frames 3 --screenshot "shot-$scale.png" > out.txt 2>&1 ||
            { cat out.txt; fail "the viewer failed at UI scale $scale"; }
        cat out.txt
        read -r top e ph s < <(panel_line out.txt)
        [ -n "${e:-}" ] || fail "no panel line"
        # Modules first (below the first-run hint only), ending on screen
        limit=$([ "$scale" = 1 ] && echo 200 || echo 300)
        [ "$top" -le "$limit" ] ||
            fail "UI $scale: the Modules section starts at $top, not first"
        [ "$e" -le "$ph" ] || fail "UI $scale: module rows end at $e, below the window's $ph"
        grep -q "^pinned (400, 300) reference ray o (0.000, 0.000, 3.000) w (0.1641, -0.1234, -0.9787)" \
            out.txt || fail "the inspector has no reference ray"
    done
    ;;
inspector)
    need xvfb-run
    xvfb "$viewer" --scene cornell --width 320 --height 240 --pin 240,225 \
        --student shadows --frames 3 > out.txt 2>&1 ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt
    grep -q "pinned (240, 225) yours light 1: lit$" out.txt ||
        fail "the shadow stub's side is not 'lit' without a ray"
    grep -q "pinned (240, 225) reference light 1: shadow, blocked by triangle [0-9]" \
        out.txt || fail "the reference's shadow ray names no blocker"
    ;;
debug-view)
    need xvfb-run
    xvfb "$viewer" --scene cornell --width 320 --height 240 --pin 240,225 --debug-view \
        --frames 3 --screenshot shot.png > out.txt 2>&1 ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt
    # 30 triangles; 3 light-cross lines + camera ray + normal + one shadow ray
    grep -q "debug view: 30 triangles, 6 lines" out.txt || fail "wrong debug view content"
    ;;
skip)
    need xvfb-run; need xdotool
    # The shadows checkbox and the exposure slider of the Rendering section (where the
    # viewer logs them; a window 1000 high shows them unscrolled); each step waits for
    # the log line it causes
    wait_for() { echo 'for _ in $(seq 100); do grep -q "'"$1"'" out.txt && break; sleep 0.1; done'; }
    drive "read -r bx by _ < <(widget shadows); read -r ex ey ew eh < <(widget exposure)
           xdotool mousemove --window \"\$wid\" \$((bx + 8)) \$((by + 8)) click 1
           $(wait_for 'shadows off')
           xdotool mousemove --window \"\$wid\" \$((bx + 8)) \$((by + 8)) click 1
           $(wait_for '^reused')
           xdotool mousemove --window \"\$wid\" \$((ex + ew / 2)) \$((ey + 8)) mousedown 1
           sleep 0.1
           xdotool mousemove --window \"\$wid\" \$((ex + ew / 2 + 67)) \$((ey + 8)); sleep 0.2
           xdotool mouseup 1
           sleep 0.5" --window 1280x1000 --width 160 --height 120 --report report ||
        { cat out.txt; fail "the viewer failed"; }
    cat out.txt
    [ "$(grep -c '^rendered' out.txt)" = 2 ] || fail "not two renders (on, off)"
    grep -q '^rendered 160x120 (lambert, shadows off)' out.txt || fail "no shadows off"
    grep -q '^reused 160x120 (lambert, shadows on)' out.txt ||
        fail "shadows on again was not the kept frame"
    # (a job for the exposure would be answered by the kept frame: one more "reused")
    [ "$(grep -c '^reused' out.txt)" = 1 ] || fail "the exposure drag sent a job"
    awk '$1 == "exposure:" { exit !($2 > 0.5) }' report/settings.txt ||
        fail "the exposure drag did not change the exposure"
    ;;
repeat)
    need xvfb-run
    "$render" "${flags[@]}" --output render.png > render.txt ||
        fail "raylab-render failed"
    xvfb "$viewer" "${flags[@]}" --repeat 3 --frames 1 --save-image saved.png \
        --report report > out.txt 2>&1 || { cat out.txt; fail "the viewer failed"; }
    cat out.txt
    [ "$(grep -c '^rendered 320x240' out.txt)" = 3 ] ||
        fail "not three renders of the frame"
    ! grep -q '^reused' out.txt || fail "--repeat reused a kept frame"
    # Each a full render, as raylab-render's: every camera ray cast again, none of the
    # last frame's camera hits shaded again, though the unchanged view would allow it
    ! grep -q 'camera hits reused' out.txt || fail "--repeat reused the camera hits"
    grep -q '^rays: 76800 camera ([0-9]* in packets, 0 more reused)' report/settings.txt ||
        fail "the last frame did not cast all 76800 camera rays: $(grep '^rays' report/settings.txt)"
    grep -q -- '--repeat: 3 full frames, render time median [0-9.]* ms, change to screen' \
        out.txt || fail "no --repeat medians in the log"
    "$png_diff" saved.png render.png --tolerance 0 ||
        fail "saved image differs from raylab-render"
    ;;
no-display)
    env -u DISPLAY -u WAYLAND_DISPLAY "$viewer" --frames 1 > out.txt 2> err.txt
    code=$?
    cat err.txt
    [ "$code" = 2 ] || fail "exit code $code, expected 2"
    [ "$(wc -l < err.txt)" = 1 ] || fail "expected one line on stderr"
    grep -q "cannot open a window" err.txt || fail "no clear message"
    # Bad flags and files are named, before any window
    "$viewer" --load-view /no/such/view.txt 2> err.txt
    [ $? = 2 ] && grep -q "/no/such/view.txt: cannot open" err.txt || fail "bad view file"
    "$viewer" --frames x 2> err.txt
    [ $? = 2 ] && grep -q "frames: 'x'" err.txt || fail "bad --frames"
    ;;
*) fail "unknown case $case_name" ;;
esac
echo "PASS: $case_name"
