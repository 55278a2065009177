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
  if (!s_.sidebar_visible) return;
  const ImGuiIO& io = ImGui::GetIO();
  const float width = io.DisplaySize.x - s_.viewport.width;
  if (width < 1 || io.DisplaySize.y < 1) return;
  ImGui::SetNextWindowPos(ImVec2(s_.viewport.width, 0));
  ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y));
  // No background of its own: Viewer::draw_gl clears the panel's rectangle to the colour it
  // would have (software GL blends a full-height background at a cost of milliseconds a frame).
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoBackground;
  s_.item_locations.rects.clear();  // what this frame draws
  if (ImGui::Begin("##sidebar", nullptr, flags)) {
    // Text wraps at the panel's edge at any UI size; labels sit right of the widgets.
    ImGui::PushTextWrapPos(0.0f);
    // The label column holds the longest label with its "(?)" ("live images/s (?)").
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 9.0f);
    ImGui::TextDisabled("phonglab %s   H hides the panels, F1 lists the keys", PHONGLAB_VERSION);
    // In the order a lecture uses them: what is shown, the coefficients, the lights, the probe
    // and the instruments; then the camera, the file and the settings.
    if (header("Show", true)) sidebar_show();
    if (lesson_shell_.state().unfold_panel) {
      ImGui::SetNextItemOpen(true);
      lesson_shell_.state().unfold_panel = false;
    }
    if (header("Lessons", false)) lesson_shell_.sidebar_lessons();
    if (s_.open_materials) {
      ImGui::SetNextItemOpen(true);
      s_.open_materials = false;
    }
    if (header("Objects", false)) sidebar_objects();
    if (header("Materials", true)) sidebar_materials();
    if (header("Lights", true)) sidebar_lights();
    if (formulas_.take_unfold()) ImGui::SetNextItemOpen(true);
    if (header("Formula: your own term", false)) formulas_.sidebar_formulas();
    if (header("Probe", true)) sidebar_probe();
    if (header("Instruments", true)) sidebar_instruments();
    if (header("Rays: tree, depth cut, heat map", false)) sidebar_rays();
    if (header("Camera", false)) sidebar_camera();
    if (header("Scene file", true)) sidebar_file();
    if (header("Render settings", false)) sidebar_render();
    if (header("Display", false)) ui::display_panel(s_.display);  // the UI size applies from the next frame
    if (header("Screenshot", false)) {
      ui::ScreenshotActions actions;
      ui::screenshot_panel(files_.screenshot_state(), actions);
      if (actions.save_png) files_.save_png(files_.screenshot_state().png_path);
      if (actions.save_pfm) files_.save_pfm(files_.screenshot_state().pfm_path);
    }
    ImGui::PopItemWidth();
    ImGui::PopTextWrapPos();
  }
  ImGui::End();
  // While a slider is held, each tick is an edit: keep the renderer at coarse levels.
  if (!ImGui::IsAnyItemActive()) s_.edits.while_active = false;
  else if (s_.edits.scene || s_.edits.camera) s_.edits.while_active = true;
}

void Sidebar::sidebar_show() {
  const Term before = s_.render_settings.term;
  const bool multiples = s_.instruments.small_multiples;
  const ui::AmbientView ambient = s_.render_settings.ambient_view;
  ui::show_panel(s_.render_settings.term, s_.instruments.small_multiples, s_.render_settings.ambient_view,
                 s_.doc.scene().specular_model == SpecularModel::kBlinn);
  if (s_.render_settings.ambient_view != ambient) s_.edits.settings = true;
  if (s_.render_settings.term != before) {
    if (s_.render_settings.term != Term::kRays) s_.rays.heat_map = false;
    s_.edits.settings = true;
  }
  if (multiples != s_.instruments.small_multiples) s_.edits.settings = true;
}

