#!/usr/bin/env bash
# The previewer's GUI tests, under Xvfb with Mesa's llvmpipe: what only the window can show.
#
#   tests/gui/run_gui_tests.sh BUILD_DIR [OUT_DIR]
#
# Starts BUILD_DIR/bin/phonglab with a test script (commands run inside its main loop; see
# docs/previewer.md) and real X input from xdotool, then checks the screenshots and state dumps
# it wrote: real input (drags, clicks, keys, the arrow of a light out of view, H taps), the GL
# window's pixels (the screen's codes against phonglab-cli's PNG, exposure, presenter mode's
# caption) and the process (signals, no display, a 1x1 window). What the screen shows of the
# instruments, the overlays, a student's formula and image, the indirect light and the browser is
# drawn headless on the CPU (tests/shell/test_screen_*.cpp); the shell's own input and state are
# tests/shell too, the rules under them GoogleTests over the session (docs/previewer.md#tests).
# tools/readme_images.sh takes the README's pictures from the screenshots written here and there.
# Exit status 0 when every check passes. Needs: xvfb-run, xdotool, ImageMagick.
set -u

SELF_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SELF=$SELF_DIR/$(basename "${BASH_SOURCE[0]}")
# shellcheck source=tests/gui/lib.sh
source "$SELF_DIR/lib.sh"
gui_script_setup gui-tests "$@"

# The viewport of a 1280x720 window is the 880x720 on the left (the panels take 400); below
# the stats overlay, this region shows only the scene.
SCENE_REGION=880x440+0+280

