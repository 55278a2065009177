#!/usr/bin/env bash
# The packet kernels' instances side by side, alternating, so a change of the machine's load hits
# them alike: each round runs `phonglab-bench SCENE --frames 15` of the old tree, then the new
# tree with its dispatch forced to each instance this CPU runs (PHONGLAB_SIMD=avx2, avx512, ...),
# on one render thread and on every core:
#
#   tools/simd-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS] [SCENE...]
#
# Each tree is a checkout with its Release build in TREE/build. Prints each round's medians and
# the medians over the rounds, as ratios to the old tree and between the instances.
set -eu
OLD=$(cd "${1:?usage: simd-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS] [SCENE...]}" && pwd)
NEW=$(cd "${2:?usage: simd-side-by-side.sh OLD_TREE NEW_TREE [ROUNDS] [SCENE...]}" && pwd)
ROUNDS=${3:-5}
shift $(($# < 3 ? $# : 3))
SCENES=("$@")
[ ${#SCENES[@]} -gt 0 ] || SCENES=(lecture cornell)
INSTANCES=()
for k in avx512 avx2 neon; do
  if PHONGLAB_SIMD=$k "$NEW/build/bin/phonglab-bench" lecture --frames 1 --width 64 --height 36 2>/dev/null |
      grep -q "packet ($(case $k in avx512) echo AVX-512;; avx2) echo AVX2;; neon) echo NEON;; esac),"; then
    INSTANCES+=("$k")
  fi
done
median_of() { tr ' ' '\n' | sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }
frame() { "$@" --frames 15 2>/dev/null | sed -n 's/^median frame: \([0-9.]*\) ms.*/\1/p'; }
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//')," \
     "flags: $(grep -m1 -o 'avx512[a-z]*' /proc/cpuinfo | sort -u | tr '\n' ' ')load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "old: $(git -C "$OLD" log --oneline -1 | cut -c1-60); new: $(git -C "$NEW" log --oneline -1 | cut -c1-60); instances: ${INSTANCES[*]}"
for threads in 1 0; do
  for scene in "${SCENES[@]}"; do
    declare -A all=()
    for r in $(seq "$ROUNDS"); do
      line="  round $r:"
      t=$(frame "$OLD/build/bin/phonglab-bench" "$scene" --threads "$threads"); all[old]+="$t "; line="$line old $t"
      for k in "${INSTANCES[@]}"; do
        t=$(PHONGLAB_SIMD=$k frame "$NEW/build/bin/phonglab-bench" "$scene" --threads "$threads"); all[$k]+="$t "
        line="$line, $k $t"
      done
      echo "$line ms"
    done
    old=$(echo "${all[old]}" | median_of)
    line="$scene threads=$threads (medians of $ROUNDS rounds): old $old ms"
    for k in "${INSTANCES[@]}"; do
      m=$(echo "${all[$k]}" | median_of)
      line="$line, $k $m ms ($(awk -v a="$old" -v b="$m" 'BEGIN { printf "%.2fx old", a / b }'))"
    done
    if [ ${#INSTANCES[@]} -ge 2 ]; then
      a=$(echo "${all[${INSTANCES[1]}]}" | median_of); b=$(echo "${all[${INSTANCES[0]}]}" | median_of)
      line="$line; ${INSTANCES[0]} $(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.2fx", a / b }') ${INSTANCES[1]}"
    fi
    echo "$line"
    unset all
  done
done
