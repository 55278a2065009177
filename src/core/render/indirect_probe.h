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
// gathers), and the ka whose ka·Ia equals that mean. The same numbers for any thread count.
struct AmbientFit {
  std::vector<Color> mean_indirect;  // by material; 0 where it has no hit
  std::vector<std::uint64_t> hits;   // primary hits counted, by material
  std::vector<Color> fitted_ka;      // by material; its ka where it has no hit
  int samples = 0;
  int bounces = 0;
};
AmbientFit fit_ambient(const PreparedScene& prepared, int width, int height, int samples, int threads = 0);

}  // namespace phonglab
