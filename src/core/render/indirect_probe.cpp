#include "core/render/indirect_probe.h"

#include <cmath>

#include "core/scene/camera.h"
#include "core/shading/shading.h"

namespace phonglab {

Color fitted_ambient(const Color& target, const Color& ia) {
  Color ka(0);
  for (int c = 0; c < 3; ++c) ka[c] = ia[c] > 0 ? target[c] / ia[c] : 0.0;
  return ka;
}

IndirectProbe probe_indirect(const PreparedScene& prepared, int width, int height, int x, int y, int samples) {
  const Scene& scene = prepared.scene();
  IndirectProbe out;
  out.bounces = scene.indirect_bounces;
  const CameraFrame frame = make_camera_frame(scene.camera, width, height);
  double u = 0, v = 0;
  sample_offset(x, y, 0, u, v);
  const Ray ray = camera_ray(frame, x, y, u, v);
  const std::optional<Hit> hit = intersect(prepared, ray);
  if (!hit || samples < 1) return out;
  out.hit = true;
  out.material = hit->material;
  const Material& m = scene.materials[static_cast<std::size_t>(hit->material)];
  out.ambient = m.ka * scene.ambient;
  const HitSide side = hit_side(*hit, ray.dir);
  const double offset = surface_offset(scene, *hit);
  const TraceLimits limits{scene.max_depth, scene.min_weight};
  const std::uint32_t key = indirect_pixel_key(x, y, 0);
  // Welford's running mean and sum of squared deviations, per channel.
  Color mean(0), m2(0);
  RayCounts counts;
  for (int k = 0; k < samples; ++k) {
    IndirectSampler sampler(scene.indirect_bounces, key, static_cast<std::uint32_t>(k));
    const Color e = indirect_estimate(prepared, limits, m, hit->p, side, offset, counts, sampler);
    const Color delta = e - mean;
    mean += delta / static_cast<double>(k + 1);
    m2 += delta * (e - mean);
  }
  out.samples = samples;
  out.mean = mean;
  if (samples > 1) out.standard_error = glm::sqrt(m2 / static_cast<double>(samples - 1) / static_cast<double>(samples));
  out.fitted_ka = fitted_ambient(mean, scene.ambient);
  return out;
}

}  // namespace phonglab
