// The session's rules of editing (src/session/session.h): edits as values, what each kind
// invalidates, the unsaved state, undo and redo one gesture at a time, documents replaced.
#include <gtest/gtest.h>

#include <string>

#include "session/session.h"

namespace phonglab {
namespace {

// A session on the embedded `lecture` scene, and the material and light its tests edit.
struct SessionOnLecture : ::testing::Test {
  Session session;
  int m = 0;
  void SetUp() override {
    ASSERT_TRUE(session.open("lecture"));
    m = session.scene().spheres.at(0).material;
  }
  Material material() const { return session.scene().materials.at(static_cast<std::size_t>(m)); }
  Light light() const { return session.scene().lights.at(0); }
  Applied set_kd(double kd, bool held = false) {
    Material changed = material();
    changed.kd = Color(kd, kd, kd);
    return session.apply({edit::SetMaterial{m, changed}, held});
  }
};

TEST_F(SessionOnLecture, OpensCleanWithNoHistory) {
  EXPECT_FALSE(session.dirty());
  EXPECT_EQ(session.undo_count(), 0U);
  EXPECT_EQ(session.redo_count(), 0U);
  EXPECT_FALSE(session.edit_pending());
}

TEST_F(SessionOnLecture, AKdEditChangesTheMaterialAndIsUnsaved) {
  const Applied a = set_kd(0.25);
  EXPECT_TRUE(a.changed);
  EXPECT_TRUE(a.unsaved);
  EXPECT_EQ(material().kd, Color(0.25));
  EXPECT_TRUE(session.dirty());
}

TEST_F(SessionOnLecture, EveryChangeOfTheSceneMovesItsVersion) {
  // What the renderer's schedule compares (RenderSchedule::send_scene): no change may go unseen.
  std::uint64_t last = session.document().version();
  const auto moved = [&] {
    const std::uint64_t now = session.document().version();
    const bool changed = now != last;
    last = now;
    return changed;
  };
  set_kd(0.25);
  EXPECT_TRUE(moved()) << "an edit";
  Camera camera = session.scene().camera;
  camera.position.x += 1;
  session.apply({edit::SetCamera{camera}});
  EXPECT_TRUE(moved()) << "navigation";
  ASSERT_TRUE(session.undo());
  EXPECT_TRUE(moved()) << "undo";
  ASSERT_TRUE(session.redo());
  EXPECT_TRUE(moved()) << "redo";
  session.adopt(session.scene(), "a lesson's step");
  EXPECT_TRUE(moved()) << "a step adopted";
  ASSERT_TRUE(session.open("mirrors"));
  EXPECT_TRUE(moved()) << "another scene";
  EXPECT_FALSE(session.open("no such scene"));
  EXPECT_FALSE(moved()) << "a failed open keeps the scene";
}

TEST_F(SessionOnLecture, AKdEditInvalidatesShadingOnly) { EXPECT_EQ(set_kd(0.25).scope, EditScope::kShading); }

TEST_F(SessionOnLecture, AKsOrShininessEditInvalidatesShadingOnly) {
  Material changed = material();
  changed.n = material().n + 7;
  EXPECT_EQ(session.apply({edit::SetMaterial{m, changed}}).scope, EditScope::kShading);
  changed.ks = Color(0.1, 0.2, 0.3);
  EXPECT_EQ(session.apply({edit::SetMaterial{m, changed}}).scope, EditScope::kShading);
}

TEST_F(SessionOnLecture, AMirrorWeightEditInvalidatesTheBounces) {
  Material changed = material();
  changed.kr = Color(0.5);
  EXPECT_EQ(session.apply({edit::SetMaterial{m, changed}}).scope, EditScope::kBounces);
}

TEST_F(SessionOnLecture, MovingALightInvalidatesItsShadowRays) {
  Light moved = light();
  moved.position += Vec3(0.5, 0, 0);
  moved.direction = glm::normalize(moved.direction + Vec3(0.1, 0, 0));
  EXPECT_EQ(session.apply({edit::SetLight{0, moved}}).scope, EditScope::kLights);
}

TEST_F(SessionOnLecture, ALightsIntensityOrMuteInvalidatesShadingOnly) {
  Light changed = light();
  changed.intensity *= 0.5;
  EXPECT_EQ(session.apply({edit::SetLight{0, changed}}).scope, EditScope::kShading);
  changed.enabled = !changed.enabled;
  EXPECT_EQ(session.apply({edit::SetLight{0, changed}}).scope, EditScope::kShading);
}

TEST_F(SessionOnLecture, TheCameraIsNavigation) {
  Camera camera = session.scene().camera;
  camera.position += Vec3(0, 1, 0);
  const Applied a = session.apply({edit::SetCamera{camera}});
  EXPECT_TRUE(a.changed);
  EXPECT_FALSE(a.unsaved);
  EXPECT_EQ(a.scope, EditScope::kRetrace);
  EXPECT_FALSE(session.dirty());
  EXPECT_EQ(session.undo_count(), 0U) << "navigation is no undo step";
  EXPECT_EQ(session.scene().camera, camera);
}

TEST_F(SessionOnLecture, AddingASphereRetraces) {
  Scene more = session.scene();
  more.spheres.push_back(Sphere{Vec3(0, 5, 0), 0.5, m});
  more.sphere_object.push_back(static_cast<int>(more.sphere_object.size() + more.plane_object.size()));
  const Applied a = session.apply({edit::SetScene{more}});
  EXPECT_EQ(a.scope, EditScope::kRetrace);
  EXPECT_TRUE(a.unsaved);
  EXPECT_EQ(session.scene().spheres.size(), more.spheres.size());
}

TEST_F(SessionOnLecture, ARenameIsUnsavedButChangesNoPixel) {
  Material renamed = material();
  renamed.name += "-renamed";
  const Applied a = session.apply({edit::SetMaterial{m, renamed}});
  EXPECT_TRUE(a.changed);
  EXPECT_TRUE(a.unsaved);
  EXPECT_EQ(a.scope, EditScope::kNothing);
  EXPECT_TRUE(session.dirty());
}

TEST_F(SessionOnLecture, TheSameValueChangesNothing) {
  const Applied a = session.apply({edit::SetMaterial{m, material()}});
  EXPECT_FALSE(a.changed);
  EXPECT_EQ(a.scope, EditScope::kNothing);
  EXPECT_FALSE(session.dirty());
  EXPECT_EQ(session.undo_count(), 0U);
}

TEST_F(SessionOnLecture, AnIndexOutOfRangeChangesNothing) {
  const Scene before = session.scene();
  EXPECT_FALSE(session.apply({edit::SetMaterial{-1, material()}}).changed);
  EXPECT_FALSE(session.apply({edit::SetMaterial{static_cast<int>(before.materials.size()), material()}}).changed);
  EXPECT_FALSE(session.apply({edit::SetLight{static_cast<int>(before.lights.size()), light()}}).changed);
  EXPECT_EQ(scene_content(session.scene()), scene_content(before));
  EXPECT_EQ(session.undo_count(), 0U);
}

TEST_F(SessionOnLecture, AnEditLetGoIsItsOwnUndoStep) {
  set_kd(0.1);
  set_kd(0.2);
  EXPECT_EQ(session.undo_count(), 2U);
  EXPECT_FALSE(session.edit_pending());
}

TEST_F(SessionOnLecture, AHeldGestureIsOneUndoStepWhenItEnds) {
  for (double kd : {0.1, 0.2, 0.3, 0.4}) set_kd(kd, true);
  EXPECT_TRUE(session.edit_pending());
  EXPECT_EQ(session.undo_count(), 0U);
  session.settle(false);
  EXPECT_EQ(session.undo_count(), 1U);
  EXPECT_FALSE(session.edit_pending());
}

TEST_F(SessionOnLecture, NavigationDuringAGestureLeavesItPending) {
  set_kd(0.1, true);
  Camera camera = session.scene().camera;
  camera.position += Vec3(0, 0.5, 0);
  session.apply({edit::SetCamera{camera}});
  EXPECT_TRUE(session.edit_pending()) << "the wheel turned while a slider is held: still one gesture";
  EXPECT_EQ(session.undo_count(), 0U);
}

TEST_F(SessionOnLecture, SettlingWhileTheGestureHoldsKeepsItPending) {
  set_kd(0.1, true);
  session.settle(true);
  EXPECT_TRUE(session.edit_pending());
  EXPECT_EQ(session.undo_count(), 0U);
}

TEST_F(SessionOnLecture, UndoRestoresTheSceneBeforeTheGesture) {
  const Color before = material().kd;
  for (double kd : {0.1, 0.2, 0.3}) set_kd(kd, true);
  session.settle(false);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(material().kd, before);
  EXPECT_EQ(session.redo_count(), 1U);
}

TEST_F(SessionOnLecture, UndoOfEveryEditMakesTheDocumentClean) {
  set_kd(0.1);
  set_kd(0.2);
  EXPECT_TRUE(session.dirty());
  ASSERT_TRUE(session.undo());
  EXPECT_TRUE(session.dirty());
  ASSERT_TRUE(session.undo());
  EXPECT_FALSE(session.dirty());
  EXPECT_FALSE(session.undo()) << "nothing further";
}

TEST_F(SessionOnLecture, UndoAndRedoKeepTheCamera) {
  set_kd(0.1);
  Camera camera = session.scene().camera;
  camera.position += Vec3(1, 0, 0);
  session.apply({edit::SetCamera{camera}});
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(session.scene().camera, camera);
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(session.scene().camera, camera);
}

TEST_F(SessionOnLecture, RedoReappliesTheUndoneStep) {
  set_kd(0.3);
  ASSERT_TRUE(session.undo());
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(material().kd, Color(0.3));
  EXPECT_TRUE(session.dirty());
  EXPECT_FALSE(session.redo());
}

TEST_F(SessionOnLecture, UndoDuringAGestureUndoesTheGestureSoFar) {
  const Color before = material().kd;
  set_kd(0.1, true);
  set_kd(0.2, true);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(material().kd, before);
  EXPECT_FALSE(session.edit_pending());
  ASSERT_TRUE(session.redo());
  EXPECT_EQ(material().kd, Color(0.2));
}

TEST_F(SessionOnLecture, AnEditAfterUndoDropsTheRedo) {
  set_kd(0.1);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(session.redo_count(), 1U);
  set_kd(0.2);
  EXPECT_EQ(session.redo_count(), 0U);
}

TEST_F(SessionOnLecture, TheHistoryIsBounded) {
  for (std::size_t k = 0; k < ui::SceneHistory::kMaxStates + 5; ++k) set_kd(0.001 * static_cast<double>(k + 1));
  EXPECT_EQ(session.undo_count(), ui::SceneHistory::kMaxStates);
}

// A panel that edits the whole scene (the shading settings) hands the session a copy: the same
// rules as any edit (the document has no other writer).
TEST_F(SessionOnLecture, AWholeSceneEditFollowsTheSameRules) {
  Scene edited = session.scene();
  edited.ambient = Color(0.3);
  session.apply({edit::SetScene{edited}, true});  // held: pending until the gesture ends
  EXPECT_TRUE(session.dirty());
  EXPECT_TRUE(session.edit_pending());
  session.settle(false);
  EXPECT_EQ(session.undo_count(), 1U);
  ASSERT_TRUE(session.undo());
  EXPECT_FALSE(session.dirty());
}

TEST_F(SessionOnLecture, OpeningAnotherSceneStartsTheHistoryAnew) {
  set_kd(0.1);
  set_kd(0.2, true);
  ASSERT_TRUE(session.open("lecture"));
  EXPECT_EQ(session.undo_count(), 0U);
  EXPECT_FALSE(session.edit_pending());
  EXPECT_FALSE(session.dirty());
}

TEST_F(SessionOnLecture, AFailedOpenKeepsTheSceneAndItsHistory) {
  set_kd(0.1);
  const std::string before = scene_content(session.scene());
  EXPECT_FALSE(session.open("/nonexistent/scene.json"));
  EXPECT_FALSE(session.document().error_text().empty());
  EXPECT_EQ(scene_content(session.scene()), before);
  EXPECT_EQ(session.undo_count(), 1U);
  EXPECT_TRUE(session.dirty());
}

TEST_F(SessionOnLecture, AnAdoptedSceneHasNoFileAndNoHistory) {
  set_kd(0.1);
  Scene step = session.scene();
  session.adopt(step, "a lesson's step");
  EXPECT_EQ(session.undo_count(), 0U);
  EXPECT_FALSE(session.dirty());
  EXPECT_TRUE(session.document().file_path().empty());
  EXPECT_EQ(session.document().save(), SceneDocument::SaveResult::kFailed) << "Save asks where";
}

TEST_F(SessionOnLecture, ResetHistoryForgetsAPendingGesture) {
  set_kd(0.1, true);
  session.reset_history();
  EXPECT_FALSE(session.edit_pending());
  session.settle(false);
  EXPECT_EQ(session.undo_count(), 0U);
}

}  // namespace
}  // namespace phonglab
