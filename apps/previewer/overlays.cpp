// What the previewer draws over the image: the stats line, legends, captions, the probe ring,
// the ray tree and the light markers. Boxes are laid out first; captions, arrows and labels then
// take places that no box holds, so nothing covers anything else, and every text sits on a dark
// plate so it reads on any image.
#include "apps/previewer/overlays.h"

#include "apps/previewer/viewer_app.h"
#include "interaction/scene_objects.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "core/scene/camera.h"
#include "io/figure.h"
#include "core/teaching/heat_map.h"
#include "core/teaching/ray_tree_view.h"
#include "interaction/camera_control.h"

namespace phonglab {

namespace {

constexpr ImGuiWindowFlags kOverlayFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                           ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                           ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoMove;
constexpr float kOverlayAlpha = 0.72f;  // boxes over the image: readable, the image still shows through

// The lowest bottom of the boxes `r` overlaps, or nothing.
std::optional<float> blocked_until(const ui::ScreenRect& r, const std::vector<ui::ScreenRect>& taken) {
  std::optional<float> bottom;
  for (const ui::ScreenRect& t : taken) {
    if (ui::overlaps(r, t)) bottom = std::max(bottom.value_or(t.max.y), t.max.y);
  }
  return bottom;
}

// A small overlay window anchored at `pos` (`pivot` (0, 0) top-left ... (1, 1) bottom-right) and
// returns where it was drawn. With the size it had last frame it is first moved clear of the
// boxes already `taken`: down when it hangs from the top, up when it stands on the bottom.
template <typename Contents>
ui::ScreenRect overlay_window(const char* id, ImVec2 pos, ImVec2 pivot, const std::vector<ui::ScreenRect>& taken,
                              const std::map<std::string, ui::ScreenRect>& last_rects,
                              std::map<std::string, ui::ScreenRect>& drawn, Contents contents, float alpha = kOverlayAlpha) {
  if (const auto it = last_rects.find(id); it != last_rects.end()) {
    const ImVec2 size = ui::size_of(it->second);
    const float gap = 4;
    for (int tries = 0; tries < 8; ++tries) {
      const ui::ScreenRect r = ui::rect_at(pos, pivot, size);
      bool moved = false;
      for (const ui::ScreenRect& t : taken) {
        if (!ui::overlaps(r, t)) continue;
        pos.y = pivot.y < 0.5f ? t.max.y + gap : t.min.y - gap;
        moved = true;
        break;
      }
      if (!moved) break;
    }
  }
  ImGui::SetNextWindowPos(pos, ImGuiCond_Always, pivot);
  ImGui::SetNextWindowBgAlpha(alpha);
  ui::ScreenRect rect;
  if (ImGui::Begin(id, nullptr, kOverlayFlags)) {
    contents();
    rect = ui::rect_at(ImGui::GetWindowPos(), ImVec2(0, 0), ImGui::GetWindowSize());
    drawn[id] = rect;
  }
  ImGui::End();
  return rect;
}

}  // namespace

void Overlays::draw_overlays() {
  s_.markers.clear();
  // Last frame's boxes give the sizes for this frame's layout; this frame's replace them (so
  // dump_state lists the boxes on screen).
  const std::map<std::string, ui::ScreenRect> last = std::move(s_.overlay_rects);
  s_.overlay_rects.clear();
  if (s_.viewport.width < 1 || s_.viewport.height < 1) return;
  const float scale = s_.platform.ui_scale();
  const float margin = 8 * scale;
  std::vector<ui::ScreenRect> taken;  // boxes and captions placed so far
  const ImVec2 top_left(s_.viewport.x + margin, s_.viewport.y + margin);
  const ImVec2 top_right(s_.viewport.x + s_.viewport.width - margin, s_.viewport.y + margin);
  // A lesson's caption takes the bottom of the view: the bottom boxes sit above it.
  float bottom_y = s_.viewport.y + s_.viewport.height - margin;
  if (const auto it = last.find("##lesson_caption"); it != last.end() && s_.lessons.lesson()) bottom_y = it->second.min.y - margin;
  const ImVec2 bottom_left(s_.viewport.x + margin, bottom_y);
  const ImVec2 bottom_right(s_.viewport.x + s_.viewport.width - margin, bottom_y);

  // Corner boxes: stats top left, the ray-tree legend top right, the head plot bottom left (top
  // left when presenting), the heat scale bottom right.
  if (s_.display.show_stats && !lesson_shell_.state().presenting) {
    taken.push_back(overlay_window("##stats", top_left, ImVec2(0, 0), taken, last, s_.overlay_rects, [&] { draw_stats(); }));
  }
  draw_ray_tree_lines();
  if (tools_.probe().tree && s_.rays.overlay && s_.rays.legend && !s_.tree_segments.empty()) {
    const bool blinn = s_.schedule.snapshot() && s_.schedule.snapshot()->scene().specular_model == SpecularModel::kBlinn;
    // The legend must not hide the tree it explains: top right, unless the probed point is there,
    // then bottom right, then bottom left.
    ImVec2 anchor = top_right, pivot(1, 0);
    if (const auto it = last.find("##ray_tree_legend"); it != last.end() && s_.schedule.width() > 0 && s_.schedule.height() > 0) {
      const ImVec2 size = ui::size_of(it->second);
      const ImVec2 hit = probe_point_in_cell(cells(s_).count() - 1);
      const float keep = 40 * scale;  // the ring and the N, L, R, V arrows around it
      const ui::ScreenRect around{ImVec2(hit.x - keep, hit.y - keep), ImVec2(hit.x + keep, hit.y + keep)};
      const std::array<std::pair<ImVec2, ImVec2>, 3> places = {
          std::pair{top_right, ImVec2(1, 0)}, std::pair{bottom_right, ImVec2(1, 1)}, std::pair{bottom_left, ImVec2(0, 1)}};
      for (const auto& [at, pv] : places) {
        const ui::ScreenRect r = ui::rect_at(at, pv, size);
        if (!ui::overlaps(r, around) && !blocked_until(r, taken)) {
          anchor = at;
          pivot = pv;
          break;
        }
      }
    }
    taken.push_back(overlay_window("##ray_tree_legend", anchor, pivot, taken, last, s_.overlay_rects,
                                   [&] { ui::ray_tree_legend(s_.tree_segments, blinn); }));
  }
  if (s_.instruments.move_head && s_.schedule.snapshot()) {
    // In presenter mode (no stats box) top left: the large caption leaves the bottom little room.
    const bool top = lesson_shell_.state().presenting;
    taken.push_back(overlay_window("##head_plot", top ? top_left : bottom_left, ImVec2(0, top ? 0.0f : 1.0f), taken, last,
                                   s_.overlay_rects, [&] { draw_head_plot(); }));
  }
  if (tools_.heat_shown() && s_.heat_max > 0) {
    taken.push_back(overlay_window("##heat_legend", bottom_right, ImVec2(1, 1), taken, last, s_.overlay_rects,
                                   [&] { ui::heat_legend(s_.heat_max, 220 * scale); }));
  } else if (tools_.ambient_view_pixels_shown(ui::AmbientView::kDifference)) {
    taken.push_back(overlay_window("##gap_legend", bottom_right, ImVec2(1, 1), taken, last, s_.overlay_rects,
                                   [&] { ui::ambient_gap_legend(kAmbientGapScale, 220 * scale); }));
  }

  // Captions at the top centre, each below whatever box it would overlap.
  float y = s_.viewport.y + margin;
  const float wrap = std::max(s_.viewport.width - 4 * margin, 1.0f);  // a caption never leaves the view
  for (const std::string& text : captions()) {
    const ImVec2 size = ImGui::CalcTextSize(text.c_str(), nullptr, false, wrap);
    const float pad = 5 * scale;
    ui::ScreenRect r{ImVec2(s_.viewport.x + (s_.viewport.width - size.x) / 2 - pad, y),
                     ImVec2(s_.viewport.x + (s_.viewport.width + size.x) / 2 + pad, y + size.y + 2 * pad)};
    while (const std::optional<float> bottom = blocked_until(r, taken)) {
      const float shift = *bottom + 4 * scale - r.min.y;
      r.min.y += shift;
      r.max.y += shift;
    }
    ui::text_on_plate(ImGui::GetBackgroundDrawList(), ImVec2(r.min.x + pad, r.min.y + pad), text.c_str(), scale, 0.75f,
                      wrap);
    taken.push_back(r);
    y = r.max.y + 4 * scale;
  }
  draw_cell_labels_and_probe_ring();
  lesson_shell_.draw_lesson_caption();
  draw_wipe_line();
  if (light_markers_shown()) draw_light_markers(taken);
  draw_selected_object();
  if (s_.hovered_light >= 0) ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);

  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  if (s_.shown.pixels.empty()) {
    const char* text = "rendering...";
    const ImVec2 size = ImGui::CalcTextSize(text);
    ui::text_on_plate(draw, ImVec2(s_.viewport.x + (s_.viewport.width - size.x) / 2, s_.viewport.y + (s_.viewport.height - size.y) / 2),
                      text, scale);
  }
  if (!s_.sidebar_visible && !s_.lessons.lesson()) {
    // With the panels hidden, say how to get them back (bottom centre, clear of the corner boxes).
    const char* text = "H shows the panels  \xC2\xB7  F1 keys";
    const ImVec2 size = ImGui::CalcTextSize(text);
    ui::text_on_plate(draw, ImVec2(s_.viewport.x + (s_.viewport.width - size.x) / 2, bottom_left.y - size.y - 4 * scale),
                      text, scale, 0.55f);
  }
  if (s_.help_visible) {
    // Over everything else, on purpose: it is asked for, and Esc closes it.
    overlay_window("##keys", ImVec2(s_.viewport.x + s_.viewport.width / 2, s_.viewport.y + s_.viewport.height / 2),
                   ImVec2(0.5f, 0.5f), {}, last, s_.overlay_rects, [] { ui::keys_help(); }, 0.94f);
  }
}

