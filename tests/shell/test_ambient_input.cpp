// What ambient stands in for, through the shell's keys and buttons, headless: I steps through the
// indirect light, beside, difference and back to ka·Ia; on the Cornell box's back wall "best ka"
// raises its ka but not past 1 and says the fit wants more, and "best Iₐ" sets the scene's one
// ambient intensity. (The four views as the screen shows them: test_screen_teaching.cpp.)
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tests/shell/shell_harness.h"

namespace phonglab {
namespace {

TEST(AmbientInput, TheIKeysViewsAndTheFitButtons) {
  test::TestFolder folder("phonglab-shell-ambient");
  const std::string d = folder.path().string() + "/";
  const test::ShellRun run = test::run_shell(folder, "cornell", R"(key H
set render target_spp 4
set render resolution_scale 0.25
wait_idle 120
key I
wait_idle 120
dump_state )" + d + R"(a1.txt
key I
wait_idle 120
dump_state )" + d + R"(a2.txt
key I
wait_idle 120
dump_state )" + d + R"(a3.txt
key I
wait_idle 120
dump_state )" + d + R"(a4.txt
key H
wait_frames 3
click 440 250
wait_frames 3
show_item materials.fit_ka
click_item materials.fit_ka
wait_frames 3
dump_state )" + d + R"(a5.txt
click_item scene.fit_ia
wait_frames 3
dump_state )" + d + R"(a6.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  EXPECT_EQ(test::read_state(d + "a1.txt")["ambient_view"], "indirect");
  EXPECT_EQ(test::read_state(d + "a2.txt")["ambient_view"], "beside");
  EXPECT_EQ(test::read_state(d + "a3.txt")["ambient_view"], "difference");
  auto a4 = test::read_state(d + "a4.txt");
  EXPECT_EQ(a4["ambient_view"], "constant") << "I steps through indirect, beside, difference and back to ka*Ia";
  auto a5 = test::read_state(d + "a5.txt");
  const std::string wall = a5["selected_material"];
  ASSERT_FALSE(wall.empty());
  const auto before = test::vec3_of(a4["material_" + wall + "_ka"]);
  const auto after = test::vec3_of(a5["material_" + wall + "_ka"]);
  EXPECT_GT(after[0], before[0]) << "best ka raises " << wall << "'s ka";
  for (const double c : after) EXPECT_LE(c, 1) << "but not past 1";
  EXPECT_FALSE(a5["item_materials.fit_ka_over"].empty()) << "and says the fit wants more";
  EXPECT_EQ(a5["dirty"], "1") << "an MTL material's edit is unsaved like any other";
  auto a6 = test::read_state(d + "a6.txt");
  const double ia_before = test::vec3_of(a5["scene_ambient"])[0], ia_after = test::vec3_of(a6["scene_ambient"])[0];
  EXPECT_GT(ia_after, ia_before) << "best Ia sets the scene's one ambient intensity";
  EXPECT_LT(ia_after, 1);
  EXPECT_EQ(a6["material_" + wall + "_ka"], a5["material_" + wall + "_ka"]) << "the materials' ka kept";
}

}  // namespace
}  // namespace phonglab