# --- Session 1: drag, pick, edit, exposure, light marker, resize, quit guard ----------------
session_view() {
  local dir=$OUT/view
  mkdir -p "$dir"
  cat >"$dir/script.txt" <<EOF
set render target_spp 1
wait_idle 120
screenshot $dir/01_start.png
save_png $dir/shown.png
save_pfm $dir/linear.pfm
dump_state $dir/s01.txt
set render resolution_scale 0.5
wait_idle 120
screenshot $dir/02_half.png
drag left 440 480 580 520 12
wait_idle 120
screenshot $dir/03_orbit.png
dump_state $dir/s03.txt
touch $dir/xdotool_ready
wait_file $dir/xdotool_done 60
wait_idle 120
screenshot $dir/04_xdotool.png
dump_state $dir/s04.txt
wait_frames 30
dump_state $dir/s04b.txt
key R
wait_idle 120
screenshot $dir/05_reset.png
dump_state $dir/s05.txt
touch $dir/pick_ready
wait_file $dir/pick_done 60
wait_frames 3
dump_state $dir/s06.txt
set material plastic kd 0.1 0.2 0.9
wait_idle 120
screenshot $dir/07_edit.png
dump_state $dir/s07.txt
set display exposure 1.5
wait_frames 3
screenshot $dir/08_exposure.png
dump_state $dir/s08.txt
set display exposure 0
set light 0 position 1.5 2.2 1.5
wait_idle 120
dump_state $dir/s09a.txt
drag_light 0 80 0
wait_idle 120
dump_state $dir/s09.txt
screenshot $dir/09_light.png
resize 1 1
wait_frames 10
dump_state $dir/s10.txt
resize 1280 720
wait_frames 5
wait_idle 120
screenshot $dir/11_back.png
dump_state $dir/s11.txt
key H
wait_idle 120
dump_state $dir/s12.txt
key H
close
wait_frames 5
dump_state $dir/s13.txt
screenshot $dir/13_modal.png
modal discard
wait_frames 300
fail the unsaved-changes dialog's Discard did not quit
EOF
  env -u LP_NUM_THREADS "$BIN" lecture --size 1280x720 --script "$dir/script.txt" --stats-log "$dir/stats.log" \
    >"$dir/stdout.txt" 2>"$dir/stderr.txt" &
  local pid=$!
  local win=""
  # Real X input: a left-drag in the viewport through the X server, then a click on the red
  # sphere to pick its material.
  if wait_for_file "$dir/xdotool_ready" 120 "$pid"; then
    cat /proc/"$pid"/task/*/comm >"$dir/threads.txt" 2>/dev/null  # the process's threads by name
    win=$(xdotool search --sync --limit 1 --name '^phonglab' 2>/dev/null | head -n 1)
    xdotool mousemove --window "$win" 300 560
    sleep 0.2
    xdotool mousedown 1
    for x in 320 340 360 380 400 420 440; do
      xdotool mousemove --window "$win" "$x" 560
      sleep 0.05
    done
    xdotool mouseup 1
    sleep 0.2
    touch "$dir/xdotool_done"
  fi
  if wait_for_file "$dir/pick_ready" 120 "$pid"; then
    xdotool mousemove --window "$win" 354 374
    sleep 0.2
    xdotool click 1
    sleep 0.2
    xdotool mousemove --window "$win" 1270 710  # out of the way of later scripted input
    touch "$dir/pick_done"
  fi
  finish "$dir" "$pid"
}

check_view() {
  local dir=$OUT/view
  echo "session 1: view, picking, editing, window handling"
  check_exit "$dir" "exits 0 after the guard's Discard"
  check "the first screenshot shows a scene, not a uniform image" greater "$(stddev "$dir/01_start.png" $SCENE_REGION)" 0.05
  check "the shown image was saved as PNG ($(state "$dir/s01.txt" image))" test -s "$dir/shown.png"
  check "the linear image was saved as PFM" test "$(head -c 2 "$dir/linear.pfm" 2>/dev/null)" = PF
  check "no NaN/Inf in the image" test "$(state "$dir/s01.txt" nan_count)" = 0
  check "a scripted orbit drag changed the camera" test "$(state "$dir/s03.txt" camera_position)" != "$(state "$dir/s01.txt" camera_position)"
  check "a scripted orbit drag changed the view" greater "$(rmse "$dir/02_half.png" "$dir/03_orbit.png" $SCENE_REGION)" 0.02
  check "software GL draws on the UI thread: no llvmpipe thread among the $(wc -l <"$dir/threads.txt") threads" \
    awk '/^llvmpipe/ { bad = 1 } END { exit bad || NR < 3 }' "$dir/threads.txt"
  check "the image's framebuffer runs from the top like the window's (flip-y): Mesa copies its rows" \
    test "$(state "$dir/s01.txt" image_rows_from_top)" = 1
  check "a real xdotool drag changed the camera" test "$(state "$dir/s04.txt" camera_position)" != "$(state "$dir/s03.txt" camera_position)"
  check "30 frames that change nothing are not drawn ($(state "$dir/s04.txt" frames_drawn) -> $(state "$dir/s04b.txt" frames_drawn) frames drawn)" \
    test "$(state "$dir/s04b.txt" frames_drawn)" -le "$(( $(state "$dir/s04.txt" frames_drawn) + 1 ))"
  check "a real xdotool drag changed the view" greater "$(rmse "$dir/03_orbit.png" "$dir/04_xdotool.png" $SCENE_REGION)" 0.02
  check "R resets the camera" test "$(state "$dir/s05.txt" camera_position)" = "$(state "$dir/s01.txt" camera_position)"
  check "the same camera renders the same image (reset vs start)" less "$(rmse "$dir/02_half.png" "$dir/05_reset.png" $SCENE_REGION)" 0.002
  check "clicking the red sphere selects its material (picked: $(state "$dir/s06.txt" picked))" test "$(state "$dir/s06.txt" selected_material)" = plastic
  check "a material edit marks the scene unsaved" test "$(state "$dir/s07.txt" dirty)" = 1
  check "a material edit changed the image" greater "$(rmse "$dir/05_reset.png" "$dir/07_edit.png" $SCENE_REGION)" 0.01
  check "exposure changed what is shown" greater "$(rmse "$dir/07_edit.png" "$dir/08_exposure.png" $SCENE_REGION)" 0.02
  check "exposure did not restart rendering" test "$(state "$dir/s08.txt" generation)" = "$(state "$dir/s07.txt" generation)"
  check "dragging the light marker moved the light ($(state "$dir/s09a.txt" light0_position) -> $(state "$dir/s09.txt" light0_position))" \
    test "$(state "$dir/s09.txt" light0_position)" != "$(state "$dir/s09a.txt" light0_position)"
  check "a 1x1 window keeps running ($(state "$dir/s10.txt" framebuffer))" test "$(state "$dir/s10.txt" framebuffer)" = 1x1
  check "back at 1280x720 the scene shows again" greater "$(stddev "$dir/11_back.png" $SCENE_REGION)" 0.05
  check "back at 1280x720 the render size follows ($(state "$dir/s11.txt" render))" test "$(state "$dir/s11.txt" render)" = 440x360
  check "H hides the panels and the render fills the window ($(state "$dir/s12.txt" render))" test "$(state "$dir/s12.txt" render)" = 640x360
  check "closing with unsaved edits opens the guard" test "$(state "$dir/s13.txt" modal)" = 1
  check "UI frames were timed" grep -q '^summary session ui_frames' "$dir/stats.log"
}

# A scene file of the test's own.
write_scene() {  # write_scene FILE RED_KD RADIUS
  cat >"$1" <<EOF
{
  "camera": {"position": [0, 1.5, 6], "look_at": [0, 0.8, 0], "up": [0, 1, 0], "fov_y": 40},
  "background": [0.05, 0.06, 0.09],
  "lights": [{"type": "point", "position": [2, 6, 4], "intensity": [0.9, 0.9, 0.9]}],
  "materials": {
    "floor": {"ka": 0.04, "kd": 0.6},
    "red": {"ka": 0.05, "kd": $2, "ks": 0.5, "n": 20}
  },
  "objects": [
    {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "floor"},
    {"type": "sphere", "center": [0, 0.8, 0], "radius": $3, "material": "red"}
  ]
}
EOF
}

# --- Session 4: rays: the ray tree overlay, the depth cut, the heat map ----------------------
session_rays() {
  local dir=$OUT/rays
  mkdir -p "$dir"
  cat >"$dir/script.txt" <<EOF
set render target_spp 1
set display stats 0
# The whole window is the image: the screen's 8-bit codes against the CLI's PNG.
set display sidebar 0
wait_idle 120
screenshot $dir/r_screen.png
dump_state $dir/r_screen.txt
set display exposure 1
wait_frames 3
screenshot $dir/r_screen_ev1.png
quit
EOF
  "$BIN" lecture --size 1280x720 --script "$dir/script.txt" >"$dir/stdout.txt" 2>"$dir/stderr.txt"
  echo "$?" >"$dir/exit_code"
}

check_rays() {
  local dir=$OUT/rays cli=$BUILD_DIR/bin/phonglab-cli
  echo "session 4: ray tree overlay, depth cut, heat map on the screen (against the CLI: tests/shell/test_rays_input.cpp)"
  check_exit "$dir" "the script ran to the end"
  # The light markers with their labels and the hint at the bottom ("H shows the panels") are
  # drawn over the image: blacked out in both before comparing.
  local masks=(-draw "rectangle 440,676 840,720") m
  for m in $(seq 0 9); do
    local at
    at=$(state "$dir/r_screen.txt" "light${m}_marker")
    [ -n "$at" ] || continue
    masks+=(-draw "rectangle $(awk -v p="$at" 'BEGIN { split(p, a, " "); printf "%d,%d %d,%d", a[1] - 56, a[2] - 32, a[1] + 32, a[2] + 32 }')")
  done
  "$cli" render lecture --width 1280 --height 720 --spp 1 -o "$dir/cli_screen.png" >/dev/null
  convert "$dir/r_screen.png" -fill black "${masks[@]}" "$dir/r_screen_masked.png"
  convert "$dir/cli_screen.png" -fill black "${masks[@]}" "$dir/cli_screen_masked.png"
  check "the screen shows the codes of phonglab-cli's PNG, pixel for pixel ($(state "$dir/r_screen.txt" render), $((${#masks[@]} / 2)) regions masked)" \
    test "$(state "$dir/r_screen.txt" render)" = 1280x720 -a \
    "$(compare -metric AE "$dir/r_screen_masked.png" "$dir/cli_screen_masked.png" null: 2>&1)" = 0
  check "exposure +1 brightens the screen" greater "$(rmse "$dir/r_screen.png" "$dir/r_screen_ev1.png" 1280x720+0+0)" 0.02
}

# --- Session 5: the lecture's first minutes: what real X input and the screen show (the rest of
# the session's checks drive the shell headless: tests/shell/test_lecture_input.cpp) ----------
session_lecture() {
  local dir=$OUT/lecture
  mkdir -p "$dir"
  cat >"$dir/script.txt" <<EOF
set render target_spp 1
wait_idle 120
dump_state $dir/l00.txt
screenshot $dir/l00_start.png
# The arrow of the light out of view is grabbed by a real xdotool drag, and brings the light in.
touch $dir/arrow_ready
wait_file $dir/arrow_done 60
wait_idle 120
dump_state $dir/l04.txt
screenshot $dir/l04_light_dragged_in.png
# Seven real H taps with no delay: none is lost (the panels end hidden).
touch $dir/keys_ready
wait_file $dir/keys_done 60
wait_frames 10
dump_state $dir/l05.txt
screenshot $dir/l05_panels_hidden.png
key H
wait_frames 3
# What the hall sees: a term's caption, the keys, the embedded scenes at this window's aspect, the
# overlays on a light background, larger UI sizes (kept for looking at).
key 4
wait_idle 120
screenshot $dir/l14_specular_caption.png
key 1
key F1
wait_frames 3
screenshot $dir/l15_keys_help.png
key ESCAPE
wait_frames 2
open glass
wait_idle 120
screenshot $dir/l30_glass.png
probe 440 300
wait_frames 3
screenshot $dir/l30b_glass_tree.png
set display stats_details 1
set display ui_size 1.5
wait_frames 5
screenshot $dir/l30c_glass_ui_1_5.png
set display ui_size 1
set display stats_details 0
open shininess
wait_idle 120
screenshot $dir/l31_shininess.png
open cornell-sphere
wait_idle 120
screenshot $dir/l33_cornell_sphere.png
set display ui_size 2
wait_frames 5
screenshot $dir/l34_ui_size_2.png
set display ui_size 1
quit
EOF
  "$BIN" lecture --size 1280x720 --script "$dir/script.txt" >"$dir/stdout.txt" 2>"$dir/stderr.txt" &
  local pid=$! win="" x y
  if wait_for_file "$dir/arrow_ready" 120 "$pid"; then
    win=$(xdotool search --sync --limit 1 --name '^phonglab' 2>/dev/null | head -n 1)
    read -r x y <<<"$(state "$dir/l00.txt" light0_marker)"
    x=${x%.*} y=${y%.*}
    xdotool mousemove --window "$win" "$x" "$y"
    sleep 0.3
    xdotool mousedown 1
    for step in 1 2 3 4 5 6 7 8; do
      xdotool mousemove --window "$win" $((x - step * 30)) $((y + step * 15))
      sleep 0.05
    done
    xdotool mouseup 1
    sleep 0.2
    xdotool mousemove --window "$win" 1270 710
    touch "$dir/arrow_done"
  fi
  if wait_for_file "$dir/keys_ready" 120 "$pid"; then
    xdotool windowfocus --sync "$win" 2>/dev/null
    xdotool key --delay 6 h h h h h h h
    touch "$dir/keys_done"
  fi
  finish "$dir" "$pid"
}

check_lecture() {
  local dir=$OUT/lecture
  echo "session 5: the lecture's first minutes"
  check_exit "$dir" "the script ran to the end"
  check "the lecture's point light starts out of view, as an arrow at the edge" test "$(state "$dir/l00.txt" light0_offscreen)" = 1
  check "dragging the arrow moved the light, not the camera ($(state "$dir/l04.txt" light0_position))" \
    test "$(state "$dir/l04.txt" camera_position)" = "$(state "$dir/l00.txt" camera_position)" \
    -a "$(state "$dir/l04.txt" light0_position)" != "$(state "$dir/l00.txt" light0_position)"
  check "and brought it into view" test "$(state "$dir/l04.txt" light0_offscreen)" = 0
  check "seven instant H taps: seven toggles, none lost ($(state "$dir/l05.txt" sidebar_toggles))" \
    test "$(state "$dir/l05.txt" sidebar_toggles)" = 7 -a "$(state "$dir/l05.txt" sidebar)" = 0
}

# --- Without a display ----------------------------------------------------------------------
check_no_display() {
  echo "without a display"
  local err code
  err=$(env -u DISPLAY -u WAYLAND_DISPLAY "$BIN" 2>&1 >/dev/null)
  code=$?
  check "exits 1 (got $code)" test "$code" = 1
  check "points at phonglab-cli ($(echo "$err" | head -n 1))" grep -q 'phonglab-cli' <<<"$err"
  "$BIN" --help >/dev/null
  check "--help exits 0" test $? = 0
  "$BIN" --version >/dev/null
  check "--version exits 0" test $? = 0
  "$BIN" --no-such-option >/dev/null 2>&1
  check "an unknown option exits 2" test $? = 2
}

# --- Session 7: building a scene (issue 16) ------------------------------------------------
session_objects() {
  local dir=$OUT/objects
  mkdir -p "$dir"
  cat >"$dir/script.txt" <<EOF
set render target_spp 1
set display stats 0
wait_idle 120
show_item panel.Objects
click_item panel.Objects
wait_frames 3
click_item objects.add_sphere
wait_idle 120
set object 6 radius 0.3
set object 6 center 0.2 0.3 1.4
new_material shiny_gold
material_preset shiny_gold gold
set object 6 material shiny_gold
wait_idle 120
screenshot $dir/b02_gold.png
dump_state $dir/b02.txt
show_item materials.preset
click_item materials.preset
wait_frames 3
screenshot $dir/b02_presets.png
click_item materials.preset
wait_frames 3
touch $dir/select_ready
wait_file $dir/select_done 60
wait_frames 3
dump_state $dir/b03.txt
touch $dir/drag_ready
wait_file $dir/drag_done 60
wait_idle 120
dump_state $dir/b04.txt
screenshot $dir/b04_dragged.png
quit
EOF
  "$BIN" lecture --size 1280x720 --script "$dir/script.txt" >"$dir/stdout.txt" 2>"$dir/stderr.txt" &
  local pid=$! win="" at x y
  # Real X input: a click on the red sphere selects it; a drag of it with X held moves it
  # along the world's x axis only.
  if wait_for_file "$dir/select_ready" 120 "$pid"; then
    win=$(xdotool search --sync --limit 1 --name '^phonglab' 2>/dev/null | head -n 1)
    at=$(state "$dir/b02.txt" object2_screen)
    x=${at% *} y=${at#* }
    x=${x%.*} y=${y%.*}
    xdotool mousemove --window "$win" "$x" "$y"
    sleep 0.2
    xdotool click 1
    sleep 0.3
    touch "$dir/select_done"
  fi
  if wait_for_file "$dir/drag_ready" 120 "$pid"; then
    xdotool mousemove --window "$win" "$x" "$y"
    sleep 0.2
    xdotool keydown x
    xdotool mousedown 1
    for step in 1 2 3 4 5 6; do
      xdotool mousemove --window "$win" $((x + step * 10)) $((y + step * 6))
      sleep 0.05
    done
    xdotool mouseup 1
    xdotool keyup x
    xdotool mousemove --window "$win" 1270 710
    touch "$dir/drag_done"
  fi
  finish "$dir" "$pid"
}

check_objects() {
  local dir=$OUT/objects a b
  echo "session 7: building a scene (the rest: tests/shell/test_building_input.cpp)"
  check_exit "$dir" "the script ran to the end"
  check "a click in the view selects the object under it ($(state "$dir/b03.txt" selected_object))" \
    test "$(state "$dir/b03.txt" selected_object)" = 2
  a=$(state "$dir/b03.txt" object2_anchor) b=$(state "$dir/b04.txt" object2_anchor)
  check "dragging it with X held moves it along x only ($a -> $b)" \
    awk -v a="$a" -v b="$b" 'BEGIN { split(a, p, " "); split(b, q, " "); exit !(q[1] > p[1] + 0.1 && q[2] == p[2] && q[3] == p[3]) }'
  check "the drag shows on screen" greater "$(rmse "$dir/b02_gold.png" "$dir/b04_dragged.png" $SCENE_REGION)" 0.005
}

# --- Session 8: the file browser (issue 16) -----------------------------------------------
session_recovery() {
  local dir=$OUT/recovery
  mkdir -p "$dir"
  run_until_killed "$dir" term TERM "set render target_spp 2
wait_idle 120
set material plastic kd 0.1 0.9 0.1
wait_idle 120"
  run_until_killed "$dir" int INT "set render target_spp 2
wait_idle 120
set material shiny kd 0.9 0.6 0.1
set light 0 intensity 0.5 0.9 0.9
wait_idle 120
save_png $dir/edited.png"
  # The next start on that scene offers the edits back.
  cat >"$dir/restore.txt" <<EOF
set render target_spp 2
wait_frames 5
screenshot $dir/r1_offer.png
modal restore
wait_frames 3
wait_idle 120
save_png $dir/restored.png
dump_state $dir/r2.txt
quit
EOF
  XDG_STATE_HOME="$dir/state" "$BIN" lecture --size 1280x720 --script "$dir/restore.txt" >"$dir/stdout.txt" 2>"$dir/stderr.txt"
  echo "$?" >"$dir/exit_code"
  # A file's edits restored after another program changed the file: Save asks, never overwrites.
  local pid
  write_scene "$dir/mine.json" "[0.8, 0.1, 0.1]" 0.8
  printf 'set render target_spp 1\nwait_idle 120\nset material red n 200\nwait_idle 120\ntouch %s\nwait_file %s 120\n' \
    "$dir/file.ready" "$dir/never" >"$dir/file.txt"
  XDG_STATE_HOME="$dir/state" "$BIN" "$dir/mine.json" --size 1280x720 --script "$dir/file.txt" >"$dir/file.out" 2>"$dir/file.err" &
  pid=$!
  if wait_for_file "$dir/file.ready" 120 "$pid"; then
    sed 's/"n": 20/"n": 50/' "$dir/mine.json" >"$dir/mine.json.new" && mv "$dir/mine.json.new" "$dir/mine.json"
    kill -TERM "$pid"
  fi
  wait "$pid"
  echo "$?" >"$dir/file.exit"
  cp "$dir/mine.json" "$dir/outside.json"
  cat >"$dir/file_restore.txt" <<EOF
set render target_spp 1
wait_frames 5
modal restore
wait_frames 3
wait_idle 120
dump_state $dir/f2.txt
save
wait_frames 3
dump_state $dir/f3.txt
screenshot $dir/f3_save_asks.png
modal cancel
wait_frames 3
dump_state $dir/f4.txt
quit
EOF
  XDG_STATE_HOME="$dir/state" "$BIN" "$dir/mine.json" --size 1280x720 --script "$dir/file_restore.txt" \
    >"$dir/file_restore.out" 2>"$dir/file_restore.err"
  echo "$?" >"$dir/file_restore.exit"
  # Autosave: a few seconds after an edit the file is there, and a crash (SIGKILL) leaves it.
  run_until_killed "$dir" crash KILL "set render target_spp 2
wait_idle 120
set material matte kd 0.9 0.1 0.9
wait_file $dir/state/phonglab/recovery/embedded-lecture.json 30"
}

check_recovery() {
  local dir=$OUT/recovery file d
  echo "session 10: nothing lost (recovery)"
  file=$(sed -n 's/^recovery: //p' "$dir/term.err")
  check "kill -TERM with unsaved edits: exit 143, 'recovery: PATH' on stderr ($file)" \
    test "$(cat "$dir/term.exit")" = 143 -a -n "$file" -a -s "$dir/term.json"
  check "kill -INT: exit 130 and the recovery file ($(sed -n 's/^recovery: //p' "$dir/int.err"))" \
    test "$(cat "$dir/int.exit")" = 130 -a -s "$dir/int.json"
  check_exit "$dir" "the restoring session ran to the end"
  d=$(compare -metric AE "$dir/edited.png" "$dir/restored.png" null: 2>&1)
  check "the next start offers the edits; restored, the image is the edited one pixel for pixel ($d pixels differ)" \
    test "$d" = 0 -a "$(state "$dir/r2.txt" dirty)" = 1
  check "a file edited, changed outside, SIGTERM; restored at the next start, Save asks (the changed-on-disk dialog) instead of writing" \
    test "$(cat "$dir/file.exit")" = 143 -a "$(state "$dir/f3.txt" conflict)" = 1 -a "$(state "$dir/f2.txt" dirty)" = 1
  check "... and the other program's change is still on disk (n 50, not 200)" \
    cmp -s "$dir/outside.json" "$dir/mine.json"
  check "... the restoring session ran to the end (exit $(cat "$dir/file_restore.exit"))" test "$(cat "$dir/file_restore.exit")" = 0
  check "autosave: the file appears a few seconds after an edit, and SIGKILL leaves it (exit $(cat "$dir/crash.exit"))" \
    test "$(cat "$dir/crash.exit")" = 137 -a -s "$dir/state/phonglab/recovery/embedded-lecture.json"
}

session_lessons() {
  local dir=$OUT/lessons
  mkdir -p "$dir"
  cat >"$dir/script.txt" <<EOF
set render target_spp 4
wait_idle 120
touch $dir/keys1_ready
wait_file $dir/keys1_done 60
wait_frames 5
wait_idle 120
dump_state $dir/n02.txt
screenshot $dir/n02_answer.png
touch $dir/keys2_ready
wait_file $dir/keys2_done 60
wait_frames 5
wait_idle 120
dump_state $dir/n03.txt
lesson_goto 6
wait_idle 120
lesson_next
wait_idle 120
touch $dir/keys3_ready
wait_file $dir/keys3_done 60
wait_frames 10
wait_idle 120
screenshot $dir/n06_presenter.png
dump_state $dir/n06p.txt
key ESCAPE
wait_frames 5
dump_state $dir/n06q.txt
quit
EOF
  "$BIN" --lesson shading --size 1280x720 --script "$dir/script.txt" >"$dir/stdout.txt" 2>"$dir/stderr.txt" &
  local pid=$! win=""
  if wait_for_file "$dir/keys1_ready" 120 "$pid"; then
    win=$(xdotool search --sync --limit 1 --name '^phonglab' 2>/dev/null | head -n 1)
    xdotool windowfocus --sync "$win" 2>/dev/null
    xdotool mousemove --window "$win" 400 300
    xdotool key --delay 150 Right space
    touch "$dir/keys1_done"
  fi
  if wait_for_file "$dir/keys2_ready" 120 "$pid"; then
    xdotool key --delay 150 Next Next Prior
    touch "$dir/keys2_done"
  fi
  if wait_for_file "$dir/keys3_ready" 120 "$pid"; then
    xdotool key F11
    touch "$dir/keys3_done"
  fi
  finish "$dir" "$pid"
}

check_lessons() {
  local dir=$OUT/lessons spread
  echo "session 9: presenting a lesson"
  check_exit "$dir" "the script ran to the end"
  check "Right, then space: step 2 and its answer revealed ($(state "$dir/n02.txt" lesson_title))" \
    test "$(state "$dir/n02.txt" lesson_step)" = 2 -a "$(state "$dir/n02.txt" lesson_revealed)" = 1 \
    -a "$(state "$dir/n02.txt" term)" = diffuse
  check "Page Down twice, Page Up once: step 3, the specular term" \
    test "$(state "$dir/n03.txt" lesson_step)" = 3 -a "$(state "$dir/n03.txt" lesson_revealed)" = 0 \
    -a "$(state "$dir/n03.txt" term)" = specular
  spread=$(stddev "$dir/n06_presenter.png" 1280x110+0+600)
  check "F11: presenter mode, the panels hidden, the caption drawn large over the image (spread $spread)" \
    test "$(state "$dir/n06p.txt" lesson_presenting)" = 1 -a "$(state "$dir/n06p.txt" sidebar)" = 0 \
    -a "$(state "$dir/n06p.txt" overlay_lesson_caption | cut -d' ' -f3)" = 1280
  check "... and Esc leaves it" test "$(state "$dir/n06q.txt" lesson_presenting)" = 0 -a "$(state "$dir/n06q.txt" sidebar)" = 1
}

# --- The second rehearsal: the indirect view of a mirror and glass, orbited and ended --------
session_mirrors() {
  local dir=$OUT/mirrors pid start
  mkdir -p "$dir"
  cat >"$dir/script.txt" <<EOF
set render resolution_scale 0.125
set render target_spp 1
wait_idle 120
key I
wait_idle 120
touch $dir/t0
drag left 300 360 380 360 12
wait_frames 2
wait_idle 120
touch $dir/t1
dump_state $dir/m1.txt
screenshot $dir/m1_indirect_orbited.png
quit
EOF
  run_script "$dir" cornell-sphere
  # SIGTERM while full-resolution indirect passes run: the program ends within 1.5 s.
  printf 'set render target_spp 4096\nkey I\nwait_frames 30\ntouch %s\nwait_file %s 120\n' "$dir/busy" "$dir/never" >"$dir/term.txt"
  "$BIN" cornell-sphere --size 1280x720 --script "$dir/term.txt" >"$dir/term.out" 2>"$dir/term.err" &
  pid=$!
  if wait_for_file "$dir/busy" 120 "$pid"; then
    sleep 0.5
    start=$(date +%s%N)
    kill -TERM "$pid"
  fi
  wait "$pid"
  echo "$?" >"$dir/term.exit"
  echo $((($(date +%s%N) - start) / 1000000)) >"$dir/term.ms"
}

check_mirrors() {
  local dir=$OUT/mirrors ms
  echo "session: the indirect view of cornell-sphere (a mirror and glass)"
  check_exit "$dir" "the script ran to the end"
  ms=$(python3 -c "import os,sys; print(int((os.stat(sys.argv[2]).st_mtime_ns - os.stat(sys.argv[1]).st_mtime_ns) / 1e6))" "$dir/t0" "$dir/t1" 2>/dev/null)
  check "an orbit in the indirect view at 1/8 resolution reaches its exact image within 4 s (${ms} ms)" \
    test -n "$ms" -a "${ms:-99999}" -lt 4000 -a "$(state "$dir/m1.txt" spp)" = 1
  check "SIGTERM during full-resolution indirect passes ends it within 1.5 s ($(cat "$dir/term.ms") ms, exit $(cat "$dir/term.exit"))" \
    test "$(cat "$dir/term.exit")" = 143 -a "$(cat "$dir/term.ms")" -lt 1500
}

# GUI_PART=1 or 2 runs one half of the sessions (about the same time each; CTest runs the halves
# side by side as previewer_gui_1 and previewer_gui_2); unset, all of them.
PART1_SESSIONS="session_view session_rays session_lecture session_lessons"
PART1_CHECKS="check_view check_rays check_lecture check_no_display check_lessons"
PART2_SESSIONS="session_objects session_recovery session_mirrors"
PART2_CHECKS="check_objects check_recovery check_mirrors"
# GUI_ONLY="recovery ambient" runs those sessions alone (while working on them).
if [[ -n "${GUI_ONLY:-}" ]]; then
  run_gui_script "GUI tests ($GUI_ONLY)" 1280x720x24 "$(printf 'session_%s ' $GUI_ONLY)" "$(printf 'check_%s ' $GUI_ONLY)"
  exit $?
fi
case "${GUI_PART:-}" in
  1) run_gui_script "GUI tests (part 1)" 1280x720x24 "$PART1_SESSIONS" "$PART1_CHECKS" ;;
  2) run_gui_script "GUI tests (part 2)" 1280x720x24 "$PART2_SESSIONS" "$PART2_CHECKS" ;;
  "") run_gui_script "GUI tests" 1280x720x24 "$PART1_SESSIONS $PART2_SESSIONS" "$PART1_CHECKS $PART2_CHECKS" ;;
  *) echo "GUI_PART: 1, 2 or unset" >&2; exit 2 ;;
esac
