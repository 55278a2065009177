#include "check/mistakes.h"

#include <cmath>

#include "core/shading/shading.h"

namespace phonglab {

namespace {

constexpr std::array<MistakeInfo, kMistakeCount> kCatalogue = {{
    {Mistake::kSpecularUnclamped, "specular-unclamped",
     "your specular term is not clamped: (R·V)^n where R·V < 0 needs max(0, R·V)", true, true},
    {Mistake::kReflectSign, "reflect-sign",
     "your R points the wrong way: reflect(L, N) is the mirror of −R; R = reflect(−L, N)", true, true},
    {Mistake::kBlinnForPhong, "blinn-for-phong",
     "you used Blinn's N·H where the scene asks for Phong's R·V", true, true},
    {Mistake::kViewReversed, "view-reversed", "your V points away from the eye: V = −D, towards the ray's origin",
     true, true},
    {Mistake::kExponentOutside, "exponent-outside",
     "your ks is inside the power: ks·max(0, R·V)^n, not (ks·max(0, R·V))^n", true, true},
    {Mistake::kAmbientPerLight, "ambient-per-light", "you add ka·Ia once for every light: it is added once", false,
     true},
    {Mistake::kNoShadows, "no-shadows", "your lights are never blocked: a shadow ray decides vis for each light", false,
     true},
    {Mistake::kNoRecursion, "no-recursion",
     "your mirrors and glass show nothing: kr and kt need the reflected and refracted rays", false, true},
    {Mistake::kDepthOffByOne, "depth-off-by-one",
     "your recursion stops one level too early or too late: max_depth counts the bounces after the primary ray", false,
     true},
    {Mistake::kEtaInverted, "eta-inverted",
     "your eta is the wrong way round: 1/ior entering the object, ior leaving it", false, true},
    {Mistake::kPixelCorner, "pixel-corner",
     "your rays go through the pixel's corner (x, y): the reference's go through its centre (x + 0.5, y + 0.5)", false,
     true},
    {Mistake::kFovHorizontal, "fov-horizontal", "you took fov_y as the horizontal angle: it is the vertical one", false,
     true},
    {Mistake::kFlippedY, "flipped-y", "your rows are stored bottom to top: row 0 is the top of the image", false, true},
    {Mistake::kLinearPng, "linear-png", "your PNG holds linear values: 8-bit PNG codes go through the sRGB curve", false,
     true},
}};

bool has(const std::vector<Mistake>& list, Mistake m) {
  for (const Mistake x : list) {
    if (x == m) return true;
  }
  return false;
}

bool any_material(const Scene& scene, bool (*test)(const Material&)) {
  for (const Material& m : scene.materials) {
    if (test(m)) return true;
  }
  return false;
}

int enabled_lights(const Scene& scene) {
  int count = 0;
  for (const Light& l : scene.lights) count += l.enabled ? 1 : 0;
  return count;
}

}  // namespace

const std::array<MistakeInfo, kMistakeCount>& mistake_catalogue() { return kCatalogue; }
const MistakeInfo& mistake_info(Mistake m) { return kCatalogue[static_cast<std::size_t>(m)]; }
std::optional<Mistake> mistake_from_name(std::string_view name) {
  for (const MistakeInfo& info : kCatalogue) {
    if (info.name == name) return info.id;
  }
  return std::nullopt;
}

Scene MistakeVariant::scene_of(const Scene& reference) const {
  Scene s = reference;
  s.max_depth = std::max(0, s.max_depth + depth_change);
  if (fov_horizontal && s.width > 0 && s.height > 0) {
    // The student's horizontal half-angle is fov_y / 2: the vertical one that gives it.
    const double half = glm::radians(s.camera.fov_y_deg) / 2;
    s.camera.fov_y_deg = glm::degrees(2.0 * std::atan(std::tan(half) * s.height / s.width));
  }
  return s;
}

std::string MistakeVariant::name() const {
  std::string out;
  for (const Mistake m : mistakes) {
    if (!out.empty()) out += " and ";
    out += mistake_info(m).name;
  }
  return out;
}

std::string specular_mistake_formula(const SpecularMistakes& m, SpecularModel model) {
  const bool blinn = model == SpecularModel::kBlinn || m.blinn;
  std::string out;
  std::string cosine;
  if (blinn) {
    out = m.view_reversed ? "H = normalize(L - V)\n" : "H = normalize(L + V)\n";
    cosine = "dot(N, H)";
  } else {
    out = m.reflect_sign ? "R = reflect(L, N)\n" : "R = reflect(-L, N)\n";
    cosine = m.view_reversed ? "dot(R, -V)" : "dot(R, V)";
  }
  const std::string base = m.unclamped ? cosine : "max(0, " + cosine + ")";
  out += m.exponent_outside ? "pow(ks * " + base + ", n)" : "ks * pow(" + base + ", n)";
  return out;
}

std::vector<Mistake> applicable_mistakes(const Scene& scene, bool formulas, bool image_8bit) {
  const bool lights = enabled_lights(scene) > 0;
  const bool specular = lights && any_material(scene, [](const Material& m) { return !is_zero(m.ks); });
  const bool phong = scene.specular_model == SpecularModel::kPhong;
  const bool children = any_material(scene, [](const Material& m) { return has_children(m); });
  std::vector<Mistake> out;
  const auto add = [&](Mistake m, bool applies) {
    if (applies && (!formulas || mistake_info(m).formulas)) out.push_back(m);
  };
  add(Mistake::kSpecularUnclamped, specular);
  add(Mistake::kReflectSign, specular && phong);
  add(Mistake::kBlinnForPhong, specular && phong);
  add(Mistake::kViewReversed, specular);
  add(Mistake::kExponentOutside, specular);
  add(Mistake::kAmbientPerLight,
      enabled_lights(scene) > 1 && !is_zero(scene.ambient) &&
          any_material(scene, [](const Material& m) { return !is_zero(m.ka); }));
  add(Mistake::kNoShadows, lights);
  add(Mistake::kNoRecursion, children && scene.max_depth > 0);
  add(Mistake::kDepthOffByOne, children);
  add(Mistake::kEtaInverted, any_material(scene, [](const Material& m) { return !is_zero(m.kt) && m.ior != 1; }));
  add(Mistake::kPixelCorner, true);
  add(Mistake::kFovHorizontal, scene.width != scene.height);
  add(Mistake::kFlippedY, scene.height > 1);
  add(Mistake::kLinearPng, image_8bit);
  return out;
}

std::vector<MistakeVariant> mistake_variants(const std::vector<Mistake>& mistakes, const Scene& scene) {
  SpecularMistakes specular;
  MistakeVariant base;
  base.mistakes = mistakes;
  bool deeper_and_shallower = false;
  for (const Mistake m : mistakes) {
    switch (m) {
      case Mistake::kSpecularUnclamped: specular.unclamped = true; break;
      case Mistake::kReflectSign: specular.reflect_sign = true; break;
      case Mistake::kBlinnForPhong: specular.blinn = true; break;
      case Mistake::kViewReversed: specular.view_reversed = true; break;
      case Mistake::kExponentOutside: specular.exponent_outside = true; break;
      case Mistake::kAmbientPerLight: base.rules.ambient_per_light = true; break;
      case Mistake::kNoShadows: base.rules.no_shadows = true; break;
      case Mistake::kNoRecursion: base.depth_change = -scene.max_depth; break;
      case Mistake::kDepthOffByOne: deeper_and_shallower = true; break;
      case Mistake::kEtaInverted: base.rules.eta_inverted = true; break;
      case Mistake::kPixelCorner: base.pixel_corner = true; break;
      case Mistake::kFovHorizontal: base.fov_horizontal = true; break;
      case Mistake::kFlippedY: base.flipped_y = true; break;
      case Mistake::kLinearPng: base.linear_png = true; break;
    }
  }
  // Pairs that say the same thing twice, or contradict each other, are no pair.
  if (specular.blinn && specular.reflect_sign) return {};
  if (deeper_and_shallower && has(mistakes, Mistake::kNoRecursion)) return {};
  if (specular.any()) {
    base.rules.formulas[static_cast<int>(FormulaSlot::kSpecular)] =
        Formula::compile(specular_mistake_formula(specular, scene.specular_model), nullptr);
  }
  if (!deeper_and_shallower) return {base};
  std::vector<MistakeVariant> out;
  for (const int change : {1, -1}) {
    if (scene.max_depth + change < 0) continue;
    MistakeVariant v = base;
    v.depth_change = change;
    out.push_back(v);
  }
  return out;
}

}  // namespace phonglab
