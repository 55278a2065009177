// The indirect light's estimate (docs/model.md, "What the ambient term stands in for"): the
// samples and directions of its gather rays. At a hit where the lecture adds ka·Ia, the indirect
// term kd ⊙ E(P) is estimated by one ray in a cosine-weighted direction about N: with density
// (N·ω)/π, the estimator kd ⊙ L_in(P, ω) is unbiased for kd ⊙ (1/π)∫ L_in (N·ω) dω.
//
// Why written here: the gather points are a shuffled, Owen-scrambled Sobol (0,2)-sequence in the
// manner of Burley, "Practical Hash-based Owen Scrambling" (JCGT 2020). No Debian package
// offers one, and it is thirty lines: each pixel and each gather of its sample's tree (the
// "dimension", counted in the tracer's order) get their own scramble, so every gather's points
// over the sample indices are stratified (the first 2^k of them fall one in each of 2^k cells),
// each point is uniform on [0,1)² (the estimate stays unbiased), and a point is a function of
// (pixel, sample index, dimension) alone: the same image for any thread count.
#pragma once

#include <cstdint>

#include "core/scene/math.h"

namespace phonglab {

// The points of one (pixel, sample) of an image, one 2D point a gather, and the bounces left to
// the gathers still to come. Used by one thread for one sample's tree.
class IndirectSampler {
 public:
  // `pixel_key`: indirect_pixel_key(x, y, seed); `bounces` >= 1.
  IndirectSampler(int bounces, std::uint32_t pixel_key, std::uint32_t sample_index)
      : bounces_left_(bounces), key_(pixel_key), sample_(sample_index) {}

  int bounces_left() const { return bounces_left_; }
  // The next gather's point in [0,1)².
  void next_point(double& u1, double& u2);
  // The next choice of a gather's path (which one way on it takes at a hit), in [0,1): its own
  // sequence of dimensions, stratified over the sample indices as the points are.
  double next_choice();
  // Around one gather's trace: its hits have one bounce fewer.
  void descend() { --bounces_left_; }
  void ascend() { ++bounces_left_; }

 private:
  int bounces_left_;
  std::uint32_t key_;
  std::uint32_t sample_;
  std::uint32_t dimension_ = 0;  // gathers taken so far in this sample's tree
  std::uint32_t choice_ = 0;     // choices taken so far in this sample's tree
};

std::uint32_t indirect_pixel_key(int x, int y, std::uint32_t seed);

// The direction for point (u1, u2) under the cosine-weighted density about the unit normal n
// (Malley's method: a uniform point of the unit disc lifted onto the hemisphere). n·ω > 0.
Vec3 cosine_direction(const Vec3& n, double u1, double u2);

}  // namespace phonglab
