// The lecture's first minutes driven through the shell's own input, headless: the script's
// drags, clicks on named widgets, typed text, keys and the wheel go through ImGui's frames and
// the viewport's input as a user's would, and dump_state reads the shell's state. (The real X
// input, xdotool's drags and taps, and the pixels on the screen are the Xvfb sessions':
// tests/gui/run_gui_tests.sh.)
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "tests/shell/shell_harness.h"

namespace phonglab {
namespace {

using test::read_state;
using test::run_shell;
using test::TestFolder;

TEST(LectureInput, TheOrbitFollowsTheHandAndStopsAtThePoles) {
  TestFolder folder("phonglab-shell-orbit");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = run_shell(folder, "lecture", R"(set render target_spp 1
set render resolution_scale 0.25
wait_idle 120
dump_state )" + d + R"(start.txt
drag left 440 400 440 420 4
wait_idle 120
dump_state )" + d + R"(down20.txt
key R
wait_idle 120
drag left 440 60 440 660 60
wait_idle 120
dump_state )" + d + R"(down600.txt
key R
wait_idle 120
drag left 440 660 440 60 60
wait_idle 120
dump_state )" + d + R"(up600.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  const auto start = test::vec3_of(read_state(d + "start.txt")["camera_position"]);
  const auto down20 = test::vec3_of(read_state(d + "down20.txt")["camera_position"]);
  const auto above = test::vec3_of(read_state(d + "down600.txt")["camera_position"]);
  const auto below = test::vec3_of(read_state(d + "up600.txt")["camera_position"]);
  EXPECT_GT(down20[1], start[1]) << "a 20 px drag down looks from higher up";
  EXPECT_GT(above[1], 6) << "600 px down: above the scene";
  EXPECT_GT(above[2], 0) << "stopped at the pole, not over it";
  EXPECT_GT(below[1], 0) << "600 px up: down to the floor, never under it";
  EXPECT_LT(below[1], 0.5);
  EXPECT_GT(below[2], 0);
}

TEST(LectureInput, PanelsKeysAndTypedValuesDoWhatTheySay) {
  TestFolder folder("phonglab-shell-lecture");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = run_shell(folder, "lecture", R"(set render target_spp 1
set render resolution_scale 0.25
wait_idle 120
dump_state )" + d + R"(l00.txt
set material plastic kd 0.9 0.1 0.1
wait_frames 3
undo
wait_frames 3
click_item panel.Display
wait_frames 3
drag_item display.ui_size 40 0
wait_frames 5
dump_state )" + d + R"(l06.txt
set display ui_size 1
wait_frames 3
click_item panel.Display
wait_frames 3
dump_state )" + d + R"(l12.txt
click_item instruments.snapshot_a
wait_frames 3
dump_state )" + d + R"(l13.txt
set instruments compare 0
key 4
wait_idle 120
dump_state )" + d + R"(l14.txt
key 1
key F1
wait_frames 3
dump_state )" + d + R"(l15.txt
key ESCAPE
wait_frames 2
key 1 shift
wait_frames 2
dump_state )" + d + R"(l16.txt
key 1 shift
wait_frames 2
dump_state )" + d + R"(l17.txt
click_item lights.add_point
wait_frames 3
dump_state )" + d + R"(l18.txt
undo
click_item panel.Camera
wait_frames 3
type_item camera.fov abc
wait_frames 3
dump_state )" + d + R"(l19a.txt
type_item camera.position xyz
wait_frames 3
dump_state )" + d + R"(l19b.txt
type_item camera.fov 0
wait_frames 3
dump_state )" + d + R"(l19.txt
scroll 440 400 -200
wait_frames 3
dump_state )" + d + R"(l20.txt
key R
wait_frames 2
click_item panel.Camera
wait_frames 3
click_item panel.Render_settings
wait_frames 3
click_item render.blinn
wait_frames 3
click_item render.convert_n
wait_frames 3
dump_state )" + d + R"(l21.txt
undo
undo
wait_frames 2
click_item panel.Render_settings
wait_frames 3
drag_item material.ks 23 0
wait_frames 3
save_as )" + d + R"(noise.json
figure )" + d + R"(figure.png
dump_state )" + d + R"(l25.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto l00 = read_state(d + "l00.txt");
  EXPECT_GT(std::stod(read_state(d + "l06.txt")["ui_size"]), 1.05) << "the UI size slider keeps the dragged value";
  // Snapshot A moves no named widget.
  auto items = [](const std::map<std::string, std::string>& state) {
    std::map<std::string, std::string> out;
    for (const auto& [key, value] : state) {
      if (key.rfind("item_", 0) == 0) out.emplace(key, value);
    }
    return out;
  };
  const auto before = items(read_state(d + "l12.txt"));
  EXPECT_FALSE(before.empty());
  EXPECT_EQ(items(read_state(d + "l13.txt")), before) << "Snapshot A moved a control";
  auto l14 = read_state(d + "l14.txt");
  EXPECT_EQ(l14["term"], "specular");
  EXPECT_EQ(l14["caption0"].rfind("specular only: ", 0), 0U) << l14["caption0"];
  EXPECT_EQ(read_state(d + "l15.txt")["help"], "1") << "F1 opens the keys";
  EXPECT_EQ(read_state(d + "l16.txt")["lights_enabled"], "10") << "Shift+1 solos L0";
  EXPECT_EQ(read_state(d + "l17.txt")["lights_enabled"], "11") << "again restores";
  auto l18 = read_state(d + "l18.txt");
  EXPECT_EQ(l18["lights"], "3");
  EXPECT_EQ(l18["light2_offscreen"], "0") << "Add point puts the new light in view";
  EXPECT_EQ(read_state(d + "l19a.txt")["camera_notice"].rfind("fov y: 'abc' is not a number", 0), 0U);
  EXPECT_EQ(read_state(d + "l19b.txt")["camera_notice"].rfind("position: 'xyz' is not a number", 0), 0U);
  auto l19 = read_state(d + "l19.txt");
  EXPECT_EQ(l19["camera_notice"].rfind("fov y must be between 0 and 180", 0), 0U) << l19["camera_notice"];
  EXPECT_EQ(l19["camera_fov"], l00["camera_fov"]) << "the camera keeps its field of view";
  EXPECT_LT(std::stod(read_state(d + "l20.txt")["camera_distance"]), 1000) << "200 wheel clicks out stop at the dolly limit";
  EXPECT_EQ(std::stod(read_state(d + "l21.txt")["material_plastic_n"]), 4 * std::stod(l00["material_plastic_n"]))
      << "Blinn-Phong offers n x 4";
  const std::string saved = test::file_bytes(d + "noise.json");
  const std::size_t plastic = saved.find("\"plastic\": {");
  ASSERT_NE(plastic, std::string::npos);
  const std::string block = saved.substr(plastic, saved.find('}', plastic) - plastic);
  EXPECT_TRUE(std::regex_search(block, std::regex(R"("ks": \[0\.[0-9]{1,3}, 0\.[0-9]{1,3}, 0\.[0-9]{1,3}\])")))
      << "a dragged slider saves the value it showed: " << block;
  EXPECT_EQ(read_state(d + "l25.txt")["figure_status"].rfind("saved /", 0), 0U) << "the figure's status names its full path";
}

TEST(LectureInput, TheEmbeddedScenesInTheNarrowView) {
  TestFolder folder("phonglab-shell-scenes");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = run_shell(folder, "glass", R"(set render target_spp 1
set render resolution_scale 0.25
wait_idle 120
probe 440 300
wait_frames 3
set display stats_details 1
set display ui_size 1.5
wait_frames 5
dump_state )" + d + R"(glass.txt
set display ui_size 1
set display stats_details 0
open shininess
wait_idle 120
set instruments depth_cut 1
wait_idle 120
dump_state )" + d + R"(shininess.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto glass = read_state(d + "glass.txt");
  EXPECT_TRUE(test::rects_apart(glass["overlay_stats"], glass["overlay_ray_tree_legend"]))
      << "UI size 1.5, stats details and the ray-tree legend: " << glass["overlay_stats"] << " / "
      << glass["overlay_ray_tree_legend"];
  EXPECT_TRUE(test::rects_apart(glass["overlay_ray_tree_legend"], glass["probe_screen"] + " 1 1")) << "the legend keeps clear of the probed point";
  EXPECT_EQ(glass["render"], "170x180") << "a larger UI size narrows the viewport, and the render follows";
  const std::string label = read_state(d + "shininess.txt")["depth_cut_label"];
  EXPECT_FALSE(label.empty());
  EXPECT_EQ(label.find("of 0"), std::string::npos) << "shininess (max depth 0): " << label;
}

}  // namespace
}  // namespace phonglab