std::vector<std::string> Overlays::captions() const {
  std::vector<std::string> lines;
  const bool blinn = s_.doc.scene().specular_model == SpecularModel::kBlinn;
  // What is on screen, when it is not the whole image: a projected slide must say so.
  const std::string ambient = ui::ambient_view_caption(s_.render_settings.ambient_view);
  if (!ambient.empty()) {
    lines.push_back(ambient);
  } else if (!s_.instruments.small_multiples && s_.render_settings.term != Term::kFull && !tools_.heat_shown()) {
    lines.push_back(ui::term_caption(s_.render_settings.term, blinn));
  }
  if (s_.schedule.snapshot() && s_.rays.depth_cut) {
    char caption[96];
    std::snprintf(caption, sizeof caption, "recursion cut at depth %d (scene max depth %d)", s_.schedule.snapshot()->scene().max_depth,
                  s_.doc.scene().max_depth);
    lines.emplace_back(caption);
  }
  if (s_.instruments.compare != 0) lines.push_back(tools_.compare_caption());
  return lines;
}

void Overlays::draw_stats() {
  const ProgressiveStatus status = s_.renderer.status();
  ui::StatsView stats;
  double sum = 0, slowest = 0;
  for (const auto& [start, seconds] : s_.stats.frame_times) {
    sum += seconds;
    slowest = std::max(slowest, seconds);
  }
  stats.ui_frame_ms = s_.stats.frame_times.empty() ? -1 : sum / static_cast<double>(s_.stats.frame_times.size()) * 1e3;
  stats.ui_frame_max_ms = slowest * 1e3;
  stats.edit_to_image_ms = s_.stats.last_latency_ms;
  stats.have_frame = !s_.shown.pixels.empty();
  stats.level_divisor = s_.shown.divisor;
  stats.level_quads = s_.shown.quads;
  stats.image_width = s_.shown.width;
  stats.image_height = s_.shown.height;
  stats.spp = s_.shown.spp;
  stats.target_spp = tools_.target_spp();
  stats.frame = s_.shown.stats;
  stats.idle = status.idle;
  stats.interacting = s_.interacting || s_.edits.while_active;
  stats.scene_error = files_.file_state().error_text;
  stats.details = s_.display.stats_details;
  ui::stats_overlay(stats);
}

