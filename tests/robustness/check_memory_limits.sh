#!/usr/bin/env bash
# Inputs too large for the memory left are refused with the size they would need, before they
# are allocated (src/io/memory_budget.h), instead of the kernel's out-of-memory kill. Under an
# address-space limit (ulimit -v) a 980 000-triangle OBJ and a 150 000-sphere scene are refused
# when the limit is tight and read when it is not.
#   tests/robustness/check_memory_limits.sh BUILD_DIR
set -uo pipefail
CLI=${1:?usage: check_memory_limits.sh BUILD_DIR}/bin/phonglab-cli
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
check() {
  local what=$1
  shift
  if "$@"; then echo "  ok    $what"; else echo "  FAIL  $what"; failures=$((failures + 1)); fi
}
awk 'BEGIN { n = 700
  for (j = 0; j <= n; ++j) for (i = 0; i <= n; ++i) printf "v %.6f %.6f %.6f\n", i / n, j / n, 0.1 * sin(i * 0.1) * cos(j * 0.1)
  for (j = 0; j < n; ++j) for (i = 0; i < n; ++i) { a = j * (n + 1) + i + 1; printf "f %d %d %d %d\n", a, a + 1, a + n + 2, a + n + 1 } }' >"$dir/grid.obj"
awk 'BEGIN { printf "{\"lights\": [{\"type\": \"point\", \"position\": [0, 5, 5]}], \"materials\": {\"m\": {\"kd\": 0.5}}, \"objects\": ["
  for (i = 0; i < 150000; ++i) printf "%s{\"type\": \"sphere\", \"center\": [%d, %d, 0], \"radius\": 0.4, \"material\": \"m\"}", (i ? "," : ""), i % 300, int(i / 300)
  print "]}" }' >"$dir/big.json"
run() {  # run LIMIT_KB FILE: validate under an address-space limit, stdout+stderr into $out, status in $status
  out=$(bash -c "ulimit -v $1; \"$CLI\" validate \"$2\"" 2>&1)
  status=$?
}
run 600000 "$dir/grid.obj"
check "a 980 000-triangle OBJ under a 600 MB limit is refused with its size: $out" \
  grep -qE "the mesh would need about [0-9.]+ MiB \(980000 triangles, 491401 vertices\) but about [0-9.]+ MiB are available" <<<"$out"
check "... exit 1" test "$status" = 1
run 1200000 "$dir/grid.obj"
check "... and read under 1.2 GB ($out)" test "$status" = 0
run 120000 "$dir/big.json"
check "a 10 MB scene under a 120 MB limit is refused with its size: $out" \
  grep -qE "reading a scene file would need about [0-9.]+ MiB \([0-9.]+ MiB of JSON\) but about [0-9.]+ MiB are available" <<<"$out"
run 400000 "$dir/big.json"
check "... and read under 400 MB ($out)" test "$status" = 0
echo "memory limits: $failures failure(s)"
((failures == 0))
