#!/usr/bin/env bash
# The previewer's responsiveness of two builds side by side, alternating, so a change of the
# machine's load hits both alike:
#
#   tools/previewer-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS]
#
# Each tree is a checkout with its Release build in TREE/build. Each round runs
# tests/gui/bench_previewer.sh of the old tree, then the new one, with the renderer on every core
# and then on one (RENDER_THREADS=1); then prints, per run, each phase's levels on screen, edit →
# full p50 / p95, UI frame p50 and the cores taken (UI thread, whole previewer; builds that log
# them). Raw output in OUT (default /tmp/previewer-side-by-side).
set -eu
OLD=$(cd "${1:?usage: previewer-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS]}" && pwd)
NEW=$(cd "${2:?usage: previewer-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS]}" && pwd)
ROUNDS=${3:-3}
OUT=${OUT:-/tmp/previewer-side-by-side}
mkdir -p "$OUT"
for r in $(seq "$ROUNDS"); do
  for threads in all 1; do
    for tree in "$OLD" "$NEW"; do
      name=$(basename "$tree")_${threads}_$r
      if [ "$threads" = all ]; then env -u RENDER_THREADS "$tree/tests/gui/bench_previewer.sh" "$tree/build" >"$OUT/$name.txt" 2>&1
      else RENDER_THREADS=1 "$tree/tests/gui/bench_previewer.sh" "$tree/build" >"$OUT/$name.txt" 2>&1; fi
    done
  done
done
for f in "$OUT"/*.txt; do
  echo "== $(basename "$f" .txt)"
  for phase in material slider light drag camera; do
    levels=$(grep "^levels $phase " "$f" | cut -d' ' -f3- | paste -sd' ')  # with the rung's line, where logged
    full=$(grep "^summary $phase edit_to_full" "$f" | awk '{printf "%.0f / %.0f ms", $7, $9}')
    ui=$(grep "^summary $phase ui_frames" "$f" | awk '{printf "%.1f ms", $8}')
    cores=$(grep "^summary $phase cores" "$f" | awk '{printf "; cores: UI thread %.2f, all %.2f", $5, $7}')
    echo "  $phase: $levels; edit -> full p50 / p95 $full; UI frame p50 $ui$cores"
  done
done
