// The previewer's sidebar: the panels in the order a lecture uses them, and what their edits request.
#include "apps/previewer/sidebar.h"

#include "apps/previewer/viewer_app.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <backends/imgui_impl_opengl3.h>

#include "core/scene/camera.h"
#include "io/figure.h"
#include "core/geometry/geometry.h"
#include "core/teaching/heat_map.h"
#include "io/image_io.h"
#include "io/probe_report.h"
#include "core/teaching/ray_tree_view.h"
#include "core/shading/shading.h"
#include "interaction/camera_control.h"
#include "interaction/scene_objects.h"
#include "ui/widgets.h"


namespace phonglab {

namespace {

// The index of the one element that differs between two lists of the same length; -1 when
// none or more than one does, or the lengths differ.
template <class T>
int only_change(const std::vector<T>& before, const std::vector<T>& after) {
  if (before.size() != after.size()) return -1;
  int changed = -1;
  for (std::size_t k = 0; k < before.size(); ++k) {
    if (before[k] == after[k]) continue;
    if (changed >= 0) return -1;
    changed = static_cast<int>(k);
  }
  return changed;
}

}  // namespace

namespace {

// A panel header that tests can find by name ("panel.Lights") and click.
bool header(const char* title, bool open_by_default) {
  const bool open = ImGui::CollapsingHeader(title, open_by_default ? ImGuiTreeNodeFlags_DefaultOpen : 0);
  std::string name = std::string("panel.") + title;
  std::replace(name.begin(), name.end(), ' ', '_');  // one word for scripts: panel.Render_settings
  name = name.substr(0, name.find(':'));             // panel.Rays
  ui::locate(name);
  return open;
}

}  // namespace

void Sidebar::draw_sidebar() {
  if (!v_.sidebar_visible_) return;
  const ImGuiIO& io = ImGui::GetIO();
  const float width = io.DisplaySize.x - v_.viewport_.width;
  if (width < 1 || io.DisplaySize.y < 1) return;
  ImGui::SetNextWindowPos(ImVec2(v_.viewport_.width, 0));
  ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y));
  // No background of its own: Viewer::draw_gl clears the panel's rectangle to the colour it
  // would have (software GL blends a full-height background at a cost of milliseconds a frame).
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoBackground;
  v_.item_locations_.rects.clear();  // what this frame draws
  if (ImGui::Begin("##sidebar", nullptr, flags)) {
    // Text wraps at the panel's edge at any UI size; labels sit right of the widgets.
    ImGui::PushTextWrapPos(0.0f);
    // The label column holds the longest label with its "(?)" ("live images/s (?)").
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);
    ImGui::TextDisabled("phonglab %s   H hides the panels, F1 lists the keys", PHONGLAB_VERSION);
    // In the order a lecture uses them: what is shown, the coefficients, the lights, the probe
    // and the instruments; then the camera, the file and the settings.
    if (header("Show", true)) sidebar_show();
    if (v_.lesson_shell_.state().unfold_panel) {
      ImGui::SetNextItemOpen(true);
      v_.lesson_shell_.state().unfold_panel = false;
    }
    if (header("Lessons", false)) v_.lesson_shell_.sidebar_lessons();
    if (v_.open_materials_) {
      ImGui::SetNextItemOpen(true);
      v_.open_materials_ = false;
    }
    if (header("Objects", false)) sidebar_objects();
    if (header("Materials", true)) sidebar_materials();
    if (header("Lights", true)) sidebar_lights();
    if (v_.formulas_.take_unfold()) ImGui::SetNextItemOpen(true);
    if (header("Formula: your own term", false)) v_.formulas_.sidebar_formulas();
    if (header("Probe", true)) sidebar_probe();
    if (header("Instruments", true)) sidebar_instruments();
    if (header("Rays: tree, depth cut, heat map", false)) sidebar_rays();
    if (header("Camera", false)) sidebar_camera();
    if (header("Scene file", true)) sidebar_file();
    if (header("Render settings", false)) sidebar_render();
    if (header("Display", false)) ui::display_panel(v_.display_);  // the UI size applies from the next frame
    if (header("Screenshot", false)) {
      ui::ScreenshotActions actions;
      ui::screenshot_panel(v_.files_.screenshot_state(), actions);
      if (actions.save_png) v_.files_.save_png(v_.files_.screenshot_state().png_path);
      if (actions.save_pfm) v_.files_.save_pfm(v_.files_.screenshot_state().pfm_path);
    }
    ImGui::PopItemWidth();
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
  // While a slider is held, each tick is an edit: keep the renderer at coarse levels.
  if (!ImGui::IsAnyItemActive()) v_.edits_.while_active = false;
  else if (v_.edits_.scene || v_.edits_.camera) v_.edits_.while_active = true;
}

