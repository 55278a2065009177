#include "core/teaching/heat_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace phonglab {

namespace {

// Nine evenly spaced stops of the ramp, sRGB 8-bit: black, deep purple, purple, magenta-red,
// red, orange-red, orange, yellow, pale yellow. Luminance rises from each stop to the next
// (a unit test checks the whole ramp).
constexpr std::array<std::array<double, 3>, 9> kStops = {{
    {0, 0, 4},
    {31, 12, 72},
    {85, 15, 109},
    {136, 34, 106},
    {186, 54, 85},
    {227, 89, 51},
    {249, 142, 9},
    {248, 201, 49},
    {252, 255, 164},
}};


}  // namespace

Color heat_ramp_srgb(double t) {
  if (!(t > 0)) t = 0;  // NaN too
  if (t > 1) t = 1;
  const double x = t * static_cast<double>(kStops.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(x), kStops.size() - 2);
  const double f = x - static_cast<double>(i);
  Color c;
  for (int k = 0; k < 3; ++k) {
    const auto ch = static_cast<std::size_t>(k);
    c[k] = ((1 - f) * kStops[i][ch] + f * kStops[i + 1][ch]) / 255.0;
  }
  return c;
}

Color heat_color(double value, double max) {
  const Color srgb = heat_ramp_srgb(max > 0 ? value / max : 0);
  return Color(srgb_to_linear(srgb.x), srgb_to_linear(srgb.y), srgb_to_linear(srgb.z));
}

double heat_max(const std::vector<glm::vec3>& rays) {
  double m = 0;
  for (const glm::vec3& p : rays) m = std::max(m, static_cast<double>(p.x));
  return m;
}

std::vector<glm::vec3> heat_map_pixels(const std::vector<glm::vec3>& rays, double max) {
  std::vector<glm::vec3> out(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) out[i] = glm::vec3(heat_color(rays[i].x, max));
  return out;
}

Color ambient_gap_srgb(double t) {
  if (!(t == t)) t = 0;  // NaN: no gap shown
  t = std::clamp(t, -1.0, 1.0);
  // Black, then the colour at |t| = 0.75, then a paler one at 1: luminance rises with |t| on
  // either side, the sign is the hue.
  const Color warm(0.98, 0.55, 0.04), warm_top(1.0, 0.93, 0.55), cool(0.16, 0.45, 1.0), cool_top(0.7, 0.88, 1.0);
  const double a = std::abs(t);
  const Color mid = t > 0 ? warm : cool, top = t > 0 ? warm_top : cool_top;
  return a <= 0.75 ? mid * (a / 0.75) : mid + (top - mid) * ((a - 0.75) / 0.25);
}

std::vector<glm::vec3> ambient_gap_pixels(const std::vector<glm::vec3>& indirect, const std::vector<glm::vec3>& ambient,
                                          double scale) {
  std::vector<glm::vec3> out(std::min(indirect.size(), ambient.size()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const glm::vec3 d = indirect[i] - ambient[i];
    const double gap = (static_cast<double>(d.x) + d.y + d.z) / 3;
    const Color srgb = ambient_gap_srgb(scale > 0 ? gap / scale : 0);
    out[i] = glm::vec3(Color(srgb_to_linear(srgb.x), srgb_to_linear(srgb.y), srgb_to_linear(srgb.z)));
  }
  return out;
}

}  // namespace phonglab
