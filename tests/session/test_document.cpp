// The scene document (src/session/document.h): a file opened, saved, reloaded, guarded against
// a change made on disk by another program, and the unsaved state beside navigation.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/scene/scene_io.h"
#include "session/document.h"
#include "tests/support/document_edits.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

// A folder of its own for each test, removed after it.
struct DocumentFiles : ::testing::Test {
  test::TestFolder temp{"phonglab-document"};
  const fs::path dir = temp.path();
  // The embedded lecture scene written as a file; its path.
  std::string lecture_file(const std::string& name = "scene.json") const {
    SceneDocument doc;
    EXPECT_TRUE(doc.open("lecture"));
    const std::string path = (dir / name).string();
    EXPECT_TRUE(doc.save_as(path));
    return path;
  }
  // Another program writes the file: its text with the first material's kd changed, and a
  // modification time a second later than before (file systems with coarse times see it too).
  static void write_outside(const std::string& path, double kd) {
    SceneDocument other;
    ASSERT_TRUE(other.open(path));
    test::edit_scene(other, [&](Scene& s) { s.materials.at(0).kd = Color(kd); });
    const auto before = fs::last_write_time(path);
    std::ofstream(path) << scene_to_json(other.scene(), fs::path(path).parent_path().string());
    fs::last_write_time(path, before + std::chrono::seconds(1));
  }
};

TEST_F(DocumentFiles, AnEmbeddedSceneHasNoFile) {
  SceneDocument doc;
  ASSERT_TRUE(doc.open("lecture"));
  EXPECT_EQ(doc.embedded_name(), "lecture");
  EXPECT_TRUE(doc.file_path().empty());
  EXPECT_FALSE(doc.dirty());
  EXPECT_EQ(doc.save(), SceneDocument::SaveResult::kFailed) << "Save asks for a name";
  EXPECT_FALSE(doc.reload(true));
}

TEST_F(DocumentFiles, ABrokenFileKeepsTheSceneAndSaysWhere) {
  SceneDocument doc;
  ASSERT_TRUE(doc.open("lecture"));
  const std::string path = (dir / "broken.json").string();
  std::ofstream(path) << "{\n  \"camera\": {\n    \"position\": [0, 1,, 2]\n  }\n}\n";
  const std::string before = scene_content(doc.scene());
  EXPECT_FALSE(doc.open(path));
  EXPECT_NE(doc.error_text().find("broken.json:3:"), std::string::npos) << doc.error_text();
  EXPECT_EQ(scene_content(doc.scene()), before);
  EXPECT_EQ(doc.embedded_name(), "lecture");
}

TEST_F(DocumentFiles, SaveAsWritesWhatOpensAgain) {
  const std::string path = lecture_file();
  SceneDocument doc;
  ASSERT_TRUE(doc.open(path));
  SceneDocument lecture;
  ASSERT_TRUE(lecture.open("lecture"));
  EXPECT_EQ(scene_content(doc.scene()), scene_content(lecture.scene()));
  EXPECT_EQ(doc.scene().camera, lecture.scene().camera);
  EXPECT_EQ(doc.file_path(), path);
}

TEST_F(DocumentFiles, SaveAsRefusesAMeshPathAndAnEmptyOne) {
  SceneDocument doc;
  ASSERT_TRUE(doc.open("lecture"));
  EXPECT_FALSE(doc.save_as((dir / "mesh.obj").string()));
  EXPECT_FALSE(doc.save_as(""));
  EXPECT_FALSE(fs::exists(dir / "mesh.obj"));
}

TEST_F(DocumentFiles, NavigationIsNotAnUnsavedChangeButSaveWritesIt) {
  const std::string path = lecture_file();
  SceneDocument doc;
  ASSERT_TRUE(doc.open(path));
  test::edit_scene(doc, [&](Scene& s) { s.camera.position += Vec3(0, 2, 0); });
  EXPECT_FALSE(doc.dirty());
  test::edit_scene(doc, [&](Scene& s) { s.materials.at(0).kd = Color(0.125); });
  EXPECT_TRUE(doc.dirty());
  ASSERT_EQ(doc.save(), SceneDocument::SaveResult::kSaved);
  EXPECT_FALSE(doc.dirty());
  SceneDocument again;
  ASSERT_TRUE(again.open(path));
  EXPECT_EQ(again.scene().camera, doc.scene().camera);
  EXPECT_EQ(again.scene().materials.at(0).kd, Color(0.125));
}