void Sidebar::sidebar_materials() {
  const Scene& scene = s_.session.scene();
  if (s_.picked_text.empty()) ImGui::TextDisabled("Click an object in the view to select its material.");
  else ImGui::TextDisabled("Clicked: %s", s_.picked_text.c_str());
  // A coefficient edited in the panel reaches the renderer as a value: the panel edits a copy,
  // the session applies it as an edit (one undo step when the slider is let go), and
  // apply_edits hands the session's scene to the renderer.
  std::vector<Material> materials = scene.materials;
  if (ui::materials_panel(materials, s_.selected_material, scene.specular_model)) {
    const int k = only_change(scene.materials, materials);
    Scene whole = scene;
    whole.materials = materials;
    const bool held = ImGui::IsAnyItemActive();
    apply_edit(s_, k >= 0 ? Edit{edit::SetMaterial{k, materials[static_cast<std::size_t>(k)]}, held}
                      : Edit{edit::SetScene{whole}, held});
  }
  sidebar_ambient_fit();
  ui::MaterialActions actions;
  ui::material_library(scene, s_.selected_material, builder_.material_name_field(), actions);
  const int m = s_.selected_material;
  if (actions.add) builder_.add_material(ui::unused_material_name(scene, "material"));
  if (actions.duplicate) {
    int copy = -1;
    if (builder_.edit_scene([&](Scene& s) { return ui::duplicate_material(s, m, copy); }, false).empty()) s_.selected_material = copy;
  }
  if (actions.remove) {
    // A mesh's faces carry their MTL materials' indices: with meshes, they are placed again.
    const bool meshes = !scene.meshes.empty();
    if (builder_.edit_scene([&](Scene& s) { return ui::delete_material(s, m); }, meshes).empty()) {
      s_.selected_material = std::max(0, m - 1);
    }
  }
  if (!actions.rename.empty()) builder_.edit_scene([&](Scene& s) { return ui::rename_material(s, m, actions.rename); }, false);
  if (!actions.preset.empty() && m >= 0 && m < static_cast<int>(scene.materials.size())) {
    builder_.apply_material_preset(scene.materials[static_cast<std::size_t>(m)].name, actions.preset);
  }
  if (builder_.notice().refused) ImGui::TextColored(ui::kErrorColor, "%s", builder_.notice().text.c_str());
  else if (builder_.notice().material) ImGui::TextWrapped("%s", ui::with_font_subscripts(builder_.notice().text).c_str());
}

