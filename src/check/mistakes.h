// The catalogue of known mistakes (docs/checking.md): what a student's formula or ray tracer
// commonly gets wrong, each the reference with one rule changed. The names are an interface.
// A mistake is data: a specular formula of its own (the five formula mistakes), a local rule
// through the experiment hook (shadows, eta, the ambient per light), a change of the scene's
// camera or recursion limit, or a transform of the reference image (rows, the sRGB curve).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "check/rules.h"
#include "core/scene/scene.h"

namespace phonglab {

enum class Mistake : std::uint8_t {
  kSpecularUnclamped,
  kReflectSign,
  kBlinnForPhong,
  kViewReversed,
  kExponentOutside,
  kAmbientPerLight,
  kNoShadows,
  kNoRecursion,
  kDepthOffByOne,
  kEtaInverted,
  kPixelCorner,
  kFovHorizontal,
  kFlippedY,
  kLinearPng,
};
inline constexpr int kMistakeCount = 14;

struct MistakeInfo {
  Mistake id;
  std::string_view name;   // "specular-unclamped"
  std::string_view words;  // for a student: "your specular term is not clamped"
  bool formulas = false;   // a formula can make it (the specular slot)
  bool images = true;      // an image can show it
};
const std::array<MistakeInfo, kMistakeCount>& mistake_catalogue();
const MistakeInfo& mistake_info(Mistake m);
std::optional<Mistake> mistake_from_name(std::string_view name);

// One image a check compares with: the reference with one or two mistakes made.
struct MistakeVariant {
  std::vector<Mistake> mistakes;  // what it makes (one, or a pair)
  LocalRules rules;               // the local rules (a specular formula, shadows, eta, ambient)
  int depth_change = 0;           // max_depth + this (depth-off-by-one: +1 or -1)
  bool pixel_corner = false;      // rays through (x, y), not the pixel centre
  bool fov_horizontal = false;    // fov_y taken as the horizontal angle
  bool flipped_y = false;         // rows bottom to top
  bool linear_png = false;        // 8-bit codes without the sRGB curve
  // The scene as the variant renders it (camera, depth changed).
  Scene scene_of(const Scene& reference) const;
  std::string name() const;  // "no-shadows", "no-shadows and flipped-y"
};

// The specular formula of a specular mistake set (the five formula mistakes, alone or together)
// for the scene's model; with none set, the reference's specular formula in that model.
struct SpecularMistakes {
  bool unclamped = false, reflect_sign = false, blinn = false, view_reversed = false, exponent_outside = false;
  bool any() const { return unclamped || reflect_sign || blinn || view_reversed || exponent_outside; }
};
std::string specular_mistake_formula(const SpecularMistakes& mistakes, SpecularModel model);

// Which catalogue entries can change `scene`'s image (a mistake that cannot is not tried): a
// Blinn scene has no R to get wrong, one light no ambient to repeat, no mirror no recursion.
// `image_8bit`: the image is 8-bit sRGB (the only place linear-png can show). `formulas`: only
// the formula mistakes (a formula check).
std::vector<Mistake> applicable_mistakes(const Scene& scene, bool formulas, bool image_8bit);

// The variants of one mistake (depth-off-by-one has two: deeper and shallower), or of a pair
// (the specular formula mistakes combine into one formula). Empty when the pair cannot combine.
std::vector<MistakeVariant> mistake_variants(const std::vector<Mistake>& mistakes, const Scene& scene);

}  // namespace phonglab
