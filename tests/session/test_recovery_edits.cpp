// Nothing lost, the recovery files' side: what a signal keeps (the shell's
// handler writes RecoveryKeeper::write on SIGTERM or SIGINT) holds the edits as a scene that loads
// (what phonglab-cli validate does), the next start on the scene finds it and restores the edits
// unsaved, a clean save then removes the recovery file, and autosave keeps an edit in the state
// folder ($XDG_STATE_HOME/phonglab/recovery) a few seconds after it. The exit codes and the
// "recovery: PATH" line stay in the GUI test (the process's own behaviour).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
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

struct RecoveryEdits : ::testing::Test {
  test::TestFolder temp{"phonglab-recovery-edits"};
  const fs::path dir = temp.path();
  std::string folder;  // the recovery folder
  void SetUp() override {
    folder = (dir / "state" / "phonglab" / "recovery").string();
  }
  static std::string read(const std::string& path) {
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    return text.str();
  }
  // `set material NAME kd R G B`, as the script and the Materials panel edit.
  static void set_kd(Session& session, const std::string& name, const Color& kd) {
    const int m = ui::find_material(session.scene(), name);
    ASSERT_GE(m, 0) << name;
    Material edited = session.scene().materials[static_cast<std::size_t>(m)];
    edited.kd = kd;
    ASSERT_TRUE(session.apply({edit::SetMaterial{m, edited}}).unsaved);
  }
  // The edits of the GUI test's SIGTERM run, kept as the signal handler keeps them; the file.
  std::string kept_after_term(Session& session) {
    EXPECT_TRUE(session.open("lecture"));
    set_kd(session, "plastic", Color(0.1, 0.9, 0.1));
    return session.recovery().write(session.document());
  }
};

TEST_F(RecoveryEdits, WhatASignalKeepsHoldsTheEditsAsAValidScene) {
  {
    Session session(folder);  // kill -TERM
    const std::string path = kept_after_term(session);
    EXPECT_EQ(path, folder + "/embedded-lecture.json");
    EXPECT_NE(read(path).find("\"kd\": [0.1, 0.9, 0.1]"), std::string::npos) << read(path);
    LoadResult valid = load_scene_arg(path);  // phonglab-cli validate
    ASSERT_TRUE(valid.ok()) << valid.error_text();
    EXPECT_EQ(scene_content(*valid.scene), scene_content(session.scene()));
  }
  {
    Session session(folder);  // kill -INT, after a material and a light were edited
    ASSERT_TRUE(session.open("lecture"));
    set_kd(session, "shiny", Color(0.9, 0.6, 0.1));
    Light light = session.scene().lights.at(0);
    light.intensity = Color(0.5, 0.9, 0.9);
    ASSERT_TRUE(session.apply({edit::SetLight{0, light}}).unsaved);
    const std::string path = session.recovery().write(session.document());
    ASSERT_FALSE(path.empty()) << session.recovery().error();
    EXPECT_NE(read(path).find("\"kd\": [0.9, 0.6, 0.1]"), std::string::npos) << read(path);
    LoadResult valid = load_scene_arg(path);
    ASSERT_TRUE(valid.ok()) << valid.error_text();
    EXPECT_EQ(valid.scene->lights.at(0).intensity, Color(0.5, 0.9, 0.9));
  }
}

TEST_F(RecoveryEdits, TheNextStartOnTheSceneOffersTheEditsAndRestoresThemUnsaved) {
  Session killed(folder);
  const std::string kept = kept_after_term(killed);
  ASSERT_FALSE(kept.empty());

  Session next(folder);  // `phonglab lecture` again
  ASSERT_TRUE(next.open("lecture"));
  const auto offer = next.recovery().find(next.document(), false);
  ASSERT_TRUE(offer);
  EXPECT_EQ(offer->source, "lecture");
  EXPECT_TRUE(offer->embedded);
  EXPECT_FALSE(next.dirty()) << "offered, not yet restored";
  const RecoveryKeeper::Restored restored = next.recovery().restore(next.document(), *offer);
  ASSERT_TRUE(restored.error.empty()) << restored.error;
  EXPECT_FALSE(restored.changed_on_disk) << "an embedded scene has no file to change";
  EXPECT_TRUE(next.dirty()) << "restored edits are unsaved";
  EXPECT_EQ(scene_content(next.scene()), scene_content(killed.scene()));
  EXPECT_EQ(next.recovery().written(), kept) << "the kept file is this document's now";
}

TEST_F(RecoveryEdits, ACleanSaveOfRestoredEditsRemovesTheRecoveryFile) {
  Session killed(folder);
  const std::string kept = kept_after_term(killed);
  ASSERT_FALSE(kept.empty());
  Session next(folder);
  ASSERT_TRUE(next.open("lecture"));
  const auto offer = next.recovery().find(next.document(), false);
  ASSERT_TRUE(offer);
  ASSERT_TRUE(next.recovery().restore(next.document(), *offer).error.empty());
  ASSERT_TRUE(next.document().save_as((dir / "saved.json").string()));
  EXPECT_FALSE(next.dirty());
  next.recovery().autosave(next.document(), 1000);  // the next UI frame
  EXPECT_FALSE(fs::exists(kept));
  EXPECT_FALSE(fs::exists(fs::path(kept).replace_extension(".source")));
  EXPECT_TRUE(next.recovery().written().empty());
  EXPECT_FALSE(next.recovery().find(next.document(), true)) << "nothing is offered at the next start";
}

// The previewer's session keeps its files in the state folder; an edit is there once it is
// kAutosaveDelay old, whatever becomes of the process after (SIGKILL: the GUI test).
TEST_F(RecoveryEdits, AutosaveKeepsAnEditInTheStateFolderAFewSecondsAfterIt) {
  const char* old = std::getenv("XDG_STATE_HOME");
  const std::string saved_env = old != nullptr ? old : "";
  setenv("XDG_STATE_HOME", (dir / "state").c_str(), 1);
  Session session;  // the default folder, as the previewer's
  if (old != nullptr) setenv("XDG_STATE_HOME", saved_env.c_str(), 1);
  else unsetenv("XDG_STATE_HOME");
  EXPECT_EQ(session.recovery().folder(), folder);
  ASSERT_TRUE(session.open("lecture"));
  set_kd(session, "matte", Color(0.9, 0.1, 0.9));
  session.recovery().edited(10);
  session.recovery().autosave(session.document(), 10 + RecoveryKeeper::kAutosaveDelay / 2);
  EXPECT_FALSE(fs::exists(folder + "/embedded-lecture.json")) << "not while the edits may go on";
  session.recovery().autosave(session.document(), 10 + RecoveryKeeper::kAutosaveDelay);
  const std::string path = folder + "/embedded-lecture.json";
  ASSERT_EQ(session.recovery().written(), path) << session.recovery().error();
  EXPECT_NE(read(path).find("\"kd\": [0.9, 0.1, 0.9]"), std::string::npos) << read(path);
}

}  // namespace
}  // namespace phonglab
