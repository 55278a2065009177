// The packet tracer (renderer/packet.h) against the scalar renderer: the same image bit for
// bit and the same ray counts, on the embedded scenes and on seeded random scenes that reach
// every branch of the equation (Phong and Blinn, point and directional lights, muted lights,
// lights on surfaces, mirrors, glass with and without Fresnel, total internal reflection, the
// depth and weight limits, loose triangles, the camera inside a sphere).
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>

#include "renderer/accel.h"
#include "renderer/packet.h"
#include "renderer/render.h"
#include "test_support.h"

using namespace phonglab;

namespace {

struct Frame {
  Accumulator accum;
  RayCounts rays;
  std::uint64_t nan_count = 0;
};

Frame render(const Scene& scene, int w, int h, int passes, bool packets, int threads = 1, std::uint32_t seed = 0) {
  Frame f;
  f.accum.reset(w, h);
  RenderOptions opt;
  opt.packets = packets;
  opt.threads = threads;
  opt.seed = seed;
  const PassStats st = render_passes(scene, opt, f.accum, passes);
  f.rays = st.rays;
  f.nan_count = st.nan_count;
  return f;
}

// Bit-for-bit comparison; the message names the first differing pixel.
::testing::AssertionResult same_bits(const Frame& a, const Frame& b) {
  for (std::size_t i = 0; i < a.accum.sum.size(); ++i) {
    if (std::memcmp(&a.accum.sum[i], &b.accum.sum[i], sizeof(Color)) != 0) {
      const Color& p = a.accum.sum[i];
      const Color& q = b.accum.sum[i];
      return ::testing::AssertionFailure()
             << "pixel " << i % static_cast<std::size_t>(a.accum.width) << "," << i / static_cast<std::size_t>(a.accum.width)
             << ": packets (" << p.x << ", " << p.y << ", " << p.z << ") scalar (" << q.x << ", " << q.y << ", " << q.z
             << ")";
    }
  }
  if (a.rays.primary != b.rays.primary || a.rays.shadow != b.rays.shadow || a.rays.reflection != b.rays.reflection ||
      a.rays.refraction != b.rays.refraction) {
    return ::testing::AssertionFailure() << "ray counts differ: shadow " << a.rays.shadow << " vs " << b.rays.shadow
                                         << ", reflection " << a.rays.reflection << " vs " << b.rays.reflection
                                         << ", refraction " << a.rays.refraction << " vs " << b.rays.refraction;
  }
  if (a.nan_count != b.nan_count) return ::testing::AssertionFailure() << "NaN counts differ";
  return ::testing::AssertionSuccess();
}

#define REQUIRE_PACKETS()                                                     \
  if (!packet_cpu_supported()) GTEST_SKIP() << "this CPU has no AVX2: the scalar renderer serves"

Color random_color(std::mt19937& rng, double zero_chance, double hi) {
  std::uniform_real_distribution<double> u(0, 1);
  if (u(rng) < zero_chance) return Color(0);
  if (u(rng) < 0.5) return Color(u(rng) * hi);
  return Color(u(rng) * hi, u(rng) * hi, u(rng) * hi);
}

// A random scene the brute-force path traces (few spheres and triangles, no mesh).
Scene random_scene(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), c(-3, 3);
  Scene s;
  const double scale = u(rng) < 0.2 ? std::pow(10.0, std::uniform_int_distribution<int>(-3, 4)(rng)) : 1.0;
  s.camera.position = Vec3(c(rng), 1 + 2 * u(rng), 5 + 3 * u(rng)) * scale;
  s.camera.look_at = Vec3(c(rng) * 0.3, c(rng) * 0.3, 0) * scale;
  s.camera.fov_y_deg = 20 + 100 * u(rng);
  s.background = random_color(rng, 0.3, 0.5);
  s.ambient = random_color(rng, 0.2, 1);
  s.max_depth = std::uniform_int_distribution<int>(0, 7)(rng);
  s.min_weight = u(rng) < 0.3 ? 0.0 : std::pow(10.0, -4 + 3 * u(rng));
  s.specular_model = u(rng) < 0.5 ? SpecularModel::kPhong : SpecularModel::kBlinn;
  const int materials = std::uniform_int_distribution<int>(1, 5)(rng);
  for (int i = 0; i < materials; ++i) {
    Material m;
    m.ka = random_color(rng, 0.3, 0.2);
    m.kd = random_color(rng, 0.3, 0.9);
    m.ks = random_color(rng, 0.3, 0.8);
    m.n = u(rng) < 0.1 ? 0.0 : (u(rng) < 0.2 ? 0.5 + u(rng) : std::pow(10.0, 3 * u(rng)));
    m.kr = random_color(rng, 0.6, 0.9);
    m.kt = random_color(rng, 0.6, 0.9);
    m.ior = 1 + u(rng);
    m.fresnel = u(rng) < 0.5;
    s.materials.push_back(m);
  }
  auto material = [&] { return std::uniform_int_distribution<int>(0, materials - 1)(rng); };
  const int spheres = std::uniform_int_distribution<int>(0, 6)(rng);
  for (int i = 0; i < spheres; ++i) {
    s.spheres.push_back(Sphere{Vec3(c(rng), u(rng) * 2, c(rng)) * scale, (0.1 + u(rng)) * scale, material()});
  }
  if (u(rng) < 0.15 && !s.spheres.empty()) {  // the camera inside a sphere
    s.spheres[0].center = s.camera.position;
    s.spheres[0].radius = 2 * scale;
  }
  const int planes = std::uniform_int_distribution<int>(0, 2)(rng);
  for (int i = 0; i < planes; ++i) {
    Vec3 n(c(rng) * 0.2, 1, c(rng) * 0.2);
    if (i == 1) n = Vec3(c(rng), c(rng), -3);  // a back wall, at any angle
    s.planes.push_back(Plane{Vec3(0, -u(rng), -4 * u(rng)) * scale, n, material()});
  }
  const int triangles = u(rng) < 0.3 ? std::uniform_int_distribution<int>(1, 2)(rng) : 0;
  for (int i = 0; i < triangles; ++i) {
    Triangle t;
    t.v0 = Vec3(c(rng), u(rng) * 2, c(rng)) * scale;
    t.v1 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
    t.v2 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
    t.material = material();
    s.triangles.push_back(t);
  }
  const int lights = std::uniform_int_distribution<int>(0, 3)(rng);
  for (int i = 0; i < lights; ++i) {
    Light l;
    l.type = u(rng) < 0.6 ? LightType::kPoint : LightType::kDirectional;
    l.position = Vec3(c(rng), 1 + 4 * u(rng), c(rng)) * scale;
    l.direction = Vec3(c(rng), -1 - u(rng), c(rng));
    l.intensity = random_color(rng, 0.0, 1.0);
    l.enabled = u(rng) < 0.9;
    s.lights.push_back(l);
  }
  if (!s.lights.empty() && !s.spheres.empty() && u(rng) < 0.2) {  // a light lying on a sphere
    Light& l = s.lights[0];
    l.type = LightType::kPoint;
    l.position = s.spheres[0].center + Vec3(0, s.spheres[0].radius, 0);
  }
  prepare_scene(s);
  return s;
}

