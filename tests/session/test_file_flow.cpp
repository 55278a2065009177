// The file dialogs' decisions (src/session/file_flow.h): what waits for the unsaved-changes
// question, what a Save that meets another program's change asks, and what runs after each
// answer, over real files.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "io/scene/scene_io.h"
#include "session/document.h"
#include "session/file_flow.h"
#include "tests/support/document_edits.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;
using Action = FileFlow::Action;
using Kind = FileFlow::Action::Kind;
using Answer = FileFlow::Answer;
using Question = FileFlow::Question;

// The lecture scene written as a file in a folder of the test's own, opened as the document.
struct FlowOnAFile : ::testing::Test {
  test::TestFolder temp{"phonglab-file-flow"};
  const fs::path dir = temp.path();
  std::string path;
  SceneDocument doc;
  FileFlow flow{doc};

  void SetUp() override {
    path = (dir / "scene.json").string();
    SceneDocument writer;
    ASSERT_TRUE(writer.open("lecture"));
    ASSERT_TRUE(writer.save_as(path));
    ASSERT_TRUE(doc.open(path));
  }

  // The first material's kd as the document holds it, edited without a save.
  void edit_kd(double kd) {
    test::edit_scene(doc, [&](Scene& s) { s.materials.at(0).kd = Color(kd); });
  }
  // The first material's kd as the file on disk holds it.
  double kd_on_disk(const std::string& file) const {
    SceneDocument disk;
    EXPECT_TRUE(disk.open(file));
    return disk.scene().materials.at(0).kd.r;
  }
  // Another program writes the file with kd changed, a second later than before.
  void write_outside(double kd) const {
    SceneDocument other;
    ASSERT_TRUE(other.open(path));
    test::edit_scene(other, [&](Scene& s) { s.materials.at(0).kd = Color(kd); });
    const auto before = fs::last_write_time(path);
    std::ofstream(path) << scene_to_json(other.scene(), dir.string());
    fs::last_write_time(path, before + std::chrono::seconds(1));
  }
};

const Action kOpenLecture{Kind::kOpen, "lecture"};
const Action kQuit{Kind::kQuit, {}};

TEST_F(FlowOnAFile, WithNothingUnsavedAnActionRunsAtOnce) {
  const FileFlow::Outcome outcome = flow.request(kOpenLecture);
  EXPECT_EQ(outcome.run, kOpenLecture);
  EXPECT_FALSE(outcome.saved);
  EXPECT_EQ(flow.question(), Question::kNone);
}

TEST_F(FlowOnAFile, OpenWithUnsavedEditsAsksFirstAndCancelKeepsTheSceneAndItsEdits) {
  edit_kd(0.25);
  FileFlow::Outcome outcome = flow.request(kOpenLecture);
  EXPECT_EQ(outcome.run.kind, Kind::kNone) << "nothing runs before the answer";
  EXPECT_EQ(flow.question(), Question::kUnsavedChanges);
  EXPECT_EQ(flow.waiting(), kOpenLecture);
  outcome = flow.answer(Answer::kCancel, "");
  EXPECT_EQ(outcome.run.kind, Kind::kNone);
  EXPECT_EQ(flow.question(), Question::kNone);
  EXPECT_EQ(flow.waiting().kind, Kind::kNone);
  EXPECT_EQ(doc.file_path(), path);
  EXPECT_TRUE(doc.dirty());
  EXPECT_EQ(doc.scene().materials.at(0).kd, Color(0.25));
  EXPECT_NE(kd_on_disk(path), 0.25) << "Cancel wrote nothing";
}

TEST_F(FlowOnAFile, SaveWritesTheEditThenRunsWhatWaited) {
  edit_kd(0.25);
  flow.request(kOpenLecture);
  const FileFlow::Outcome outcome = flow.answer(Answer::kSave, "");
  ASSERT_TRUE(outcome.saved);
  EXPECT_TRUE(*outcome.saved);
  EXPECT_EQ(outcome.run, kOpenLecture);
  EXPECT_EQ(flow.question(), Question::kNone);
  EXPECT_EQ(kd_on_disk(path), 0.25);
  EXPECT_FALSE(doc.dirty());
}

TEST_F(FlowOnAFile, DiscardRunsWhatWaitedAndWritesNothing) {
  edit_kd(0.25);
  flow.request(kQuit);
  const FileFlow::Outcome outcome = flow.answer(Answer::kDiscard, "");
  EXPECT_FALSE(outcome.saved);
  EXPECT_EQ(outcome.run, kQuit);
  EXPECT_NE(kd_on_disk(path), 0.25);
}

TEST_F(FlowOnAFile, SaveAsWritesTheFileClearsTheUnsavedMarkAndMakesItTheDocument) {
  edit_kd(0.25);
  const std::string other = (dir / "saved.json").string();
  const FileFlow::Outcome outcome = flow.save(true, other);
  ASSERT_TRUE(outcome.saved);
  EXPECT_TRUE(*outcome.saved);
  EXPECT_EQ(outcome.run.kind, Kind::kNone) << "nothing waited behind it";
  EXPECT_EQ(doc.file_path(), other);
  EXPECT_FALSE(doc.dirty());
  EXPECT_EQ(kd_on_disk(other), 0.25);
}

