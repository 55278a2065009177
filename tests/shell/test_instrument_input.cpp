// The teaching instruments driven through the shell's input, headless: the probe at a window
// pixel is the shown linear pixel exactly (also with the head moved), Ctrl+click and probe mode
// probe elsewhere, Ctrl+Z and Ctrl+Shift+Z undo and redo an edit. (The compare views, the small
// multiples and the two-eye differences on the screen: test_screen_views.cpp.)
#include <gtest/gtest.h>

#include <string>

#include "tests/shell/shell_harness.h"

namespace phonglab {
namespace {

TEST(InstrumentInput, TheProbeIsTheShownPixelAndKeysUndoAndRedo) {
  test::TestFolder folder("phonglab-shell-instruments");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
wait_idle 120
probe 440 401
wait_frames 2
dump_state )" + d + R"(i01.txt
ctrl_click 309 497
dump_state )" + d + R"(i02.txt
set instruments probe_mode 1
click 550 497
wait_frames 2
dump_state )" + d + R"(i03.txt
set instruments probe_mode 0
set material plastic kd 0.9 0.1 0.1
wait_frames 2
key Z ctrl
wait_frames 2
dump_state )" + d + R"(i05.txt
key Z ctrl shift
wait_frames 2
dump_state )" + d + R"(i06.txt
probe 354 338
set instruments head 1
set instruments head_angle 15
wait_idle 120
dump_state )" + d + R"(h03.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto i01 = test::read_state(d + "i01.txt");
  auto i02 = test::read_state(d + "i02.txt");
  auto i03 = test::read_state(d + "i03.txt");
  EXPECT_EQ(i01["probe_hit"], "1") << "the probe hits the scene at " << i01["probe_pixel"];
  EXPECT_EQ(i01["probe_match"], "1") << "its total equals the shown linear pixel exactly";
  EXPECT_NE(i02["probe_pixel"], i01["probe_pixel"]) << "Ctrl+click probes another pixel";
  EXPECT_NE(i03["probe_pixel"], i02["probe_pixel"]) << "a plain click in probe mode probes";
  auto i05 = test::read_state(d + "i05.txt");
  EXPECT_NE(i05["material_plastic_kd"], "0.9 0.1 0.1") << "Ctrl+Z restores the material";
  EXPECT_EQ(i05["redo"], "1");
  EXPECT_EQ(test::read_state(d + "i06.txt")["material_plastic_kd"], "0.9 0.1 0.1") << "Ctrl+Shift+Z redoes it";
  auto h03 = test::read_state(d + "h03.txt");
  EXPECT_EQ(h03["head"], "1");
  EXPECT_EQ(h03["probe_match"], "1") << "move your head: the probe follows the moved eye";
}

}  // namespace
}  // namespace phonglab
