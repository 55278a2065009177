#!/usr/bin/env bash
# The handout of every embedded lesson opens in a browser (Chromium from Debian, headless) and
# shows all of its images: phonglab-cli lesson writes it, Chromium loads index.html and counts
# the images it decoded, and a screenshot of the page is checked for content.
#   tests/handout/check_handout.sh BUILD_DIR   (output in BUILD_DIR/handout-test)
set -uo pipefail
BUILD_DIR=${1:?usage: check_handout.sh BUILD_DIR}
CLI=$BUILD_DIR/bin/phonglab-cli
OUT=$(cd "$BUILD_DIR" && pwd)/handout-test
BROWSER=$(command -v chromium || command -v chromium-browser || true)
[[ -n "$BROWSER" ]] || { echo "check_handout.sh: needs chromium (tools/dev.sh deps installs it)"; exit 2; }
rm -rf "$OUT"
mkdir -p "$OUT"
failures=0
check() {
  local what=$1
  shift
  if "$@"; then echo "  ok    $what"; else echo "  FAIL  $what"; failures=$((failures + 1)); fi
}
# Chromium as root (CI) needs --no-sandbox; no GPU here.
browse() { "$BROWSER" --headless --no-sandbox --disable-gpu --hide-scrollbars "$@" 2>>"$OUT/chromium.log"; }

for lesson in $("$CLI" lessons | awk '{print $1}'); do
  dir=$OUT/$lesson
  "$CLI" lesson "$lesson" -o "$dir" --width 320 --height 180 --spp 1 >"$dir.files" 2>"$dir.err"
  check "$lesson: the handout is written ($(wc -l <"$dir.files") files)" test -s "$dir/index.html"
  pngs=$(ls "$dir"/step-*.png "$dir"/answer-*.png 2>/dev/null | wc -l)
  # The page as written, plus a script that counts the images the browser decoded once loaded.
  sed 's|</body>|<script>addEventListener("load",()=>{const i=[...document.images];document.body.dataset.shown=i.filter(x=>x.complete\&\&x.naturalWidth>0).length+"/"+i.length})</script></body>|' \
    "$dir/index.html" >"$dir/check.html"
  shown=$(browse --dump-dom "file://$dir/check.html" | sed -n 's/.*data-shown="\([0-9]*\/[0-9]*\)".*/\1/p' | head -n 1)
  check "$lesson: Chromium shows every image of the page ($shown of the $pngs step and answer images)" test "$shown" = "$pngs/$pngs"
  browse --window-size=1000,1400 --screenshot="$dir/page.png" "file://$dir/index.html" >/dev/null
  # The first step's image sits below the title and caption: the page there is not blank.
  spread=$(convert "$dir/page.png" -crop 320x180+16+230 +repage -colorspace Gray -format '%[fx:standard_deviation]' info: 2>/dev/null)
  check "$lesson: the page's screenshot shows the first image (grey spread $spread)" \
    awk -v s="${spread:-0}" 'BEGIN { exit !(s > 0.03) }'
done
# The shading lesson's exercises: each task with room to write, and the reference formulas at
# the end, on a page of their own when printed (a page break before them).
dir=$OUT/shading
tasks=$(grep -c 'class="write"' "$dir/index.html")
check "shading: its three exercises have room to write ($tasks)" test "$tasks" = 3
check "shading: the reference formulas close the handout on a page of their own" \
  grep -q '<section class="reference" id="reference-formulas">' "$dir/index.html"
echo "handout: $failures failure(s); pages and screenshots in $OUT"
((failures == 0))
