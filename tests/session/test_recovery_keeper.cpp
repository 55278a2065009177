// Unsaved edits kept in a recovery file (src/session/recovery_keeper.h): written once a burst of
// edits is two seconds old, not again while nothing changes, removed once the document is
// clean, found again for its source, and what is written loads back to the edited scene.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/scene/scene_io.h"
#include "session/recovery_keeper.h"
#include "tests/support/document_edits.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

struct RecoveryFiles : ::testing::Test {
  test::TestFolder temp{"phonglab-recovery", false};
  const fs::path dir = temp.path();
  SceneDocument doc;
  void SetUp() override {
    ASSERT_TRUE(doc.open("lecture"));
  }
  void edit(double kd) {
    test::edit_scene(doc, [&](Scene& s) { s.materials.at(0).kd = Color(kd); });
  }
  static std::string read(const std::string& path) {
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    return text.str();
  }
};

TEST_F(RecoveryFiles, ACleanDocumentKeepsNoFile) {
  RecoveryKeeper keeper(dir.string());
  keeper.autosave(doc, 100);
  EXPECT_TRUE(keeper.written().empty());
  EXPECT_FALSE(fs::exists(dir));
}

TEST_F(RecoveryFiles, EditsAreWrittenOnceTheBurstIsTwoSecondsOld) {
  RecoveryKeeper keeper(dir.string());
  edit(0.25);
  keeper.edited(10);
  keeper.autosave(doc, 11.9);
  EXPECT_TRUE(keeper.written().empty()) << "the burst may go on";
  keeper.autosave(doc, 12.0);
  ASSERT_FALSE(keeper.written().empty());
  EXPECT_EQ(fs::path(keeper.written()).filename().string(), "embedded-lecture.json");
  EXPECT_TRUE(fs::exists(fs::path(keeper.written()).replace_extension(".source")));
  const auto first = fs::last_write_time(keeper.written());
  fs::last_write_time(keeper.written(), first - std::chrono::seconds(5));
  keeper.autosave(doc, 20);
  EXPECT_EQ(fs::last_write_time(keeper.written()), first - std::chrono::seconds(5)) << "written once per burst";
}

TEST_F(RecoveryFiles, WhatIsKeptLoadsBackToTheEditedScene) {
  RecoveryKeeper keeper(dir.string());
  edit(0.125);
  const std::string path = keeper.write(doc);
  ASSERT_FALSE(path.empty());
  LoadResult back = load_scene_text(read(path), path, dir.string(), true);
  ASSERT_TRUE(back.ok()) << back.error_text();
  EXPECT_EQ(scene_content(*back.scene), scene_content(doc.scene()));
}

TEST_F(RecoveryFiles, TheFileGoesOnceTheDocumentIsCleanAgain) {
  RecoveryKeeper keeper(dir.string());
  edit(0.5);
  const std::string path = keeper.write(doc);
  ASSERT_TRUE(fs::exists(path));
  ASSERT_TRUE(doc.open("lecture"));  // the edits discarded
  keeper.autosave(doc, 50);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(fs::path(path).replace_extension(".source")));
  EXPECT_TRUE(keeper.written().empty());
}

TEST_F(RecoveryFiles, AKeptFileIsFoundForItsSourceOnly) {
  RecoveryKeeper keeper(dir.string());
  edit(0.5);
  ASSERT_FALSE(keeper.write(doc).empty());
  const RecoveryKeeper next_start(dir.string());
  const auto found = next_start.find(doc, false);
  ASSERT_TRUE(found);
  EXPECT_EQ(found->source, "lecture");
  EXPECT_TRUE(found->embedded);
  SceneDocument other;
  ASSERT_TRUE(other.open("cornell"));
  EXPECT_FALSE(next_start.find(other, false)) << "another scene's edits are not offered over it";
  EXPECT_TRUE(next_start.find(other, true)) << "with no scene given, the newest of any";
}

TEST_F(RecoveryFiles, ALessonsStepIsNobodysFile) {
  RecoveryKeeper keeper(dir.string());
  doc.adopt(doc.scene(), "a lesson's step");
  test::edit_scene(doc, [&](Scene& s) { s.materials.at(0).kd = Color(0.5); });
  EXPECT_FALSE(RecoveryKeeper::source_of(doc));
  EXPECT_TRUE(keeper.write(doc).empty());
}

TEST_F(RecoveryFiles, AFailedWriteSaysWhyAndLosesNothing) {
  fs::create_directories(dir.parent_path());
  std::ofstream(dir.string()) << "a file where the folder should be";
  RecoveryKeeper keeper(dir.string());
  edit(0.5);
  EXPECT_TRUE(keeper.write(doc).empty());
  EXPECT_FALSE(keeper.error().empty());
  EXPECT_TRUE(doc.dirty()) << "the edits are still the document's";
  fs::remove(dir);
  EXPECT_FALSE(keeper.write(doc).empty()) << "the next write can succeed";
  EXPECT_TRUE(keeper.error().empty());
}

