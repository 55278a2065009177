// The previewer's teaching instruments: the probe, undo and redo, snapshot A and the compare
// views, the heat map, "move your head" and the slide figure.
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

std::optional<std::array<int, 2>> Viewer::render_pixel_at(ImVec2 mouse) const {
  if (render_width_ <= 0 || render_height_ <= 0 || viewport_.width < 1 || viewport_.height < 1) return std::nullopt;
  const Cells c = cells();
  // In double, as the image's pixels are counted.
  const double cell_w = static_cast<double>(viewport_.width) / c.columns;
  const double cell_h = static_cast<double>(viewport_.height) / c.rows;
  const double x = mouse.x - viewport_.x;
  const double y = mouse.y - viewport_.y;
  // Within its cell, the point maps to the render pixel the cell shows there.
  const double u = (x - std::floor(x / cell_w) * cell_w) / cell_w;
  const double v = (y - std::floor(y / cell_h) * cell_h) / cell_h;
  return std::array<int, 2>{std::clamp(static_cast<int>(std::floor(u * render_width_)), 0, render_width_ - 1),
                            std::clamp(static_cast<int>(std::floor(v * render_height_)), 0, render_height_ - 1)};
}

void Viewer::probe_at(ImVec2 mouse) {
  const auto pixel = render_pixel_at(mouse);
  if (!pixel || !snapshot_) return;
  probed_.x = (*pixel)[0];
  probed_.y = (*pixel)[1];
  refresh_probe();
}

void Viewer::refresh_probe() {
  if (!snapshot_ || render_width_ <= 0 || render_height_ <= 0) {
    probed_.tree.reset();
    return;
  }
  probed_.x = std::clamp(probed_.x, 0, render_width_ - 1);
  probed_.y = std::clamp(probed_.y, 0, render_height_ - 1);
  // The renderer's own replay of the pixel's centre ray: the numbers are the image's.
  probed_.tree = probe_pixel(*snapshot_, render_width_, render_height_, probed_.x, probed_.y, shading_eye_);
  probed_.report = probe_to_text(snapshot_->scene(), *probed_.tree, probed_.every_digit ? 17 : 4);
  probed_.occluders.clear();
  for (const ProbeLight& light : probed_.tree->root.lights) probed_.occluders.push_back(object_name(snapshot_->scene(), light.occluder));
  probed_.indirect = probe_indirect(*snapshot_, render_width_, render_height_, probed_.x, probed_.y, kProbeIndirectSamples);
}

void Viewer::snapshot_a(bool first_full) {
  // A is the finished image of what is on screen now, never a half-converged one (its noise
  // would show in |live - A| as if something had changed). Until it is done, A waits; an edit
  // before then means the image asked for no longer exists. A lesson's A is its first image at
  // full resolution (every pixel's centre sample): the answer is on screen in seconds, and its
  // difference stays exact by keeping the live image at A's samples (target_spp).
  compare_.requested = true;
  compare_.first_full = first_full;
  a_generation_ = renderer_.status().generation;
  compare_.dropped = false;
  if (instruments_.compare == 0) instruments_.compare = 1;
  take_a_when_final();
}

void Viewer::take_a_when_final() {
  if (!compare_.requested) return;
  if (renderer_.status().generation != a_generation_) {
    compare_.requested = false;
    compare_.dropped = true;
    return;
  }
  const bool ready = compare_.first_full ? shown_.generation == a_generation_ && shown_.divisor == 1 : image_is_final();
  if (!ready || shown_.pixels.empty()) return;
  compare_.image = shown_;
  compare_.requested = false;
  upload_pending_ = true;
}

int Viewer::target_spp() const {
  // (Not for the indirect light: its noise settles only with samples; A's edges are what differ.)
  const bool lesson_difference = lessons_.lesson() && !lessons_.exploring() && compare_.first_full && instruments_.compare == 2 &&
                                 !compare_.image.pixels.empty() && render_settings_.ambient_view == ui::AmbientView::kConstant;
  const int target = std::max(render_settings_.target_spp, 1);
  return lesson_difference ? std::min(target, static_cast<int>(std::max(compare_.image.spp, 1u))) : target;
}

bool Viewer::a_comparable() const {
  if (compare_.image.pixels.empty() || compare_.image.width != shown_.width || compare_.image.height != shown_.height ||
      compare_.image.divisor != shown_.divisor || compare_.image.pixels.size() != shown_.pixels.size()) {
    return false;
  }
  // The difference compares like with like: the same samples, so only a change shows. The
  // indirect light against ka·Ia differs everywhere: it is shown as it settles.
  return instruments_.compare != 2 || compare_.image.spp == shown_.spp ||
         render_settings_.ambient_view != ui::AmbientView::kConstant;
}