void Overlays::draw_head_plot() {
  // "Move your head": the highlight against the head angle.
  ui::HeadPlotView plot;
  plot.hit = tools_.probe().tree ? &tools_.probe().tree->root : nullptr;
  plot.eye_at_zero = s_.schedule.snapshot()->scene().camera.position;
  plot.axis = glm::normalize(make_camera_frame(s_.schedule.snapshot()->scene().camera, 1, 1).up);
  if (tools_.probe().tree && tools_.probe().tree->root.hit && tools_.probe().tree->root.material >= 0 &&
      tools_.probe().tree->root.material < static_cast<int>(s_.schedule.snapshot()->scene().materials.size())) {
    plot.shininess = s_.schedule.snapshot()->scene().materials[static_cast<std::size_t>(tools_.probe().tree->root.material)].n;
  }
  plot.blinn = s_.schedule.snapshot()->scene().specular_model == SpecularModel::kBlinn;
  plot.angle_deg = s_.instruments.head_angle_deg;
  plot.width = 340 * s_.platform.ui_scale();
  ui::head_plot(plot);
}

ImVec2 Overlays::probe_point_in_cell(int cell) const {
  // The probed pixel's centre as cell `cell` shows it.
  const Cells c = cells(s_);
  const ImVec2 origin = c.origin(cell);
  return ImVec2(origin.x + (static_cast<float>(tools_.probe().x) + 0.5f) / static_cast<float>(std::max(s_.schedule.width(), 1)) * c.width,
                origin.y + (static_cast<float>(tools_.probe().y) + 0.5f) / static_cast<float>(std::max(s_.schedule.height(), 1)) * c.height);
}