TEST_F(RecoveryFiles, AFileOnDiskIsKeptUnderItsAbsolutePath) {
  fs::create_directories(dir / "scenes");
  const std::string path = (dir / "scenes" / "mine.json").string();
  ASSERT_TRUE(doc.save_as(path));
  ASSERT_TRUE(doc.open(path));
  const auto source = RecoveryKeeper::source_of(doc);
  ASSERT_TRUE(source);
  EXPECT_FALSE(source->second);
  EXPECT_EQ(source->first, fs::absolute(path).lexically_normal().string());
  RecoveryKeeper keeper((dir / "recovery").string());
  edit(0.75);
  const std::string kept = keeper.write(doc);
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(fs::path(kept).filename().string(), ui::recovery_key(source->first, false) + ".json");
}


// The rehearsal's loss: a file opened and edited, changed on disk by another program, the
// previewer killed; the next start opens the file as it is now and restores the kept edits. The
// recovery carries the file's identity of the edits' time, so Save asks (kChangedOnDisk) rather
// than overwrite the other program's change; with no outside change it saves as usual.
TEST_F(RecoveryFiles, ARestoredSessionAsksBeforeItOverwritesAnOutsideChange) {
  fs::create_directories(dir / "scenes");
  const std::string file = (dir / "scenes" / "mine.json").string();
  ASSERT_TRUE(doc.save_as(file));
  for (const bool outside_change : {true, false}) {
    SceneDocument first;
    ASSERT_TRUE(first.open(file));
    RecoveryKeeper keeper((dir / "recovery").string());
    test::edit_scene(first, [&](Scene& s) { s.materials.at(0).kd = Color(0.125); });
    ASSERT_FALSE(keeper.write(first).empty());  // what a signal's write keeps
    if (outside_change) {
      Scene theirs = first.scene();
      theirs.materials.at(0).kd = Color(0.875);
      std::ofstream(file) << scene_to_json(theirs, (dir / "scenes").string());
    }
    const std::string on_disk = read(file);

    SceneDocument next;  // the next start, on the file
    ASSERT_TRUE(next.open(file));
    RecoveryKeeper next_keeper((dir / "recovery").string());
    const auto entry = next_keeper.find(next, false);
    ASSERT_TRUE(entry);
    EXPECT_FALSE(entry->base.empty());
    const RecoveryKeeper::Restored restored = next_keeper.restore(next, *entry);
    ASSERT_TRUE(restored.error.empty()) << restored.error;
    EXPECT_EQ(next.scene().materials.at(0).kd, Color(0.125));
    EXPECT_EQ(restored.changed_on_disk, outside_change);
    EXPECT_EQ(restored.status, "restored the unsaved edits kept in " + entry->scene_path +
                                   (outside_change ? "; " + file +
                                                         " changed on disk since they were made: Save asks before it "
                                                         "overwrites that change"
                                                   : ""));
    EXPECT_EQ(next.changed_on_disk(), outside_change);
    if (outside_change) {
      EXPECT_EQ(next.save(), SceneDocument::SaveResult::kChangedOnDisk);
      EXPECT_EQ(read(file), on_disk) << "the other program's change is still there";
      // The restored edits, rewritten, still carry the identity they were made over.
      test::edit_scene(next, [&](Scene& s) { s.materials.at(0).ks = Color(0.25); });
      ASSERT_FALSE(next_keeper.write(next).empty());
      SceneDocument third;
      ASSERT_TRUE(third.open(file));
      const auto again = RecoveryKeeper((dir / "recovery").string()).find(third, false);
      ASSERT_TRUE(again);
      EXPECT_EQ(again->base, entry->base);
      // Saved over with consent, the file is the document's again.
      EXPECT_EQ(next.save(true), SceneDocument::SaveResult::kSaved);
      EXPECT_FALSE(next.changed_on_disk());
    } else {
      EXPECT_EQ(next.save(), SceneDocument::SaveResult::kSaved);
    }
    next_keeper.autosave(next, 100);  // clean now: the recovery goes
  }
}

// A recovery written by an older version has no identity: the file may have changed, so Save
// asks.
TEST_F(RecoveryFiles, AnUnknownIdentityCountsAsChanged) {
  fs::create_directories(dir / "scenes");
  const std::string file = (dir / "scenes" / "mine.json").string();
  ASSERT_TRUE(doc.save_as(file));
  SceneDocument reopened;
  ASSERT_TRUE(reopened.open(file));
  EXPECT_FALSE(reopened.changed_on_disk());
  EXPECT_TRUE(reopened.edits_made_over(""));
  EXPECT_TRUE(reopened.changed_on_disk());
  EXPECT_EQ(reopened.save(), SceneDocument::SaveResult::kChangedOnDisk);
  ASSERT_TRUE(reopened.reload(false));
  EXPECT_FALSE(reopened.changed_on_disk()) << "read again: the document is the file's";
}

}  // namespace
}  // namespace phonglab