void Sidebar::sidebar_show() {
  const Term before = v_.render_settings_.term;
  const bool multiples = v_.instruments_.small_multiples;
  const ui::AmbientView ambient = v_.render_settings_.ambient_view;
  ui::show_panel(v_.render_settings_.term, v_.instruments_.small_multiples, v_.render_settings_.ambient_view,
                 v_.doc_.scene().specular_model == SpecularModel::kBlinn);
  if (v_.render_settings_.ambient_view != ambient) v_.edits_.settings = true;
  if (v_.render_settings_.term != before) {
    if (v_.render_settings_.term != Term::kRays) v_.rays_.heat_map = false;
    v_.edits_.settings = true;
  }
  if (multiples != v_.instruments_.small_multiples) v_.edits_.settings = true;
}

void Sidebar::sidebar_materials() {
  const Scene& scene = v_.session_.scene();
  if (v_.picked_text_.empty()) ImGui::TextDisabled("Click an object in the view to select its material.");
  else ImGui::TextDisabled("Clicked: %s", v_.picked_text_.c_str());
  // A coefficient edited in the panel reaches the renderer as a value: the panel edits a copy,
  // the session applies it as an edit (one undo step when the slider is let go), and
  // apply_edits hands the session's scene to the renderer.
  std::vector<Material> materials = scene.materials;
  if (ui::materials_panel(materials, v_.selected_material_, scene.specular_model)) {
    const int k = only_change(scene.materials, materials);
    Scene whole = scene;
    whole.materials = materials;
    const bool held = ImGui::IsAnyItemActive();
    v_.apply_edit(k >= 0 ? Edit{edit::SetMaterial{k, materials[static_cast<std::size_t>(k)]}, held}
                      : Edit{edit::SetScene{whole}, held});
  }
  sidebar_ambient_fit();
  ui::MaterialActions actions;
  ui::material_library(scene, v_.selected_material_, v_.builder_.material_name_field(), actions);
  const int m = v_.selected_material_;
  if (actions.add) v_.builder_.add_material(ui::unused_material_name(scene, "material"));
  if (actions.duplicate) {
    int copy = -1;
    if (v_.builder_.edit_scene([&](Scene& s) { return ui::duplicate_material(s, m, copy); }, false).empty()) v_.selected_material_ = copy;
  }
  if (actions.remove) {
    // A mesh's faces carry their MTL materials' indices: with meshes, they are placed again.
    const bool meshes = !scene.meshes.empty();
    if (v_.builder_.edit_scene([&](Scene& s) { return ui::delete_material(s, m); }, meshes).empty()) {
      v_.selected_material_ = std::max(0, m - 1);
    }
  }
  if (!actions.rename.empty()) v_.builder_.edit_scene([&](Scene& s) { return ui::rename_material(s, m, actions.rename); }, false);
  if (!actions.preset.empty() && m >= 0 && m < static_cast<int>(scene.materials.size())) {
    v_.builder_.apply_material_preset(scene.materials[static_cast<std::size_t>(m)].name, actions.preset);
  }
  if (v_.builder_.notice().refused) ImGui::TextColored(ui::kErrorColor, "%s", v_.builder_.notice().text.c_str());
  else if (v_.builder_.notice().material) ImGui::TextWrapped("%s", ui::with_font_subscripts(v_.builder_.notice().text).c_str());
}

