#!/usr/bin/env bash
# The README's screenshots, from the screenshots the GUI tests write in a window and the shell's
# screen tests draw headless (ui::SoftwareScreen):
#
#   tests/gui/run_gui_tests.sh build && tools/readme_images.sh build
#
# runs the screen tests keeping their screenshots (PHONGLAB_SCREENSHOTS), copies them and the GUI
# tests' from BUILD_DIR/gui-tests into docs/images, scaled to 960 pixels wide (the depth
# cut as the viewports of cut 0, 1 and 2 side by side), and renders the Cornell boxes with
# BUILD_DIR/bin/phonglab-cli. Needs ImageMagick.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:?usage: tools/readme_images.sh BUILD_DIR}
SRC=$BUILD/gui-tests
OUT=docs/images
mkdir -p "$OUT"
rm -rf "$SRC/screens"
PHONGLAB_SCREENSHOTS="$SRC/screens" "$BUILD/bin/phonglab_shell_tests" --gtest_filter='Screen*' >/dev/null

shot() {  # shot SOURCE NAME: one screenshot, 960 wide
  convert "$SRC/$1" -resize 960x -strip "$OUT/$2"
  echo "$OUT/$2 <- $1"
}
shot view/01_start.png previewer.png
shot screens/i10_multiples.png small-multiples.png
shot screens/i09_wipe.png wipe.png
shot screens/figure.png figure.png
shot screens/r00_probe_panel.png probe.png
shot screens/r01_tree_glass.png ray-tree.png
shot screens/r08_heat.png heat-map.png
shot screens/h03_head_full.png move-your-head.png
shot screens/h02_head_specular_difference.png head-difference.png
shot objects/b04_dragged.png objects.png
shot objects/b02_presets.png presets.png
shot screens/f5_recent.png file-browser.png
shot lessons/n06_presenter.png presenter.png
shot screens/a2_beside.png ambient-beside.png
shot screens/a3_difference.png ambient-difference.png
# The viewport (left of the 400-pixel panels) of cut 0, 1, 2 in a row.
convert "$SRC/screens/r04_cut0.png" "$SRC/screens/r05_cut1.png" "$SRC/screens/r06_cut2.png" -crop 880x720+0+0 +repage \
  -bordercolor black -border 4x0 +append -resize 960x -strip "$OUT/depth-cut.png"
echo "$OUT/depth-cut.png <- screens/r04_cut0.png screens/r05_cut1.png screens/r06_cut2.png"
# The two embedded Cornell boxes side by side, 1 spp renders at 480x480.
for scene in cornell cornell-sphere; do
  "$BUILD/bin/phonglab-cli" render "$scene" -o "$SRC/$scene.png" --width 480 --height 480 2>/dev/null
done
convert "$SRC/cornell.png" "$SRC/cornell-sphere.png" -bordercolor black -border 4x0 +append -strip "$OUT/cornell.png"
echo "$OUT/cornell.png <- phonglab-cli render cornell, cornell-sphere"
# indirect-2s.png is tools/indirect-two-seconds.sh's (real time: it needs a quiet machine).
