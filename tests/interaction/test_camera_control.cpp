// The viewport's camera control: the orbit follows the hand and stops short of the poles, the
// dolly has a far limit, and a narrow view widens the field of view so the framed scene stays.
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "core/scene/camera.h"
#include "interaction/camera_control.h"
#include "interaction/numbers.h"

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
