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
  if (v_.schedule_.width() <= 0 || v_.schedule_.height() <= 0 || v_.viewport_.width < 1 || v_.viewport_.height < 1) return std::nullopt;
  const Viewer::Cells c = v_.cells();
  // In double, as the image's pixels are counted.
  const double cell_w = static_cast<double>(v_.viewport_.width) / c.columns;
  const double cell_h = static_cast<double>(v_.viewport_.height) / c.rows;
  const double x = mouse.x - v_.viewport_.x;
  const double y = mouse.y - v_.viewport_.y;
  // Within its cell, the point maps to the render pixel the cell shows there.
  const double u = (x - std::floor(x / cell_w) * cell_w) / cell_w;
  const double v = (y - std::floor(y / cell_h) * cell_h) / cell_h;
  return std::array<int, 2>{std::clamp(static_cast<int>(std::floor(u * v_.schedule_.width())), 0, v_.schedule_.width() - 1),
                            std::clamp(static_cast<int>(std::floor(v * v_.schedule_.height())), 0, v_.schedule_.height() - 1)};
}

void Instruments::probe_at(ImVec2 mouse) {
  const auto pixel = render_pixel_at(mouse);
  if (!pixel || !v_.schedule_.snapshot()) return;
  probed_.x = (*pixel)[0];
  probed_.y = (*pixel)[1];
  refresh_probe();
}

void Instruments::refresh_probe() {
  if (!v_.schedule_.snapshot() || v_.schedule_.width() <= 0 || v_.schedule_.height() <= 0) {
    probed_.tree.reset();
    return;
  }
  probed_.x = std::clamp(probed_.x, 0, v_.schedule_.width() - 1);
  probed_.y = std::clamp(probed_.y, 0, v_.schedule_.height() - 1);
  // The renderer's own replay of the pixel's centre ray: the numbers are the image's.
  probed_.tree = probe_pixel(*v_.schedule_.snapshot(), v_.schedule_.width(), v_.schedule_.height(), probed_.x, probed_.y, v_.schedule_.eye());
  probed_.report = probe_to_text(v_.schedule_.snapshot()->scene(), *probed_.tree, probed_.every_digit ? 17 : 4);
  probed_.occluders.clear();
  for (const ProbeLight& light : probed_.tree->root.lights) probed_.occluders.push_back(object_name(v_.schedule_.snapshot()->scene(), light.occluder));
  // The indirect term's numbers only with an ambient view on: 256 gathers, every refresh.
  probed_.with_indirect = shows_indirect();
  probed_.indirect = probed_.with_indirect ? probe_indirect(*v_.schedule_.snapshot(), v_.schedule_.width(), v_.schedule_.height(), probed_.x,
                                                            probed_.y, kProbeIndirectSamples)
                                           : IndirectProbe{};
}

bool Instruments::shows_indirect() const { return v_.render_settings_.ambient_view != ui::AmbientView::kConstant; }

void Instruments::snapshot_a(bool first_full) {
  a_.request(v_.renderer_.status().generation, first_full);
  if (v_.instruments_.compare == 0) v_.instruments_.compare = 1;
  take_a_when_final();
}

void Instruments::take_a_when_final() {
  if (a_.take_when_ready(v_.renderer_.status().generation, v_.shown_, a_.requested() && v_.image_is_final())) {
    v_.upload_pending_ = true;
  }
}

CompareView Instruments::compare_view() const { return static_cast<CompareView>(v_.instruments_.compare); }

int Instruments::target_spp() const {
  // Exploring a compare step (a term key on it) keeps live at A's samples: the difference
  // follows the view instead of waiting for a sample count it will never have.
  return a_.target_spp(v_.render_settings_.target_spp, v_.lessons_.lesson() != nullptr, compare_view(), !shows_indirect());
}

bool Instruments::a_comparable() const { return a_.comparable(v_.shown_, compare_view(), !shows_indirect()); }

std::string Instruments::compare_caption() const {
  return a_.caption(v_.shown_, compare_view(), !shows_indirect(), v_.render_settings_.target_spp,
                    static_cast<double>(v_.instruments_.difference_gain));
}

std::string Instruments::probe_cli_command() const {
  const std::string name = !v_.doc_.embedded_name().empty() ? v_.doc_.embedded_name() : v_.doc_.file_path();
  const Scene* scene = v_.schedule_.snapshot() ? &v_.schedule_.snapshot()->scene() : nullptr;
  if (!probed_.tree || scene == nullptr || name.empty()) return "";
  const Camera& loaded = v_.doc_.loaded_camera();
  if (v_.doc_.dirty() || scene->camera.position != loaded.position || scene->camera.look_at != loaded.look_at ||
      scene->camera.up != loaded.up) {
    return "(the view or the scene changed since it was read: save it for the same pixel in phonglab-cli)";
  }
  char command[1024];
  std::snprintf(command, sizeof command, "phonglab-cli probe %s --pixel %d,%d --width %d --height %d --fov-y %.17g",
                name.c_str(), probed_.x, probed_.y, v_.schedule_.width(), v_.schedule_.height(), scene->camera.fov_y_deg);
  return command;
}