TEST_F(FlowOnAFile, AFailedSaveSaysSoAndWhatWaitedDoesNotRun) {
  edit_kd(0.25);
  flow.request(kQuit);
  const FileFlow::Outcome outcome = flow.answer(Answer::kSaveAs, (dir / "no-such-folder" / "x.json").string());
  ASSERT_TRUE(outcome.saved);
  EXPECT_FALSE(*outcome.saved);
  EXPECT_FALSE(doc.error_text().empty());
  EXPECT_EQ(outcome.run.kind, Kind::kNone) << "a quit behind a failed save would lose the edits";
  EXPECT_EQ(flow.question(), Question::kNone);
  EXPECT_TRUE(doc.dirty());
}

TEST_F(FlowOnAFile, SaveOverAChangeMadeOnDiskAsksAndCancelWritesNothing) {
  edit_kd(0.25);
  write_outside(0.75);
  EXPECT_TRUE(flow.file_changed());
  const FileFlow::Outcome outcome = flow.save(false, "");
  EXPECT_FALSE(outcome.saved) << "nothing was tried yet: the question comes first";
  EXPECT_EQ(flow.question(), Question::kChangedOnDisk);
  EXPECT_EQ(flow.answer(Answer::kCancel, "").run.kind, Kind::kNone);
  EXPECT_EQ(kd_on_disk(path), 0.75) << "the other program's change stays";
  EXPECT_TRUE(doc.dirty()) << "and the edits stay";
  EXPECT_EQ(doc.scene().materials.at(0).kd, Color(0.25));
}

TEST_F(FlowOnAFile, TheGuardsSaveMeetsTheOutsideChangeAsksAgainAndOverwriteWritesThenQuits) {
  edit_kd(0.25);
  write_outside(0.75);
  flow.request(kQuit);
  ASSERT_EQ(flow.question(), Question::kUnsavedChanges);
  FileFlow::Outcome outcome = flow.answer(Answer::kSave, "");
  EXPECT_EQ(outcome.run.kind, Kind::kNone);
  EXPECT_EQ(flow.question(), Question::kChangedOnDisk);
  EXPECT_EQ(flow.waiting(), kQuit) << "the quit waits behind the save";
  EXPECT_EQ(kd_on_disk(path), 0.75);
  outcome = flow.answer(Answer::kOverwrite, "");
  ASSERT_TRUE(outcome.saved);
  EXPECT_TRUE(*outcome.saved);
  EXPECT_EQ(outcome.run, kQuit);
  EXPECT_EQ(kd_on_disk(path), 0.25) << "Overwrite wrote the previewer's version";
}

TEST_F(FlowOnAFile, ReloadTakesTheFilesVersionAndRunsWhatWaitedUnlessItWasTheReload) {
  for (const Action& waited : {kQuit, Action{Kind::kReload, {}}}) {
    edit_kd(0.25);
    write_outside(0.75);
    flow.request(waited);
    flow.answer(Answer::kSave, "");
    ASSERT_EQ(flow.question(), Question::kChangedOnDisk);
    const FileFlow::Outcome outcome = flow.answer(Answer::kReload, "");
    EXPECT_TRUE(outcome.reload);
    EXPECT_FALSE(outcome.saved);
    EXPECT_EQ(outcome.run.kind, waited.kind == Kind::kReload ? Kind::kNone : waited.kind);
    ASSERT_TRUE(doc.reload(false));  // what the client does with `reload`
  }
}

TEST_F(FlowOnAFile, ASaveWhileAQuestionIsOpenWaitsForTheAnswer) {
  edit_kd(0.25);
  flow.request(kQuit);
  const FileFlow::Outcome outcome = flow.save(false, "");  // Ctrl+S under the dialog
  EXPECT_FALSE(outcome.saved);
  EXPECT_EQ(outcome.run.kind, Kind::kNone) << "the quit still waits for its answer";
  EXPECT_EQ(flow.question(), Question::kUnsavedChanges);
  EXPECT_EQ(flow.waiting(), kQuit);
  EXPECT_NE(kd_on_disk(path), 0.25);
}

TEST_F(FlowOnAFile, AnAnswerThatIsNotTheQuestionsChangesNothing) {
  EXPECT_EQ(flow.answer(Answer::kDiscard, "").run.kind, Kind::kNone);
  edit_kd(0.25);
  flow.request(kQuit);
  EXPECT_EQ(flow.answer(Answer::kOverwrite, "").run.kind, Kind::kNone);
  EXPECT_EQ(flow.question(), Question::kUnsavedChanges);
  EXPECT_EQ(flow.waiting(), kQuit);
}

TEST_F(FlowOnAFile, AChangeOnDiskReloadsACleanDocumentAndIsOnlyFlaggedOverEdits) {
  EXPECT_EQ(flow.poll(true), FileFlow::OnDisk::kNothing);
  write_outside(0.75);
  EXPECT_EQ(flow.poll(false), FileFlow::OnDisk::kNothing) << "auto-reload off";
  EXPECT_EQ(flow.poll(true), FileFlow::OnDisk::kReload);
  edit_kd(0.25);
  EXPECT_EQ(flow.poll(true), FileFlow::OnDisk::kKeepEdits) << "edits are never thrown away silently";
}

TEST(FileFlow, AnEmbeddedSceneOrAnObjOpenedAloneCannotBeSavedOver) {
  SceneDocument doc;
  FileFlow flow(doc);
  ASSERT_TRUE(doc.open("lecture"));
  EXPECT_FALSE(flow.can_save());
  EXPECT_FALSE(flow.file_changed());
  ASSERT_TRUE(doc.open(PHONGLAB_SOURCE_DIR "/assets/scenes/cornell/CornellBox-Original.obj"));
  EXPECT_TRUE(doc.opened_mesh());
  EXPECT_FALSE(flow.can_save());
}

}  // namespace
}  // namespace phonglab
