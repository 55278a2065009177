// The `set` command of test scripts: a field of a material, a light, the camera, the render
// settings, the instruments or the display (docs/previewer.md lists them).
#include <optional>

#include "apps/previewer/script_words.h"
#include "apps/previewer/viewer_app.h"
#include "interaction/camera_control.h"

namespace phonglab {

using script::parse_double;
using script::parse_int;
using script::parse_vec3;

bool ScriptDriver::script_set(const std::vector<std::string>& w) {
  if (w.size() < 4) return false;
  const std::string& subject = w[1];
  if (subject == "material" && w.size() >= 5) return set_material_field(w);
  if (subject == "light" && w.size() >= 5) return set_light_field(w);
  if (subject == "camera") return set_camera_field(w);
  if (subject == "render" && w.size() == 4) return set_render_field(w);
  if (subject == "instruments" && w.size() == 4) return set_instrument(w);
  if (subject == "display" && w.size() == 4) return set_display_field(w);
  return false;
}

// `set material NAME ka|kd|ks|kr|kt|n|ior|fresnel V..`.
bool ScriptDriver::set_material_field(const std::vector<std::string>& w) {
  const Scene& scene = s_.session.scene();
  int index = -1;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    if (scene.materials[i].name == w[2]) index = static_cast<int>(i);
  }
  if (index < 0) return false;
  s_.selected_material = index;
  Material changed = scene.materials[static_cast<std::size_t>(index)];
  Material* m = &changed;
  const std::string& field = w[3];
  double v = 0;
  if (field == "ka" || field == "kd" || field == "ks" || field == "kr" || field == "kt") {
    Color c;
    if (!parse_vec3(w, 4, true, c) || c.x < 0 || c.y < 0 || c.z < 0) return false;
    (field == "ka" ? m->ka : field == "kd" ? m->kd : field == "ks" ? m->ks : field == "kr" ? m->kr : m->kt) = c;
  } else if (field == "n" && w.size() == 5 && parse_double(w[4], v) && v >= 0) {
    m->n = v;
  } else if (field == "ior" && w.size() == 5 && parse_double(w[4], v) && v > 0) {
    m->ior = v;
  } else if (field == "fresnel" && w.size() == 5) {
    m->fresnel = w[4] == "1" || w[4] == "true";
  } else {
    return false;
  }
  apply_edit(s_, {edit::SetMaterial{index, changed}});
  return true;
}

// `set light I position|direction|intensity|enabled V..`.
bool ScriptDriver::set_light_field(const std::vector<std::string>& w) {
  const Scene& scene = s_.session.scene();
  int index = 0;
  if (!parse_int(w[2], index) || index < 0 || index >= static_cast<int>(scene.lights.size())) return false;
  Light light = scene.lights[static_cast<std::size_t>(index)];
  const std::string& field = w[3];
  Vec3 v;
  if (field == "position" && parse_vec3(w, 4, false, v)) light.position = v;
  else if (field == "direction" && parse_vec3(w, 4, false, v) && glm::length(v) > 0) light.direction = v;
  else if (field == "intensity" && parse_vec3(w, 4, true, v)) light.intensity = v;
  else if (field == "enabled" && w.size() == 5) light.enabled = w[4] == "1" || w[4] == "true";
  else return false;
  s_.selected_light = index;
  apply_edit(s_, {edit::SetLight{index, light}});
  return true;
}

// `set camera position|look_at|up|fov V..`: refused when the camera would be invalid.
bool ScriptDriver::set_camera_field(const std::vector<std::string>& w) {
  Camera edit = s_.session.scene().camera;
  const std::string& field = w[2];
  Vec3 v;
  double fov = 0;
  if (field == "position" && parse_vec3(w, 3, false, v)) edit.position = v;
  else if (field == "look_at" && parse_vec3(w, 3, false, v)) edit.look_at = v;
  else if (field == "up" && parse_vec3(w, 3, false, v)) edit.up = v;
  else if (field == "fov" && w.size() == 4 && parse_double(w[3], fov)) edit.fov_y_deg = fov;
  else return false;
  if (!ui::camera_is_valid(edit)) return false;
  move_camera(s_, edit);
  return true;
}

