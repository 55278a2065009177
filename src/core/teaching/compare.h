// The A/B compare's pixels: A left of a wipe line and the live image right of it, or the
// difference |live - A| scaled by a gain. One rule for the previewer's compare view and the
// lesson handouts.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace phonglab {

enum class CompareView : std::uint8_t { kNone, kWipe, kDifference };

// `live` and `a` are width-wide row-major images of the same size. kWipe: columns below
// round(wipe * width) show A; kDifference: |live - A| * gain; kNone: live.
std::vector<glm::vec3> compare_pixels(const std::vector<glm::vec3>& live, const std::vector<glm::vec3>& a, int width,
                                      CompareView view, double wipe, double gain);

// An ambient view's pixels (AmbientShown) from one image of Term::kIndirect with its term
// images: `indirect` the indirect term, `ambient` ka·Iₐ (the ambient term image), width-wide.
// kBeside: ka·Iₐ left of round(wipe * width), the indirect term right; kDifference: the signed
// gap's heat map (ambient_gap_pixels); kImage: `indirect`.
enum class AmbientShown : std::uint8_t;
std::vector<glm::vec3> ambient_shown_pixels(AmbientShown shown, const std::vector<glm::vec3>& indirect,
                                            const std::vector<glm::vec3>& ambient, int width, double wipe);

}  // namespace phonglab
