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

}  // namespace phonglab
