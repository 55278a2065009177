# The helpers of the previewer's Xvfb test scripts (run_gui_tests.sh, soak.sh): checks,
# dump_state values, image regions compared with ImageMagick, waiting for a session's files.
# Sourced, not run.

failures=0

# gui_script_setup OUT_NAME [--inside-x] BUILD_DIR [OUT_DIR]: the script's words (the usage names
# $SELF, set before lib.sh is sourced) and the environment of its previewer sessions.
gui_script_setup() {
  local name=$1
  shift
  INSIDE_X=0
  if [[ "${1:-}" == "--inside-x" ]]; then
    INSIDE_X=1
    shift
  fi
  if [[ $# -lt 1 || ! -d "$1" ]]; then
    echo "usage: $(basename "$SELF") BUILD_DIR [OUT_DIR]" >&2
    exit 2
  fi
  BUILD_DIR=$(cd "$1" && pwd)
  OUT=${2:-$BUILD_DIR/$name}
  BIN=$BUILD_DIR/bin/phonglab
  CLI=$BUILD_DIR/bin/phonglab-cli
  # Sanitizer builds: GL drivers and X libraries keep allocations alive until exit on purpose.
  export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
  # All sessions, seconds: a hang guard, not a benchmark. Each script step has its own bound
  # (wait_idle 120 ...); this one only ends a run that hangs between them. Generous: the ASan
  # build's sessions took 250-300 s on this 2-core machine when quiet and 430 s beside two busy
  # loops (stopped here at 420 s, the last sessions were never run).
  TIMEOUT=${PHONGLAB_GUI_TIMEOUT:-1500}
  # The recent-files list and recovery files of these sessions stay with their output.
  export XDG_STATE_HOME=$OUT/state
}
pass() { echo "  ok    $*"; }
fail() { echo "  FAIL  $*"; failures=$((failures + 1)); }
check() {  # check "description" command...
  local what=$1
  shift
  if "$@"; then pass "$what"; else fail "$what"; fi
}
state() {  # state FILE KEY: the value of KEY= in a dump_state file
  sed -n "s/^$2=//p" "$1" 2>/dev/null | head -n 1
}
# Standard deviation of the grey levels in a region (0 = uniform).
stddev() {
  convert "$1" -crop "$2" +repage -colorspace Gray -format '%[fx:standard_deviation]' info: 2>/dev/null
}
# rmse_crops IMAGE1 REGION1 IMAGE2 REGION2: normalised RMS difference of two image regions.
rmse_crops() {
  local a b
  a=$(mktemp --suffix=.png) b=$(mktemp --suffix=.png)
  convert "$1" -crop "$2" +repage "$a" && convert "$3" -crop "$4" +repage "$b"
  compare -metric RMSE "$a" "$b" null: 2>&1 | sed -n 's/.*(\(.*\)).*/\1/p'
  rm -f "$a" "$b"
}
# Normalised RMS difference of two regions of one image.
rmse_regions() { rmse_crops "$1" "$2" "$1" "$3"; }
# Normalised RMS difference of two images in a region.
rmse() { rmse_crops "$1" "$3" "$2" "$3"; }
# apart FILE KEY1 KEY2: the rectangles "x y w h" under KEY1 and KEY2 in a dump do not overlap.
apart() {
  awk -v a="$(state "$1" "$2")" -v b="$(state "$1" "$3")" 'BEGIN {
    if (split(a, p, " ") != 4 || split(b, q, " ") != 4) exit 1
    exit !(p[1] + p[3] <= q[1] || q[1] + q[3] <= p[1] || p[2] + p[4] <= q[2] || q[2] + q[4] <= p[2]) }'
}
quiet() { "$@" >/dev/null 2>&1; }
greater() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 > b + 0) }'; }
less() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 < b + 0) }'; }
# run_script DIR SCENE: the previewer on SCENE at 1280x720 runs DIR/script.txt; its output and
# exit status stay in DIR (stdout.txt, stderr.txt, exit_code), as check_exit reads them.
run_script() {
  "$BIN" "$2" --size 1280x720 --script "$1/script.txt" >"$1/stdout.txt" 2>"$1/stderr.txt"
  echo "$?" >"$1/exit_code"
}
finish() {  # finish DIR PID: waits for the session's program and keeps its exit status
  wait "$2"
  echo "$?" >"$1/exit_code"
}
# check_exit DIR WHAT: the session's program exited 0 (the message shows the end of its stderr).
check_exit() {
  check "$2 (exit $(cat "$1/exit_code"); stderr: $(tail -n 2 "$1/stderr.txt" | tr '\n' ' '))" test "$(cat "$1/exit_code")" = 0
}
wait_for_file() {  # wait_for_file FILE SECONDS PID
  local deadline=$((SECONDS + $2))
  while [[ ! -e "$1" ]]; do
    if ((SECONDS > deadline)) || ! kill -0 "$3" 2>/dev/null; then return 1; fi
    sleep 0.1
  done
}


# run_until_killed DIR NAME SIGNAL SCRIPT_LINES: the previewer on lecture (state in DIR/state) runs
# the lines, touches DIR/NAME.ready and waits; the shell sends SIGNAL and keeps the exit status.
run_until_killed() {
  local dir=$1 name=$2 sig=$3 lines=$4 pid
  printf '%s\ntouch %s\nwait_file %s 120\n' "$lines" "$dir/$name.ready" "$dir/never" >"$dir/$name.txt"
  XDG_STATE_HOME="$dir/state" "$BIN" lecture --size 1280x720 --script "$dir/$name.txt" >"$dir/$name.out" 2>"$dir/$name.err" &
  pid=$!
  if wait_for_file "$dir/$name.ready" 120 "$pid"; then kill "-$sig" "$pid"; fi
  wait "$pid"
  echo "$?" >"$dir/$name.exit"
  # The file as this kill left it (the next session rewrites it).
  cp "$(sed -n 's/^recovery: //p' "$dir/$name.err")" "$dir/$name.json" 2>/dev/null
}

# The script's two halves (run_gui_script NAME SCREEN "SESSIONS" "CHECKS"): inside Xvfb
# (--inside-x) each session function runs the previewer; outside, the script starts Xvfb with
# itself inside, then runs each check function and exits 0 when every check passed.
run_gui_script() {
  local step start
  if ((INSIDE_X)); then
    for step in $3; do "$step"; done
    exit 0
  fi
  for step in xvfb-run xdotool convert compare; do
    command -v "$step" >/dev/null || { echo "$1: needs $step"; exit 2; }
  done
  [[ -x "$BIN" ]] || { echo "$1: no previewer at $BIN"; exit 2; }
  rm -rf "$OUT"
  mkdir -p "$OUT"
  start=$SECONDS
  timeout "$TIMEOUT" xvfb-run -a -s "-screen 0 $2" "$SELF" --inside-x "$BUILD_DIR" "$OUT"
  for step in $4; do "$step"; done
  echo "$1: $failures failure(s) in $((SECONDS - start)) s; screenshots and logs in $OUT"
  ((failures == 0))
}
