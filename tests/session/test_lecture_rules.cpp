// The lecture's first minutes (tests/gui's lecture session), the rules under its input: a typed
// camera the renderer cannot use is refused with the reason, the wheel's dolly stops at its limit,
// the point light starts out of the view (its marker an arrow at the edge), and a slider's value
// or a light marker's drag leaves no float noise in the saved file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "core/accel/prepared_scene.h"
#include "interaction/camera_control.h"
#include "interaction/numbers.h"
#include "interaction/scene_objects.h"
#include "io/scene/scene_io.h"
#include "session/session.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

// The viewport beside the panels in a 1280x720 window, and the camera the previewer renders the
// lecture with there (view_camera: the file's fov widened so the framed width stays in view).
constexpr int kViewW = 880;
constexpr int kViewH = 720;
Camera view_camera_of(const Scene& scene) {
  return ui::fit_to_view(scene.camera, static_cast<double>(scene.width) / scene.height,
                         static_cast<double>(kViewW) / kViewH);
}

// A plastic material's block of a saved scene: from its name to its closing brace.
std::string material_block(const std::string& text, const std::string& name) {
  const std::size_t start = text.find("\"" + name + "\": {");
  if (start == std::string::npos) return "";
  return text.substr(start, text.find('}', start) - start);
}

struct LectureSession : ::testing::Test {
  Session session{""};  // no recovery files
  void SetUp() override { ASSERT_TRUE(session.open("lecture")); }
};

// A typed fov of 0 (the Camera panel, `set camera fov`): the reason the panel shows, the same rule
// camera_is_valid applies before any camera reaches the session.
TEST_F(LectureSession, AFovOfZeroIsRefusedWithTheReason) {
  Camera typed = session.scene().camera;
  typed.fov_y_deg = 0;
  EXPECT_EQ(ui::camera_problem(typed), "fov y must be between 0 and 180 degrees (got 0)");
  EXPECT_FALSE(ui::camera_is_valid(typed));
  typed.fov_y_deg = 180;
  EXPECT_EQ(ui::camera_problem(typed), "fov y must be between 0 and 180 degrees (got 180)");
  typed.fov_y_deg = 39.5;
  EXPECT_EQ(ui::camera_problem(typed), "");
  EXPECT_EQ(session.scene().camera.fov_y_deg, 40) << "the file's, until a valid one is applied";
}

// `scroll X Y -200`: one frame's wheel of 200 clicks out (Viewer::handle_viewport_input), the
// dolly's limit 20 times the loaded camera's distance (the lecture's spheres lie well within it).
TEST_F(LectureSession, TwoHundredWheelClicksOutStopAtTheDollyLimit) {
  const Scene& scene = session.scene();
  const Camera& loaded = session.document().loaded_camera();
  const double limit = ui::dolly_limit(scene, loaded);
  EXPECT_DOUBLE_EQ(limit, 20 * glm::length(loaded.position - loaded.look_at));
  EXPECT_LT(limit, 1000);
  const PreparedScene prepared(scene);
  Camera camera = scene.camera;
  ui::dolly_in(prepared, camera, std::pow(0.85, -200.0), limit);
  EXPECT_NEAR(glm::length(camera.position - camera.look_at), limit, 1e-9 * limit);
  EXPECT_TRUE(ui::camera_is_valid(camera));
  ui::dolly_in(prepared, camera, 1 / 0.85, limit);
  EXPECT_NEAR(glm::length(camera.position - camera.look_at), limit, 1e-9 * limit) << "one more click out stays";
}

// The lecture's point light is above and right of the 880x720 view (in front of the eye): its
// marker is drawn as an arrow at the edge, pointing at it (Overlays::draw_light_markers).
TEST_F(LectureSession, ThePointLightStartsOutOfTheViewInFrontOfTheEye) {
  const Scene& scene = session.scene();
  const Camera view = view_camera_of(scene);
  EXPECT_GT(view.fov_y_deg, scene.camera.fov_y_deg) << "the view is narrower than the file's 960x540";
  ASSERT_EQ(scene.lights.at(0).type, LightType::kPoint);
  const auto at = ui::project(view, scene.lights[0].position, kViewW, kViewH);
  ASSERT_TRUE(at) << "behind the eye it would have no marker";
  EXPECT_LT(at->y, 0);
  EXPECT_GT(at->x, kViewW);
}

// A dragged ks slider keeps the value its text shows ("%.3f", color_strength_edit: a grey ks
// becomes that value in every channel), a dragged light marker puts the light at float precision
// (Viewer::drag_viewport: tidy_float of the unprojected point), and the saved file shows them as
// such: three decimals, and no number anywhere with ten digits after its point.
TEST_F(LectureSession, ASliderValueAndALightDragSaveWithoutFloatNoise) {
  const int plastic = ui::find_material(session.scene(), "plastic");
  ASSERT_GE(plastic, 0);
  const std::regex three_decimals(R"("ks": \[0\.[0-9]{1,3}, 0\.[0-9]{1,3}, 0\.[0-9]{1,3}\])");
  const std::regex noise("[0-9]\\.[0-9]{10,}");
  for (int k = 1; k < 1000; k += 7) {
    const float dragged = static_cast<float>(k) / 1000.0f + 0.00037f;  // between two values the slider shows
    Scene scene = session.scene();
    scene.materials[static_cast<std::size_t>(plastic)].ks = Color(ui::shown_value(static_cast<double>(dragged), "%.3f"));
    const std::string text = scene_to_json(scene);
    ASSERT_TRUE(std::regex_search(material_block(text, "plastic"), three_decimals)) << material_block(text, "plastic");
    ASSERT_FALSE(std::regex_search(text, noise)) << k;
  }
  // Through the session, as the panel and the marker drag hand them over, then Save as.
  Material m = session.scene().materials[static_cast<std::size_t>(plastic)];
  m.ks = Color(ui::shown_value(static_cast<double>(0.5f + 23.0f / 260.0f), "%.3f"));
  session.apply({edit::SetMaterial{plastic, m}, true});
  session.settle(false);
  const Camera view = view_camera_of(session.scene());
  Light light = session.scene().lights[0];
  const Vec3 p = ui::unproject(view, ui::ViewportPoint{300, 150}, ui::view_depth(view, light.position), kViewW, kViewH);
  light.position = Vec3(ui::tidy_float(p.x), ui::tidy_float(p.y), ui::tidy_float(p.z));
  session.apply({edit::SetLight{0, light}, true});
  session.settle(false);
  const auto marker = ui::project(view, light.position, kViewW, kViewH);
  ASSERT_TRUE(marker);
  EXPECT_GT(marker->x, 0);
  EXPECT_LT(marker->x, kViewW);
  EXPECT_GT(marker->y, 0);
  EXPECT_LT(marker->y, kViewH) << "the drag brought the light into view";
  EXPECT_EQ(session.undo_count(), 2U);
  const fs::path path = fs::temp_directory_path() / ("phonglab-lecture-noise-" + std::to_string(::getpid()) + ".json");
  ASSERT_TRUE(session.document().save_as(path.string())) << session.document().error_text();
  std::stringstream saved;
  saved << std::ifstream(path).rdbuf();
  fs::remove(path);
  EXPECT_TRUE(std::regex_search(material_block(saved.str(), "plastic"), three_decimals)) << saved.str();
  EXPECT_FALSE(std::regex_search(saved.str(), noise)) << saved.str();
  EXPECT_FALSE(session.dirty());
}

}  // namespace
}  // namespace phonglab
