// The indirect light's estimate on the Cornell box agrees with an independent, simple estimator
// written here for the test: uniform (not cosine-weighted) hemisphere directions from a Mersenne
// Twister, the direct light summed by hand. Two unbiased estimators of one integral must agree
// within their standard errors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/render/indirect_probe.h"
#include "core/render/render.h"
#include "tests/support/test_support.h"

using namespace phonglab;

namespace {

class SimplePathTracer {
 public:
  explicit SimplePathTracer(const PreparedScene& prepared, std::uint64_t seed)
      : prepared_(prepared), scene_(prepared.scene()), rng_(seed) {}

  // One estimate of kd ⊙ (1/π)∫ L_in (N·ω) dω at a hit, with `bounces` left.
  Color indirect(const Hit& hit, const Vec3& d, int bounces) {
    const Material& m = scene_.materials[static_cast<std::size_t>(hit.material)];
    if (bounces == 0 || is_zero(m.kd)) return Color(0);
    const Vec3 ng = glm::dot(hit.ng, d) < 0 ? hit.ng : -hit.ng;
    const Vec3 n = glm::dot(hit.ns, d) < 0 ? hit.ns : -hit.ns;
    // A uniform direction on the sphere, folded into N's hemisphere: density 1 / (2π).
    Vec3 w;
    do {
      w = Vec3(uniform_(rng_) * 2 - 1, uniform_(rng_) * 2 - 1, uniform_(rng_) * 2 - 1);
    } while (glm::dot(w, w) > 1 || glm::dot(w, w) < 1e-6);
    w = glm::normalize(w);
    if (glm::dot(w, n) < 0) w = -w;
    const Ray ray = make_ray(offset_origin(hit.p, ng, w, surface_offset(scene_, hit)), w);
    // (1/π) L cos / (1 / 2π) = 2 L cos.
    return m.kd * radiance(ray, bounces - 1) * (2 * glm::dot(w, n));
  }

 private:
  Color radiance(const Ray& ray, int bounces) {
    const std::optional<Hit> hit = intersect(prepared_, ray);
    if (!hit) return scene_.background;
    const Material& m = scene_.materials[static_cast<std::size_t>(hit->material)];
    EXPECT_TRUE(is_zero(m.kr) && is_zero(m.kt)) << "the simple estimator has no mirrors or glass";
    return direct(*hit, ray.dir, m) + indirect(*hit, ray.dir, bounces);
  }

  Color direct(const Hit& hit, const Vec3& d, const Material& m) const {
    const Vec3 ng = glm::dot(hit.ng, d) < 0 ? hit.ng : -hit.ng;
    const Vec3 n = glm::dot(hit.ns, d) < 0 ? hit.ns : -hit.ns;
    Color sum(0);
    for (const Light& light : scene_.lights) {
      EXPECT_EQ(light.type, LightType::kPoint);
      const Vec3 to = light.position - hit.p;
      const Vec3 l = glm::normalize(to);
      const double n_dot_l = glm::dot(n, l);
      if (n_dot_l <= 0) continue;
      const Vec3 origin = offset_origin(hit.p, ng, l, surface_offset(scene_, hit));
      const double dist = glm::length(light.position - origin);
      if (occluded(prepared_, make_ray(origin, (light.position - origin) / dist), dist * (1 - 1e-9))) continue;
      const Vec3 r = 2 * n_dot_l * n - l;
      const double spec = std::pow(std::max(0.0, glm::dot(r, -d)), m.n);
      sum += light.intensity * (m.kd * n_dot_l + m.ks * spec);
    }
    return sum;
  }

  const PreparedScene& prepared_;
  const Scene& scene_;
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

}  // namespace

TEST(IndirectCornell, AgreesWithAnIndependentEstimatorWithinItsStandardError) {
  const PreparedScene prepared = load_prepared("cornell");
  const Scene& scene = prepared.scene();
  ASSERT_EQ(scene.indirect_bounces, 4);
  constexpr int kWidth = 64, kHeight = 36;
  // The red wall, the back wall, the floor, the tall box, the ceiling.
  const int pixels[][2] = {{20, 18}, {32, 14}, {36, 33}, {27, 20}, {34, 2}};
  const CameraFrame frame = make_camera_frame(scene.camera, kWidth, kHeight);
  int compared = 0;
  for (const auto& [x, y] : pixels) {
    const IndirectProbe ours = probe_indirect(prepared, kWidth, kHeight, x, y, 4096);
    ASSERT_TRUE(ours.hit) << x << "," << y;
    const Ray ray = camera_ray(frame, x, y, 0.5, 0.5);
    const std::optional<Hit> hit = intersect(prepared, ray);
    ASSERT_TRUE(hit);
    SimplePathTracer simple(prepared, 1234567u + static_cast<std::uint64_t>(x * 100 + y));
    constexpr int kSamples = 8192;
    Color mean(0), m2(0);
    for (int k = 0; k < kSamples; ++k) {
      const Color e = simple.indirect(*hit, ray.dir, scene.indirect_bounces);
      const Color delta = e - mean;
      mean += delta / static_cast<double>(k + 1);
      m2 += delta * (e - mean);
    }
    const Color se = glm::sqrt(m2 / double(kSamples - 1) / double(kSamples));
    for (int c = 0; c < 3; ++c) {
      const double sigma = std::sqrt(se[c] * se[c] + ours.standard_error[c] * ours.standard_error[c]);
      EXPECT_GT(mean[c], 0) << x << "," << y;
      EXPECT_LE(std::abs(ours.mean[c] - mean[c]), 4 * sigma)
          << "pixel " << x << "," << y << " channel " << c << ": ours " << ours.mean[c] << " ± "
          << ours.standard_error[c] << ", simple " << mean[c] << " ± " << se[c];
    }
    ++compared;
  }
  EXPECT_EQ(compared, 5);
}
