// The renderer's scheduling (src/session/render_schedule.h) over a real progressive renderer:
// at most one restart a frame, a snapshot only when the scene or its view changed, a drag's
// edit deferred until the previous image is in (for at most kMaxDeferral), the size and the
// settings sent when they change, "move your head"'s eye held while a slider is.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "io/scene/scene_io.h"
#include "session/render_schedule.h"

namespace phonglab {
namespace {

using namespace std::chrono_literals;

// `mirrors` on one thread: a pass takes milliseconds, so the frame after a restart finds its
// first image not yet in (the tests that rely on that skip, saying so, should it be).
struct ScheduleOnMirrors : ::testing::Test {
  Scene scene;
  ProgressiveRenderer renderer{settings()};
  RenderSchedule schedule{renderer};
  int snapshots = 0;  // snapshots sent
  std::uint64_t version = 0;  // the scene's version, as SceneDocument::version counts it

  static ProgressiveSettings settings() {
    ProgressiveSettings s;
    s.target_spp = 1;
    s.threads = 1;
    return s;
  }
  void SetUp() override {
    LoadResult loaded = load_scene_arg("mirrors");
    ASSERT_TRUE(loaded.ok()) << loaded.error_text();
    scene = *loaded.scene;
  }
  RenderSchedule::Sent send(bool edited, bool dragging, double now, int width = 640, int height = 360,
                            bool replaced = false) {
    const RenderSchedule::Sent sent = schedule.send_scene({edited, replaced, dragging, width, height, now, std::nullopt, std::nullopt}, scene, version);
    if (sent.scene) ++snapshots;
    return sent;
  }
  void wait_for_image() { ASSERT_TRUE(renderer.wait_idle(60s)); }
  // Until the first image of the last generation sent is in.
  void wait_published() {
    const auto until = std::chrono::steady_clock::now() + 60s;
    while (schedule.image_pending() && std::chrono::steady_clock::now() < until) std::this_thread::sleep_for(1ms);
    ASSERT_FALSE(schedule.image_pending());
  }
};

TEST_F(ScheduleOnMirrors, AnEditReachesTheRendererByTheScenesVersionAlone) {
  send(false, false, 0.0);
  wait_for_image();
  EXPECT_FALSE(send(false, false, 0.1).scene);  // nothing changed
  scene.materials[0].kd = Color(0.1, 0.5, 0.2);
  ++version;                                   // the session's edit: no caller reports it
  const RenderSchedule::Sent sent = send(false, false, 0.2);
  EXPECT_TRUE(sent.scene);
  ASSERT_NE(schedule.snapshot(), nullptr);
  EXPECT_EQ(schedule.snapshot()->scene().materials[0].kd, Color(0.1, 0.5, 0.2));
  EXPECT_FALSE(send(false, false, 0.3).scene);  // sent once
}

TEST_F(ScheduleOnMirrors, TheFirstFrameSendsASnapshotAndItsSize) {
  const RenderSchedule::Sent sent = send(false, false, 0.0);  // nothing sent yet: a snapshot all the same
  EXPECT_TRUE(sent.scene);
  EXPECT_TRUE(sent.restarted);
  EXPECT_GT(sent.generation, 0U);
  EXPECT_EQ(sent.generation, schedule.sent_generation());
  ASSERT_NE(schedule.snapshot(), nullptr);
  EXPECT_EQ(schedule.width(), 640);
  EXPECT_EQ(schedule.height(), 360);
  EXPECT_EQ(snapshots, 1);
}

TEST_F(ScheduleOnMirrors, AFrameWithoutEditsSendsNothing) {
  send(false, false, 0.0);
  wait_for_image();
  const RenderSchedule::Sent sent = send(false, false, 0.1);
  EXPECT_FALSE(sent.restarted);
  EXPECT_EQ(snapshots, 1);
}

TEST_F(ScheduleOnMirrors, AResizeRestartsWithTheSameSnapshot) {
  send(false, false, 0.0);
  const auto before = schedule.snapshot();
  const RenderSchedule::Sent sent = send(false, false, 0.1, 320, 180);
  EXPECT_TRUE(sent.restarted);
  EXPECT_FALSE(sent.scene);
  EXPECT_EQ(schedule.snapshot(), before);
  EXPECT_EQ(schedule.width(), 320);
  EXPECT_EQ(snapshots, 1);
}

TEST_F(ScheduleOnMirrors, AnEditSendsANewSnapshotOfTheSceneAsItIsNow) {
  send(false, false, 0.0);
  wait_for_image();
  scene.materials.at(0).kd = Color(0.125);
  const RenderSchedule::Sent sent = send(true, false, 0.5);
  EXPECT_TRUE(sent.scene);
  EXPECT_DOUBLE_EQ(sent.edit_time, 0.5);
  EXPECT_EQ(schedule.snapshot()->scene().materials.at(0).kd, Color(0.125));
}

TEST_F(ScheduleOnMirrors, ADragsEditWaitsForThePreviousImageThenGoesWithTheOldestEditsTime) {
  send(false, false, 0.0);
  wait_published();
  ASSERT_TRUE(send(true, true, 1.0).scene);  // the previous image is in: the edit goes at once
  if (!schedule.image_pending()) GTEST_SKIP() << "the renderer published before the next frame";
  const RenderSchedule::Sent held = send(true, true, 1.01);
  EXPECT_TRUE(held.deferred);
  EXPECT_FALSE(held.restarted);
  EXPECT_TRUE(send(true, true, 1.02).deferred);  // a later edit joins the one held
  const int before = snapshots;
  // The image comes: the next frame sends the held edits, dated by the oldest.
  wait_published();
  const RenderSchedule::Sent sent = send(false, true, 1.5);
  EXPECT_TRUE(sent.scene);
  EXPECT_FALSE(sent.deferred);
  EXPECT_DOUBLE_EQ(sent.edit_time, 1.01);
  EXPECT_EQ(snapshots, before + 1);
}

TEST_F(ScheduleOnMirrors, ADeferralEndsAfterMaxDeferralEvenWithoutAnImage) {
  send(false, false, 0.0);
  wait_published();
  ASSERT_TRUE(send(true, true, 0.0).restarted);
  if (!schedule.image_pending()) GTEST_SKIP() << "the renderer published before the next frame";
  EXPECT_TRUE(send(true, true, 0.01).deferred);
  // The same edit still waiting a second later goes out whether or not the image came.
  const RenderSchedule::Sent late = send(false, true, 0.01 + RenderSchedule::kMaxDeferral);
  EXPECT_FALSE(late.deferred);
  EXPECT_TRUE(late.scene);
}

TEST_F(ScheduleOnMirrors, AReplacedDocumentOrAResizeIsNeverDeferred) {
  send(false, false, 0.0);
  wait_published();
  send(true, true, 0.0);
  if (!schedule.image_pending()) GTEST_SKIP() << "the renderer published before the next frame";
  EXPECT_TRUE(send(true, true, 0.01, 640, 360, true).scene);
  if (!schedule.image_pending()) GTEST_SKIP() << "the renderer published before the next frame";
  EXPECT_TRUE(send(true, true, 0.02, 320, 180).restarted);
}

TEST_F(ScheduleOnMirrors, SettingsRestartOnlyWhenTheyChange) {
  send(false, false, 0.0);
  EXPECT_FALSE(schedule.wants_changed(false, 0));
  EXPECT_TRUE(schedule.wants_changed(true, 0));
  EXPECT_TRUE(schedule.wants_changed(false, 64));
  // More samples continue the image (no restart); the small multiples' term images restart it.
  ProgressiveSettings s = settings();
  s.target_spp = 2;
  EXPECT_EQ(schedule.send_settings(s, false), 0U);
  EXPECT_FALSE(schedule.wants_changed(false, 2));
  s.term_images = true;
  const std::uint64_t generation = schedule.send_settings(s, true);
  EXPECT_GT(generation, 0U);
  EXPECT_EQ(schedule.sent_generation(), generation);
  EXPECT_FALSE(schedule.wants_changed(true, 2));
  EXPECT_EQ(schedule.send_settings(s, true), 0U);  // the same again: no restart
}

TEST_F(ScheduleOnMirrors, TheEyeGoesWithTheSettingsAndWaitsWhileHeld) {
  send(false, false, 0.0);
  wait_for_image();
  EXPECT_EQ(schedule.send_settings(settings(), false), 0U);  // what the renderer has
  const Vec3 eye(1, 2, 3);
  EXPECT_TRUE(schedule.offer_eye(eye, false));
  EXPECT_FALSE(schedule.offer_eye(eye, false));  // the same eye: nothing to send
  EXPECT_GT(schedule.send_settings(settings(), false), 0U);  // the eye goes with them: a restart
  // Held with the last image not in: the next eye waits.
  if (!schedule.image_pending()) GTEST_SKIP() << "the renderer published before the next frame";
  EXPECT_FALSE(schedule.offer_eye(Vec3(0, 0, 9), true));
  EXPECT_EQ(schedule.eye(), std::optional<Vec3>(eye));
  EXPECT_TRUE(schedule.offer_eye(Vec3(0, 0, 9), false));
}

}  // namespace
}  // namespace phonglab
