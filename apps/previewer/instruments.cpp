// The previewer's teaching instruments: the probe, undo and redo, snapshot A and the compare
// views, the heat map, "move your head" and the slide figure.
#include "apps/previewer/instruments.h"

#include "apps/previewer/viewer_app.h"
#include "core/teaching/compare.h"
#include "interaction/scene_objects.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "io/figure.h"
#include "core/teaching/heat_map.h"
#include "io/probe_report.h"
#include "interaction/camera_control.h"

namespace phonglab {

namespace {

constexpr int kFigureCellHeight = 270;  // slide figure cells: a quarter of 1080p per row
constexpr int kProbeIndirectSamples = 256;  // the probe's gathers for the indirect term: its error about 1/16 of one

}  // namespace

std::optional<std::array<int, 2>> Instruments::render_pixel_at(ImVec2 mouse) const {
  if (s_.schedule.width() <= 0 || s_.schedule.height() <= 0 || s_.viewport.width < 1 || s_.viewport.height < 1) return std::nullopt;
  const Cells c = cells(s_);
  // In double, as the image's pixels are counted.
  const double cell_w = static_cast<double>(s_.viewport.width) / c.columns;
  const double cell_h = static_cast<double>(s_.viewport.height) / c.rows;
  const double x = mouse.x - s_.viewport.x;
  const double y = mouse.y - s_.viewport.y;
  // Within its cell, the point maps to the render pixel the cell shows there.
  const double u = (x - std::floor(x / cell_w) * cell_w) / cell_w;
  const double v = (y - std::floor(y / cell_h) * cell_h) / cell_h;
  return std::array<int, 2>{std::clamp(static_cast<int>(std::floor(u * s_.schedule.width())), 0, s_.schedule.width() - 1),
                            std::clamp(static_cast<int>(std::floor(v * s_.schedule.height())), 0, s_.schedule.height() - 1)};
}

void Instruments::probe_at(ImVec2 mouse) {
  const auto pixel = render_pixel_at(mouse);
  if (!pixel || !s_.schedule.snapshot()) return;
  probed_.x = (*pixel)[0];
  probed_.y = (*pixel)[1];
  refresh_probe();
}

void Instruments::refresh_probe() {
  if (!s_.schedule.snapshot() || s_.schedule.width() <= 0 || s_.schedule.height() <= 0) {
    probed_.tree.reset();
    return;
  }
  probed_.x = std::clamp(probed_.x, 0, s_.schedule.width() - 1);
  probed_.y = std::clamp(probed_.y, 0, s_.schedule.height() - 1);
  // The renderer's own replay of the pixel's centre ray: the numbers are the image's.
  probed_.tree = probe_pixel(*s_.schedule.snapshot(), s_.schedule.width(), s_.schedule.height(), probed_.x, probed_.y, s_.schedule.eye());
  probed_.report = probe_to_text(s_.schedule.snapshot()->scene(), *probed_.tree, probed_.every_digit ? 17 : 4);
  probed_.occluders.clear();
  for (const ProbeLight& light : probed_.tree->root.lights) probed_.occluders.push_back(object_name(s_.schedule.snapshot()->scene(), light.occluder));
  // The indirect term's numbers only with an ambient view on: 256 gathers, every refresh.
  probed_.with_indirect = shows_indirect();
  probed_.indirect = probed_.with_indirect ? probe_indirect(*s_.schedule.snapshot(), s_.schedule.width(), s_.schedule.height(), probed_.x,
                                                            probed_.y, kProbeIndirectSamples)
                                           : IndirectProbe{};
}

bool Instruments::shows_indirect() const { return s_.render_settings.ambient_view != ui::AmbientView::kConstant; }

void Instruments::snapshot_a(bool first_full) {
  a_.request(s_.renderer.status().generation, first_full);
  if (s_.instruments.compare == 0) s_.instruments.compare = 1;
  take_a_when_final();
}

void Instruments::take_a_when_final() {
  if (a_.take_when_ready(s_.renderer.status().generation, s_.shown, a_.requested() && image_is_final(s_))) {
    s_.upload_pending = true;
  }
}

CompareView Instruments::compare_view() const { return static_cast<CompareView>(s_.instruments.compare); }

int Instruments::target_spp() const {
  // Exploring a compare step (a term key on it) keeps live at A's samples: the difference
  // follows the view instead of waiting for a sample count it will never have.
  return a_.target_spp(s_.render_settings.target_spp, s_.lessons.lesson() != nullptr, compare_view(), !shows_indirect());
}

bool Instruments::a_comparable() const { return a_.comparable(s_.shown, compare_view(), !shows_indirect()); }

std::string Instruments::compare_caption() const {
  return a_.caption(s_.shown, compare_view(), !shows_indirect(), s_.render_settings.target_spp,
                    static_cast<double>(s_.instruments.difference_gain));
}

std::string Instruments::probe_cli_command() const {
  const std::string name = !s_.doc.embedded_name().empty() ? s_.doc.embedded_name() : s_.doc.file_path();
  const Scene* scene = s_.schedule.snapshot() ? &s_.schedule.snapshot()->scene() : nullptr;
  if (!probed_.tree || scene == nullptr || name.empty()) return "";
  const Camera& loaded = s_.doc.loaded_camera();
  if (s_.doc.dirty() || scene->camera.position != loaded.position || scene->camera.look_at != loaded.look_at ||
      scene->camera.up != loaded.up) {
    return "(the view or the scene changed since it was read: save it for the same pixel in phonglab-cli)";
  }
  char command[1024];
  std::snprintf(command, sizeof command, "phonglab-cli probe %s --pixel %d,%d --width %d --height %d --fov-y %.17g",
                name.c_str(), probed_.x, probed_.y, s_.schedule.width(), s_.schedule.height(), scene->camera.fov_y_deg);
  return command;
}

bool Instruments::heat_shown() const {
  return s_.render_settings.term == Term::kRays && s_.instruments.compare == 0 && !s_.instruments.small_multiples;
}

void Instruments::set_heat_map(bool on) {
  if (on == (s_.render_settings.term == Term::kRays)) return;
  if (on) term_before_heat_ = s_.render_settings.term;
  s_.render_settings.term = on ? Term::kRays : (term_before_heat_ == Term::kRays ? Term::kFull : term_before_heat_);
  s_.rays.heat_map = on;
  s_.edits.settings = true;
}

std::vector<glm::vec3> Instruments::display_pixels() const {
  // The Formula panel's difference view: the check's image, yours against the reference.
  if (auto difference = formulas_.difference_pixels(s_.shown.width, s_.shown.height)) return *difference;
  if (heat_shown()) {
    // Rays per pixel on the ramp, 0 to the image's maximum. With the sRGB curve the shader
    // encodes heat_color back to the ramp; raw display shows the ramp's codes themselves.
    const double max = heat_max(s_.shown.pixels);
    if (s_.display.srgb) return heat_map_pixels(s_.shown.pixels, max);
    std::vector<glm::vec3> out(s_.shown.pixels.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(heat_ramp_srgb(max > 0 ? s_.shown.pixels[i].x / max : 0));
    return out;
  }
  if (const std::optional<std::vector<glm::vec3>> ambient = ambient_view_pixels()) return *ambient;
  if (s_.instruments.compare == 0 || !a_comparable()) return s_.shown.pixels;
  return compare_pixels(s_.shown.pixels, a_.image().pixels, s_.shown.width,
                        s_.instruments.compare == 1 ? CompareView::kWipe : CompareView::kDifference,
                        static_cast<double>(s_.instruments.wipe), static_cast<double>(s_.instruments.difference_gain));
}

bool Instruments::ambient_view_pixels_shown(ui::AmbientView view) const {
  return s_.render_settings.ambient_view == view && !s_.instruments.small_multiples &&
         s_.shown.terms[0].size() == s_.shown.pixels.size() && !s_.shown.pixels.empty();
}

// The indirect term beside the ambient term, or their difference as heat: from one frame of
// Term::kIndirect with the term images (the ambient one is ka·Ia). Nothing for the other views.
std::optional<std::vector<glm::vec3>> Instruments::ambient_view_pixels() const {
  const std::vector<glm::vec3>& ambient = s_.shown.terms[0];
  const bool beside = ambient_view_pixels_shown(ui::AmbientView::kBeside);
  if (!beside && !ambient_view_pixels_shown(ui::AmbientView::kDifference)) return std::nullopt;
  return ambient_shown_pixels(beside ? AmbientShown::kBeside : AmbientShown::kDifference, s_.shown.pixels, ambient,
                              s_.shown.width, static_cast<double>(s_.instruments.wipe));
}

Vec3 Instruments::head_pivot() const {
  if (probed_.tree && probed_.tree->root.hit) return probed_.tree->root.p;
  return s_.doc.scene().camera.look_at;
}

std::optional<Vec3> Instruments::head_eye() const {
  if (!s_.instruments.move_head) return std::nullopt;
  return phonglab::head_eye(s_.doc.scene().camera, head_pivot(), static_cast<double>(s_.instruments.head_angle_deg));
}

void Instruments::save_figure(const std::string& path) {
  if (!s_.schedule.snapshot() || s_.viewport.height < 1) {
    s_.figure_status = "no scene yet";
    return;
  }
  FigureOptions options;
  options.cell_height = kFigureCellHeight;
  options.cell_width = std::max(1, static_cast<int>(std::lround(kFigureCellHeight * s_.viewport.width / s_.viewport.height)));
  options.threads = s_.render_settings.threads;
  const std::string error = write_figure(path, *s_.schedule.snapshot(), options);
  s_.figure_status = error.empty() ? "saved " + std::filesystem::absolute(path).lexically_normal().string() : error;
}

}  // namespace phonglab