TEST_F(DocumentFiles, AChangeOnDiskIsNeverOverwrittenSilently) {
  const std::string path = lecture_file();
  SceneDocument doc;
  ASSERT_TRUE(doc.open(path));
  EXPECT_FALSE(doc.changed_on_disk());
  write_outside(path, 0.75);
  EXPECT_TRUE(doc.changed_on_disk());
  test::edit_scene(doc, [&](Scene& s) { s.materials.at(0).kd = Color(0.25); });
  EXPECT_EQ(doc.save(), SceneDocument::SaveResult::kChangedOnDisk);
  SceneDocument disk;
  ASSERT_TRUE(disk.open(path));
  EXPECT_EQ(disk.scene().materials.at(0).kd, Color(0.75)) << "the other program's change is still there";
  EXPECT_EQ(doc.save(true), SceneDocument::SaveResult::kSaved) << "overwriting it is asked for";
  EXPECT_FALSE(doc.changed_on_disk()) << "our own write is not a change on disk";
  ASSERT_TRUE(disk.open(path));
  EXPECT_EQ(disk.scene().materials.at(0).kd, Color(0.25));
}

TEST_F(DocumentFiles, ReloadTakesTheFileAndKeepsTheViewWhenItsCameraStayed) {
  const std::string path = lecture_file();
  SceneDocument doc;
  ASSERT_TRUE(doc.open(path));
  Camera view = doc.scene().camera;
  view.position += Vec3(3, 0, 0);
  test::edit_scene(doc, [&](Scene& s) { s.camera = view; });
  write_outside(path, 0.5);
  ASSERT_TRUE(doc.reload(true));
  EXPECT_EQ(doc.scene().materials.at(0).kd, Color(0.5));
  EXPECT_EQ(doc.scene().camera, view) << "a text editor changed materials, not the view";
  EXPECT_FALSE(doc.dirty());
  EXPECT_FALSE(doc.changed_on_disk());
}

TEST_F(DocumentFiles, ReloadWithoutKeepingTheViewTakesTheFilesCamera) {
  const std::string path = lecture_file();
  SceneDocument doc;
  ASSERT_TRUE(doc.open(path));
  const Camera file_camera = doc.scene().camera;
  test::edit_scene(doc, [&](Scene& s) { s.camera.position += Vec3(3, 0, 0); });
  ASSERT_TRUE(doc.reload(false));
  EXPECT_EQ(doc.scene().camera, file_camera);
}

TEST_F(DocumentFiles, AReloadOfABrokenFileKeepsTheSceneAndReportsOnce) {
  const std::string path = lecture_file();
  SceneDocument doc;
  ASSERT_TRUE(doc.open(path));
  const std::string before = scene_content(doc.scene());
  const auto t = fs::last_write_time(path);
  std::ofstream(path) << "{ \"camera\": ";
  fs::last_write_time(path, t + std::chrono::seconds(1));
  EXPECT_TRUE(doc.changed_on_disk());
  EXPECT_FALSE(doc.reload(true));
  EXPECT_FALSE(doc.error_text().empty());
  EXPECT_EQ(scene_content(doc.scene()), before);
  EXPECT_FALSE(doc.changed_on_disk()) << "the broken file is not read again twice a second";
}

TEST_F(DocumentFiles, AnObjOpenedOnItsOwnIsNeverOverwrittenBySave) {
  const std::string path = (dir / "tri.obj").string();
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  SceneDocument doc;
  ASSERT_TRUE(doc.open(path)) << doc.error_text();
  EXPECT_TRUE(doc.opened_mesh());
  EXPECT_EQ(doc.save(true), SceneDocument::SaveResult::kFailed);
  std::stringstream text;
  text << std::ifstream(path).rdbuf();
  EXPECT_EQ(text.str(), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
}

}  // namespace
}  // namespace phonglab
