// The viewport's camera control: the orbit follows the hand and stops short of the poles, the
// dolly has a far limit, and a narrow view widens the field of view so the framed scene stays.
#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "core/scene/camera.h"
#include "core/teaching/ray_tree_view.h"
#include "interaction/camera_control.h"
#include "interaction/numbers.h"
#include "interaction/scene_objects.h"
#include "io/embedded_scenes.h"
#include "io/scene/scene_io.h"
#include "tests/support/test_support.h"

namespace phonglab {
namespace {

Camera lecture_camera() {
  Camera c;
  c.position = Vec3(0, 1.5, 6);
  c.look_at = Vec3(0, 0.8, 0);
  c.up = Vec3(0, 1, 0);
  c.fov_y_deg = 40;
  return c;
}

// Angle between the eye's offset from look_at and up, radians.
double polar_angle(const Camera& c) {
  const Vec3 offset = glm::normalize(c.position - c.look_at);
  return std::acos(glm::dot(offset, glm::normalize(c.up)));
}

TEST(CameraControl, OrbitWithPositivePitchLooksFromHigherUp) {
  Camera c = lecture_camera();
  ui::orbit(c, 0, 0.16);  // a 20-pixel drag down
  EXPECT_GT(c.position.y, 1.5);
  Camera d = lecture_camera();
  ui::orbit(d, 0, -0.16);  // a 20-pixel drag up
  EXPECT_LT(d.position.y, 1.5);
  // The distance to look_at is kept.
  EXPECT_NEAR(glm::length(c.position - c.look_at), glm::length(lecture_camera().position - c.look_at), 1e-12);
}

TEST(CameraControl, OrbitWithNegativeYawTurnsTheSceneRight) {
  // The drag right passes -dx as yaw: the eye moves left, so the scene's front turns right.
  Camera c = lecture_camera();
  ui::orbit(c, -0.1, 0);
  EXPECT_LT(c.position.x, 0);
  EXPECT_NEAR(c.position.y, 1.5, 1e-12);
}

TEST(CameraControl, OrbitStopsShortOfBothPolesAndNeverFlips) {
  for (const double step : {0.1, -0.1}) {
    Camera c = lecture_camera();
    for (int i = 0; i < 100; ++i) {  // 10 radians: far past the pole
      ui::orbit(c, 0, step);
      ASSERT_TRUE(ui::camera_is_valid(c));
      const double polar = polar_angle(c);
      ASSERT_GT(polar, 0.005);
      ASSERT_LT(polar, glm::pi<double>() - 0.005);
      // The image's up stays on the side of the camera's up: the view is never upside down.
      const CameraFrame frame = make_camera_frame(c, 16, 9);
      ASSERT_GT(glm::dot(frame.up, c.up), 0);
    }
    // Looking straight down (or up) at the end, not back past the pole.
    if (step > 0) EXPECT_GT(c.position.y, 6.0);
    else EXPECT_LT(c.position.y, -4.0);
  }
}

TEST(CameraControl, DollyStopsAtItsFarLimit) {
  Camera c = lecture_camera();
  for (int i = 0; i < 500; ++i) ui::dolly(c, 1 / 0.85, 100);
  EXPECT_NEAR(glm::length(c.position - c.look_at), 100, 1e-9);
  ui::dolly(c, 0.5, 100);
  EXPECT_NEAR(glm::length(c.position - c.look_at), 50, 1e-9);
}

// F frames tight: every sphere's silhouette inside the image, and together they span nearly all
// of its width or its height, from any direction and at any aspect.
TEST(CameraControl, FrameSceneFitsTheObjectsTightly) {
  const LoadResult loaded = load_scene_arg("lecture");
  ASSERT_TRUE(loaded.ok());
  for (const double aspect : {16.0 / 9, 1.0, 0.5}) {
    for (const double yaw : {0.0, 0.7, 2.0}) {
      Scene scene = *loaded.scene;
      ui::orbit(scene.camera, yaw, 0.2);
      ASSERT_TRUE(ui::frame_scene(scene.camera, scene, aspect));
      const int h = 900, w = static_cast<int>(std::lround(h * aspect));
      const CameraFrame frame = make_camera_frame(scene.camera, w, h);
      const Vec3 right = glm::normalize(frame.right), up = glm::normalize(frame.up);
      double x0 = w, x1 = 0, y0 = h, y1 = 0;
      for (const Sphere& s : scene.spheres) {
        // The silhouette's extremes seen from the eye: tangent points in the view's axes.
        const Vec3 to = s.center - frame.origin;
        const double dist = glm::length(to);
        const double tan_r = s.radius / std::sqrt(dist * dist - s.radius * s.radius);
        for (const Vec3& axis : {right, up}) {
          for (const double side : {-1.0, 1.0}) {
            const Vec3 dir = glm::normalize(glm::normalize(to) + side * tan_r * glm::normalize(axis - glm::dot(axis, glm::normalize(to)) * glm::normalize(to)));
            const auto p = project_point(frame, frame.origin + dir);
            ASSERT_TRUE(p);
            x0 = std::min(x0, p->x), x1 = std::max(x1, p->x), y0 = std::min(y0, p->y), y1 = std::max(y1, p->y);
          }
        }
      }
      SCOPED_TRACE("aspect " + std::to_string(aspect) + ", yaw " + std::to_string(yaw));
      EXPECT_GE(x0, 0);
      EXPECT_LE(x1, w);
      EXPECT_GE(y0, 0);
      EXPECT_LE(y1, h);
      EXPECT_GT(std::max((x1 - x0) / w, (y1 - y0) / h), 0.85);
    }
  }
}

TEST(CameraControl, FitToViewKeepsTheFramedWidthInANarrowView) {
  const Camera c = lecture_camera();
  const double framed = 960.0 / 540.0;
  const double view = 880.0 / 720.0;
  const Camera fitted = ui::fit_to_view(c, framed, view);
  // tan(fov/2) * aspect is the horizontal half-extent: the same as the framed image's.
  EXPECT_NEAR(std::tan(glm::radians(fitted.fov_y_deg) / 2) * view, std::tan(glm::radians(c.fov_y_deg) / 2) * framed,
              1e-12);
  EXPECT_GT(fitted.fov_y_deg, c.fov_y_deg);
  EXPECT_EQ(fitted.position, c.position);
}

TEST(CameraControl, FitToViewLeavesWideViewsAlone) {
  const Camera c = lecture_camera();
  EXPECT_EQ(ui::fit_to_view(c, 16.0 / 9.0, 16.0 / 9.0).fov_y_deg, c.fov_y_deg);
  EXPECT_EQ(ui::fit_to_view(c, 16.0 / 9.0, 3.0).fov_y_deg, c.fov_y_deg);
  // A sliver of a window still gives a valid camera.
  EXPECT_TRUE(ui::camera_is_valid(ui::fit_to_view(c, 16.0 / 9.0, 1e-4)));
}

TEST(PanelNumbers, AFloatWidgetsValueIsItsShortestDecimal) {
  // 0.366 through a float slider is 0.3659999966621399 as a double: the file would say so.
  const double through_float = static_cast<double>(0.366f);
  EXPECT_NE(through_float, 0.366);
  EXPECT_EQ(ui::tidy_float(through_float), 0.366);
  EXPECT_EQ(ui::tidy_float(1.0), 1.0);
  EXPECT_EQ(ui::tidy_float(0.0), 0.0);
  EXPECT_EQ(ui::tidy_float(static_cast<double>(1e-7f)), 1e-7);
}

TEST(PanelNumbers, ASliderKeepsTheValueItsTextShows) {
  EXPECT_EQ(ui::shown_value(0.36612345, "%.3f"), 0.366);
  EXPECT_EQ(ui::shown_value(39.96, "%.1f"), 40.0);
  EXPECT_EQ(ui::shown_value(0.00123456, "%.4g"), 0.001235);
  EXPECT_EQ(ui::shown_value(-2.5, "x%.1f"), -2.5);  // text before the number
  EXPECT_EQ(ui::shown_value(7.25, "none"), 7.25);  // no number to read back: unchanged
}

}  // namespace
}  // namespace phonglab

