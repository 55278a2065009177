// What the previewer draws over the image: light markers, captions, the probe ring, the ray tree, legends and the stats line, laid out so that none covers another.
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

void Viewer::draw_overlays() {
  if (viewport_.width < 1 || viewport_.height < 1) return;
  const Scene& scene = doc_.scene();
  const float scale = platform_.ui_scale();
  const int view_w = static_cast<int>(std::lround(viewport_.width));
  const int view_h = static_cast<int>(std::lround(viewport_.height));

  std::vector<ui::LightMarker> markers;
  for (int i = 0; i < static_cast<int>(scene.lights.size()); ++i) {
    const Light& light = scene.lights[static_cast<std::size_t>(i)];
    if (light.type != LightType::kPoint) continue;
    const auto p = ui::project(scene.camera, light.position, view_w, view_h);
    if (!p) continue;  // behind the camera
    ui::LightMarker marker;
    const ImVec2 at(static_cast<float>(p->x), static_cast<float>(p->y));
    const float inset = 2.5f * ui::light_marker_radius(scale);
    const ImVec2 clamped(std::clamp(at.x, inset, std::max(inset, viewport_.width - inset)),
                         std::clamp(at.y, inset, std::max(inset, viewport_.height - inset)));
    if (clamped.x != at.x || clamped.y != at.y) {
      const float dx = at.x - clamped.x, dy = at.y - clamped.y;
      const float length = std::sqrt(dx * dx + dy * dy);
      marker.offscreen = true;
      marker.toward = ImVec2(dx / length, dy / length);
    }
    marker.pos = ImVec2(viewport_.x + clamped.x, viewport_.y + clamped.y);
    const double m = std::max(max_channel(light.intensity), 1e-9);
    marker.color = ImVec4(static_cast<float>(light.intensity.x / m), static_cast<float>(light.intensity.y / m),
                          static_cast<float>(light.intensity.z / m), 1.0f);
    marker.enabled = light.enabled;
    marker.selected = i == selected_light_;
    marker.hovered = i == hovered_light_ || (drag_.mode == DragMode::kLight && drag_.light == i);
    marker.index = i;
    markers.push_back(marker);
  }
  ui::draw_light_markers(markers, ui::light_marker_radius(scale));
  if (hovered_light_ >= 0) ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);

  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const bool multiples = instruments_.small_multiples;
  const int columns = multiples ? kMultiplesColumns : 1;
  const int rows = multiples ? kMultiplesRows : 1;
  const float cell_w = viewport_.width / static_cast<float>(columns);
  const float cell_h = viewport_.height / static_cast<float>(rows);
  if (multiples) {
    for (int cell = 0; cell < columns * rows; ++cell) {
      const ImVec2 at(viewport_.x + static_cast<float>(cell % columns) * cell_w + 4 * scale,
                      viewport_.y + static_cast<float>(cell / columns) * cell_h + cell_h - ImGui::GetFontSize() - 4 * scale);
      const std::string_view label = figure_label(cell < kTermCells ? kCellTerms[static_cast<std::size_t>(cell)] : Term::kFull);
      draw->AddText(at, IM_COL32(255, 255, 255, 230), label.data(), label.data() + label.size());
    }
  }
  // The probed pixel: a ring with a gap in every cell, so the term images can be compared there.
  if (probe_ && render_width_ > 0 && render_height_ > 0) {
    for (int cell = 0; cell < columns * rows; ++cell) {
      const float x = viewport_.x + static_cast<float>(cell % columns) * cell_w +
                      (static_cast<float>(probe_x_) + 0.5f) / static_cast<float>(render_width_) * cell_w;
      const float y = viewport_.y + static_cast<float>(cell / columns) * cell_h +
                      (static_cast<float>(probe_y_) + 0.5f) / static_cast<float>(render_height_) * cell_h;
      const float r = 6 * scale;
      draw->AddCircle(ImVec2(x, y), r, IM_COL32(0, 0, 0, 255), 20, 3 * scale);
      draw->AddCircle(ImVec2(x, y), r, IM_COL32(255, 230, 0, 255), 20, 1.5f * scale);
      draw->AddLine(ImVec2(x - 2.2f * r, y), ImVec2(x - r, y), IM_COL32(255, 230, 0, 255), 1.5f * scale);
      draw->AddLine(ImVec2(x + r, y), ImVec2(x + 2.2f * r, y), IM_COL32(255, 230, 0, 255), 1.5f * scale);
      draw->AddLine(ImVec2(x, y - 2.2f * r), ImVec2(x, y - r), IM_COL32(255, 230, 0, 255), 1.5f * scale);
      draw->AddLine(ImVec2(x, y + r), ImVec2(x, y + 2.2f * r), IM_COL32(255, 230, 0, 255), 1.5f * scale);
    }
  }
  // The depth cut is a way of looking: say so on the image, at the top centre.
  if (snapshot_ && rays_.depth_cut) {
    char caption[96];
    std::snprintf(caption, sizeof caption, "recursion cut at depth %d (scene max depth %d)", snapshot_->max_depth,
                  doc_.scene().max_depth);
    const ImVec2 size = ImGui::CalcTextSize(caption);
    const ImVec2 at(viewport_.x + (viewport_.width - size.x) / 2, viewport_.y + 8 * scale);
    draw->AddRectFilled(ImVec2(at.x - 6 * scale, at.y - 3 * scale), ImVec2(at.x + size.x + 6 * scale, at.y + size.y + 3 * scale),
                        IM_COL32(0, 0, 0, 170), 4 * scale);
    draw->AddText(at, IM_COL32(255, 255, 255, 240), caption);
  }
  // The ray tree over the full image: the only cell, or the last of the small multiples.
  tree_segments_.clear();
  const int full_cell = columns * rows - 1;
  draw_ray_tree_overlay(viewport_.x + static_cast<float>(full_cell % columns) * cell_w,
                        viewport_.y + static_cast<float>(full_cell / columns) * cell_h, cell_w, cell_h);
  if (heat_shown() && heat_max_ > 0) {
    ImGui::SetNextWindowPos(ImVec2(viewport_.x + viewport_.width - 8 * scale, viewport_.y + viewport_.height - 8 * scale),
                            ImGuiCond_Always, ImVec2(1, 1));
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("##heat_legend", nullptr, flags)) ui::heat_legend(heat_max_, 220 * scale);
    ImGui::End();
  }
  if (instruments_.compare == 1 && !image_a_.pixels.empty()) {
    const float x = viewport_.x + instruments_.wipe * cell_w + static_cast<float>(columns - 1) * cell_w;
    const float y0 = viewport_.y + static_cast<float>(rows - 1) * cell_h;
    draw->AddLine(ImVec2(x, y0), ImVec2(x, y0 + cell_h), IM_COL32(255, 255, 255, 200), 2 * scale);
    draw->AddText(ImVec2(x - ImGui::CalcTextSize("A ").x, y0 + cell_h / 2), IM_COL32(255, 255, 255, 230), "A");
  }

  // "Move your head": the highlight against the head angle, in a small window at the
  // viewport's bottom-left (visible however the panels are scrolled).
  if (instruments_.move_head && snapshot_) {
    ui::HeadPlotView plot;
    plot.hit = probe_ ? &probe_->root : nullptr;
    plot.eye_at_zero = snapshot_->camera.position;
    plot.axis = glm::normalize(make_camera_frame(snapshot_->camera, 1, 1).up);
    if (probe_ && probe_->root.hit && probe_->root.material >= 0 &&
        probe_->root.material < static_cast<int>(snapshot_->materials.size())) {
      plot.shininess = snapshot_->materials[static_cast<std::size_t>(probe_->root.material)].n;
    }
    plot.blinn = snapshot_->specular_model == SpecularModel::kBlinn;
    plot.angle_deg = instruments_.head_angle_deg;
    plot.width = 340 * scale;
    ImGui::SetNextWindowPos(ImVec2(viewport_.x + 8 * scale, viewport_.y + viewport_.height - 8 * scale), ImGuiCond_Always,
                            ImVec2(0, 1));
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("##head_plot", nullptr, flags)) ui::head_plot(plot);
    ImGui::End();
  }

  if (display_.show_stats) {
    const ProgressiveStatus status = renderer_.status();
    ui::StatsView stats;
    double sum = 0, slowest = 0;
    for (const auto& [start, seconds] : frame_times_) {
      sum += seconds;
      slowest = std::max(slowest, seconds);
    }
    stats.ui_frame_ms = frame_times_.empty() ? 0 : sum / static_cast<double>(frame_times_.size()) * 1e3;
    stats.ui_frame_max_ms = slowest * 1e3;
    stats.edit_to_image_ms = last_latency_ms_;
    stats.have_frame = !shown_.pixels.empty();
    stats.level_divisor = shown_.divisor;
    stats.image_width = shown_.width;
    stats.image_height = shown_.height;
    stats.spp = shown_.spp;
    stats.target_spp = render_settings_.target_spp;
    stats.frame = shown_.stats;
    stats.idle = status.idle;
    stats.interacting = interacting_ || edited_while_active_;
    stats.scene_error = file_state_.error_text;
    ui::stats_overlay(stats, ImVec2(viewport_.x + 8 * scale, viewport_.y + 8 * scale));
  }
  if (shown_.pixels.empty()) {
    const char* text = "rendering...";
    const ImVec2 size = ImGui::CalcTextSize(text);
    ImGui::GetBackgroundDrawList()->AddText(
        ImVec2(viewport_.x + (viewport_.width - size.x) / 2, viewport_.y + (viewport_.height - size.y) / 2),
        IM_COL32(200, 200, 200, 255), text);
  }
}

