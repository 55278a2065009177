#include "interaction/material_presets.h"

#include <array>
#include <cmath>
#include <sstream>

#include "interaction/numbers.h"

namespace phonglab::ui {

namespace {

constexpr Color rgb(double r, double g, double b) { return Color(r, g, b); }
constexpr Color grey(double v) { return Color(v, v, v); }

// The table of Mark J. Kilgard's teapots.c (Silicon Graphics, 1994), as reproduced in
// McReynolds and Blythe, "Advanced Graphics Programming Using OpenGL" (2005), which adds pewter
// and the polished metals. Shininess in GL units (the table's fraction times 128).
constexpr std::array<MaterialPreset, 35> kPresets = {{
    {"brass", "metal", rgb(0.329412, 0.223529, 0.027451), rgb(0.780392, 0.568627, 0.113725), rgb(0.992157, 0.941176, 0.807843), 27.8974},
    {"bronze", "metal", rgb(0.2125, 0.1275, 0.054), rgb(0.714, 0.4284, 0.18144), rgb(0.393548, 0.271906, 0.166721), 25.6},
    {"polished_bronze", "metal", rgb(0.25, 0.148, 0.06475), rgb(0.4, 0.2368, 0.1036), rgb(0.774597, 0.458561, 0.200621), 76.8},
    {"chrome", "metal", grey(0.25), grey(0.4), grey(0.774597), 76.8},
    {"copper", "metal", rgb(0.19125, 0.0735, 0.0225), rgb(0.7038, 0.27048, 0.0828), rgb(0.256777, 0.137622, 0.086014), 12.8},
    {"polished_copper", "metal", rgb(0.2295, 0.08825, 0.0275), rgb(0.5508, 0.2118, 0.066), rgb(0.580594, 0.223257, 0.0695701), 51.2},
    {"gold", "metal", rgb(0.24725, 0.1995, 0.0745), rgb(0.75164, 0.60648, 0.22648), rgb(0.628281, 0.555802, 0.366065), 51.2},
    {"polished_gold", "metal", rgb(0.24725, 0.2245, 0.0645), rgb(0.34615, 0.3143, 0.0903), rgb(0.797357, 0.723991, 0.208006), 83.2},
    {"pewter", "metal", rgb(0.105882, 0.058824, 0.113725), rgb(0.427451, 0.470588, 0.541176), rgb(0.333333, 0.333333, 0.521569), 9.84615},
    {"silver", "metal", grey(0.19225), grey(0.50754), grey(0.508273), 51.2},
    {"polished_silver", "metal", grey(0.23125), grey(0.2775), grey(0.773911), 89.6},
    {"emerald", "gem", rgb(0.0215, 0.1745, 0.0215), rgb(0.07568, 0.61424, 0.07568), rgb(0.633, 0.727811, 0.633), 76.8},
    {"jade", "gem", rgb(0.135, 0.2225, 0.1575), rgb(0.54, 0.89, 0.63), grey(0.316228), 12.8},
    {"obsidian", "gem", rgb(0.05375, 0.05, 0.06625), rgb(0.18275, 0.17, 0.22525), rgb(0.332741, 0.328634, 0.346435), 38.4},
    {"pearl", "gem", rgb(0.25, 0.20725, 0.20725), rgb(1, 0.829, 0.829), grey(0.296648), 11.264},
    {"ruby", "gem", rgb(0.1745, 0.01175, 0.01175), rgb(0.61424, 0.04136, 0.04136), rgb(0.727811, 0.626959, 0.626959), 76.8},
    {"turquoise", "gem", rgb(0.1, 0.18725, 0.1745), rgb(0.396, 0.74151, 0.69102), rgb(0.297254, 0.30829, 0.306678), 12.8},
    {"black_plastic", "plastic", grey(0), grey(0.01), grey(0.5), 32},
    {"cyan_plastic", "plastic", rgb(0, 0.1, 0.06), rgb(0, 0.50980392, 0.50980392), grey(0.50196078), 32},
    {"green_plastic", "plastic", grey(0), rgb(0.1, 0.35, 0.1), rgb(0.45, 0.55, 0.45), 32},
    {"red_plastic", "plastic", grey(0), rgb(0.5, 0, 0), rgb(0.7, 0.6, 0.6), 32},
    {"white_plastic", "plastic", grey(0), grey(0.55), grey(0.7), 32},
    {"yellow_plastic", "plastic", grey(0), rgb(0.5, 0.5, 0), rgb(0.6, 0.6, 0.5), 32},
    {"black_rubber", "rubber", grey(0.02), grey(0.01), grey(0.4), 10},
    {"cyan_rubber", "rubber", rgb(0, 0.05, 0.05), rgb(0.4, 0.5, 0.5), rgb(0.04, 0.7, 0.7), 10},
    {"green_rubber", "rubber", rgb(0, 0.05, 0), rgb(0.4, 0.5, 0.4), rgb(0.04, 0.7, 0.04), 10},
    {"red_rubber", "rubber", rgb(0.05, 0, 0), rgb(0.5, 0.4, 0.4), rgb(0.7, 0.04, 0.04), 10},
    {"white_rubber", "rubber", grey(0.05), grey(0.5), grey(0.7), 10},
    {"yellow_rubber", "rubber", rgb(0.05, 0.05, 0), rgb(0.5, 0.5, 0.4), rgb(0.7, 0.7, 0.04), 10},
    // The lecture's own, as its scenes use them (n as it is, for either model), and the
    // transparent ones with their indices of refraction (water 1.333, diamond 2.417).
    {"matte", "lecture", rgb(0.02, 0.06, 0.02), rgb(0.25, 0.7, 0.25), grey(0), 1, grey(0), grey(0), 1.5, false, true, 1},
    {"plastic", "lecture", rgb(0.08, 0.02, 0.02), rgb(0.8, 0.15, 0.1), grey(0.5), 20, grey(0), grey(0), 1.5, false, true, 1},
    {"mirror", "lecture", grey(0), grey(0.05), grey(0.6), 200, grey(0.85), grey(0), 1.5, false, true, 1},
    {"glass", "lecture", grey(0), grey(0), grey(0.5), 300, grey(0), grey(0.9), 1.5, true, true, 1},
    {"water", "lecture", grey(0), grey(0), grey(0.5), 300, grey(0), grey(0.9), 1.333, true, true, 1},
    {"diamond", "lecture", grey(0), grey(0), grey(0.8), 500, grey(0), grey(0.9), 2.417, true, true, 1},
}};

}  // namespace

std::span<const MaterialPreset> material_presets() { return kPresets; }

const MaterialPreset* find_preset(std::string_view name) {
  for (const MaterialPreset& p : kPresets) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

double preset_exponent(const MaterialPreset& p, SpecularModel model) {
  if (p.lecture || model == SpecularModel::kBlinn) return p.shininess;
  return p.shininess / 4;
}

Color apply_preset(Material& m, const MaterialPreset& p, SpecularModel model, const Color& ambient) {
  Color scale(1);
  for (int c = 0; c < 3; ++c) {
    if (ambient[c] > 0 && std::isfinite(ambient[c])) scale[c] = p.assumed_ambient / ambient[c];
  }
  // Scaled, to six significant digits: a saved file reads 0.0399, not 0.039900000000000005.
  for (int c = 0; c < 3; ++c) m.ka[c] = scale[c] == 1 ? p.ka[c] : significant(p.ka[c] * scale[c], 6);
  m.kd = p.kd;
  m.ks = p.ks;
  m.n = preset_exponent(p, model);
  m.kr = p.kr;
  m.kt = p.kt;
  m.ior = p.ior;
  m.fresnel = p.fresnel;
  return scale;
}

namespace {

std::string numbers(const Color& c) {
  std::ostringstream text;
  text.precision(3);
  if (c.x == c.y && c.y == c.z) text << c.x;
  else text << "(" << c.x << ", " << c.y << ", " << c.z << ")";
  return text.str();
}

}  // namespace

std::string preset_note(const MaterialPreset& p) {
  std::ostringstream text;
  text << "made for " << (p.lecture ? "the lecture's" : "OpenGL's dim global ambient") << " Iₐ = " << p.assumed_ambient
       << ": ka is scaled to the scene's Iₐ";
  return text.str();
}

std::string preset_applied_text(const MaterialPreset& p, const Color& scale, const Color& ambient) {
  std::ostringstream text;
  text << p.name << ": ";
  if (scale == Color(1)) text << "ka as in the table (the preset assumes Iₐ = " << p.assumed_ambient << ", this scene's Iₐ = " << numbers(ambient) << ")";
  else text << "ka scaled by " << numbers(scale) << " for this scene's Iₐ = " << numbers(ambient) << " (the preset assumes Iₐ = " << p.assumed_ambient << ")";
  return text.str();
}

}  // namespace phonglab::ui
