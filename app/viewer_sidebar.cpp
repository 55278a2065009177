// The previewer's sidebar: the panels in the order a lecture uses them, and what their edits request.
#include "app/viewer_app.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <backends/imgui_impl_opengl3.h>

#include "renderer/camera.h"
#include "renderer/figure.h"
#include "renderer/geometry.h"
#include "renderer/heat_map.h"
#include "renderer/image_io.h"
#include "renderer/probe_report.h"
#include "renderer/ray_tree_view.h"
#include "renderer/shading.h"
#include "ui/camera_control.h"


namespace phonglab {

void Viewer::draw_sidebar() {
  if (!sidebar_visible_) return;
  const ImGuiIO& io = ImGui::GetIO();
  const float width = io.DisplaySize.x - viewport_.width;
  if (width < 1 || io.DisplaySize.y < 1) return;
  ImGui::SetNextWindowPos(ImVec2(viewport_.width, 0));
  ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoFocusOnAppearing;
  if (ImGui::Begin("##sidebar", nullptr, flags)) {
    ImGui::Text("phonglab %s", PHONGLAB_VERSION);
    ImGui::SameLine();
    ImGui::TextDisabled(" H hides the panels");
    // Labels sit right of the widgets; leave them room.
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 6.5f);
    Scene& scene = doc_.scene();

    if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) {
      file_state_.source = doc_.source();
      file_state_.file_path = doc_.file_path();
      file_state_.dirty = doc_.dirty();
      ui::SceneFileActions actions;
      ui::scene_file_panel(file_state_, actions);
      if (actions.open) request(PendingAction{PendingAction::Kind::kOpen, file_state_.path_field});
      if (!actions.open_embedded.empty()) request(PendingAction{PendingAction::Kind::kOpen, actions.open_embedded});
      if (actions.save) save_scene(false);
      if (actions.save_as) save_scene(true);
      if (actions.reload) request(PendingAction{PendingAction::Kind::kReload, {}});
    }
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
      ui::CameraActions actions;
      if (ui::camera_panel(scene.camera, actions)) camera_changed_ = true;
      frame_requested_ |= actions.frame_scene;
      reset_requested_ |= actions.reset;
    }
    if (open_materials_) {
      ImGui::SetNextItemOpen(true);
      open_materials_ = false;
    }
    if (ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (picked_text_.empty()) ImGui::TextDisabled("Click an object in the view to select its material.");
      else ImGui::TextDisabled("Clicked: %s", picked_text_.c_str());
      if (ui::materials_panel(scene.materials, selected_material_, scene.specular_model)) scene_edited_ = true;
    }
    if (ImGui::CollapsingHeader("Lights")) {
      if (ui::lights_panel(scene.lights, selected_light_, solo_)) scene_edited_ = true;
    }
    if (ImGui::CollapsingHeader("Instruments", ImGuiTreeNodeFlags_DefaultOpen)) {
      ui::InstrumentActions actions;
      const ui::InstrumentSettings before = instruments_;
      if (ui::instruments_panel(instruments_, actions, !image_a_.pixels.empty(), history_.undo_count(),
                                history_.redo_count(), figure_path_, figure_status_)) {
        if (before.small_multiples != instruments_.small_multiples) settings_changed_ = true;
        upload_pending_ = upload_pending_ || !shown_.pixels.empty();  // a compare view changed
      }
      if (actions.snapshot_a) snapshot_a();
      if (actions.undo) undo();
      if (actions.redo) redo();
      if (actions.save_figure) save_figure(figure_path_);
      if (actions.head_reference) {
        snapshot_a();
        instruments_.compare = 2;
        upload_pending_ = upload_pending_ || !shown_.pixels.empty();
      }
    }
    if (ImGui::CollapsingHeader("Rays: tree, depth cut, heat map", ImGuiTreeNodeFlags_DefaultOpen)) {
      rays_.heat_map = render_settings_.term == Term::kRays;
      const ui::RayTreeSettings before = rays_;
      ui::RayTreeSummary summary;
      summary.probe = probe_ ? &*probe_ : nullptr;
      summary.scene_max_depth = scene.max_depth;
      summary.heat_max = heat_max_;
      if (ui::rays_panel(rays_, summary)) {
        if (before.depth_cut != rays_.depth_cut || (rays_.depth_cut && before.cut_depth != rays_.cut_depth)) {
          view_changed_ = true;
        }
        if (before.heat_map != rays_.heat_map) set_heat_map(rays_.heat_map);
      }
    }
    if (probe_ && ImGui::CollapsingHeader("Probe", ImGuiTreeNodeFlags_DefaultOpen)) {
      ui::ProbeView view;
      view.scene = snapshot_.get();
      view.probe = &*probe_;
      view.image_width = render_width_;
      view.image_height = render_height_;
      view.report = probe_report_;
      view.occluders = probe_occluders_;
      view.exposure_ev = display_.exposure_ev;
      const double gain = std::exp2(static_cast<double>(display_.exposure_ev));
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp(probe_->root.total[c] * gain, 0.0, 1.0);
        view.srgb[c] = display_.srgb ? linear_to_srgb8(v) : static_cast<unsigned char>(std::lround(v * 255));
      }
      ui::probe_panel(view);
    }
    if (ImGui::CollapsingHeader("Render")) {
      if (ui::shading_settings_panel(scene)) scene_edited_ = true;
      ImGui::Separator();
      const int hardware = resolve_thread_count(0);
      if (ui::render_settings_panel(render_settings_, hardware)) settings_changed_ = true;
    }
    if (ImGui::CollapsingHeader("Display") && ui::display_panel(display_)) platform_.set_user_scale(display_.ui_size);
    if (ImGui::CollapsingHeader("Screenshot")) {
      ui::ScreenshotActions actions;
      ui::screenshot_panel(screenshot_state_, actions);
      if (actions.save_png) save_png(screenshot_state_.png_path);
      if (actions.save_pfm) save_pfm(screenshot_state_.pfm_path);
    }
    ImGui::PopItemWidth();
  }
  ImGui::End();
  // While a slider is held, each tick is an edit: keep the renderer at coarse levels.
  if (!ImGui::IsAnyItemActive()) edited_while_active_ = false;
  else if (scene_edited_ || camera_changed_) edited_while_active_ = true;
}

}  // namespace phonglab
