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
};

std::span<const MaterialPreset> material_presets();
const MaterialPreset* find_preset(std::string_view name);

// The lecture's n for a table shininess under `model`: Blinn-Phong's (N.H)^s is the table's own
// exponent; Phong's (R.V)^n gives about the same highlight with n = s / 4 (as for MTL's Ns).
double preset_exponent(const MaterialPreset& preset, SpecularModel model);

// `material` with the preset's coefficients (its name and source kept).
void apply_preset(Material& material, const MaterialPreset& preset, SpecularModel model);

}  // namespace phonglab::ui
