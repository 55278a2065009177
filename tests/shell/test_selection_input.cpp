// A selected room (the Cornell box: one mesh, every wall of it) is still probed and orbited, the
// shell driven headless by the script's clicks and drag (the second rehearsal's find).
#include <gtest/gtest.h>

#include <string>

#include "tests/shell/shell_harness.h"

namespace phonglab {
namespace {

TEST(SelectionInput, ASelectedRoomIsStillProbedAndOrbited) {
  test::TestFolder folder("phonglab-shell-select");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "cornell", R"(set render target_spp 1
set render resolution_scale 0.25
wait_idle 120
click 300 360
wait_frames 3
wait_idle 120
dump_state )" + d + R"(s1.txt
ctrl_click 300 360
wait_frames 3
wait_idle 120
dump_state )" + d + R"(s2.txt
drag left 300 360 360 380 12
wait_frames 3
wait_idle 120
dump_state )" + d + R"(s3.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto s1 = test::read_state(d + "s1.txt");
  auto s2 = test::read_state(d + "s2.txt");
  auto s3 = test::read_state(d + "s3.txt");
  EXPECT_EQ(s1["selected_object"], "0") << "a click on a wall selects the room";
  EXPECT_FALSE(s2["probe_pixel"].empty());
  EXPECT_EQ(s2["probe_hit"], "1") << "Ctrl+click on the selected room probes it";
  EXPECT_NE(s3["camera_position"], s2["camera_position"]) << "a plain drag starting on the selected room orbits";
  EXPECT_EQ(s3["object0_anchor"], s2["object0_anchor"]) << "and leaves the room where it was";
  EXPECT_EQ(s3["dirty"], "0");
}

}  // namespace
}  // namespace phonglab
