// The heat map of rays per pixel (Term::kRays): a perceptual colour ramp from black through
// purple, red and orange to pale yellow (after matplotlib's "inferno"), rising in luminance
// all the way, so brighter always means more rays. Pure.
#pragma once

#include <vector>

#include "core/scene/math.h"

namespace phonglab {

// The ramp's display colour (sRGB-encoded, each channel in [0, 1]) at t in [0, 1]; t outside
// is clamped. Piecewise linear between nine control points.
Color heat_ramp_srgb(double t);

// The linear RGB whose sRGB encoding is heat_ramp_srgb(value / max): what the image pipeline
// (exposure 0, sRGB display, PNG writer) shows as the ramp. max <= 0 maps everything to t = 0.
Color heat_color(double value, double max);

// Largest value of the first channel over the image (rays per pixel are grey): the top of
// the scale. 0 for an empty image.
double heat_max(const std::vector<glm::vec3>& rays);

// The heat map of a rays-per-pixel image (linear, as heat_color), scaled so that `max` is
// the top of the ramp.
std::vector<glm::vec3> heat_map_pixels(const std::vector<glm::vec3>& rays, double max);

// The ambient gap: indirect − ka·Iₐ at a pixel (the mean of its three channels), on a diverging
// ramp at a fixed scale, so its colours do not change as the estimate's noise settles: black
// where ka·Iₐ is right, orange to pale yellow where more light arrives than ka·Iₐ says (at +scale
// and beyond), blue to pale blue where less does (at -scale and beyond). The display colour
// (sRGB-encoded) for t = gap / scale in [-1, 1], clamped.
Color ambient_gap_srgb(double t);
// The fixed scale of the previewer, the page and the handouts (linear units of radiance).
inline constexpr double kAmbientGapScale = 0.25;
// The gap image: linear RGB whose sRGB encoding is ambient_gap_srgb((mean(indirect) -
// mean(ambient)) / scale) per pixel; `indirect` and `ambient` of one size.
std::vector<glm::vec3> ambient_gap_pixels(const std::vector<glm::vec3>& indirect, const std::vector<glm::vec3>& ambient,
                                          double scale = kAmbientGapScale);

}  // namespace phonglab