TEST(PacketTracer, EmbeddedScenesAreBitIdenticalToTheScalarRenderer) {
  REQUIRE_PACKETS();
  for (const char* name : {"lecture", "shininess", "lights", "mirrors", "glass"}) {
    SCOPED_TRACE(name);
    const Scene scene = load_prepared(name);
    ASSERT_TRUE(packet_tracing_applies(scene));
    // Odd sizes leave partial tiles and lanes; three passes take jittered samples too.
    const Frame packets = render(scene, 157, 91, 3, true);
    const Frame scalar = render(scene, 157, 91, 3, false);
    EXPECT_GT(packets.rays.shadow, 0u);
    EXPECT_TRUE(same_bits(packets, scalar));
  }
}

TEST(PacketTracer, RandomScenesAreBitIdenticalToTheScalarRenderer) {
  REQUIRE_PACKETS();
  RayCounts seen;
  for (std::uint32_t seed = 1; seed <= 300; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Scene scene = random_scene(seed);
    if (!packet_tracing_applies(scene)) continue;
    const Frame packets = render(scene, 29, 17, 2, true, 1, seed);
    const Frame scalar = render(scene, 29, 17, 2, false, 1, seed);
    ASSERT_TRUE(same_bits(packets, scalar));
    seen += packets.rays;
  }
  // The cases did reach the recursion.
  EXPECT_GT(seen.reflection, 1000u);
  EXPECT_GT(seen.refraction, 1000u);
  EXPECT_GT(seen.shadow, 10000u);
}

