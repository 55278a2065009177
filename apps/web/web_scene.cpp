#include "apps/web/web_scene.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "apps/web/web_lesson.h"
#include "interaction/camera_control.h"
#include "interaction/numbers.h"
#include "io/scene/scene_io.h"

namespace phonglab {
namespace {

Color* colour(Material& m, const std::string& name) {
  if (name == "ka") return &m.ka;
  if (name == "kd") return &m.kd;
  if (name == "ks") return &m.ks;
  if (name == "kr") return &m.kr;
  if (name == "kt") return &m.kt;
  return nullptr;
}
double largest(const Color& c) { return std::max({c.x, c.y, c.z}); }
// A colour to `value` at its largest channel, keeping its hue (black becomes grey), each channel
// to float precision as the desktop's panels keep it: a saved file reads 0.008, not
// 0.008000000000000002.
Color scaled(const Color& c, double value) { return ui::tidy_color(largest(c) > 0 ? c * (value / largest(c)) : Color(value)); }


}  // namespace

std::string WebScene::open(const std::string& scene_arg) {
  if (!s_.session.open(scene_arg)) return s_.session.document().error_text();
  s_.step_scene.clear();
  s_.tree_pixel.reset();
  s_.probe_pixel.reset();
  s_.a.clear();
  lesson_.close_lesson();
  image_.restart();
  return "";
}

std::string WebScene::scene_json() const { return scene_to_json(s_.session.scene()); }

std::string WebScene::mesh_files_json() const {
  nlohmann::json files = nlohmann::json::array();
  for (const SceneFileText& file : embedded_mesh_files(s_.session.scene())) files.push_back({{"path", file.path}, {"text", file.text}});
  return files.dump();
}

std::string WebScene::scene_label() const {
  const SceneDocument& document = s_.session.document();
  if (!document.embedded_name().empty()) return document.embedded_name();
  if (!document.file_path().empty()) return std::filesystem::path(document.file_path()).filename().string();
  return s_.step_scene.empty() ? document.source() : s_.step_scene;
}

void WebScene::orbit(double dx_px, double dy_px) {
  Camera camera = s_.session.scene().camera;
  ui::orbit_in(s_.session.scene(), camera, -dx_px * 0.01, dy_px * 0.01);  // never under the floor
  apply({edit::SetCamera{camera}, false});
}

void WebScene::reset_camera() { apply({edit::SetCamera{s_.session.document().loaded_camera()}, false}); }

void WebScene::dolly(double steps) {
  Camera camera = s_.session.scene().camera;
  if (s_.prepared) ui::dolly_in(*s_.prepared, camera, std::pow(0.9, steps));  // never inside an object
  else ui::dolly(camera, std::pow(0.9, steps));
  apply({edit::SetCamera{camera}, false});
}

void WebScene::pan(double dx_px, double dy_px) {
  Camera camera = s_.session.scene().camera;
  ui::pan(camera, dx_px, dy_px, s_.height);
  apply({edit::SetCamera{camera}, false});
}

std::string WebScene::light_markers() const {
  // Each light's point on the canvas, or null (a directional light, or behind the eye).
  nlohmann::json out = nlohmann::json::array();
  if (!s_.view.light_markers) return out.dump();  // a lesson step that does not show where the lights are
  const Scene& scene = s_.session.scene();
  for (const Light& light : scene.lights) {
    const auto at = light.type == LightType::kPoint ? ui::project(scene.camera, light.position, s_.width, s_.height)
                                                    : std::nullopt;
    out.push_back(at ? nlohmann::json::array({at->x, at->y}) : nlohmann::json(nullptr));
  }
  return out.dump();
}

double WebScene::light_depth(int l) const {
  if (l < 0 || l >= light_count()) return 0;
  const Scene& scene = s_.session.scene();
  return ui::view_depth(scene.camera, scene.lights[static_cast<std::size_t>(l)].position);
}

void WebScene::drag_light(int l, double x_px, double y_px, double depth) {
  if (l < 0 || l >= light_count() || !(depth > 0)) return;
  const Scene& scene = s_.session.scene();
  const Vec3 p = ui::unproject(scene.camera, {x_px, y_px}, depth, s_.width, s_.height);
  Light light = scene.lights[static_cast<std::size_t>(l)];
  // Kept to float precision, as the desktop keeps a dragged light: a saved file reads 1.8074448.
  light.position = Vec3(ui::tidy_float(p.x), ui::tidy_float(p.y), ui::tidy_float(p.z));
  apply({edit::SetLight{l, light}, true});
}

std::string WebScene::material_name(int m) const {
  return m >= 0 && m < material_count() ? s_.session.scene().materials[static_cast<std::size_t>(m)].name : "";
}

double WebScene::coefficient(int m, const std::string& name) const {
  if (m < 0 || m >= material_count()) return 0;
  Material mat = s_.session.scene().materials[static_cast<std::size_t>(m)];
  if (const Color* c = colour(mat, name)) return largest(*c);
  if (name == "n") return mat.n;
  if (name == "ior") return mat.ior;
  return 0;
}

void WebScene::set_coefficient(int m, const std::string& name, double value, bool held) {
  if (m < 0 || m >= material_count()) return;
  Material mat = s_.session.scene().materials[static_cast<std::size_t>(m)];
  if (Color* c = colour(mat, name)) {
    *c = scaled(*c, value);
  } else if (name == "n") {
    mat.n = value;
  } else if (name == "ior") {
    mat.ior = value;
  } else {
    return;
  }
  apply({edit::SetMaterial{m, mat}, held});
}

double WebScene::light_intensity(int l) const {
  return l >= 0 && l < light_count() ? largest(s_.session.scene().lights[static_cast<std::size_t>(l)].intensity) : 0;
}

void WebScene::set_light_intensity(int l, double value, bool held) {
  if (l < 0 || l >= light_count()) return;
  Light light = s_.session.scene().lights[static_cast<std::size_t>(l)];
  light.intensity = scaled(light.intensity, value);
  apply({edit::SetLight{l, light}, held});
}

bool WebScene::undo() {
  if (!s_.session.undo()) return false;
  lesson_.edited_by_hand();
  image_.restart();
  return true;
}

bool WebScene::redo() {
  if (!s_.session.redo()) return false;
  lesson_.edited_by_hand();
  image_.restart();
  return true;
}

void WebScene::apply(const Edit& e) {
  if (!s_.session.apply(e).changed) return;
  lesson_.edited_by_hand();
  image_.restart();
}

}  // namespace phonglab
