// What a dropped file is taken as (session/dropped_file.h): by its ending, a lesson file told from
// a scene by its content, anything else refused naming the file and what is taken.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "session/dropped_file.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;
using Kind = DroppedFile::Kind;

struct Drops : ::testing::Test {
  test::TestFolder temp{"phonglab-drops"};
  const fs::path dir = temp.path();
  std::string file(const std::string& name, const std::string& text) const {
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
  }
};

TEST_F(Drops, EachKindByItsEndingAndALessonByItsContent) {
  EXPECT_EQ(classify_drop(file("tetra.obj", "v 0 0 0\n")).kind, Kind::kMesh);
  EXPECT_EQ(classify_drop(file("TETRA.OBJ", "v 0 0 0\n")).kind, Kind::kMesh);
  EXPECT_EQ(classify_drop(file("scene.json", R"({"objects": []})")).kind, Kind::kScene);
  EXPECT_EQ(classify_drop(file("my-lesson.json",
                               R"({"title": "Dropped", "steps": [{"title": "Ambient", "caption": "ka only.", "scene": "lecture"}]})"))
                .kind,
            Kind::kLesson);
  for (const char* name : {"mine.png", "mine.PPM", "mine.pfm"}) EXPECT_EQ(classify_drop(file(name, "x")).kind, Kind::kImage) << name;
}

TEST_F(Drops, AnythingElseIsRefusedNamingTheFileAndWhatIsTaken) {
  const std::string notes = file("notes.txt", "notes, not a scene\n");
  const DroppedFile dropped = classify_drop(notes);
  EXPECT_EQ(dropped.kind, Kind::kRefused);
  EXPECT_EQ(dropped.refusal, "dropped '" + notes +
                                 "': not a scene or a lesson (.json), a mesh (.obj), nor an image to check (.png, .ppm, .pfm)");
  const DroppedFile folder = classify_drop(dir.string());
  EXPECT_EQ(folder.kind, Kind::kRefused);
  EXPECT_EQ(folder.refusal, "dropped '" + dir.string() + "': not a file");
}

}  // namespace
}  // namespace phonglab
