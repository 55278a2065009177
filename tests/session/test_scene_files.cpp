// A scene file as the previewer's document: the file
// given is the document's, a change made on disk by another program reloads (the previewer polls
// changed_on_disk() and, with no unsaved edits, reloads keeping the view), a broken file shows its
// diagnostics while the last good scene stays, Save as writes the file and makes it the document,
// and a missing file is reported with the document kept. The file is the GUI test's own scene.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "interaction/scene_objects.h"
#include "io/scene/scene_io.h"
#include "session/session.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

// The GUI test's scene: a floor and a sphere of material "red" with kd `red_kd` and `radius`.
std::string scene_text(const std::string& red_kd, const std::string& radius) {
  return "{\n"
         "  \"camera\": {\"position\": [0, 1.5, 6], \"look_at\": [0, 0.8, 0], \"up\": [0, 1, 0], \"fov_y\": 40},\n"
         "  \"background\": [0.05, 0.06, 0.09],\n"
         "  \"lights\": [{\"type\": \"point\", \"position\": [2, 6, 4], \"intensity\": [0.9, 0.9, 0.9]}],\n"
         "  \"materials\": {\n"
         "    \"floor\": {\"ka\": 0.04, \"kd\": 0.6},\n"
         "    \"red\": {\"ka\": 0.05, \"kd\": " + red_kd + ", \"ks\": 0.5, \"n\": 20}\n"
         "  },\n"
         "  \"objects\": [\n"
         "    {\"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 1, 0], \"material\": \"floor\"},\n"
         "    {\"type\": \"sphere\", \"center\": [0, 0.8, 0], \"radius\": " + radius + ", \"material\": \"red\"}\n"
         "  ]\n"
         "}\n";
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

// A folder of its own for each test, removed after it; the session keeps no recovery files.
struct SceneFileDocument : ::testing::Test {
  test::TestFolder temp{"phonglab-scene-files"};
  const fs::path dir = temp.path();
  std::string scene;  // dir/scene.json
  Session session{""};
  void SetUp() override {
    scene = (dir / "scene.json").string();
    std::ofstream(scene) << scene_text("[0.8, 0.1, 0.1]", "0.8");
  }
  // Another program replaces the file (written beside it, then renamed over it, as the GUI test
  // does), its modification time a second later (file systems with coarse times see it too).
  void replace_outside(const std::string& red_kd, const std::string& radius) const {
    const auto before = fs::last_write_time(scene);
    const std::string next = scene + ".new";
    std::ofstream(next) << scene_text(red_kd, radius);
    fs::rename(next, scene);
    fs::last_write_time(scene, before + std::chrono::seconds(1));
  }
  Color red_kd() const {
    const int red = ui::find_material(session.scene(), "red");
    EXPECT_GE(red, 0);
    return red < 0 ? Color(-1) : session.scene().materials[static_cast<std::size_t>(red)].kd;
  }
};

TEST_F(SceneFileDocument, TheFileGivenIsTheDocumentsFile) {
  ASSERT_TRUE(session.open(scene)) << session.document().error_text();
  EXPECT_EQ(session.document().file_path(), scene);
  EXPECT_EQ(session.document().source(), scene);
  EXPECT_TRUE(session.document().embedded_name().empty());
  EXPECT_FALSE(session.dirty());
  EXPECT_EQ(red_kd(), Color(0.8, 0.1, 0.1));
}

// What the previewer's poll does with a file changed on disk and no unsaved edits: reload it,
// keeping the view (the file's camera stayed).
TEST_F(SceneFileDocument, AFileChangedOnDiskWithNoEditsReloadsToItsNewMaterials) {
  ASSERT_TRUE(session.open(scene));
  EXPECT_FALSE(session.document().changed_on_disk());
  replace_outside("[0, 0, 1]", "0.8");
  EXPECT_TRUE(session.document().changed_on_disk());
  ASSERT_FALSE(session.dirty()) << "nothing to lose: the file may be read again";
  ASSERT_TRUE(session.reload(true)) << session.document().error_text();
  EXPECT_EQ(red_kd(), Color(0, 0, 1));
  EXPECT_EQ(session.document().status(), "reloaded " + scene);
  EXPECT_FALSE(session.document().changed_on_disk());
  EXPECT_FALSE(session.dirty());
}

TEST_F(SceneFileDocument, ABrokenFileShowsItsDiagnosticsAndKeepsTheLastGoodScene) {
  ASSERT_TRUE(session.open(scene));
  replace_outside("[0, 0, 1]", "0.8");
  ASSERT_TRUE(session.reload(true));
  const std::string good = scene_content(session.scene());
  replace_outside("[0, 1, 0]", "-1");  // line 11: the sphere's radius, its value at column 57
  EXPECT_FALSE(session.reload(true));
  EXPECT_EQ(first_line(session.document().error_text()), scene + ":11:57: objects[1].radius: must be > 0 (got -1)");
  EXPECT_EQ(red_kd(), Color(0, 0, 1)) << "the last good scene stays";
  EXPECT_EQ(scene_content(session.scene()), good);
  EXPECT_EQ(session.document().file_path(), scene);
  EXPECT_FALSE(session.document().changed_on_disk()) << "reported once, not read again twice a second";
}

TEST_F(SceneFileDocument, SaveAsWritesTheFileClearsTheUnsavedMarkAndMakesItTheDocument) {
  ASSERT_TRUE(session.open(scene));
  const int red = ui::find_material(session.scene(), "red");
  ASSERT_GE(red, 0);
  Material edited = session.scene().materials[static_cast<std::size_t>(red)];
  edited.kd = Color(0.5);
  ASSERT_TRUE(session.apply({edit::SetMaterial{red, edited}}).unsaved);
  ASSERT_TRUE(session.dirty());
  const std::string saved = (dir / "saved.json").string();
  ASSERT_TRUE(session.document().save_as(saved)) << session.document().error_text();
  EXPECT_FALSE(session.dirty());
  ASSERT_TRUE(fs::exists(saved));
  EXPECT_GT(fs::file_size(saved), 0U);
  EXPECT_EQ(session.document().file_path(), saved);
  EXPECT_EQ(session.document().source(), saved);
  EXPECT_EQ(session.document().status(), "saved " + saved);
  LoadResult back = load_scene_arg(saved);
  ASSERT_TRUE(back.ok()) << back.error_text();
  EXPECT_EQ(back.scene->materials[static_cast<std::size_t>(red)].kd, Color(0.5));
  std::stringstream text;
  text << std::ifstream(scene).rdbuf();
  EXPECT_EQ(text.str(), scene_text("[0.8, 0.1, 0.1]", "0.8")) << "the file opened first is left as it was";
}

TEST_F(SceneFileDocument, OpeningAMissingFileSaysWhichAndKeepsTheDocument) {
  ASSERT_TRUE(session.open(scene));
  const std::string saved = (dir / "saved.json").string();
  ASSERT_TRUE(session.document().save_as(saved));
  const std::string before = scene_content(session.scene());
  const std::string missing = (dir / "missing.json").string();
  EXPECT_FALSE(session.open(missing));
  EXPECT_EQ(first_line(session.document().error_text()).rfind(missing + ": ", 0), 0U) << session.document().error_text();
  EXPECT_EQ(session.document().file_path(), saved);
  EXPECT_EQ(scene_content(session.scene()), before);
  EXPECT_FALSE(session.dirty());
}

}  // namespace
}  // namespace phonglab