// The probe panel's numbers: "≈ 0" for a value under 1e-12 that is not zero, %g otherwise.
TEST(ProbeNumbers, TinyValuesReadAsAboutZero) {
  EXPECT_EQ(phonglab::ui::probe_number(9.039e-22, 4), "\xE2\x89\x88 0");
  EXPECT_EQ(phonglab::ui::probe_number(-3e-13, 4), "\xE2\x89\x88 0");
  EXPECT_EQ(phonglab::ui::probe_number(0.0, 4), "0");
  EXPECT_EQ(phonglab::ui::probe_number(1e-12, 4), "1e-12");
  EXPECT_EQ(phonglab::ui::probe_number(-0.18571234, 4), "-0.1857");
}

// The equation box's text wraps at spaces only: a number is never split at its point, every
// line fits (but a word wider than a line), and nothing but the breaks and indents is added.
TEST(ProbeNumbers, WrapsAtSpacesOnly) {
  const auto measure = [](std::string_view s) { return static_cast<float>(s.size()); };  // one unit a character
  const std::string text = "N.L = -0.1857 and R.V = 0.5 so max(0,R.V)^n = 0.03125\nnext line  kept";
  const std::string wrapped = phonglab::ui::wrap_at_spaces(text, 16, measure);
  std::string joined;
  std::size_t start = 0;
  while (start <= wrapped.size()) {
    const std::size_t end = std::min(wrapped.find('\n', start), wrapped.size());
    const std::string line = wrapped.substr(start, end - start);
    EXPECT_TRUE(line.size() <= 16 || line.find(' ', 2) == std::string::npos) << "'" << line << "'";
    EXPECT_EQ(line.find("-0.\n"), std::string::npos);
    start = end + 1;
  }
  EXPECT_NE(wrapped.find("-0.1857"), std::string::npos);
  EXPECT_NE(wrapped.find("max(0,R.V)^n"), std::string::npos);
  EXPECT_NE(wrapped.find("\nnext line  kept"), std::string::npos) << "the text's own break and spaces stay";
  std::string squeezed;
  for (const char c : wrapped) if (c != '\n' && c != ' ') squeezed += c;
  std::string expected;
  for (const char c : text) if (c != '\n' && c != ' ') expected += c;
  EXPECT_EQ(squeezed, expected);
  EXPECT_EQ(phonglab::ui::wrap_at_spaces("short", 16, measure), "short");
  EXPECT_EQ(phonglab::ui::wrap_at_spaces("", 16, measure), "");
}

