// Presenting a lesson through the shell's keys and panels, headless: a term key on a step is
// exploring and Back shows the step as written; the move-your-head question's answer is shown as
// the compare view; exploring a lesson file's step and Ctrl+S asks where to save (the lesson file
// is nobody's scene file). (The images on the screen: test_screen_teaching.cpp; the real keys and
// presenter mode: the Xvfb session's.)
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/shell/shell_harness.h"

namespace phonglab {
namespace {

TEST(LessonInput, ExploringAStepBackToItAndSavingAnExploredLessonFileStep) {
  test::TestFolder folder("phonglab-shell-lesson");
  const std::string d = folder.path().string() + "/";
  std::ofstream(d + "mine.json") << R"({"title": "Mine", "description": "a lesson file of the test's own",
 "steps": [{"title": "The plastic sphere", "caption": "kd is 0.8, 0.15, 0.1.", "scene": "lecture"}]})";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
set render resolution_scale 0.25
lesson_open shading
wait_idle 120
lesson_goto 10
wait_idle 120
key 2
wait_frames 3
dump_state )" + d + R"(n10e.txt
click_item lesson.back
wait_frames 3
wait_idle 120
dump_state )" + d + R"(n10b.txt
lesson_goto 6
wait_idle 120
lesson_next
wait_idle 120
dump_state )" + d + R"(n06.txt
lesson_open )" + d + R"(mine.json
wait_idle 120
set material plastic kd 0.1 0.1 0.9
wait_frames 3
key S ctrl
wait_frames 5
dump_state )" + d + R"(n_mine.txt
key ESCAPE
wait_frames 3
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto explored = test::read_state(d + "n10e.txt");
  auto back = test::read_state(d + "n10b.txt");
  EXPECT_EQ(explored["lesson_exploring"], "1") << "a term key while on a step is exploring";
  EXPECT_EQ(explored["term"], "ambient");
  EXPECT_EQ(back["lesson_exploring"], "0") << "Back shows the step as written";
  EXPECT_EQ(back["term"], "full");
  auto answer = test::read_state(d + "n06.txt");
  EXPECT_EQ(answer["lesson_revealed"], "1");
  EXPECT_EQ(answer["compare"], "2") << "move your head's answer is shown as the compare view: " << answer["compare_caption"];
  auto mine = test::read_state(d + "n_mine.txt");
  EXPECT_EQ(mine["lesson"], "mine");
  EXPECT_EQ(mine["lesson_exploring"], "1");
  EXPECT_EQ(mine["file_browser"], "save") << "Ctrl+S on an explored step of a lesson file asks where to save";
}

}  // namespace
}  // namespace phonglab