// `set render target_spp|resolution_scale|threads|live_images_per_s|tree_budget_mib|term|ambient V`.
bool ScriptDriver::set_render_field(const std::vector<std::string>& w) {
  const std::string& field = w[2];
  double v = 0;
  if (field == "term") {
    const std::optional<Term> term = term_from_name(w[3]);
    if (!term) return false;
    s_.render_settings.term = *term;
  } else if (field == "ambient") {
    const std::optional<ui::AmbientView> view = ui::ambient_view_from_name(w[3]);
    if (!view) return false;
    s_.render_settings.ambient_view = *view;
    if (*view == ui::AmbientView::kBeside || *view == ui::AmbientView::kDifference) s_.instruments.small_multiples = false;
  } else if (!parse_double(w[3], v)) {
    return false;
  } else if (field == "target_spp" && v >= 1) {
    s_.render_settings.target_spp = static_cast<int>(v);
  } else if (field == "resolution_scale" && v > 0 && v <= 1) {
    s_.render_settings.resolution_scale = static_cast<float>(v);
  } else if (field == "threads" && v >= 0) {
    s_.render_settings.threads = static_cast<int>(v);
  } else if (field == "live_images_per_s" && v >= 0 && v <= 1000) {
    s_.render_settings.live_images_per_s = static_cast<int>(v);
  } else if (field == "tree_budget_mib" && v >= 0 && v <= 65536) {
    s_.render_settings.tree_budget_mib = static_cast<int>(v);
  } else {
    return false;
  }
  s_.edits.settings = true;
  return true;
}

// `set instruments NAME V`: probe mode, multiples, compare, head, the ray tree, depth cut, heat map.
bool ScriptDriver::set_instrument(const std::vector<std::string>& w) {
  double v = 0;
  if (!parse_double(w[3], v)) return false;
  if (w[2] == "probe_mode") s_.instruments.probe_mode = v != 0;
  else if (w[2] == "multiples") s_.instruments.small_multiples = v != 0;
  else if (w[2] == "compare" && v >= 0 && v <= 2) s_.instruments.compare = static_cast<int>(v);
  else if (w[2] == "wipe" && v >= 0 && v <= 1) s_.instruments.wipe = static_cast<float>(v);
  else if (w[2] == "gain" && v > 0) s_.instruments.difference_gain = static_cast<float>(v);
  else if (w[2] == "head") s_.instruments.move_head = v != 0;
  else if (w[2] == "head_angle" && v >= -90 && v <= 90) s_.instruments.head_angle_deg = static_cast<float>(v);
  else if (w[2] == "ray_tree") s_.rays.overlay = v != 0;
  else if (w[2] == "tree_shadows") s_.rays.shadow_rays = v != 0;
  else if (w[2] == "tree_secondary") s_.rays.secondary_rays = v != 0;
  else if (w[2] == "tree_arrows") s_.rays.arrows = v != 0;
  else if (w[2] == "tree_legend") s_.rays.legend = v != 0;
  else if (w[2] == "depth_cut" && v >= -1 && v <= 100) {
    // -1 ends the cut; 0, 1, ... cut there (as the panel's box and slider).
    s_.rays.depth_cut = v >= 0;
    if (v >= 0) s_.rays.cut_depth = static_cast<int>(v);
    s_.edits.view = true;
  }
  else if (w[2] == "heat") tools_.set_heat_map(v != 0);
  else return false;
  s_.upload_pending = s_.upload_pending || !s_.shown.pixels.empty();
  return true;
}

// `set display exposure|srgb|light_markers|stats|stats_details|sidebar|ui_size V`.
bool ScriptDriver::set_display_field(const std::vector<std::string>& w) {
  double v = 0;
  if (!parse_double(w[3], v)) return false;
  if (w[2] == "exposure") s_.display.exposure_ev = static_cast<float>(v);
  else if (w[2] == "srgb") s_.display.srgb = v != 0;
  else if (w[2] == "light_markers") s_.display.light_markers = v != 0;
  else if (w[2] == "stats") s_.display.show_stats = v != 0;
  else if (w[2] == "stats_details") s_.display.stats_details = v != 0;
  else if (w[2] == "sidebar") s_.sidebar_visible = v != 0;
  else if (w[2] == "ui_size" && v >= 0.5 && v <= 4) s_.display.ui_size = static_cast<float>(v);
  else return false;
  return true;
}

}  // namespace phonglab