void Overlays::draw_cell_labels_and_probe_ring() {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const float scale = s_.platform.ui_scale();
  const Cells c = cells(s_);
  if (s_.instruments.small_multiples) {
    const bool blinn = s_.doc.scene().specular_model == SpecularModel::kBlinn;
    for (int cell = 0; cell < c.count(); ++cell) {
      const Term term = cell < kTermCells ? kCellTerms[static_cast<std::size_t>(cell)] : Term::kFull;
      const std::string label = ui::term_caption(term, blinn);
      const ImVec2 origin = c.origin(cell);
      ui::text_on_plate(draw, ImVec2(origin.x + 6 * scale, origin.y + c.height - ImGui::GetFontSize() - 8 * scale),
                        label.c_str(), scale);
    }
  }
  // The probed pixel: a ring with a gap in every cell, so the term images can be compared there.
  if (!tools_.probe().tree || s_.schedule.width() <= 0 || s_.schedule.height() <= 0) return;
  for (int cell = 0; cell < c.count(); ++cell) ui::draw_probe_ring(draw, probe_point_in_cell(cell), scale);
}

std::optional<float> Overlays::wipe_line_x() const {
  if (tools_.ambient_view_pixels_shown(ui::AmbientView::kBeside)) return s_.viewport.x + s_.instruments.wipe * s_.viewport.width;
  if (s_.instruments.compare != 1 || !tools_.a_comparable() || s_.instruments.small_multiples) return std::nullopt;
  // compare_pixels shows A left of column wipe * width: the line is drawn at that edge.
  return s_.viewport.x + s_.instruments.wipe * s_.viewport.width;
}

