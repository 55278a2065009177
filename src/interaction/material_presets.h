// A library of materials to start from: the classic Phong table of OpenGL teaching (ka, kd, ks
// and shininess as published) and the lecture's own (matte, plastic, mirror, glass, water,
// diamond). Sources and the shininess conversion: docs/previewer.md, "Materials".
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "core/scene/scene.h"

namespace phonglab::ui {

struct MaterialPreset {
  std::string_view name;   // lower case, words joined by '_': "gold", "black_rubber"
  std::string_view group;  // "metal", "gem", "plastic", "rubber", "lecture"
  Color ka, kd, ks;
  double shininess = 0;    // the table's GL_SHININESS (Blinn-Phong exponent); lecture presets: n itself
  Color kr{0}, kt{0};
  double ior = 1.5;
  bool fresnel = false;
  bool lecture = false;    // one of the lecture's own: shininess is n for either model
  // The global ambient Iₐ its ka was made for: OpenGL's default light model ambient 0.2 for the
  // classic table (which looks pale under the lecture's Iₐ = 1), 1 for the lecture's own.
  double assumed_ambient = 0.2;
};

std::span<const MaterialPreset> material_presets();
const MaterialPreset* find_preset(std::string_view name);

// The lecture's n for a table shininess under `model`: Blinn-Phong's (N.H)^s is the table's own
// exponent; Phong's (R.V)^n gives about the same highlight with n = s / 4 (as for MTL's Ns).
double preset_exponent(const MaterialPreset& preset, SpecularModel model);

// `material` with the preset's coefficients (its name and source kept); ka is scaled, channel by
// channel, by the preset's assumed ambient over the scene's Iₐ `ambient` (a channel of Iₐ = 0
// keeps the table's ka), so that ka Iₐ is the preset's own. Returns that scale.
Color apply_preset(Material& material, const MaterialPreset& preset, SpecularModel model, const Color& ambient);

// The preset's note for its tooltip: "made for OpenGL's dim global ambient Iₐ = 0.2: ka is scaled
// to the scene's Iₐ" or "made for the lecture's Iₐ = 1: ka is scaled to the scene's Iₐ".
std::string preset_note(const MaterialPreset& preset);
// What applying it did, for the Materials panel: "gold: ka scaled by 0.2 for this scene's Iₐ = 1
// (the preset assumes Iₐ = 0.2)"; per channel "(0.2, 0.25, 0.2)" when they differ.
std::string preset_applied_text(const MaterialPreset& preset, const Color& scale, const Color& ambient);

}  // namespace phonglab::ui
