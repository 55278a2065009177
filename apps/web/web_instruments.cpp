#include "apps/web/web_instruments.h"

#include <algorithm>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "apps/web/web_lesson.h"
#include "core/teaching/ray_tree_view.h"
#include "io/probe_report.h"

namespace phonglab {

int WebInstruments::view_term() const {
  if (s_.view.small_multiples) return -2;
  if (s_.view.term == Term::kRays) return -3;
  const int term = static_cast<int>(s_.view.term);
  return term <= static_cast<int>(Term::kRefraction) ? term : -1;
}

void WebInstruments::set_term(int term) {
  s_.view.term = static_cast<Term>(std::clamp(term, 0, 5));
  s_.view.small_multiples = false;
  lesson_.edited_by_hand();
  image_.restart();
}

void WebInstruments::set_heat_map(bool on) {
  s_.view.term = on ? Term::kRays : Term::kFull;
  s_.view.small_multiples = false;
  lesson_.edited_by_hand();
  image_.restart();
}

void WebInstruments::set_head_angle(double degrees) {
  s_.view.head_angle_deg = degrees != 0 ? std::optional<double>(degrees) : std::nullopt;
  lesson_.edited_by_hand();
  image_.restart();
}

void WebInstruments::set_small_multiples(bool on) {
  s_.view.small_multiples = on;
  lesson_.edited_by_hand();
  image_.restart();
}

void WebInstruments::take_a() {
  s_.a.request(static_cast<std::uint64_t>(s_.generation), false);
  if (s_.a.take_when_ready(static_cast<std::uint64_t>(s_.generation), s_.shown, image_.finished())) image_.reshow();
}

std::string WebInstruments::compare_caption() const {
  return s_.a.caption(s_.shown, s_.view.compare, image_.constant_ambient(), image_.target_spp(), s_.view.difference_gain);
}

void WebInstruments::set_compare(int mode, double wipe) {
  s_.view.compare = static_cast<CompareView>(std::clamp(mode, 0, 2));
  s_.view.wipe = std::clamp(wipe, 0.0, 1.0);
  image_.reshow();  // the same live image, shown against A
}

void WebInstruments::set_depth_cut(int cut) {
  s_.view.depth_cut = cut > 0 ? std::optional<int>(cut) : std::nullopt;
  lesson_.edited_by_hand();
  image_.restart();
}

std::string WebInstruments::probed_pixel() const {
  if (!s_.probe_pixel || s_.view.small_multiples) return "null";
  return nlohmann::json::array({(*s_.probe_pixel)[0], (*s_.probe_pixel)[1]}).dump();
}

std::string WebInstruments::ray_tree() const {
  if (!s_.tree_shown || !s_.tree_pixel || s_.view.small_multiples) return "[]";
  const std::shared_ptr<const PreparedScene> prepared =
      s_.prepared ? s_.prepared : std::make_shared<const PreparedScene>(view_scene(s_.session.scene(), s_.view));
  const Scene& shown = prepared->scene();
  const PixelProbe probe = probe_pixel(*prepared, s_.width, s_.height, (*s_.tree_pixel)[0], (*s_.tree_pixel)[1], s_.eye);
  const CameraFrame frame = make_camera_frame(shown.camera, s_.width, s_.height);
  const bool blinn = shown.specular_model == SpecularModel::kBlinn;
  nlohmann::json out = nlohmann::json::array();
  for (const ScreenSegment& s : project_ray_tree(frame, ray_tree_segments(shown, probe.root), ray_tree_near(shown, probe.root))) {
    static constexpr const char* kKinds[] = {"primary", "seen", "blocked", "reflection", "refraction"};
    const std::string kind = is_arrow(s.kind) ? arrow_letter(s.kind, blinn) : kKinds[static_cast<int>(s.kind)];
    const std::array<std::uint8_t, 3> c = segment_srgb8(s.kind, s.depth, s.blocked);  // the one palette
    char colour[8];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", c[0], c[1], c[2]);
    out.push_back({{"kind", kind}, {"depth", s.depth}, {"light", s.light}, {"escapes", s.escapes},
                   {"blocked", s.blocked}, {"colour", colour},
                   {"from", {s.from.x, s.from.y}}, {"to", {s.to.x, s.to.y}}, {"end", s.to_visible}});
  }
  return out.dump();
}

int WebInstruments::material_at(double u, double v) const {
  const PixelProbe probe = probe_at(u, v);
  return probe.root.hit ? probe.root.material : -1;
}

std::string WebInstruments::probe(double u, double v) {
  const PixelProbe probe = probe_at(u, v);
  s_.tree_pixel = std::array<int, 2>{probe.x, probe.y};
  s_.probe_pixel = s_.tree_pixel;
  // With formulas: yours against the reference at the hit, with your statements' values.
  const std::string formulas = formula_probe_text(s_.session.scene(), probe.root, s_.session.formulas().rules());
  return probe_to_text(s_.session.scene(), probe, 4) + (formulas.empty() ? "" : "\n" + formulas);
}

PixelProbe WebInstruments::probe_at(double u, double v) const {
  const PreparedScene prepared(view_scene(s_.session.scene(), s_.view));
  const int x = std::clamp(static_cast<int>(u * s_.width), 0, s_.width - 1);
  const int y = std::clamp(static_cast<int>(v * s_.height), 0, s_.height - 1);
  return probe_pixel(prepared, s_.width, s_.height, x, y, s_.eye);
}

}  // namespace phonglab