bool Instruments::heat_shown() const {
  return v_.render_settings_.term == Term::kRays && v_.instruments_.compare == 0 && !v_.instruments_.small_multiples;
}

void Instruments::set_heat_map(bool on) {
  if (on == (v_.render_settings_.term == Term::kRays)) return;
  if (on) term_before_heat_ = v_.render_settings_.term;
  v_.render_settings_.term = on ? Term::kRays : (term_before_heat_ == Term::kRays ? Term::kFull : term_before_heat_);
  v_.rays_.heat_map = on;
  v_.edits_.settings = true;
}

std::vector<glm::vec3> Instruments::display_pixels() const {
  // The Formula panel's difference view: the check's image, yours against the reference.
  if (auto difference = v_.formulas_.difference_pixels(v_.shown_.width, v_.shown_.height)) return *difference;
  if (heat_shown()) {
    // Rays per pixel on the ramp, 0 to the image's maximum. With the sRGB curve the shader
    // encodes heat_color back to the ramp; raw display shows the ramp's codes themselves.
    const double max = heat_max(v_.shown_.pixels);
    if (v_.display_.srgb) return heat_map_pixels(v_.shown_.pixels, max);
    std::vector<glm::vec3> out(v_.shown_.pixels.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(heat_ramp_srgb(max > 0 ? v_.shown_.pixels[i].x / max : 0));
    return out;
  }
  if (const std::optional<std::vector<glm::vec3>> ambient = ambient_view_pixels()) return *ambient;
  if (v_.instruments_.compare == 0 || !a_comparable()) return v_.shown_.pixels;
  return compare_pixels(v_.shown_.pixels, a_.image().pixels, v_.shown_.width,
                        v_.instruments_.compare == 1 ? CompareView::kWipe : CompareView::kDifference,
                        static_cast<double>(v_.instruments_.wipe), static_cast<double>(v_.instruments_.difference_gain));
}

bool Instruments::ambient_view_pixels_shown(ui::AmbientView view) const {
  return v_.render_settings_.ambient_view == view && !v_.instruments_.small_multiples &&
         v_.shown_.terms[0].size() == v_.shown_.pixels.size() && !v_.shown_.pixels.empty();
}

// The indirect term beside the ambient term, or their difference as heat: from one frame of
// Term::kIndirect with the term images (the ambient one is ka·Ia). Nothing for the other views.
std::optional<std::vector<glm::vec3>> Instruments::ambient_view_pixels() const {
  const std::vector<glm::vec3>& ambient = v_.shown_.terms[0];
  const bool beside = ambient_view_pixels_shown(ui::AmbientView::kBeside);
  if (!beside && !ambient_view_pixels_shown(ui::AmbientView::kDifference)) return std::nullopt;
  return ambient_shown_pixels(beside ? AmbientShown::kBeside : AmbientShown::kDifference, v_.shown_.pixels, ambient,
                              v_.shown_.width, static_cast<double>(v_.instruments_.wipe));
}

Vec3 Instruments::head_pivot() const {
  if (probed_.tree && probed_.tree->root.hit) return probed_.tree->root.p;
  return v_.doc_.scene().camera.look_at;
}

std::optional<Vec3> Instruments::head_eye() const {
  if (!v_.instruments_.move_head) return std::nullopt;
  return phonglab::head_eye(v_.doc_.scene().camera, head_pivot(), static_cast<double>(v_.instruments_.head_angle_deg));
}

void Instruments::save_figure(const std::string& path) {
  if (!v_.schedule_.snapshot() || v_.viewport_.height < 1) {
    v_.figure_status_ = "no scene yet";
    return;
  }
  FigureOptions options;
  options.cell_height = kFigureCellHeight;
  options.cell_width = std::max(1, static_cast<int>(std::lround(kFigureCellHeight * v_.viewport_.width / v_.viewport_.height)));
  options.threads = v_.render_settings_.threads;
  const std::string error = write_figure(path, *v_.schedule_.snapshot(), options);
  v_.figure_status_ = error.empty() ? "saved " + std::filesystem::absolute(path).lexically_normal().string() : error;
}

}  // namespace phonglab
