// The teaching instruments' rules on the lecture, as the previewer's scripts and keys reach them
// (tests/gui's instruments and lecture sessions): solo is one scene edit each way, the moved head
// is an eye turned about the probed point and never a camera edit, and A asked for while the image
// converges says that it waits for the finished image.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "core/scene/camera.h"
#include "interaction/history.h"
#include "session/session.h"
#include "session/snapshot_a.h"

namespace phonglab {
namespace {

// The lights' enabled flags as dump_state's lights_enabled writes them: "10" is L0 on, L1 off.
std::string lights_enabled(const Scene& scene) {
  std::string flags;
  for (const Light& light : scene.lights) flags += light.enabled ? '1' : '0';
  return flags;
}

struct InstrumentsOnTheLecture : ::testing::Test {
  Session session{""};  // no recovery files
  void SetUp() override { ASSERT_TRUE(session.open("lecture")); }
  // `solo I` of the scripts and Shift+1..9 (Viewer::shortcut): toggle_solo on a copy of the
  // scene, handed to the session as one scene edit.
  void solo(ui::LightSolo& state, int light) {
    Scene soloed = session.scene();
    ui::toggle_solo(soloed.lights, state, light);
    session.apply({edit::SetScene{std::move(soloed)}});
  }
};

TEST_F(InstrumentsOnTheLecture, SoloLeavesOneLightOnAndAgainRestoresEachAnUndoStep) {
  ASSERT_EQ(lights_enabled(session.scene()), "11");  // the point light and the directional one
  ui::LightSolo state;
  solo(state, 0);
  EXPECT_EQ(lights_enabled(session.scene()), "10");
  EXPECT_EQ(session.undo_count(), 1U);
  solo(state, 0);
  EXPECT_EQ(lights_enabled(session.scene()), "11");
  EXPECT_EQ(session.undo_count(), 2U);
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(lights_enabled(session.scene()), "10") << "Ctrl+Z takes back the restore alone";
}

// "Move your head" (Instruments::head_eye): the eye that shades V turns about the camera's up
// through the probed point; the camera, what the view rays and the file hold, stays.
TEST_F(InstrumentsOnTheLecture, TheMovedHeadIsAnEyeTurnedAboutTheProbedPointNotACameraEdit) {
  const Camera camera = session.scene().camera;
  const Vec3 pivot(-0.75, 0.7, 0.7);  // the front of the plastic sphere, where a probe hits it
  EXPECT_NEAR(glm::length(head_eye(camera, pivot, 0) - camera.position), 0, 1e-12);
  const Vec3 eye = head_eye(camera, pivot, 40);
  EXPECT_GT(glm::length(eye - camera.position), 1.0);
  EXPECT_NEAR(glm::length(eye - pivot), glm::length(camera.position - pivot), 1e-12);
  // A turn of 40 degrees about the camera's up: the height along it kept, the angle seen from above 40.
  const Vec3 up = glm::normalize(make_camera_frame(camera, 1, 1).up);
  const Vec3 before = camera.position - pivot, after = eye - pivot;
  EXPECT_NEAR(glm::dot(after, up), glm::dot(before, up), 1e-12);
  const Vec3 flat_before = before - glm::dot(before, up) * up, flat_after = after - glm::dot(after, up) * up;
  const double cosine = glm::dot(flat_before, flat_after) / (glm::length(flat_before) * glm::length(flat_after));
  EXPECT_NEAR(glm::degrees(std::acos(cosine)), 40.0, 1e-9);
  EXPECT_EQ(session.scene().camera, camera);
  EXPECT_FALSE(session.dirty());
  EXPECT_EQ(session.undo_count(), 0U);
}

ProgressiveFrame frame(std::uint64_t generation, std::uint32_t spp) {
  ProgressiveFrame f;
  f.generation = generation;
  f.divisor = 1;
  f.spp = spp;
  f.width = 8;
  f.height = 4;
  f.pixels.assign(32, glm::vec3(0.5f));
  return f;
}

// Snapshot A asked for while the image converges (the lecture's `snapshot_a` at 3 of 8 spp): the
// compare view's caption says it waits, and the finished image it takes is compared at its samples.
TEST(SnapshotA, AskedForMidRenderItSaysItWaitsForTheFinishedImage) {
  SnapshotA a;
  a.request(5, false);
  const ProgressiveFrame converging = frame(5, 3);
  EXPECT_FALSE(a.take_when_ready(5, converging, false));
  EXPECT_EQ(a.caption(converging, CompareView::kDifference, true, 8, 4), "A is taken when the image is done (3 of 8 spp)");
  EXPECT_EQ(a.caption(converging, CompareView::kWipe, true, 8, 4).rfind("A is taken when the image is done", 0), 0U);
  const ProgressiveFrame done = frame(5, 8);
  ASSERT_TRUE(a.take_when_ready(5, done, true));
  EXPECT_EQ(a.image().spp, 8U);
  EXPECT_TRUE(a.comparable(done, CompareView::kDifference, true));
  EXPECT_EQ(a.caption(done, CompareView::kDifference, true, 8, 4), "|live - A| \xC3\x97 4 (8 spp each)");
}

}  // namespace
}  // namespace phonglab