// The per-tile culling (the primary rays' cone, the shadow rays' capsule) must never drop a
// sphere a ray meets: many small spheres whose outlines cross tile edges and shadow volumes,
// at several scales and far from the origin, rendered over many tiles.
TEST(PacketTracer, CullingNeverDropsASphereARayMeets) {
  REQUIRE_PACKETS();
  std::uint64_t shadow_rays = 0;
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1), c(-2, 2);
    const double scale = std::pow(10.0, std::uniform_int_distribution<int>(-2, 3)(rng));
    const Vec3 shift = u(rng) < 0.3 ? Vec3(1e5, -3e4, 2e4) * scale : Vec3(0);
    Scene s;
    s.camera.position = (Vec3(0, 1, 6) + shift / scale) * scale;
    s.camera.look_at = (Vec3(0, 0.5, 0) + shift / scale) * scale;
    s.camera.fov_y_deg = 10 + 80 * u(rng);
    Material m;
    m.ka = Color(0.1);
    m.kd = Color(0.7);
    m.ks = Color(0.3);
    m.n = 20;
    s.materials = {m};
    for (int i = 0; i < 8; ++i) {
      s.spheres.push_back(Sphere{Vec3(c(rng), 0.5 + c(rng) * 0.4, c(rng)) * scale + shift, (0.02 + 0.3 * u(rng)) * scale, 0});
    }
    s.planes.push_back(Plane{Vec3(0, -0.2, 0) * scale + shift, Vec3(0, 1, 0), 0});
    Light point;
    point.position = Vec3(c(rng), 3 + u(rng), c(rng)) * scale + shift;
    Light sun;
    sun.type = LightType::kDirectional;
    sun.direction = Vec3(c(rng), -1, c(rng));
    s.lights = {point, sun};
    prepare_scene(s);
    ASSERT_TRUE(packet_tracing_applies(s));
    const Frame packets = render(s, 96, 64, 2, true, 1, seed);
    const Frame scalar = render(s, 96, 64, 2, false, 1, seed);
    ASSERT_TRUE(same_bits(packets, scalar));
    shadow_rays += packets.rays.shadow;
  }
  EXPECT_GT(shadow_rays, 100000u);
}

TEST(PacketTracer, TheImageDoesNotDependOnTheThreadCount) {
  REQUIRE_PACKETS();
  const Scene scene = load_prepared("glass");
  EXPECT_TRUE(same_bits(render(scene, 200, 120, 2, true, 1), render(scene, 200, 120, 2, true, 3)));
}

TEST(PacketTracer, ServesOnlyWhatItCanTraceExactly) {
  Scene scene = load_prepared("lecture");
  EXPECT_EQ(packet_tracing_applies(scene), packet_cpu_supported());
  Scene with_bvh = scene;
  with_bvh.accel = build_scene_accel(with_bvh, /*force_bvh=*/true);
  EXPECT_FALSE(packet_tracing_applies(with_bvh));
  Scene variant = scene;
  variant.numerics.schlick_fresnel = true;
  EXPECT_FALSE(packet_tracing_applies(variant));
  variant = scene;
  variant.numerics.fixed_offset = 1e-4;
  EXPECT_FALSE(packet_tracing_applies(variant));
  EXPECT_FALSE(packet_tracing_applies(load_prepared("cornell")));  // a mesh: the BVH serves
}

}  // namespace
