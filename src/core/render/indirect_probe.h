// The probe's side of "what ambient stands in for": at one pixel's centre ray, the lecture's
// ka·Ia beside the indirect term's estimate, its standard error, and the ka that would match it.
#pragma once

#include <cstdint>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/scene/scene.h"

namespace phonglab {

struct IndirectProbe {
  bool hit = false;          // the centre ray meets something (else every value is 0)
  int material = -1;
  int bounces = 0;           // the scene's
  int samples = 0;           // gathers averaged
  Color ambient{0};          // ka·Ia at the hit
  Color mean{0};             // the indirect term's estimate: the mean of `samples` estimates
  Color standard_error{0};   // of the mean: the estimates' sample standard deviation / sqrt(samples)
  Color fitted_ka{0};        // per channel, the ka with ka·Ia = mean (0 where Ia is 0)
};

// Samples 0..samples-1 of the indirect term at the primary hit of pixel (x, y)'s centre ray in a
// width x height image (the estimates of a render's samples there, but all from the centre ray).
IndirectProbe probe_indirect(const PreparedScene& prepared, int width, int height, int x, int y, int samples);

// ka whose ka·Ia equals `target`, per channel (0 where Ia is 0 or negative).
Color fitted_ambient(const Color& target, const Color& ia);

// "The best constant ambient for this view": per material, the mean of the indirect term over its
// primary hits in a width x height image (`samples` per pixel, the render's sample positions and
// gathers); the scene's Iₐ that makes ka·Iₐ (ka as the materials give it) nearest to the indirect
// term over all those hits; and per material the ka whose ka·Ia equals its mean, as wanted and
// as a material can have it (in [0, 1]). The same numbers for any thread count.
struct AmbientFit {
  std::vector<Color> mean_indirect;  // by material; 0 where it has no hit
  std::vector<std::uint64_t> hits;   // primary hits counted, by material
  std::vector<Color> wanted_ka;      // by material: mean / Ia per channel; its ka where it has no hit
  std::vector<Color> fitted_ka;      // wanted_ka clamped to [0, 1]
  // Per channel, the Iₐ minimising the sum over the hits of (ka·Iₐ − indirect)²:
  // Σ_m hits_m ka_m mean_m / Σ_m hits_m ka_m² (materials with ka = 0 do not count); the scene's
  // Iₐ where no hit has a ka in that channel.
  Color fitted_ia{0};
  int samples = 0;
  int bounces = 0;
};
// Whether a wanted ka is over what a material can have (a channel over 1).
inline bool ka_over_one(const Color& ka) { return ka.x > 1 || ka.y > 1 || ka.z > 1; }
AmbientFit fit_ambient(const PreparedScene& prepared, int width, int height, int samples, int threads = 0);

}  // namespace phonglab
