#!/usr/bin/env bash
# The kd slider dragged for 10 seconds (600 UI frames) with the panels shown, by two previewer
# binaries in turn under Xvfb, ROUNDS times each, alternating:
#
#   tools/slider-drag-side-by-side.sh OLD_PHONGLAB NEW_PHONGLAB [ROUNDS]
#   PERF=1 tools/slider-drag-side-by-side.sh ...   # also `perf record` each run (OUT/NAME.perf)
#   RENDER_THREADS=1 tools/slider-drag-side-by-side.sh ...   # the renderer on one thread
#
# Prints each run's edit-to-image latency and cores (the stats log's summary lines); logs go to
# OUT (default /tmp/slider-drag). `lecture`, view 1280x720 beside a 400-pixel sidebar.
set -eu
OLD=${1:?usage: slider-drag-side-by-side.sh OLD_PHONGLAB NEW_PHONGLAB [ROUNDS]}
NEW=${2:?usage: slider-drag-side-by-side.sh OLD_PHONGLAB NEW_PHONGLAB [ROUNDS]}
ROUNDS=${3:-3}
OUT=${OUT:-/tmp/slider-drag}
mkdir -p "$OUT"
THREADS=
if [ -n "${RENDER_THREADS:-}" ]; then THREADS="set render threads $RENDER_THREADS"; fi
cat >"$OUT/script.txt" <<SCRIPT
log slider drag
$THREADS
wait_image 60
resize 1680 720
wait_image 60
show_item material.kd
wait_frames 30
stats_reset
drag_item material.kd 240 0 600
wait_frames 30
stats_summary slider
quit
SCRIPT
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), render threads ${RENDER_THREADS:-all}"
for round in $(seq "$ROUNDS"); do
  for name in old new; do
    bin=$OLD
    [ "$name" = new ] && bin=$NEW
    log="$OUT/$name$round.log"
    run=("$bin" lecture --size 1280x720 --script "$OUT/script.txt" --stats-log "$log")
    if [ "${PERF:-0}" = 1 ]; then run=(perf record -q -F 1000 -o "$OUT/$name$round.perf" "${run[@]}"); fi
    timeout 300 xvfb-run -a -s '-screen 0 1920x1080x24' "${run[@]}" >/dev/null 2>&1
    echo "$name $round: $(grep -E '^summary slider (edit_to_image|cores)' "$log" | sed 's/^summary slider //' | tr '\n' ' ')"
  done
done
