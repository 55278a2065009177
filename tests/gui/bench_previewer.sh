#!/usr/bin/env bash
# Measures the previewer's responsiveness (issue 3's targets) under Xvfb:
#
#   tests/gui/bench_previewer.sh BUILD_DIR [SCENE]
#
# The window is 1280x720 with the panels hidden, so the render is 1280x720. Three phases,
# each while the renderer is working (target 64 spp):
#   material: 30 isolated edits of the selected material's kd, each 10 UI frames after the
#             first image of the previous one (the renderer is then mid-pass again);
#   camera:   30 isolated orbit steps, the same way;
#   drag:     a continuous 2-second left-drag orbit (one restart per UI frame).
# For each phase: UI frame times (frames paced while rendering) and the time from an edit to
# the first image of it on screen (after the buffer swap). Figures go to stdout; the raw log
# (every frame and latency) to BUILD_DIR/gui-bench/stats.log.
set -eu
BUILD_DIR=$(cd "${1:?usage: bench_previewer.sh BUILD_DIR [SCENE]}" && pwd)
SCENE=${2:-lecture}
OUT=$BUILD_DIR/gui-bench
mkdir -p "$OUT"
cat >"$OUT/script.txt" <<SCRIPT
key H
wait_image 60
wait_frames 30
stats_reset
bench_edits 30 material
stats_summary material
stats_reset
bench_edits 30 camera
stats_summary camera
stats_reset
drag left 200 360 1000 380 120
wait_frames 5
stats_summary drag
quit
SCRIPT
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg)"
timeout 300 xvfb-run -a -s '-screen 0 1280x720x24' "$BUILD_DIR/bin/phonglab" "$SCENE" --size 1280x720 \
  --script "$OUT/script.txt" --stats-log "$OUT/stats.log"
grep '^summary' "$OUT/stats.log" | grep -v ' session '
echo "first-image levels: $(grep '^latency' "$OUT/stats.log" | awk '{print $4}' | sort | uniq -c | tr '\n' ' ')"