// "The best constant ambient for this view": the selected material's ka set so that ka·Ia is the
// mean indirect term over its hits in the image (fit_ambient at a quarter of the render's size,
// 4 samples a pixel: about a second on two cores for the Cornell box), one undo step.
void Sidebar::sidebar_ambient_fit() {
  const Scene& scene = v_.doc_.scene();
  const int m = v_.selected_material_;
  if (m < 0 || m >= static_cast<int>(scene.materials.size()) || !v_.schedule_.snapshot()) return;
  const auto index = static_cast<std::size_t>(m);
  const auto fit_now = [&] {
    v_.tools_.ambient_fit() = fit_ambient(*v_.schedule_.snapshot(), std::max(1, v_.schedule_.width() / 4),
                                          std::max(1, v_.schedule_.height() / 4), 4, v_.render_settings_.threads);
    v_.tools_.ambient_fit_material() = scene.materials[index].name;
  };
  // The lecture's "ambient intensity of the scene": one Iₐ, ka as the materials give it.
  if (ImGui::Button("best I\xE2\x82\x90 for this view")) {
    fit_now();
    Scene whole = scene;
    whole.ambient = ui::tidy_color(v_.tools_.ambient_fit()->fitted_ia);
    v_.apply_edit({edit::SetScene{std::move(whole)}, false});
  }
  ui::locate("scene.fit_ia");
  ui::help_marker("Sets the scene's ambient intensity I\xE2\x82\x90 so that ka*I\xE2\x82\x90 (each material's own ka) is as "
                  "near as one colour can be to the indirect light arriving at every visible point. Show 'indirect - ambient' "
                  "to see what is left.");
  ImGui::SameLine();
  if (ImGui::Button("best ka")) {
    fit_now();
    if (v_.tools_.ambient_fit()->hits[index] > 0) {
      Material fitted = scene.materials[index];
      fitted.ka = ui::tidy_color(v_.tools_.ambient_fit()->fitted_ka[index]);
      v_.apply_edit({edit::SetMaterial{m, fitted}, false});
    }
  }
  ui::locate("materials.fit_ka");
  ui::help_marker("Sets this material's ka (within 0..1, what a surface can reflect) so that ka*I\xE2\x82\x90 equals the indirect "
                  "light it receives, averaged over its hits in this view.");
  const auto& fit = v_.tools_.ambient_fit();
  if (fit && v_.tools_.ambient_fit_material() == scene.materials[index].name && index < fit->hits.size()) {
    ImGui::TextDisabled("fitted I\xE2\x82\x90 (%.3g, %.3g, %.3g) over the view", fit->fitted_ia.x, fit->fitted_ia.y, fit->fitted_ia.z);
    const Color ka = fit->fitted_ka[index], wanted = fit->wanted_ka[index];
    if (fit->hits[index] == 0) {
      ImGui::TextDisabled("%s is not seen in this view: its ka is kept", scene.materials[index].name.c_str());
    } else if (ka_over_one(wanted)) {
      ImGui::TextColored(ui::kWarningColor, "ka wanted (%.3g, %.3g, %.3g) is over 1, more than a surface reflects: "
                         "ka set to (%.3g, %.3g, %.3g); raise I\xE2\x82\x90 instead", wanted.x, wanted.y, wanted.z, ka.x, ka.y, ka.z);
      ui::locate("materials.fit_ka_over");
    } else {
      ImGui::TextDisabled("fitted ka (%.3g, %.3g, %.3g) over %llu hits", ka.x, ka.y, ka.z,
                          static_cast<unsigned long long>(fit->hits[index]));
    }
  }
}

