// Building a scene through the shell's panels and script commands, headless: the + sphere button,
// a duplicate dragged with Y held, meshes added and dropped, deletions undone with Ctrl+Z, a scene
// dropped on an edited one asking first, the saved scene rendered by phonglab-cli to the
// previewer's image bit for bit. (A click selecting an object and a drag with X held, through real
// X input, are the Xvfb session's.)
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "tests/shell/shell_harness.h"
#include "tests/support/run_cli.h"

namespace phonglab {
namespace {

TEST(BuildingInput, ObjectsAddedMovedDroppedDeletedAndSavedAsTheCliRendersThem) {
  test::TestFolder folder("phonglab-shell-building");
  const std::string d = folder.path().string() + "/";
  std::ofstream(d + "tetra.obj") << "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::ofstream(d + "broken.obj") << "v 0 0 0\nf 1 2 3\n";
  std::ofstream(d + "notes.txt") << "not a scene\n";
  std::filesystem::copy_file(PHONGLAB_SOURCE_DIR "/assets/scenes/glass.json", d + "other.json");
  std::string deletions;
  for (int i = 0; i < 11; ++i) deletions += "delete_object 0\nwait_frames 1\n";
  const test::ShellRun run = test::run_shell(folder, "lecture", R"(set render target_spp 1
set render resolution_scale 0.5
set display stats 0
wait_idle 120
dump_state )" + d + R"(b00.txt
show_item panel.Objects
click_item panel.Objects
wait_frames 3
click_item objects.add_sphere
wait_idle 120
dump_state )" + d + R"(b01.txt
set object 6 radius 0.3
set object 6 center 0.2 0.3 1.4
duplicate_object 6
drag_object 7 0 -60 y
wait_idle 120
dump_state )" + d + R"(b05.txt
add_object mesh )" + d + R"(tetra.obj
wait_idle 120
add_object mesh )" + d + R"(broken.obj
drop )" + d + R"(notes.txt
drop )" + d + R"(tetra.obj
wait_frames 3
dump_state )" + d + R"(b09.txt
delete_object 0
wait_frames 3
key Z ctrl
wait_frames 3
dump_state )" + d + R"(b10.txt
add_object triangle
wait_frames 3
drop )" + d + R"(other.json
wait_frames 5
dump_state )" + d + R"(b10g.txt
modal cancel
wait_frames 3
wait_idle 120
save_as )" + d + R"(built.json
save_pfm )" + d + R"(built.pfm
dump_state )" + d + R"(b11.txt
)" + deletions + R"(wait_frames 3
dump_state )" + d + R"(b12.txt
key Z ctrl
wait_frames 3
dump_state )" + d + R"(b13.txt
quit
)");
  ASSERT_EQ(run.exit_status, 0);
  auto b00 = test::read_state(d + "b00.txt");
  auto b01 = test::read_state(d + "b01.txt");
  const int n0 = std::stoi(b00["objects"]);
  EXPECT_EQ(std::stoi(b01["objects"]), n0 + 1) << "the + sphere button adds an object last";
  EXPECT_EQ(b01["selected_object"], std::to_string(n0)) << "and selects it";
  EXPECT_EQ(b01["object" + std::to_string(n0) + "_kind"], "sphere");
  auto b05 = test::read_state(d + "b05.txt");
  const auto original = test::vec3_of(b05["object6_anchor"]);
  const auto duplicate = test::vec3_of(b05["object7_anchor"]);
  EXPECT_EQ(duplicate[0], original[0]) << "a duplicate, made in place and dragged up with Y held, moves along y only";
  EXPECT_GT(duplicate[1], original[1] + 0.05);
  EXPECT_EQ(duplicate[2], original[2]);
  auto b09 = test::read_state(d + "b09.txt");
  EXPECT_EQ(b09["objects"], "10") << "the tetrahedron added and dropped; the broken OBJ and the notes refused";
  EXPECT_EQ(b09["object9_kind"], "mesh");
  auto b10 = test::read_state(d + "b10.txt");
  EXPECT_EQ(b10["objects"], "10") << "deleting objects[0] is undone by Ctrl+Z, one step";
  EXPECT_EQ(b10["object0_kind"], "plane");
  EXPECT_EQ(test::read_state(d + "b10g.txt")["modal"], "1") << "a scene dropped on an edited one asks first";
  auto b11 = test::read_state(d + "b11.txt");
  EXPECT_EQ(b11["objects"], "11") << "Cancel keeps the edits";
  auto b12 = test::read_state(d + "b12.txt");
  EXPECT_EQ(b12["objects"], "0");
  EXPECT_NE(b12["objects_notice"].find("last object"), std::string::npos) << "deleting every object says so";
  EXPECT_EQ(test::read_state(d + "b13.txt")["objects"], "1") << "Ctrl+Z brings the last one back";

  EXPECT_EQ(test::run_cli("validate " + d + "built.json").exit_code, 0) << "phonglab-cli validate accepts the saved scene";
  const std::string size = b11["render"];
  const std::string w = size.substr(0, size.find('x')), h = size.substr(size.find('x') + 1);
  ASSERT_EQ(test::run_cli("render " + d + "built.json --width " + w + " --height " + h + " --fov-y " + b11["camera_fov"] +
                          " --spp 1 -o " + d + "cli_built.pfm")
                .exit_code,
            0);
  const std::string ours = test::file_bytes(d + "built.pfm");
  EXPECT_FALSE(ours.empty());
  EXPECT_TRUE(ours == test::file_bytes(d + "cli_built.pfm")) << "the CLI renders the saved scene to the previewer's image, bit for bit";
}

}  // namespace
}  // namespace phonglab
