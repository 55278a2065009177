#!/usr/bin/env bash
# Runs the fuzzers (libFuzzer with ASan and UBSan, built by tools/dev.sh test in build-asan):
#
#   tools/fuzz.sh SECONDS [TARGET...]    TARGET: scene, obj, lesson, formula, formula_file, image (default: all six,
#                                        side by side)
#
# Each starts from its seed corpus (scene: assets/scenes; obj: tests/fuzz/corpus/obj; lesson:
# tests/fuzz/corpus/lesson and assets/lessons; formula: tests/fuzz/corpus/formula; formula_file:
# tests/fuzz/corpus/formula_file; image:
# tests/fuzz/corpus/image) in a fresh temporary folder and prints libFuzzer's final statistics
# (stat::number_of_executed_units is the executions). Any crash, hang (-timeout), sanitizer report,
# NaN in a render (the file targets abort on one; a formula's own NaN is the student's, as is a
# PFM's), disagreement of a formula's evaluations or an image value outside its kind's range fails
# the run; the input is kept in BUILD/fuzz-crashes/. BUILD defaults to build-asan (FUZZ_BUILD=...).
set -uo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:?usage: tools/fuzz.sh SECONDS [scene|obj|lesson|formula|formula_file|image ...]}
shift
TARGETS=("$@")
((${#TARGETS[@]})) || TARGETS=(scene obj lesson formula formula_file image)
BUILD=${FUZZ_BUILD:-build-asan}
mkdir -p "$BUILD/fuzz-crashes"
pids=()
for t in "${TARGETS[@]}"; do
  corpus=$(mktemp -d)
  case $t in
    scene) cp assets/scenes/*.json "$corpus"/; max_len=4096 ;;
    obj) cp tests/fuzz/corpus/obj/* "$corpus"/; max_len=8192 ;;
    lesson) cp tests/fuzz/corpus/lesson/* assets/lessons/*.json "$corpus"/; max_len=8192 ;;
    formula) cp tests/fuzz/corpus/formula/* "$corpus"/; max_len=8192 ;;
    formula_file) cp tests/fuzz/corpus/formula_file/* "$corpus"/; max_len=4096 ;;
    image) cp tests/fuzz/corpus/image/* "$corpus"/; max_len=4096 ;;
    *) echo "tools/fuzz.sh: unknown target $t" >&2; exit 2 ;;
  esac
  (
    "$BUILD/bin/phonglab_fuzz_$t" -max_total_time="$SECONDS_EACH" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$BUILD/fuzz-crashes/$t-" "$corpus" >"$corpus.log" 2>&1
    status=$?
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$corpus.log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$corpus.log")
    if ((status == 0)); then
      echo "== fuzz $t: $runs executions in $SECONDS_EACH s ($rate a second), no failure"
    else
      echo "== fuzz $t: FAILED after $runs executions ($rate a second); the input is in $BUILD/fuzz-crashes/"
      tail -n 30 "$corpus.log"
    fi
    rm -rf "$corpus" "$corpus.log"
    exit "$status"
  ) &
  pids+=($!)
done
failed=0
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
exit "$failed"