void Overlays::draw_wipe_line() {
  const std::optional<float> x = wipe_line_x();
  if (!x) return;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const float scale = s_.platform.ui_scale();
  const float top = s_.viewport.y, bottom = s_.viewport.y + s_.viewport.height, mid = (top + bottom) / 2;
  draw->AddLine(ImVec2(*x, top), ImVec2(*x, bottom), IM_COL32(0, 0, 0, 160), 4 * scale);
  draw->AddLine(ImVec2(*x, top), ImVec2(*x, bottom), IM_COL32(255, 255, 255, 230), 2 * scale);
  // A handle in the middle, with arrows: it can be dragged.
  const float r = 1.5f * ui::light_marker_radius(scale);
  draw->AddCircleFilled(ImVec2(*x, mid), r, IM_COL32(255, 255, 255, 230));
  draw->AddCircle(ImVec2(*x, mid), r, IM_COL32(0, 0, 0, 200), 0, 1.5f * scale);
  const ImU32 arrow = IM_COL32(40, 40, 40, 255);
  const float a = r * 0.55f;
  draw->AddTriangleFilled(ImVec2(*x - a * 1.6f, mid), ImVec2(*x - a * 0.4f, mid - a), ImVec2(*x - a * 0.4f, mid + a), arrow);
  draw->AddTriangleFilled(ImVec2(*x + a * 1.6f, mid), ImVec2(*x + a * 0.4f, mid + a), ImVec2(*x + a * 0.4f, mid - a), arrow);
  const bool ambient = tools_.ambient_view_pixels_shown(ui::AmbientView::kBeside);
  const std::string left = ambient ? "ka\xC2\xB7" + ui::i_a() : "A";
  const char* right = ambient ? "indirect" : "live";
  ui::text_on_plate(draw, ImVec2(*x - ImGui::CalcTextSize(left.c_str()).x - 10 * scale, mid + r + 6 * scale), left.c_str(),
                    scale);
  ui::text_on_plate(draw, ImVec2(*x + 8 * scale, mid + r + 6 * scale), right, scale);
}

bool Overlays::light_markers_shown() const {
  // Hidden by the Display toggle, over the small multiples (the markers belong to the one full
  // view), and where a lesson's step asks where the lights are (until exploring).
  if (!s_.display.light_markers || s_.instruments.small_multiples) return false;
  return !s_.lessons.lesson() || s_.lessons.view().light_markers || s_.lessons.exploring();
}

void Overlays::draw_light_markers(const std::vector<ui::ScreenRect>& taken) {
  const Scene& scene = s_.doc.scene();
  const Camera view = view_camera(s_);
  const float scale = s_.platform.ui_scale();
  const float radius = ui::light_marker_radius(scale);
  const int view_w = static_cast<int>(std::lround(s_.viewport.width));
  const int view_h = static_cast<int>(std::lround(s_.viewport.height));
  const ImVec2 lo(s_.viewport.x, s_.viewport.y);
  const ImVec2 hi(s_.viewport.x + s_.viewport.width, s_.viewport.y + s_.viewport.height);
  std::vector<ui::ScreenRect> occupied = taken;
  for (int i = 0; i < static_cast<int>(scene.lights.size()); ++i) {
    const Light& light = scene.lights[static_cast<std::size_t>(i)];
    if (light.type != LightType::kPoint) continue;
    const auto p = ui::project(view, light.position, view_w, view_h);
    if (!p) continue;  // behind the camera
    ui::LightMarker marker;
    const ImVec2 at(s_.viewport.x + static_cast<float>(p->x), s_.viewport.y + static_cast<float>(p->y));
    const float inset = 2.5f * radius;
    marker.pos = ImVec2(std::clamp(at.x, lo.x + inset, std::max(lo.x + inset, hi.x - inset)),
                        std::clamp(at.y, lo.y + inset, std::max(lo.y + inset, hi.y - inset)));
    if (marker.pos.x != at.x || marker.pos.y != at.y) {
      const float dx = at.x - marker.pos.x, dy = at.y - marker.pos.y;
      const float length = std::sqrt(dx * dx + dy * dy);
      marker.offscreen = true;
      marker.toward = ImVec2(dx / length, dy / length);
      // An arrow at the edge that a box covers slides along the edge until it is clear.
      marker.pos = ui::slide_clear(marker.pos, inset, occupied, lo, hi);
    }
    const double m = std::max(max_channel(light.intensity), 1e-9);
    marker.color = ImVec4(static_cast<float>(light.intensity.x / m), static_cast<float>(light.intensity.y / m),
                          static_cast<float>(light.intensity.z / m), 1.0f);
    marker.enabled = light.enabled;
    marker.selected = i == s_.selected_light;
    marker.hovered = i == s_.hovered_light || (s_.drag.mode == DragMode::kLight && s_.drag.light == i);
    marker.index = i;
    occupied.push_back(ui::ScreenRect{ImVec2(marker.pos.x - inset, marker.pos.y - inset),
                                      ImVec2(marker.pos.x + inset, marker.pos.y + inset)});
    s_.markers.push_back(marker);
  }
  // Labels last: each at the first place beside its marker that no box, marker or label holds.
  for (ui::LightMarker& marker : s_.markers) {
    marker.label_pos = ui::place_label(marker, radius, occupied, lo, hi);
    const ImVec2 size = ImGui::CalcTextSize("L00");
    occupied.push_back(ui::ScreenRect{marker.label_pos, ImVec2(marker.label_pos.x + size.x, marker.label_pos.y + size.y)});
  }
  ui::draw_light_markers(s_.markers, radius, scale);
}

