// What the screen shows of the teaching instruments, headless: the window's pixels drawn on the
// CPU (ui::SoftwareScreen) as the GL window draws them. The compare views, the small multiples,
// the two-eye differences, an A asked for mid-render, the ray tree overlay and the depth cut as
// they look. (The screen's codes against phonglab-cli's PNG in a real window, and real input, are
// the Xvfb session's: tests/gui/run_gui_tests.sh.)
#include <gtest/gtest.h>

#include <string>

#include "tests/shell/shell_harness.h"

namespace phonglab {
namespace {

using test::kSceneRegion;
using test::read_shot;

TEST(ScreenViews, CompareViewsSmallMultiplesAndTheTwoEyeDifferences) {
  test::TestFolder folder("phonglab-screen-instruments");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
wait_idle 120
set material plastic kd 0.9 0.1 0.1
wait_idle 120
screenshot $OUT/i07_red.png
snapshot_a
set material plastic kd 0.1 0.1 0.9
set instruments compare 2
wait_idle 120
screenshot $OUT/i08_difference.png
set instruments compare 1
wait_idle 120
screenshot $OUT/i09_wipe.png
set instruments compare 0
wait_idle 120
screenshot $OUT/i09b_blue.png
set instruments multiples 1
wait_idle 120
probe 440 401
wait_frames 2
screenshot $OUT/i10_multiples.png
figure $OUT/figure.png
set instruments multiples 0
set display stats 0
set render term diffuse
set instruments head 1
wait_idle 120
snapshot_a
set instruments compare 2
set instruments head_angle 40
wait_idle 120
screenshot $OUT/h01_head_diffuse_difference.png
set render term specular
set instruments head_angle 0
set instruments compare 0
wait_idle 120
snapshot_a
set instruments compare 2
set instruments head_angle 40
wait_idle 120
screenshot $OUT/h02_head_specular_difference.png
set render term full
set instruments compare 0
set display stats 1
probe 354 338
set instruments head_angle 15
wait_idle 120
screenshot $OUT/h03_head_full.png
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  const test::Shot red = read_shot(d + "i07_red.png"), blue = read_shot(d + "i09b_blue.png");
  const test::Shot difference = read_shot(d + "i08_difference.png"), wipe = read_shot(d + "i09_wipe.png");
  // The red sphere turned blue: the difference view is |blue - red| where the sphere is, black
  // where nothing changed.
  EXPECT_GT(test::luma_stddev(difference, kSceneRegion), 0.02) << "the difference view shows the edited sphere";
  const double black = test::share(difference, kSceneRegion, [](double r, double g, double b) { return r + g + b == 0; });
  EXPECT_GT(black, 0.5) << "the unchanged floor and spheres are black in the difference view";
  EXPECT_GT(test::rmse(difference, wipe, kSceneRegion), 0.02) << "the wipe differs from the difference view";
  // The wipe's line runs down the middle of the view; the edited sphere, left of it, shows A (red).
  const test::Region sphere{300, 320, 110, 100};
  EXPECT_GT(test::rmse(red, blue, sphere), 0.1) << "the sphere's region is the edited one";
  EXPECT_LT(test::rmse(wipe, red, sphere), 0.01) << "left of the wipe's line: A";
  const test::Shot multiples = read_shot(d + "i10_multiples.png");
  EXPECT_GT(test::rmse(multiples, {5, 30, 280, 300}, multiples, {298, 30, 280, 300}), 0.02)
      << "small multiples: the ambient and diffuse cells differ";
  test::keep_screenshot(d, "i10_multiples.png");
  test::keep_screenshot(d, "i09_wipe.png");
  test::keep_screenshot(d, "figure.png");
  // Move your head: the diffuse term does not depend on the eye, the specular term does.
  const test::Region below_horizon{0, 280, 880, 290};
  const double diffuse = test::mean(read_shot(d + "h01_head_diffuse_difference.png"), below_horizon);
  const double specular = test::mean(read_shot(d + "h02_head_specular_difference.png"), below_horizon);
  EXPECT_GE(diffuse, 0);
  EXPECT_LT(diffuse, 0.002) << "the diffuse term cancels in the two-eye difference";
  EXPECT_GT(specular, 0.004) << "the specular term does not";
  test::keep_screenshot(d, "h02_head_specular_difference.png");
  test::keep_screenshot(d, "h03_head_full.png");
}

TEST(ScreenViews, AnAAskedForMidRenderIsTheFinishedImage) {
  test::TestFolder folder("phonglab-screen-a");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(key H
set render target_spp 8
set instruments head 1
wait_frames 2
snapshot_a
set instruments compare 2
wait_frames 1
wait_idle 120
wait_frames 3
screenshot $OUT/l10_difference_same_eye.png
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  const double m = test::mean(read_shot(d + "l10_difference_same_eye.png"), {0, 300, 880, 300});
  EXPECT_GE(m, 0);
  EXPECT_LT(m, 0.0005) << "the same eye against an A asked for mid-render: |live - A| is black";
}

TEST(ScreenViews, TheRayTreeOverlayAndTheDepthCut) {
  test::TestFolder folder("phonglab-screen-rays");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
set display stats 0
wait_idle 120
# The red sphere's highlight, with the probe panel scrolled into view.
probe 371 339
wait_frames 3
show_item panel.Probe
wait_frames 5
screenshot $OUT/r00_probe_panel.png
# The glass sphere: reflected and refracted rays to several depths, blocked shadow rays inside.
probe 543 415
wait_frames 3
screenshot $OUT/r01_tree_glass.png
# The floor in the red sphere's shadow.
probe 316 442
wait_frames 3
screenshot $OUT/r02_tree_shadow.png
set instruments ray_tree 0
wait_frames 3
screenshot $OUT/r03_no_tree.png
set instruments ray_tree 1
# The mirror sphere, then the image with recursion cut at depth 0, 1, 2.
probe 667 339
set instruments depth_cut 0
wait_idle 120
screenshot $OUT/r04_cut0.png
set instruments depth_cut 1
wait_idle 120
screenshot $OUT/r05_cut1.png
set instruments depth_cut 2
wait_idle 120
screenshot $OUT/r06_cut2.png
set instruments depth_cut -1
set instruments ray_tree 0
set instruments heat 1
wait_idle 120
screenshot $OUT/r08_heat.png
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  EXPECT_GT(test::rmse(read_shot(d + "r02_tree_shadow.png"), read_shot(d + "r03_no_tree.png"), kSceneRegion), 0.005)
      << "the overlay is visible on the screen";
  const test::Shot cut0 = read_shot(d + "r04_cut0.png"), cut1 = read_shot(d + "r05_cut1.png"), cut2 = read_shot(d + "r06_cut2.png");
  EXPECT_GT(test::rmse(cut0, cut1, kSceneRegion), 0.01) << "cut 0 and cut 1 look different";
  EXPECT_GT(test::rmse(cut1, cut2, kSceneRegion), 0.001) << "cut 1 and cut 2 look different";
  for (const char* name : {"r00_probe_panel.png", "r01_tree_glass.png", "r04_cut0.png", "r05_cut1.png", "r06_cut2.png", "r08_heat.png"}) {
    test::keep_screenshot(d, name);
  }
}

}  // namespace
}  // namespace phonglab