void Sidebar::sidebar_objects() {
  ui::ObjectActions actions;
  int selected = v_.selected_object_;
  ui::objects_panel(v_.doc_.scene(), selected, v_.builder_.mesh_path_field(), v_.builder_.notice(), actions);
  if (selected != v_.selected_object_) v_.builder_.select_object(selected);
  if (actions.add != ObjectRef::Kind::kNone) v_.builder_.add_object(actions.add, v_.builder_.mesh_path_field());
  if (actions.duplicate >= 0) v_.builder_.duplicate(actions.duplicate);
  if (actions.remove >= 0) v_.builder_.delete_object(actions.remove);
  if (!actions.field.empty() && v_.selected_object_ >= 0) {
    v_.builder_.set_object(v_.selected_object_, actions.field, actions.values, actions.text);
  }
}

void Sidebar::sidebar_lights() {
  const Scene& scene = v_.session_.scene();
  std::vector<Light> lights = scene.lights;
  if (!ui::lights_panel(lights, v_.selected_light_, v_.solo_)) return;
  // A new point light goes where the lecturer can see it and grab it: above and left of the
  // look-at point, in the view, at the look-at point's depth.
  if (lights.size() == scene.lights.size() + 1 && lights.back().type == LightType::kPoint) {
    const Camera view = v_.view_camera();
    const int w = std::max(1, static_cast<int>(std::lround(v_.viewport_.width)));
    const int h = std::max(1, static_cast<int>(std::lround(v_.viewport_.height)));
    const double depth = ui::view_depth(view, view.look_at);
    lights.back().position = ui::unproject(view, ui::ViewportPoint{0.3 * w, 0.2 * h}, depth, w, h);
  }
  // One light changed is that light's edit; a light added or removed, or a solo, the scene's.
  const int k = only_change(scene.lights, lights);
  Scene whole = scene;
  whole.lights = lights;
  const bool held = ImGui::IsAnyItemActive();
  v_.apply_edit(k >= 0 ? Edit{edit::SetLight{k, lights[static_cast<std::size_t>(k)]}, held} : Edit{edit::SetScene{whole}, held});
}

void Sidebar::sidebar_probe() {
  // In the sidebar itself, wrapped at its width: the wheel scrolls the panels, never a box inside.
  {
    ui::ProbeView view;
    view.scene = v_.schedule_.snapshot() ? &v_.schedule_.snapshot()->scene() : nullptr;
    view.probe = v_.tools_.probe().tree ? &*v_.tools_.probe().tree : nullptr;
    view.image_width = v_.schedule_.width();
    view.image_height = v_.schedule_.height();
    view.report = v_.tools_.probe().report;
    view.occluders = v_.tools_.probe().occluders;
    view.indirect = v_.tools_.probe().tree ? &v_.tools_.probe().indirect : nullptr;
    view.exposure_ev = v_.display_.exposure_ev;
    view.cli_command = v_.tools_.probe_cli_command();
    if (v_.tools_.probe().tree) {
      const double gain = std::exp2(static_cast<double>(v_.display_.exposure_ev));
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp(v_.tools_.probe().tree->root.total[c] * gain, 0.0, 1.0);
        view.srgb[c] = v_.display_.srgb ? linear_to_srgb8(v) : static_cast<unsigned char>(std::lround(v * 255));
      }
    }
    const bool digits_before = v_.tools_.probe().every_digit;
    const int key[3] = {v_.tools_.probe().x, v_.tools_.probe().y, view.probe != nullptr ? 1 : 0};
    if (key[0] != probe_key_[0] || key[1] != probe_key_[1] || key[2] != probe_key_[2]) {
      probe_height_ = 0;
      std::copy(key, key + 3, probe_key_);
    }
    const float top = ImGui::GetCursorPosY();
    ui::probe_panel(view, v_.tools_.probe().every_digit);
    const float height = ImGui::GetCursorPosY() - top;
    if (height < probe_height_) ImGui::Dummy(ImVec2(1, std::max(probe_height_ - height - ImGui::GetStyle().ItemSpacing.y, 0.0f)));
    probe_height_ = std::max(probe_height_, height);
    if (v_.tools_.probe().every_digit != digits_before) v_.tools_.refresh_probe();
  }
}