void Overlays::draw_ray_tree_lines() {
  // The ray tree over the full image: the only cell, or the last of the small multiples.
  s_.tree_segments.clear();
  if (!tools_.probe().tree || !s_.rays.overlay || !s_.schedule.snapshot() || s_.schedule.width() <= 0 || s_.schedule.height() <= 0) return;
  const Cells c = cells(s_);
  const ImVec2 full_cell = c.origin(c.count() - 1);
  RayTreeViewOptions options;
  options.shadow_rays = s_.rays.shadow_rays;
  options.secondary_rays = s_.rays.secondary_rays;
  options.arrows = s_.rays.arrows;
  // The probe was taken in schedule_.snapshot() at the render size: project with that camera and size.
  const CameraFrame frame = make_camera_frame(s_.schedule.snapshot()->scene().camera, s_.schedule.width(), s_.schedule.height());
  s_.tree_segments = project_ray_tree(frame, ray_tree_segments(s_.schedule.snapshot()->scene(), tools_.probe().tree->root, options),
                                    ray_tree_near(s_.schedule.snapshot()->scene(), tools_.probe().tree->root));
  int lit_lights = 0;
  for (const ProbeLight& light : tools_.probe().tree->root.lights) lit_lights += light.lit_side ? 1 : 0;
  const ui::ImageRect rect{full_cell, ImVec2(c.width / static_cast<float>(s_.schedule.width()),
                                             c.height / static_cast<float>(s_.schedule.height()))};
  const bool blinn = s_.schedule.snapshot()->scene().specular_model == SpecularModel::kBlinn;
  ui::draw_ray_tree(ImGui::GetBackgroundDrawList(), s_.tree_segments, rect, s_.platform.ui_scale(), blinn, lit_lights);
}

// The selected object, marked where the view shows it: a sphere's outline (its silhouette's
// radius at its centre's depth), and for every kind a square handle at its anchor to grab it by.
void Overlays::draw_selected_object() {
  const std::optional<ImVec2> at = builder_.object_screen_point(s_.selected_object);
  if (!at) return;
  const Scene& scene = s_.doc.scene();
  const float scale = s_.platform.ui_scale();
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const ImU32 colour = IM_COL32(255, 170, 40, 255);
  const ObjectRef r = ui::object_at(scene, s_.selected_object);
  if (r.kind == ObjectRef::Kind::kSphere) {
    const Camera view = view_camera(s_);
    const Sphere& sp = scene.spheres[static_cast<std::size_t>(r.index)];
    const double depth = ui::view_depth(view, sp.center);
    const double pixels_per_unit =
        depth > 0 ? s_.viewport.height / (2 * depth * std::tan(glm::radians(view.fov_y_deg) / 2)) : 0;
    const auto radius = static_cast<float>(sp.radius * pixels_per_unit);
    if (radius > 2 && radius < 1e4f) draw->AddCircle(*at, radius, colour, 64, 2 * scale);
  }
  const float h = ui::light_marker_radius(scale) * 0.8f;
  draw->AddRect(ImVec2(at->x - h, at->y - h), ImVec2(at->x + h, at->y + h), colour, 0, 0, 2 * scale);
  draw->AddLine(ImVec2(at->x - h * 0.5f, at->y), ImVec2(at->x + h * 0.5f, at->y), colour, 1.5f * scale);
  draw->AddLine(ImVec2(at->x, at->y - h * 0.5f), ImVec2(at->x, at->y + h * 0.5f), colour, 1.5f * scale);
}

}  // namespace phonglab