// "The best constant ambient for this view": the selected material's ka set so that ka·Ia is the
// mean indirect term over its hits in the image (fit_ambient at a quarter of the render's size,
// 4 samples a pixel: about a second on two cores for the Cornell box), one undo step.
void Sidebar::sidebar_ambient_fit() {
  const Scene& scene = s_.doc.scene();
  const int m = s_.selected_material;
  if (m < 0 || m >= static_cast<int>(scene.materials.size()) || !s_.schedule.snapshot()) return;
  const auto index = static_cast<std::size_t>(m);
  const auto fit_now = [&] {
    tools_.ambient_fit() = fit_ambient(*s_.schedule.snapshot(), std::max(1, s_.schedule.width() / 4),
                                          std::max(1, s_.schedule.height() / 4), 4, s_.render_settings.threads);
    tools_.ambient_fit_material() = scene.materials[index].name;
  };
  // The lecture's "ambient intensity of the scene": one Iₐ, ka as the materials give it.
  if (ImGui::Button("best I\xE2\x82\x90 for this view")) {
    fit_now();
    Scene whole = scene;
    whole.ambient = ui::tidy_color(tools_.ambient_fit()->fitted_ia);
    apply_edit(s_, {edit::SetScene{std::move(whole)}, false});
  }
  ui::locate("scene.fit_ia");
  ui::help_marker("Sets the scene's ambient intensity I\xE2\x82\x90 so that ka*I\xE2\x82\x90 (each material's own ka) is as "
                  "near as one colour can be to the indirect light arriving at every visible point. Show 'indirect - ambient' "
                  "to see what is left.");
  ImGui::SameLine();
  if (ImGui::Button("best ka")) {
    fit_now();
    if (tools_.ambient_fit()->hits[index] > 0) {
      Material fitted = scene.materials[index];
      fitted.ka = ui::tidy_color(tools_.ambient_fit()->fitted_ka[index]);
      apply_edit(s_, {edit::SetMaterial{m, fitted}, false});
    }
  }
  ui::locate("materials.fit_ka");
  ui::help_marker("Sets this material's ka (within 0..1, what a surface can reflect) so that ka*I\xE2\x82\x90 equals the indirect "
                  "light it receives, averaged over its hits in this view.");
  const auto& fit = tools_.ambient_fit();
  if (fit && tools_.ambient_fit_material() == scene.materials[index].name && index < fit->hits.size()) {
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
  int selected = s_.selected_object;
  ui::objects_panel(s_.doc.scene(), selected, builder_.mesh_path_field(), builder_.notice(), actions);
  if (selected != s_.selected_object) builder_.select_object(selected);
  if (actions.add != ObjectRef::Kind::kNone) builder_.add_object(actions.add, builder_.mesh_path_field());
  if (actions.duplicate >= 0) builder_.duplicate(actions.duplicate);
  if (actions.remove >= 0) builder_.delete_object(actions.remove);
  if (!actions.field.empty() && s_.selected_object >= 0) {
    builder_.set_object(s_.selected_object, actions.field, actions.values, actions.text);
  }
}

void Sidebar::sidebar_lights() {
  const Scene& scene = s_.session.scene();
  std::vector<Light> lights = scene.lights;
  if (!ui::lights_panel(lights, s_.selected_light, s_.solo)) return;
  // A new point light goes where the lecturer can see it and grab it: above and left of the
  // look-at point, in the view, at the look-at point's depth.
  if (lights.size() == scene.lights.size() + 1 && lights.back().type == LightType::kPoint) {
    const Camera view = view_camera(s_);
    const int w = std::max(1, static_cast<int>(std::lround(s_.viewport.width)));
    const int h = std::max(1, static_cast<int>(std::lround(s_.viewport.height)));
    const double depth = ui::view_depth(view, view.look_at);
    lights.back().position = ui::unproject(view, ui::ViewportPoint{0.3 * w, 0.2 * h}, depth, w, h);
  }
  // One light changed is that light's edit; a light added or removed, or a solo, the scene's.
  const int k = only_change(scene.lights, lights);
  Scene whole = scene;
  whole.lights = lights;
  const bool held = ImGui::IsAnyItemActive();
  apply_edit(s_, k >= 0 ? Edit{edit::SetLight{k, lights[static_cast<std::size_t>(k)]}, held} : Edit{edit::SetScene{whole}, held});
}

void Sidebar::sidebar_probe() {
  // In the sidebar itself, wrapped at its width: the wheel scrolls the panels, never a box inside.
  {
    ui::ProbeView view;
    view.scene = s_.schedule.snapshot() ? &s_.schedule.snapshot()->scene() : nullptr;
    view.probe = tools_.probe().tree ? &*tools_.probe().tree : nullptr;
    view.image_width = s_.schedule.width();
    view.image_height = s_.schedule.height();
    view.report = tools_.probe().report;
    view.occluders = tools_.probe().occluders;
    view.indirect = tools_.probe().tree ? &tools_.probe().indirect : nullptr;
    view.exposure_ev = s_.display.exposure_ev;
    view.cli_command = tools_.probe_cli_command();
    if (tools_.probe().tree) {
      const double gain = std::exp2(static_cast<double>(s_.display.exposure_ev));
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp(tools_.probe().tree->root.total[c] * gain, 0.0, 1.0);
        view.srgb[c] = s_.display.srgb ? linear_to_srgb8(v) : static_cast<unsigned char>(std::lround(v * 255));
      }
    }
    const bool digits_before = tools_.probe().every_digit;
    const int key[3] = {tools_.probe().x, tools_.probe().y, view.probe != nullptr ? 1 : 0};
    if (key[0] != probe_key_[0] || key[1] != probe_key_[1] || key[2] != probe_key_[2]) {
      probe_height_ = 0;
      std::copy(key, key + 3, probe_key_);
    }
    const float top = ImGui::GetCursorPosY();
    ui::probe_panel(view, tools_.probe().every_digit);
    const float height = ImGui::GetCursorPosY() - top;
    if (height < probe_height_) ImGui::Dummy(ImVec2(1, std::max(probe_height_ - height - ImGui::GetStyle().ItemSpacing.y, 0.0f)));
    probe_height_ = std::max(probe_height_, height);
    if (tools_.probe().every_digit != digits_before) tools_.refresh_probe();
  }
}