std::string Viewer::compare_caption() const {
  char text[160];
  if (compare_.requested && compare_.first_full) {
    std::snprintf(text, sizeof text, "A is taken at its first full-resolution image");
  } else if (compare_.requested) {
    std::snprintf(text, sizeof text, "A is taken when the image is done (%u of %d spp)", shown_.spp,
                  render_settings_.target_spp);
  } else if (compare_.image.pixels.empty()) {
    std::snprintf(text, sizeof text, "%s", compare_.dropped ? "A was not taken: the view changed before the image was done"
                                                      : "no A yet: Snapshot A keeps the finished image");
  } else if (compare_.image.width != shown_.width || compare_.image.height != shown_.height) {
    std::snprintf(text, sizeof text, "A is %dx%d, the view is now %dx%d: take A again to compare", compare_.image.width,
                  compare_.image.height, shown_.width, shown_.height);
  } else if (!a_comparable()) {
    std::snprintf(text, sizeof text, "|live - A| shows when live has A's %u spp (now %u)", compare_.image.spp, shown_.spp);
  } else if (instruments_.compare == 1) {
    std::snprintf(text, sizeof text, "wipe: A (%u spp) left of the line, live right", compare_.image.spp);
  } else {
    std::snprintf(text, sizeof text, "|live - A| \xC3\x97 %.0f (%u spp each)", static_cast<double>(instruments_.difference_gain),
                  compare_.image.spp);
  }
  return text;
}

bool Viewer::heat_shown() const {
  return render_settings_.term == Term::kRays && instruments_.compare == 0 && !instruments_.small_multiples;
}

void Viewer::set_heat_map(bool on) {
  if (on == (render_settings_.term == Term::kRays)) return;
  if (on) term_before_heat_ = render_settings_.term;
  render_settings_.term = on ? Term::kRays : (term_before_heat_ == Term::kRays ? Term::kFull : term_before_heat_);
  rays_.heat_map = on;
  edits_.settings = true;
}

std::vector<glm::vec3> Viewer::display_pixels() const {
  if (heat_shown()) {
    // Rays per pixel on the ramp, 0 to the image's maximum. With the sRGB curve the shader
    // encodes heat_color back to the ramp; raw display shows the ramp's codes themselves.
    const double max = heat_max(shown_.pixels);
    if (display_.srgb) return heat_map_pixels(shown_.pixels, max);
    std::vector<glm::vec3> out(shown_.pixels.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(heat_ramp_srgb(max > 0 ? shown_.pixels[i].x / max : 0));
    return out;
  }
  if (const std::optional<std::vector<glm::vec3>> ambient = ambient_view_pixels()) return *ambient;
  if (instruments_.compare == 0 || !a_comparable()) return shown_.pixels;
  return compare_pixels(shown_.pixels, compare_.image.pixels, shown_.width,
                        instruments_.compare == 1 ? CompareView::kWipe : CompareView::kDifference,
                        static_cast<double>(instruments_.wipe), static_cast<double>(instruments_.difference_gain));
}

bool Viewer::ambient_view_pixels_shown(ui::AmbientView view) const {
  return render_settings_.ambient_view == view && !instruments_.small_multiples &&
         shown_.terms[0].size() == shown_.pixels.size() && !shown_.pixels.empty();
}

// The indirect term beside the ambient term, or their difference as heat: from one frame of
// Term::kIndirect with the term images (the ambient one is ka·Ia). Nothing for the other views.
std::optional<std::vector<glm::vec3>> Viewer::ambient_view_pixels() const {
  const std::vector<glm::vec3>& ambient = shown_.terms[0];
  const bool beside = ambient_view_pixels_shown(ui::AmbientView::kBeside);
  if (!beside && !ambient_view_pixels_shown(ui::AmbientView::kDifference)) return std::nullopt;
  if (beside) {
    return compare_pixels(shown_.pixels, ambient, shown_.width, CompareView::kWipe, static_cast<double>(instruments_.wipe), 1);
  }
  std::vector<glm::vec3> gap(shown_.pixels.size());
  for (std::size_t i = 0; i < gap.size(); ++i) {
    const glm::vec3 d = glm::abs(shown_.pixels[i] - ambient[i]);
    gap[i] = glm::vec3(std::max({d.x, d.y, d.z}));
  }
  return heat_map_pixels(gap, heat_max(gap));
}

Vec3 Viewer::head_pivot() const {
  if (probed_.tree && probed_.tree->root.hit) return probed_.tree->root.p;
  return doc_.scene().camera.look_at;
}

std::optional<Vec3> Viewer::head_eye() const {
  if (!instruments_.move_head) return std::nullopt;
  return phonglab::head_eye(doc_.scene().camera, head_pivot(), static_cast<double>(instruments_.head_angle_deg));
}

void Viewer::save_figure(const std::string& path) {
  if (!snapshot_ || viewport_.height < 1) {
    figure_status_ = "no scene yet";
    return;
  }
  FigureOptions options;
  options.cell_height = kFigureCellHeight;
  options.cell_width = std::max(1, static_cast<int>(std::lround(kFigureCellHeight * viewport_.width / viewport_.height)));
  options.threads = render_settings_.threads;
  const std::string error = write_figure(path, *snapshot_, options);
  figure_status_ = error.empty() ? "saved " + std::filesystem::absolute(path).lexically_normal().string() : error;
}

}  // namespace phonglab
