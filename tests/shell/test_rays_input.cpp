// The ray tree overlay, the depth cut and the heat map through the shell, headless: the probed
// trees' segments and blocked shadow rays, the cut renders with the cut depth and is not an edit,
// the images at cut 0 and 1 and the scene's own are phonglab-cli's bit for bit, the heat map's
// scale, counts and PNG are the CLI's. (The overlay and the cut as they look on the screen:
// test_screen_views.cpp; the GL window's codes against the CLI's PNG: the Xvfb session's.)
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "io/image_read.h"
#include "tests/shell/shell_harness.h"
#include "tests/support/run_cli.h"

namespace phonglab {
namespace {

TEST(RaysInput, TheTreesTheDepthCutAndTheHeatMapAreTheClis) {
  test::TestFolder folder("phonglab-shell-rays");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
set render resolution_scale 0.5
wait_idle 120
probe 543 415
wait_frames 3
dump_state )" + d + R"(r01.txt
probe 316 442
wait_frames 3
dump_state )" + d + R"(r02.txt
set instruments ray_tree 0
wait_frames 3
dump_state )" + d + R"(r03.txt
set instruments ray_tree 1
probe 667 339
set instruments depth_cut 0
wait_idle 120
save_pfm )" + d + R"(cut0.pfm
dump_state )" + d + R"(r04.txt
set instruments depth_cut 1
wait_idle 120
save_pfm )" + d + R"(cut1.pfm
dump_state )" + d + R"(r05.txt
set instruments depth_cut -1
wait_idle 120
save_pfm )" + d + R"(cut_off.pfm
set instruments ray_tree 0
set instruments heat 1
wait_idle 120
save_png )" + d + R"(heat_shown.png
save_pfm )" + d + R"(rays.pfm
dump_state )" + d + R"(r08.txt
set instruments heat 0
wait_idle 120
dump_state )" + d + R"(r09.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto r01 = test::read_state(d + "r01.txt");
  EXPECT_GE(std::stoi(r01["tree_segments"]), 10) << "the glass sphere's tree is drawn";
  EXPECT_GE(std::stoi(r01["tree_deepest"]), 2);
  auto r02 = test::read_state(d + "r02.txt");
  EXPECT_GE(std::stoi(r02["probe_blocked"]), 1);
  EXPECT_EQ(r02["tree_blocked"], r02["probe_blocked"]) << "a shaded floor point: the overlay's blocked shadow rays are the probe's";
  EXPECT_EQ(test::read_state(d + "r03.txt")["tree_segments"], "0") << "switching the overlay off draws nothing";
  auto r04 = test::read_state(d + "r04.txt");
  EXPECT_EQ(r04["render_max_depth"], "0") << "the depth cut renders with max depth 0";
  EXPECT_EQ(r04["scene_max_depth"], "5") << "the scene keeps 5";
  EXPECT_EQ(r04["undo"], "0") << "the depth cut is not an edit";
  EXPECT_EQ(r04["dirty"], "0");
  EXPECT_EQ(r04["tree_deepest"], "0") << "the probed tree follows the cut";
  EXPECT_EQ(test::read_state(d + "r05.txt")["tree_deepest"], "1");
  // The 880x720 view is narrower than the scene's 16:9 image: the previewer widens the field of
  // view (dump_state's camera_fov, every digit) and the CLI renders with the same one.
  const std::string fov = r04["camera_fov"];
  EXPECT_GT(std::stod(fov), 40) << "the narrow view renders with a widened field of view";
  const std::string size = r04["render"];
  const std::string view = "lecture --width " + size.substr(0, size.find('x')) + " --height " +
                           size.substr(size.find('x') + 1) + " --fov-y " + fov + " --spp 1";
  ASSERT_EQ(test::run_cli("render " + view + " --max-depth 0 -o " + d + "cli_cut0.pfm").exit_code, 0);
  ASSERT_EQ(test::run_cli("render " + view + " --max-depth 1 -o " + d + "cli_cut1.pfm").exit_code, 0);
  ASSERT_EQ(test::run_cli("render " + view + " -o " + d + "cli_full.pfm").exit_code, 0);
  EXPECT_TRUE(test::file_bytes(d + "cut0.pfm") == test::file_bytes(d + "cli_cut0.pfm")) << "cut at depth 0: the CLI's --max-depth 0, bit for bit";
  EXPECT_TRUE(test::file_bytes(d + "cut1.pfm") == test::file_bytes(d + "cli_cut1.pfm")) << "cut at depth 1: the CLI's --max-depth 1, bit for bit";
  EXPECT_TRUE(test::file_bytes(d + "cut_off.pfm") == test::file_bytes(d + "cli_full.pfm")) << "ending the cut gives the scene's own image back";

  auto r08 = test::read_state(d + "r08.txt");
  EXPECT_EQ(r08["term"], "rays") << "the heat map shows the rays view";
  EXPECT_EQ(r08["heat"], "1");
  const test::RunResult heat = test::run_cli_stdout("render " + view + " --term rays -o " + d + "cli_heat.png");
  std::smatch top;
  ASSERT_TRUE(std::regex_search(heat.out, top, std::regex(R"(heat map: 0 \(black\) \.\. ([0-9.e+]+) \(pale yellow\))"))) << heat.out;
  EXPECT_EQ(r08["heat_max"], top[1].str()) << "its scale tops at the image's maximum, as phonglab-cli's";
  ASSERT_EQ(test::run_cli("render " + view + " --term rays -o " + d + "cli_rays.pfm").exit_code, 0);
  EXPECT_TRUE(test::file_bytes(d + "rays.pfm") == test::file_bytes(d + "cli_rays.pfm")) << "its counts are phonglab-cli's --term rays, bit for bit";
  std::string error;
  const auto shown = read_image_file(d + "heat_shown.png", &error);
  const auto cli = read_image_file(d + "cli_heat.png", &error);
  ASSERT_TRUE(shown && cli) << error;
  EXPECT_TRUE(shown->rgb == cli->rgb) << "its PNG is phonglab-cli's heat map PNG, pixel for pixel";
  EXPECT_EQ(test::read_state(d + "r09.txt")["term"], "full") << "switching the heat map off goes back to the full image";
}

}  // namespace
}  // namespace phonglab
