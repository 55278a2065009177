#!/usr/bin/env bash
# The tracer's frame time of two builds side by side, alternating, so a change of the machine's
# load hits both alike:
#
#   tools/tracer-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS] [SCENE...]
#
# Each tree is a checkout with its Release build in TREE/build (phonglab-bench at least). Each
# round runs `phonglab-bench SCENE --frames 15` of the old tree, then the new one, on one render
# thread and on every core, for every scene (default: lecture and its floor as two triangles);
# then prints each scene's median frames of each build and the ratio old / new per round.
set -eu
OLD=$(cd "${1:?usage: tracer-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS] [SCENE...]}" && pwd)
NEW=$(cd "${2:?usage: tracer-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS] [SCENE...]}" && pwd)
ROUNDS=${3:-3}
shift $(($# < 3 ? $# : 3))
HERE=$(cd "$(dirname "$0")/.." && pwd)
SCENES=("$@")
[ ${#SCENES[@]} -gt 0 ] || SCENES=(lecture "$HERE/docs/bench/lecture-triangle-floor.json")
median() { "$1/build/bin/phonglab-bench" "$2" --frames 15 --threads "$3" | sed -n 's/^median frame: \([0-9.]*\) ms.*/\1/p'; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'), load $(cut -d' ' -f1-3 /proc/loadavg)"
for threads in 1 0; do
  for scene in "${SCENES[@]}"; do
    line="$(basename "$scene") threads=$threads:"
    for r in $(seq "$ROUNDS"); do
      old=$(median "$OLD" "$scene" "$threads")
      new=$(median "$NEW" "$scene" "$threads")
      line="$line  $old -> $new ms ($(awk -v a="$old" -v b="$new" 'BEGIN { printf "%.2fx", a / b }'))"
    done
    echo "$line"
  done
done
