#!/usr/bin/env bash
# Measures the previewer's responsiveness (issues 3 and 15) under Xvfb:
#
#   tests/gui/bench_previewer.sh BUILD_DIR [SCENE]
#   BASELINE=1 tests/gui/bench_previewer.sh BUILD_DIR [SCENE]   # live levels and re-shading off
#   RENDER_THREADS=1 tests/gui/bench_previewer.sh BUILD_DIR      # the renderer on one thread
#   LIVE_IMAGES_PER_S=24 tests/gui/bench_previewer.sh BUILD_DIR  # another budget for live levels
#
# The window is 1280x720 with the panels hidden, so the render is 1280x720 (for the slider phase
# the panels are shown and the window widened by the sidebar, so the render stays 1280x720).
# Five phases, each while the renderer is working (target 64 spp):
#   material: 30 isolated edits of the selected material's kd, each 10 UI frames after the
#             first image of the previous one (the renderer is then mid-pass again);
#   camera:   30 isolated orbit steps, the same way;
#   drag:     a continuous 2-second left-drag orbit (one restart per UI frame);
#   light:    a continuous 2-second drag of light 0's marker;
#   slider:   a continuous 2-second drag of the kd slider, through ImGui.
# For each phase: UI frame times (frames paced while rendering), the time from an edit to the
# first image of it on screen (after the buffer swap) and to the first full-resolution image of
# it or a later edit, the level of the image on screen at every UI frame while the hand is on
# (`levels PHASE full=N half=N quarter=N eighth=N`, `full` counting exact images only, and
# `levels PHASE rung quads=N` for the quad-shaded live rung), the cores taken (`cores ui U all A
# drawn_frames N`: the UI thread's share of a core, drawing included, the whole previewer's, and
# the frames drawn, the others changing nothing), and the passes' Mrays/s by level. Figures
# go to stdout; the raw log (every frame and latency) to BUILD_DIR/gui-bench/stats.log.
set -eu
BUILD_DIR=$(cd "${1:?usage: bench_previewer.sh BUILD_DIR [SCENE]}" && pwd)
SCENE=${2:-lecture}
OUT=$BUILD_DIR/gui-bench
mkdir -p "$OUT"
if [ "${BASELINE:-0}" = 1 ]; then
  # What the previewer did before issue 15: every restart at 1/8, no stored ray trees.
  SETTINGS=$'set render live_images_per_s 0\nset render tree_budget_mib 0'
else
  SETTINGS='log live levels and re-shading on'
fi
# RENDER_THREADS=N: the renderer's thread count (Render settings' "threads"); 1 on this 2-core
# machine is a lecturer's laptop busy with slides and a browser beside the previewer.
if [ -n "${RENDER_THREADS:-}" ]; then SETTINGS="$SETTINGS"$'\n'"set render threads $RENDER_THREADS"; fi
# LIVE_IMAGES_PER_S=N: the live levels' budget (Render settings' "live images/s").
if [ -n "${LIVE_IMAGES_PER_S:-}" ]; then SETTINGS="$SETTINGS"$'\n'"set render live_images_per_s $LIVE_IMAGES_PER_S"; fi
cat >"$OUT/script.txt" <<SCRIPT
$SETTINGS
key H
wait_image 60
wait_frames 30
stats_reset
bench_edits 30 material
wait_frames 30
stats_summary material
stats_reset
bench_edits 30 camera
wait_frames 30
stats_summary camera
stats_reset
drag left 200 360 1000 380 120
wait_frames 30
stats_summary drag
stats_reset
drag_light 0 300 40 120
wait_frames 30
stats_summary light
key H
resize 1680 720
wait_image 60
show_item material.kd
wait_frames 30
stats_reset
drag_item material.kd 240 0 120
wait_frames 30
stats_summary slider
quit
SCRIPT
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), render threads ${RENDER_THREADS:-all}"
timeout 300 xvfb-run -a -s '-screen 0 1920x1080x24' "$BUILD_DIR/bin/phonglab" "$SCENE" --size 1280x720 \
  --script "$OUT/script.txt" --stats-log "$OUT/stats.log"
grep -E '^(summary|levels) ' "$OUT/stats.log" | grep -v ' session '
echo "first-image levels: $(grep '^latency' "$OUT/stats.log" | awk '{print $4}' | sort | uniq -c | tr '\n' ' ')"
