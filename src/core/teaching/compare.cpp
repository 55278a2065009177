#include "core/teaching/compare.h"

#include <cmath>
#include <cstddef>

#include "core/teaching/heat_map.h"
#include "core/teaching/lesson.h"

namespace phonglab {

std::vector<glm::vec3> compare_pixels(const std::vector<glm::vec3>& live, const std::vector<glm::vec3>& a, int width,
                                      CompareView view, double wipe, double gain) {
  if (view == CompareView::kNone || a.size() != live.size() || width <= 0) return live;
  std::vector<glm::vec3> out(live.size());
  const auto w = static_cast<std::size_t>(width);
  const auto wipe_x = static_cast<std::size_t>(std::max(0L, std::lround(wipe * width)));
  const auto g = static_cast<float>(gain);
  for (std::size_t i = 0; i < live.size(); ++i) {
    if (view == CompareView::kWipe) out[i] = i % w < wipe_x ? a[i] : live[i];
    else out[i] = glm::abs(live[i] - a[i]) * g;
  }
  return out;
}

std::vector<glm::vec3> ambient_shown_pixels(AmbientShown shown, const std::vector<glm::vec3>& indirect,
                                            const std::vector<glm::vec3>& ambient, int width, double wipe) {
  switch (shown) {
    case AmbientShown::kBeside: return compare_pixels(indirect, ambient, width, CompareView::kWipe, wipe, 1);
    case AmbientShown::kDifference: return ambient_gap_pixels(indirect, ambient);
    case AmbientShown::kImage: break;
  }
  return indirect;
}

}  // namespace phonglab
