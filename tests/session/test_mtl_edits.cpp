// An OBJ's MTL materials edited in the session (the Cornell box's walls): the edit is an unsaved
// change like any other, Save writes it into the scene file's "materials" under the MTL
// material's name, and the file read again gives the mesh that material, once, with the edit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/render/render.h"
#include "interaction/scene_objects.h"
#include "io/scene/scene_io.h"
#include "session/session.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

struct MtlEdits : ::testing::Test {
  test::TestFolder temp{"phonglab-mtl-edits"};
  const fs::path dir = temp.path();
  Session session{""};  // no recovery files
  int wall = -1;

  void SetUp() override {
    ASSERT_TRUE(session.open("cornell"));
    wall = ui::find_material(session.scene(), "CornellBox-Original/backWall");
    ASSERT_GE(wall, 0);
    ASSERT_FALSE(session.scene().materials[static_cast<std::size_t>(wall)].source.empty()) << "the MTL's";
  }

  Material wall_material() const { return session.scene().materials.at(static_cast<std::size_t>(wall)); }
  Applied set_wall_kd(const Color& kd) {
    Material m = wall_material();
    m.kd = kd;
    return session.apply({edit::SetMaterial{wall, m}});
  }
};

// The linear image of `scene` at 48x48, one sample: what the faces' materials make of it.
std::vector<Color> image_of(const Scene& scene) {
  const PreparedScene prepared(scene);
  Accumulator acc;
  acc.reset(48, 48);
  RenderOptions options;
  options.threads = 1;
  render_pass(prepared, options, acc);
  return acc.sum;
}

TEST_F(MtlEdits, AnEditOfAnMtlMaterialIsAnUnsavedChangeAndUndoGivesTheMtlsBack) {
  const Material mtl = wall_material();
  const Applied applied = set_wall_kd(Color(0.1, 0.2, 0.7));
  EXPECT_TRUE(applied.unsaved);
  EXPECT_TRUE(session.dirty()) << "quitting must ask, the recovery must keep it";
  EXPECT_TRUE(wall_material().source.empty()) << "the scene file's own from now on";
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(wall_material(), mtl);
  EXPECT_FALSE(session.dirty());
}

TEST_F(MtlEdits, SaveWritesTheEditAndTheFileReadAgainGivesTheMeshThatMaterialOnce) {
  const std::size_t materials = session.scene().materials.size();
  set_wall_kd(Color(0.1, 0.2, 0.7));
  const std::vector<Color> edited = image_of(session.scene());
  const std::string path = (dir / "walls.json").string();
  ASSERT_TRUE(session.document().save_as(path)) << session.document().error_text();
  EXPECT_FALSE(session.dirty());
  // Edited again and kept by a recovery (written in the state folder): it loads back there too.
  set_wall_kd(Color(0.3, 0.2, 0.1));
  RecoveryKeeper keeper((dir / "state").string());
  ASSERT_FALSE(keeper.write(session.document()).empty()) << keeper.error();
  const auto entry = keeper.find(session.document(), false);
  ASSERT_TRUE(entry);
  SceneDocument restored;
  ASSERT_TRUE(restored.open(path));
  ASSERT_EQ(keeper.restore(restored, *entry).error, "");
  const int kept = ui::find_material(restored.scene(), "CornellBox-Original/backWall");
  ASSERT_GE(kept, 0);
  EXPECT_EQ(restored.scene().materials.at(static_cast<std::size_t>(kept)).kd, Color(0.3, 0.2, 0.1));
  ASSERT_TRUE(session.undo());

  Session again{""};
  ASSERT_TRUE(again.open(path)) << again.document().error_text();
  EXPECT_EQ(again.scene().materials.size(), materials) << "no second backWall beside the file's";
  const int i = ui::find_material(again.scene(), "CornellBox-Original/backWall");
  ASSERT_GE(i, 0);
  const Material& read = again.scene().materials[static_cast<std::size_t>(i)];
  EXPECT_EQ(read.kd, Color(0.1, 0.2, 0.7));
  EXPECT_TRUE(read.source.empty());
  EXPECT_FALSE(again.dirty());
  EXPECT_EQ(image_of(again.scene()), edited) << "the mesh's faces use the saved material, bit for bit";
  EXPECT_EQ(ui::mtl_origin(again.scene(), i), again.scene().meshes.at(0).file);
  Scene renamed = again.scene();
  EXPECT_NE(ui::rename_material(renamed, i, "wall").find("MTL file: rename it there"), std::string::npos)
      << "a rename would cut it off from the mesh's faces";
}

// Saved as a copy, the embedded Cornell box takes its OBJ and MTL along (above: it opens again);
// a file of the same name with other contents is never replaced, and then nothing is written.
TEST_F(MtlEdits, SaveAsNeverOverwritesAnotherMeshFileOfTheSameName) {
  fs::create_directories(dir / "cornell");
  const fs::path theirs = dir / "cornell" / "CornellBox-Original.obj";
  std::ofstream(theirs) << "# someone else's\nv 0 0 0\n";
  set_wall_kd(Color(0.1, 0.2, 0.7));
  const std::string path = (dir / "walls.json").string();
  EXPECT_FALSE(session.document().save_as(path));
  EXPECT_NE(session.document().error_text().find("exists with other contents, which were kept"), std::string::npos)
      << session.document().error_text();
  EXPECT_FALSE(fs::exists(path)) << "no scene naming a mesh it does not have";
  std::ifstream in(theirs);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "# someone else's");
  EXPECT_TRUE(session.dirty()) << "the edits stay";
}

TEST_F(MtlEdits, AnUneditedMtlMaterialStaysTheMtls) {
  Material m = wall_material();
  Scene before = session.scene();
  Scene after = before;
  after.materials[static_cast<std::size_t>(wall)] = m;  // the same values
  ui::own_edited_mtl_materials(before, after);
  EXPECT_FALSE(after.materials[static_cast<std::size_t>(wall)].source.empty());
  const std::string text = scene_to_json(session.scene(), dir.string());
  EXPECT_EQ(text.find("backWall"), std::string::npos) << "the MTL brings it back";
}

}  // namespace
}  // namespace phonglab