// The hand's orbit never takes the eye under the scene's floor (a student's 30-pixel drag up took
// it there): the pitch that would is dropped, the yaw kept; without a floor it turns freely.
TEST(CameraControl, TheHandsOrbitStaysAboveTheFloor) {
  using namespace phonglab;
  Scene s = load_scene_or_fail("lecture");
  const ui::Floor floor = *ui::find_floor(s, s.camera);
  Camera c = s.camera;
  for (int i = 0; i < 200; ++i) {
    ui::orbit_in(s, c, 0.01, -0.05);  // downwards, turning a little
    ASSERT_GT(glm::dot(c.position - floor.point, floor.normal), 0) << i;
  }
  const Vec3 before = c.position;
  ui::orbit_in(s, c, 0.2, -0.5);
  EXPECT_NE(c.position, before) << "the yaw is kept";
  ui::orbit_in(s, c, 0, 0.3);
  EXPECT_GT(glm::dot(c.position - floor.point, floor.normal), glm::dot(before - floor.point, floor.normal))
      << "upwards it goes as before";
  Scene open_sky = s;
  open_sky.planes.clear();
  Camera free = open_sky.camera;
  for (int i = 0; i < 60; ++i) ui::orbit_in(open_sky, free, 0, -0.05);
  EXPECT_LT(glm::dot(free.position - floor.point, floor.normal), 0) << "no floor: nothing to stay above";
}

// The wheel stops before the eye enters an object between it and look_at (a sphere centred on
// look_at here); plain dolly would go in. Going out is as before.
TEST(CameraControl, TheWheelStopsBeforeItEntersAnObject) {
  using namespace phonglab;
  Scene s;
  s.camera.position = Vec3(0, 0, 5);
  s.camera.look_at = Vec3(0, 0, 0);
  s.materials = {Material{}};
  s.spheres = {Sphere{{0, 0, 0}, 1, 0}};
  const PreparedScene prepared(s);
  Camera wheel = s.camera, plain = s.camera;
  for (int i = 0; i < 30; ++i) {
    ui::dolly_in(prepared, wheel, 0.7);
    ui::dolly(plain, 0.7);
    ASSERT_GT(glm::length(wheel.position), 1.0) << i;
  }
  EXPECT_LT(glm::length(plain.position), 1.0) << "plain dolly goes inside";
  EXPECT_LT(glm::length(wheel.position), 1.1) << "it comes close to the surface";
  const Vec3 close = wheel.position;
  ui::dolly_in(prepared, wheel, 2.0);
  EXPECT_GT(glm::length(wheel.position), glm::length(close) * 1.9) << "out, as before";
}