void Sidebar::sidebar_instruments() {
  ui::InstrumentActions actions;
  const ui::InstrumentSettings before = s_.instruments;
  if (ui::instruments_panel(s_.instruments, actions, tools_.compare().has_image(), s_.session.undo_count(),
                            s_.session.redo_count(), s_.figure_path, s_.figure_status)) {
    if (before.small_multiples != s_.instruments.small_multiples) s_.edits.settings = true;
    s_.upload_pending = s_.upload_pending || !s_.shown.pixels.empty();  // a compare view changed
  }
  if (actions.snapshot_a) tools_.snapshot_a();
  if (actions.undo) builder_.undo();
  if (actions.redo) builder_.redo();
  if (actions.save_figure) tools_.save_figure(s_.figure_path);
  if (actions.head_reference) {
    tools_.snapshot_a();
    s_.instruments.compare = 2;
    s_.upload_pending = s_.upload_pending || !s_.shown.pixels.empty();
  }
}

void Sidebar::sidebar_rays() {
  s_.rays.heat_map = s_.render_settings.term == Term::kRays;
  const ui::RayTreeSettings before = s_.rays;
  ui::RayTreeSummary summary;
  summary.probe = tools_.probe().tree ? &*tools_.probe().tree : nullptr;
  summary.scene_max_depth = s_.doc.scene().max_depth;
  summary.heat_max = s_.heat_max;
  if (ui::rays_panel(s_.rays, summary)) {
    if (before.depth_cut != s_.rays.depth_cut || (s_.rays.depth_cut && before.cut_depth != s_.rays.cut_depth)) {
      s_.edits.view = true;
    }
    if (before.heat_map != s_.rays.heat_map) tools_.set_heat_map(s_.rays.heat_map);
  }
}

void Sidebar::sidebar_camera() {
  ui::CameraActions actions;
  Camera camera = s_.session.scene().camera;
  if (ui::camera_panel(camera, actions, s_.camera_notice)) move_camera(s_, camera);
  s_.edits.frame_requested |= actions.frame_scene;
  s_.edits.reset_requested |= actions.reset;
  if (view_camera(s_).fov_y_deg != s_.doc.scene().camera.fov_y_deg) {
    ImGui::TextDisabled("Shown with fov y %.1f: the view is narrower than the scene's %dx%d image.",
                        view_camera(s_).fov_y_deg, s_.doc.scene().width, s_.doc.scene().height);
  }
}

void Sidebar::sidebar_file() {
  files_.file_state().source = s_.doc.source();
  files_.file_state().file_path = s_.doc.file_path();
  files_.file_state().dirty = s_.doc.dirty();
  files_.file_state().opened_mesh = s_.doc.opened_mesh();
  ui::SceneFileActions actions;
  ui::scene_file_panel(files_.file_state(), actions);
  if (actions.open) files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kOpen, files_.file_state().path_field});
  if (!actions.open_embedded.empty()) files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kOpen, actions.open_embedded});
  if (actions.save) files_.save_scene(false);
  if (actions.save_as) files_.save_scene(true);
  if (actions.reload) files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kReload, {}});
  if (actions.browse_open) files_.browser().open(false, s_.doc.file_path());
  if (actions.browse_save) files_.browser().open(true, s_.doc.file_path());
}

void Sidebar::sidebar_render() {
  Scene scene = s_.session.scene();
  if (ui::shading_settings_panel(scene)) apply_edit(s_, {edit::SetScene{std::move(scene)}, ImGui::IsAnyItemActive()});
  ImGui::Separator();
  const int hardware = resolve_thread_count(0);
  if (ui::render_settings_panel(s_.render_settings, hardware)) s_.edits.settings = true;
}

}  // namespace phonglab
