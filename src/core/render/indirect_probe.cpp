#include "core/render/indirect_probe.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/base/threads.h"
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

AmbientFit fit_ambient(const PreparedScene& prepared, int width, int height, int samples, int threads) {
  const Scene& scene = prepared.scene();
  const std::size_t materials = scene.materials.size();
  const CameraFrame frame = make_camera_frame(scene.camera, width, height);
  const TraceLimits limits{scene.max_depth, scene.min_weight};
  // A row's sums, by material: added up row by row in order afterwards, so that the thread count
  // does not change a bit of the result.
  struct RowSums {
    std::vector<Color> sum;
    std::vector<std::uint64_t> hits;
  };
  std::vector<RowSums> rows(static_cast<std::size_t>(std::max(height, 0)));
  std::atomic<int> next_row{0};
  const auto work = [&](int) {
    RayCounts counts;
    for (int y = next_row.fetch_add(1); y < height; y = next_row.fetch_add(1)) {
      RowSums& row = rows[static_cast<std::size_t>(y)];
      row.sum.assign(materials, Color(0));
      row.hits.assign(materials, 0);
      for (int x = 0; x < width; ++x) {
        for (int s = 0; s < samples; ++s) {
          double u = 0, v = 0;
          sample_offset(x, y, static_cast<std::uint32_t>(s), u, v);
          const Ray ray = camera_ray(frame, x, y, u, v);
          const std::optional<Hit> hit = intersect(prepared, ray);
          if (!hit) continue;
          const auto m = static_cast<std::size_t>(hit->material);
          IndirectSampler sampler(scene.indirect_bounces, indirect_pixel_key(x, y, 0), static_cast<std::uint32_t>(s));
          row.sum[m] += indirect_estimate(prepared, limits, scene.materials[m], hit->p, hit_side(*hit, ray.dir),
                                          surface_offset(scene, *hit), counts, sampler);
          ++row.hits[m];
        }
      }
    }
  };
  run_workers(std::max(1, std::min(resolve_thread_count(threads), height)), work);
  AmbientFit fit;
  fit.samples = samples;
  fit.bounces = scene.indirect_bounces;
  fit.mean_indirect.assign(materials, Color(0));
  fit.hits.assign(materials, 0);
  for (const RowSums& row : rows) {
    for (std::size_t m = 0; m < row.sum.size(); ++m) {
      fit.mean_indirect[m] += row.sum[m];
      fit.hits[m] += row.hits[m];
    }
  }
  Color ka_indirect(0), ka_squared(0);  // Σ hits ka mean, Σ hits ka², per channel
  for (std::size_t m = 0; m < materials; ++m) {
    if (fit.hits[m] > 0) fit.mean_indirect[m] /= static_cast<double>(fit.hits[m]);
    const Color wanted = fit.hits[m] > 0 ? fitted_ambient(fit.mean_indirect[m], scene.ambient) : scene.materials[m].ka;
    fit.wanted_ka.push_back(wanted);
    fit.fitted_ka.push_back(glm::clamp(wanted, Color(0), Color(1)));
    const auto n = static_cast<double>(fit.hits[m]);
    const Color& ka = scene.materials[m].ka;
    ka_indirect += n * ka * fit.mean_indirect[m];
    ka_squared += n * ka * ka;
  }
  for (int c = 0; c < 3; ++c) fit.fitted_ia[c] = ka_squared[c] > 0 ? std::max(ka_indirect[c] / ka_squared[c], 0.0) : scene.ambient[c];
  return fit;
}

}  // namespace phonglab
