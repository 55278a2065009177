// What the screen shows of a student's formula and image, the indirect light's views, a lesson's
// steps and the file browser, headless: the window's pixels drawn on the CPU
// (ui::SoftwareScreen) as the GL window draws them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/shell/shell_harness.h"
#include "tests/support/run_cli.h"

namespace phonglab {
namespace {

using test::read_shot;

// The difference view's marks in the 880x720 view: orange where yours is brighter, blue where
// darker, each on at least this share of the view.
void expect_marks(const std::string& screenshot, double brighter, double darker) {
  const test::Shot shot = read_shot(screenshot);
  const test::Region view{0, 0, 880, 720};
  EXPECT_GT(test::share(shot, view, [](double r, double, double b) { return r > 0.9 && b < 0.2; }), brighter)
      << "orange where yours is brighter";
  EXPECT_GT(test::share(shot, view, [](double r, double, double b) { return b > 0.9 && r < 0.4; }), darker)
      << "blue where darker";
}

const char* const kWrongSign = "R = reflect(L, N); ks * pow(max(0, dot(R, V)), n)";

TEST(ScreenTeaching, AFormulasDifferenceViewMarksBrighterAndDarker) {
  test::TestFolder folder("phonglab-screen-formula");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", std::string(R"(set render resolution_scale 0.5
set render target_spp 4
click_item panel.Formula
wait_frames 3
formula specular )") + kWrongSign + R"(
wait_idle 120
formula_view difference
wait_idle 120
screenshot $OUT/f3_difference.png
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  expect_marks(d + "f3_difference.png", 0.05, 0.05);  // the sign of R wrong moves the highlights
}

TEST(ScreenTeaching, AStudentsImageDroppedIsCheckedAndItsDifferenceShown) {
  test::TestFolder folder("phonglab-screen-image");
  const std::string d = folder.path().string() + "/";
  const std::string setup = R"(set render resolution_scale 0.5
set render target_spp 1
click_item panel.Formula
wait_idle 120
)";
  // The view's size and field of view, as the Probe panel's command names them.
  ASSERT_EQ(test::run_shell(folder, "lecture", setup + "dump_state $OUT/i0.txt\nquit\n").exit_status, 0);
  auto i0 = test::read_state(d + "i0.txt");
  const std::string size = i0["render"];
  ASSERT_NE(size.find('x'), std::string::npos);
  const test::RunResult rendered = test::run_cli_with(
      "render lecture --width " + size.substr(0, size.find('x')) + " --height " + size.substr(size.find('x') + 1) +
          " --fov-y " + i0["camera_fov"] + " --spp 1 -o " + d + "mine.png --formula 'specular=" + kWrongSign + "'",
      " 2>&1");
  ASSERT_EQ(rendered.exit_code, 0) << rendered.out;
  const test::ShellRun run = test::run_shell(folder, "lecture", setup + R"(drop $OUT/mine.png
wait_idle 120
show_item formula.image_verdict
wait_frames 3
screenshot $OUT/i2_difference.png
dump_state $OUT/i2.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto i2 = test::read_state(d + "i2.txt");
  EXPECT_EQ(i2["image_check_verdict"] + "/" + i2["image_check_mistake"], "differs/reflect-sign or view-reversed")
      << i2["image_check_summary"];
  expect_marks(d + "i2_difference.png", 0.02, 0.003);
}

TEST(ScreenTeaching, TheIndirectLightsFourViewsAndTheLessonsLastStep) {
  test::TestFolder folder("phonglab-screen-ambient");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "cornell", R"(key H
set render target_spp 2
set render resolution_scale 0.25
wait_idle 120
screenshot $OUT/a0_constant.png
key I
wait_idle 120
screenshot $OUT/a1_indirect.png
key I
wait_idle 120
screenshot $OUT/a2_beside.png
key I
wait_idle 120
screenshot $OUT/a3_difference.png
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  const test::Region view{0, 60, 1280, 600};
  const test::Shot constant = read_shot(d + "a0_constant.png"), indirect = read_shot(d + "a1_indirect.png");
  const test::Shot beside = read_shot(d + "a2_beside.png"), difference = read_shot(d + "a3_difference.png");
  EXPECT_GT(test::rmse(constant, indirect, view), 0.02) << "the indirect image differs from ka*Ia's";
  EXPECT_GT(test::rmse(indirect, beside, view), 0.02) << "the beside view differs from the indirect image";
  EXPECT_GT(test::rmse(beside, difference, view), 0.02) << "the difference view differs from the beside view";
  test::keep_screenshot(d, "a2_beside.png");
  test::keep_screenshot(d, "a3_difference.png");
}

TEST(ScreenTeaching, ALessonsStepsAsTheyLook) {
  test::TestFolder folder("phonglab-screen-lesson");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(lesson_open shading
set render target_spp 4
lesson_goto 10
wait_idle 120
screenshot $OUT/n10_no_light.png
key 2
wait_frames 3
wait_idle 120
screenshot $OUT/n10_ambient.png
lesson_goto 6
wait_idle 120
lesson_next
wait_idle 120
screenshot $OUT/n06_answer.png
set render target_spp 2
set render resolution_scale 0.25
lesson_goto 13
wait_idle 120
lesson_next
wait_idle 120
wait_idle 120
dump_state $OUT/l13a.txt
screenshot $OUT/l13_answer.png
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  // Below the horizon every pixel is an object's: with the lights muted the full image is the ambient term.
  const test::Region below{10, 440, 860, 120};
  EXPECT_LT(test::rmse(read_shot(d + "n10_no_light.png"), read_shot(d + "n10_ambient.png"), below), 0.004)
      << "the lights muted: the image is the ambient term";
  const test::Shot answer = read_shot(d + "n06_answer.png");
  const test::Region view{0, 150, 880, 400};
  const auto luma = [](double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; };
  EXPECT_LT(test::mean(answer, view), 0.06) << "move your head, revealed: |moved - unmoved| is dark";
  EXPECT_GT(test::share(answer, view, [&](double r, double g, double b) { return luma(r, g, b) > 0.5; }), 0)
      << "but for the highlights";
  auto l13 = test::read_state(d + "l13a.txt");
  EXPECT_EQ(l13["lesson_revealed"] + "/" + l13["ambient_view"] + "/" + l13["compare"], "1/difference/0")
      << "the last step's answer: the signed gap of ka*Ia and the indirect light";
  EXPECT_FALSE(l13["overlay_gap_legend"].empty()) << "with its legend";
}

TEST(ScreenTeaching, TheFileBrowserIsDrawnOverTheView) {
  test::TestFolder folder("phonglab-screen-browser");
  const std::string d = folder.path().string() + "/";
  std::filesystem::create_directories(d + "scenes/sub");
  std::filesystem::create_directories(d + "state/phonglab");
  for (const char* name : {"glass.json", "copy.json"}) {
    std::filesystem::copy_file(PHONGLAB_SOURCE_DIR "/assets/scenes/glass.json", d + "scenes/sub/" + name);
  }
  std::ofstream(d + "state/phonglab/recent") << d << "scenes/sub/copy.json\n" << d << "scenes/sub/glass.json\n";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
wait_idle 120
screenshot $OUT/f4_view.png
key O ctrl
wait_frames 5
type_item browser.name $OUT/scenes/sub
wait_frames 3
screenshot $OUT/f5_recent.png
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  const test::Region list{270, 180, 500, 300};
  const test::Shot view = read_shot(d + "f4_view.png"), browser = read_shot(d + "f5_recent.png");
  EXPECT_GT(test::luma_stddev(browser, list), 0.01) << "the browser's list shows";
  EXPECT_GT(test::rmse(view, browser, list), 0.05) << "over the view";
  test::keep_screenshot(d, "f5_recent.png");
}

}  // namespace
}  // namespace phonglab