void Viewer::draw_ray_tree_overlay(float cell_x, float cell_y, float cell_w, float cell_h) {
  if (!probe_ || !rays_.overlay || !snapshot_ || render_width_ <= 0 || render_height_ <= 0) return;
  RayTreeViewOptions options;
  options.shadow_rays = rays_.shadow_rays;
  options.secondary_rays = rays_.secondary_rays;
  options.arrows = rays_.arrows;
  // The probe was taken in snapshot_ at the render size: project with that camera and size.
  const CameraFrame frame = make_camera_frame(snapshot_->camera, render_width_, render_height_);
  tree_segments_ = project_ray_tree(frame, ray_tree_segments(*snapshot_, probe_->root, options),
                                    ray_tree_near(*snapshot_, probe_->root));
  int lit_lights = 0;
  for (const ProbeLight& light : probe_->root.lights) lit_lights += light.lit_side ? 1 : 0;
  const float scale = platform_.ui_scale();
  const ui::ImageRect rect{ImVec2(cell_x, cell_y), ImVec2(cell_w / static_cast<float>(render_width_),
                                                          cell_h / static_cast<float>(render_height_))};
  const bool blinn = snapshot_->specular_model == SpecularModel::kBlinn;
  ui::draw_ray_tree(ImGui::GetBackgroundDrawList(), tree_segments_, rect, scale, blinn, lit_lights);
  if (!rays_.legend) return;
  ImGui::SetNextWindowPos(ImVec2(viewport_.x + viewport_.width - 8 * scale, viewport_.y + 8 * scale), ImGuiCond_Always,
                          ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.75f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##ray_tree_legend", nullptr, flags)) ui::ray_tree_legend(tree_segments_, blinn);
  ImGui::End();
}

}  // namespace phonglab