void Sidebar::sidebar_instruments() {
  ui::InstrumentActions actions;
  const ui::InstrumentSettings before = v_.instruments_;
  if (ui::instruments_panel(v_.instruments_, actions, v_.tools_.compare().has_image(), v_.session_.undo_count(),
                            v_.session_.redo_count(), v_.figure_path_, v_.figure_status_)) {
    if (before.small_multiples != v_.instruments_.small_multiples) v_.edits_.settings = true;
    v_.upload_pending_ = v_.upload_pending_ || !v_.shown_.pixels.empty();  // a compare view changed
  }
  if (actions.snapshot_a) v_.tools_.snapshot_a();
  if (actions.undo) v_.undo();
  if (actions.redo) v_.redo();
  if (actions.save_figure) v_.tools_.save_figure(v_.figure_path_);
  if (actions.head_reference) {
    v_.tools_.snapshot_a();
    v_.instruments_.compare = 2;
    v_.upload_pending_ = v_.upload_pending_ || !v_.shown_.pixels.empty();
  }
}

void Sidebar::sidebar_rays() {
  v_.rays_.heat_map = v_.render_settings_.term == Term::kRays;
  const ui::RayTreeSettings before = v_.rays_;
  ui::RayTreeSummary summary;
  summary.probe = v_.tools_.probe().tree ? &*v_.tools_.probe().tree : nullptr;
  summary.scene_max_depth = v_.doc_.scene().max_depth;
  summary.heat_max = v_.heat_max_;
  if (ui::rays_panel(v_.rays_, summary)) {
    if (before.depth_cut != v_.rays_.depth_cut || (v_.rays_.depth_cut && before.cut_depth != v_.rays_.cut_depth)) {
      v_.edits_.view = true;
    }
    if (before.heat_map != v_.rays_.heat_map) v_.tools_.set_heat_map(v_.rays_.heat_map);
  }
}

void Sidebar::sidebar_camera() {
  ui::CameraActions actions;
  Camera camera = v_.session_.scene().camera;
  if (ui::camera_panel(camera, actions, v_.camera_notice_)) v_.move_camera(camera);
  v_.edits_.frame_requested |= actions.frame_scene;
  v_.edits_.reset_requested |= actions.reset;
  if (v_.view_camera().fov_y_deg != v_.doc_.scene().camera.fov_y_deg) {
    ImGui::TextDisabled("Shown with fov y %.1f: the view is narrower than the scene's %dx%d image.",
                        v_.view_camera().fov_y_deg, v_.doc_.scene().width, v_.doc_.scene().height);
  }
}

void Sidebar::sidebar_file() {
  v_.files_.file_state().source = v_.doc_.source();
  v_.files_.file_state().file_path = v_.doc_.file_path();
  v_.files_.file_state().dirty = v_.doc_.dirty();
  v_.files_.file_state().opened_mesh = v_.doc_.opened_mesh();
  ui::SceneFileActions actions;
  ui::scene_file_panel(v_.files_.file_state(), actions);
  if (actions.open) v_.files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kOpen, v_.files_.file_state().path_field});
  if (!actions.open_embedded.empty()) v_.files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kOpen, actions.open_embedded});
  if (actions.save) v_.files_.save_scene(false);
  if (actions.save_as) v_.files_.save_scene(true);
  if (actions.reload) v_.files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kReload, {}});
  if (actions.browse_open) v_.files_.browser().open(false, v_.doc_.file_path());
  if (actions.browse_save) v_.files_.browser().open(true, v_.doc_.file_path());
}

void Sidebar::sidebar_render() {
  Scene scene = v_.session_.scene();
  if (ui::shading_settings_panel(scene)) v_.apply_edit({edit::SetScene{std::move(scene)}, ImGui::IsAnyItemActive()});
  ImGui::Separator();
  const int hardware = resolve_thread_count(0);
  if (ui::render_settings_panel(v_.render_settings_, hardware)) v_.edits_.settings = true;
}

}  // namespace phonglab
