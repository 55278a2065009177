#!/usr/bin/env bash
# What the hall sees 2 s after switching to the indirect light: the previewer on `cornell` at
# 1280x720 (panels hidden), the key I pressed with xdotool once the first image has settled, and
# a screenshot of the screen 2 s later (docs/images/indirect-2s.png; the overlay says its spp).
#
#   xvfb-run -a -s '-screen 0 1280x720x24' tools/indirect-two-seconds.sh BUILD_DIR OUT.png
#
# RENDER_THREADS=N renders on N threads (the slow case: 1). Needs xdotool and ImageMagick (import).
set -euo pipefail
BUILD=${1:?usage: tools/indirect-two-seconds.sh BUILD_DIR OUT.png}
OUT=${2:?usage: tools/indirect-two-seconds.sh BUILD_DIR OUT.png}
script=$(mktemp)
{
  [ -n "${RENDER_THREADS:-}" ] && echo "set render threads $RENDER_THREADS"
  echo "wait_file /nonexistent-$$ 600"  # the script waits; the window takes real input meanwhile
} >"$script"
"$BUILD/bin/phonglab" cornell --size 1280x720 --script "$script" &
pid=$!
trap 'kill $pid 2>/dev/null || true; rm -f "$script"' EXIT
sleep 12  # start, and the lecture's image at its target spp
xdotool search --sync --onlyvisible --name phonglab windowactivate --sync >/dev/null 2>&1 || true
xdotool key h
sleep 3
t0=$(date +%s.%N)
xdotool key i
sleep 2
import -window root "$OUT"
echo "$OUT: $(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }') s after the key"
