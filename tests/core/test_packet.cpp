// The packet tracer (src/core/packet/packet.h) against the scalar renderer: the same image bit for
// bit and the same ray counts, on the embedded scenes and on seeded random scenes that reach
// every branch of the equation (Phong and Blinn, point and directional lights, muted lights,
// lights on surfaces, mirrors, glass with and without Fresnel, total internal reflection, the
// depth and weight limits, loose triangles, the camera inside a sphere).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>

#include "core/accel/accel.h"
#include "core/accel/prepared_scene.h"
#include "experiments/numerics_variants.h"
#include "core/packet/packet.h"
#include "tests/support/kernel_checks.h"
#include "tests/support/simd_targets.h"
#include "core/render/render.h"
#include "tests/support/random_scenes.h"
#include "tests/support/test_support.h"

using namespace phonglab;

namespace {

struct Frame {
  Accumulator accum;
  RayCounts rays;
  std::uint64_t nan_count = 0;
};

Frame render(const PreparedScene& scene, int w, int h, int passes, bool packets, int threads = 1, std::uint32_t seed = 0,
             Term term = Term::kFull, std::optional<Vec3> eye = std::nullopt) {
  Frame f;
  f.accum.reset(w, h);
  RenderOptions opt;
  opt.packets = packets;
  opt.threads = threads;
  opt.seed = seed;
  opt.term = term;
  opt.shading_eye = eye;
  const PassStats st = render_passes(scene, opt, f.accum, passes);
  EXPECT_EQ(st.packets, packets && packet_tracing_applies(scene) && PacketTracer::draws(term));
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

// The random cases did reach the recursion and the lights.
void expect_every_ray_kind(const RayCounts& seen) {
  EXPECT_GT(seen.reflection, 1000u);
  EXPECT_GT(seen.refraction, 1000u);
  EXPECT_GT(seen.shadow, 10000u);
}

#define REQUIRE_PACKETS()                                                     \
  if (!packet_cpu_supported()) GTEST_SKIP() << "this CPU runs no packet kernels: the scalar renderer serves"

// The forced hierarchy over every primitive (a SceneBvh even where brute force would serve).
std::shared_ptr<const Accelerator> forced_bvh(const Scene& s) { return build_scene_accel(s, /*force_bvh=*/true); }

TEST(PacketTracer, EmbeddedScenesAreBitIdenticalToTheScalarRenderer) {
  REQUIRE_PACKETS();
  test::for_each_simd_target([&] {
    for (const char* name : {"lecture", "shininess", "lights", "mirrors", "glass", "cornell", "cornell-sphere"}) {
      SCOPED_TRACE(name);
      const PreparedScene scene = load_prepared(name);
      ASSERT_TRUE(packet_tracing_applies(scene));
      // Odd sizes leave partial tiles and lanes; three passes take jittered samples too.
      const Frame packets = render(scene, 157, 91, 3, true);
      const Frame scalar = render(scene, 157, 91, 3, false);
      EXPECT_GT(packets.rays.shadow, 0u);
      EXPECT_TRUE(same_bits(packets, scalar));
    }
  });
}

TEST(PacketTracer, RandomScenesAreBitIdenticalToTheScalarRenderer) {
  REQUIRE_PACKETS();
  test::for_each_simd_target([&] {
    RayCounts seen;
    for (std::uint32_t seed = 1; seed <= 300; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      const PreparedScene scene = random_scene(seed);
      if (!packet_tracing_applies(scene)) continue;
      const Frame packets = render(scene, 29, 17, 2, true, 1, seed);
      const Frame scalar = render(scene, 29, 17, 2, false, 1, seed);
      ASSERT_TRUE(same_bits(packets, scalar));
      seen += packets.rays;
    }
    expect_every_ray_kind(seen);
  });
}

// A tracer that takes over the buffers of another scene's tracer (as render_pass does after every
// edit) draws what a new one draws: from a deeper scene to a shallower one and back, with a
// hierarchy and without, tiles of different sizes.
TEST(PacketTracer, ARecycledTracerDrawsWhatANewOneDraws) {
  REQUIRE_PACKETS();
  std::optional<PreparedScene> previous;
  std::unique_ptr<PacketTracer> kept;
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const PreparedScene& scene = previous.emplace(random_scene(seed, seed % 3 == 0));
    if (!packet_tracing_applies(scene)) continue;
    const int w = 8 + static_cast<int>(seed % 9), h = 5 + static_cast<int>(seed % 7);
    const CameraFrame frame = make_camera_frame(scene.scene().camera, w, h);
    std::vector<Color> fresh_out(static_cast<std::size_t>(w * h)), kept_out(fresh_out.size());
    RayCounts fresh_rays, kept_rays;
    PacketTracer fresh(scene);
    fresh.render_tile(frame, 0, 0, w, h, seed, seed, fresh_out.data(), fresh_rays);
    kept = kept ? std::make_unique<PacketTracer>(scene, std::move(*kept)) : std::make_unique<PacketTracer>(scene);
    kept->render_tile(frame, 0, 0, w, h, seed, seed, kept_out.data(), kept_rays);
    ASSERT_EQ(std::memcmp(fresh_out.data(), kept_out.data(), fresh_out.size() * sizeof(Color)), 0);
    ASSERT_EQ(fresh_rays.total(), kept_rays.total());
  }
}

// The same random scenes traced through the scene's hierarchy: its spheres and loose triangles
// (force_bvh), then with meshes and more spheres added, some far from the origin. Lanes of a
// packet that differ in the signs of their directions or in the axes of their triangle shear are
// among them (wide fields of view, tiles across the image's axes).
TEST(PacketTracer, HierarchyScenesAreBitIdenticalToTheScalarRenderer) {
  REQUIRE_PACKETS();
  test::for_each_simd_target([&] {
    RayCounts seen;
    int with_meshes = 0;
    std::uint64_t far_shadow = 0;
    for (std::uint32_t seed = 1; seed <= 200; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      Scene data = random_scene_data(seed, seed % 4 != 0);
      // Every fifth scene far from the origin (docs/accuracy.md O5): coordinates 1e5 times its size
      // (moved once prepared, then prepared again).
      if (seed % 5 == 0) {
        data = transformed_scene(PreparedScene(data).scene(), 1, Vec3(1e5, -4e4, 3e4) * glm::length(data.camera.position));
      }
      const PreparedScene scene(std::move(data), forced_bvh);
      ASSERT_TRUE(packet_tracing_applies(scene));
      with_meshes += !scene.scene().meshes.empty();
      const Frame packets = render(scene, 37, 23, 2, true, 1, seed);
      const Frame scalar = render(scene, 37, 23, 2, false, 1, seed);
      ASSERT_TRUE(same_bits(packets, scalar));
      seen += packets.rays;
      if (seed % 5 == 0) far_shadow += packets.rays.shadow;
    }
    EXPECT_GT(with_meshes, 100);
    EXPECT_GT(far_shadow, 10000u);  // the moved scenes are lit and seen, not lost to rounding
    expect_every_ray_kind(seen);
  });
}

// Brute-force scenes of mixed primitives with several loose triangles (the four-wide loose
// triangle tests, nearest and shadow): a floor quad sometimes, some scenes far from the origin
// or at extreme scales (random_scene_data's), lights, mirrors and glass.
TEST(PacketTracer, LooseTrianglesAmongSpheresAndPlanesAreBitIdenticalToTheScalarRenderer) {
  REQUIRE_PACKETS();
  test::for_each_simd_target([&] {
    RayCounts seen;
    int traced = 0;
    for (std::uint32_t seed = 1; seed <= 200; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      Scene data = random_scene_data(seed + 5000);
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> c(-3, 3);
      const double scale = std::max(1e-3, glm::length(data.camera.position) / 6);
      const int room = 8 - static_cast<int>(data.spheres.size() + data.triangles.size());
      if (seed % 3 == 0 && room >= 2) {  // a floor of two triangles under everything
        const double h = 50 * scale;
        const Vec3 a(-h, -0.5 * scale, -h), b(h, -0.5 * scale, -h), cc(h, -0.5 * scale, h), d(-h, -0.5 * scale, h);
        data.triangles.push_back(Triangle{a, d, cc, 0});
        data.triangles.push_back(Triangle{a, cc, b, 0});
      }
      while (data.spheres.size() + data.triangles.size() < 8) {
        Triangle t;
        t.v0 = Vec3(c(rng), c(rng) * 0.5 + 1, c(rng)) * scale;
        t.v1 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
        t.v2 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
        t.material = static_cast<int>(seed % data.materials.size());
        data.triangles.push_back(t);
      }
      if (seed % 7 == 0) data = transformed_scene(data, 1, Vec3(1e5, -4e4, 3e4) * scale);
      const PreparedScene scene(std::move(data));
      if (!packet_tracing_applies(scene)) continue;
      ASSERT_EQ(scene.accel(), nullptr);  // brute force: the loose-triangle kernels, not the walk
      ++traced;
      const Frame packets = render(scene, 31, 19, 2, true, 1, seed);
      const Frame scalar = render(scene, 31, 19, 2, false, 1, seed);
      ASSERT_TRUE(same_bits(packets, scalar));
      seen += packets.rays;
    }
    EXPECT_GT(traced, 150);
    expect_every_ray_kind(seen);
  });
}

// Rays exactly through edges that two triangles share: a camera straight above a flat grid of
// triangles in seven colours, on a grid line, so that the pixel-centre rays of the middle column
// lie in the plane x = 0 and those of the middle row in z = 0 (the width and height are odd).
// Where both triangles give the same t, the tie goes to the first in the scene's order, in the
// packet walk as in the scalar one, whichever child each visits first.
TEST(PacketTracer, RaysThroughSharedEdgesGetTheScalarRenderersTriangle) {
  REQUIRE_PACKETS();
  test::for_each_simd_target([&] {
    Scene s;
    for (int k = 0; k < 7; ++k) {
      Material m;
      m.kd = Color(0.1 + 0.8 * (k & 1), 0.1 + 0.4 * (k & 2), 0.1 + 0.2 * (k & 4));
      s.materials.push_back(m);
    }
    std::vector<Triangle> tris;
    for (int j = -4; j < 4; ++j) {
      for (int i = -4; i < 4; ++i) {
        const Vec3 a(0.25 * i, 0, 0.25 * j), b(0.25 * (i + 1), 0, 0.25 * j);
        const Vec3 c(0.25 * i, 0, 0.25 * (j + 1)), d(0.25 * (i + 1), 0, 0.25 * (j + 1));
        const int k = static_cast<int>(tris.size());
        tris.push_back(Triangle{a, d, b, k % 7});
        tris.push_back(Triangle{a, c, d, (k + 1) % 7});
      }
    }
    Mesh mesh;
    mesh.geometry = make_mesh_geometry(std::move(tris), {});
    s.meshes.push_back(std::move(mesh));
    s.mesh_object.push_back(0);
    s.camera.position = Vec3(0, 2, 0);
    s.camera.look_at = Vec3(0, 0, 0);
    s.camera.up = Vec3(0, 0, -1);
    s.camera.fov_y_deg = 60;
    Light sun;
    sun.type = LightType::kDirectional;
    sun.direction = Vec3(0.3, -1, 0.2);
    s.lights = {sun};
    {
      const PreparedScene p(s);
      ASSERT_TRUE(packet_tracing_applies(p));
      for (const int size : {63, 65, 127}) {
        SCOPED_TRACE("size " + std::to_string(size));
        EXPECT_TRUE(same_bits(render(p, size, size, 1, true), render(p, size, size, 1, false)));
      }
    }
    // The middle pixel's ray runs along the diagonal (-1, -1, -1) exactly through the vertex at the
    // origin: all six triangles around it are met at the same t, and a walk along the negative
    // axes visits the ones later in the scene's order first.
    for (const Vec3& eye : {Vec3(1, 1, 1), Vec3(0.5, 1, 0.5), Vec3(-1, 1, 1)}) {
      s.camera.position = eye;
      s.camera.up = Vec3(0, 1, 0);
      const PreparedScene p(s);
      const Frame packets = render(p, 31, 31, 1, true);
      const Frame scalar = render(p, 31, 31, 1, false);
      EXPECT_TRUE(same_bits(packets, scalar));
    }
  });
}

// The five term images and "move your head" (V towards a moved eye at the primary hit) are the
// scalar renderer's too, through brute force and through the hierarchy.
TEST(PacketTracer, TermImagesAndAMovedEyeAreBitIdenticalToTheScalarRenderer) {
  REQUIRE_PACKETS();
  test::for_each_simd_target([&] {
    std::vector<std::pair<std::string, PreparedScene>> scenes;
    for (const char* name : {"lecture", "glass", "cornell-sphere"}) scenes.emplace_back(name, load_prepared(name));
    for (std::uint32_t seed = 1; seed <= 40; ++seed) {
      scenes.emplace_back("seed " + std::to_string(seed), random_scene(seed, seed % 2 == 0));
    }
    const Term terms[] = {Term::kFull, Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection,
                          Term::kRefraction};
    for (const auto& [name, scene] : scenes) {
      SCOPED_TRACE(name);
      const Camera& c = scene.scene().camera;
      const double reach = glm::length(c.position - c.look_at);
      const std::optional<Vec3> eyes[] = {std::nullopt, c.position + reach * Vec3(0.4, 0.3, -0.1),
                                          c.look_at + reach * Vec3(-0.5, 0.2, 0.6)};
      for (const Term term : terms) {
        for (const std::optional<Vec3>& eye : eyes) {
          SCOPED_TRACE("term " + std::string(term_name(term)) + (eye ? ", moved eye" : ""));
          ASSERT_TRUE(same_bits(render(scene, 33, 19, 2, true, 1, 7, term, eye),
                                render(scene, 33, 19, 2, false, 1, 7, term, eye)));
        }
      }
    }
  });
}

// The culling tests' view: a scale of 10^-2 .. 10^3, sometimes far from the origin, and a camera
// at (0, 1, 6) looking at (0, 0.5, 0) in those units with a random field of view.
struct CullingView {
  double scale;
  Vec3 shift;
  Scene scene;
};
CullingView culling_view(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  CullingView v;
  v.scale = std::pow(10.0, std::uniform_int_distribution<int>(-2, 3)(rng));
  v.shift = u(rng) < 0.3 ? Vec3(1e5, -3e4, 2e4) * v.scale : Vec3(0);
  v.scene.camera.position = (Vec3(0, 1, 6) + v.shift / v.scale) * v.scale;
  v.scene.camera.look_at = (Vec3(0, 0.5, 0) + v.shift / v.scale) * v.scale;
  v.scene.camera.fov_y_deg = 10 + 80 * u(rng);
  return v;
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
    const CullingView view = culling_view(rng);
    const double scale = view.scale;
    const Vec3 shift = view.shift;
    Scene s = view.scene;
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
    const PreparedScene p(std::move(s));
    ASSERT_TRUE(packet_tracing_applies(p));
    const Frame packets = render(p, 96, 64, 2, true, 1, seed);
    const Frame scalar = render(p, 96, 64, 2, false, 1, seed);
    ASSERT_TRUE(same_bits(packets, scalar));
    shadow_rays += packets.rays.shadow;
  }
  EXPECT_GT(shadow_rays, 100000u);
}

// A tile's primary rays skip a loose triangle when the hull of its corner rays lies outside a
// plane through the eye and one of the triangle's edges, or every corner ray leaves its plane
// (PacketTracer's primary_triangles). Triangles across the view whose edges run through tiles,
// very large ones, ones behind the eye or beside it, and ones whose plane holds the eye, at
// several scales and far from the origin, with jittered samples and tiles cut by the image's
// edges: the image is the scalar renderer's, bit for bit.
TEST(PacketTracer, PrimaryCullingNeverDropsATriangleARayMeets) {
  REQUIRE_PACKETS();
  std::uint64_t primary = 0;
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1), c(-2, 2);
    const CullingView view = culling_view(rng);
    const double scale = view.scale;
    const Vec3 shift = view.shift;
    Scene s = view.scene;
    const Vec3 eye = s.camera.position;
    for (int k = 0; k < 4; ++k) {
      Material m;
      m.kd = Color(0.2 + 0.2 * k, 0.7 - 0.15 * k, 0.3);
      m.ks = Color(0.3);
      m.n = 20;
      s.materials.push_back(m);
    }
    for (int i = 0; i < 8; ++i) {
      const int kind = static_cast<int>((seed + static_cast<std::uint32_t>(i)) % 4);
      Triangle t;
      t.material = i % 4;
      if (kind == 0) {  // in front, edges across the view
        t.v0 = Vec3(c(rng), c(rng) * 0.5 + 0.5, c(rng)) * scale + shift;
        t.v1 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
        t.v2 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
      } else if (kind == 1) {  // large, around the view
        t.v0 = Vec3(-40 + c(rng), c(rng) * 0.3, -40 + c(rng)) * scale + shift;
        t.v1 = Vec3(40 + c(rng), c(rng) * 0.3, -30 + c(rng)) * scale + shift;
        t.v2 = Vec3(c(rng), c(rng) * 0.3, 40 + c(rng)) * scale + shift;
      } else if (kind == 2) {  // its plane through the eye
        const Vec3 a = Vec3(c(rng), c(rng), -3 + c(rng)) * scale, b = Vec3(c(rng), c(rng), -3 + c(rng)) * scale;
        t.v0 = eye + a;
        t.v1 = eye + b;
        t.v2 = eye + (0.5 + 0.4 * u(rng)) * a + (0.5 + 0.4 * u(rng)) * b;
      } else {  // behind or beside the eye
        t.v0 = eye + Vec3(c(rng), c(rng), 1 + u(rng)) * scale;
        t.v1 = eye + Vec3(c(rng), c(rng), -0.5 + u(rng)) * scale;
        t.v2 = eye + Vec3(c(rng), c(rng), u(rng)) * scale;
      }
      s.triangles.push_back(t);
    }
    Light sun;
    sun.type = LightType::kDirectional;
    sun.direction = Vec3(c(rng), -1, c(rng));
    s.lights = {sun};
    const PreparedScene p(std::move(s));
    ASSERT_TRUE(packet_tracing_applies(p));
    ASSERT_EQ(p.accel(), nullptr);  // brute force: the loose-triangle kernels
    const int w = 61 + static_cast<int>(seed % 5), h = 43 + static_cast<int>(seed % 3);
    const Frame packets = render(p, w, h, 2, true, 1, seed);
    const Frame scalar = render(p, w, h, 2, false, 1, seed);
    ASSERT_TRUE(same_bits(packets, scalar));
    primary += packets.rays.primary;
  }
  EXPECT_GT(primary, 60u * 61 * 43 * 2);
}

// Shadow rays skip a loose triangle whose plane has all their origins and the light strictly on
// one side (PacketTracer's shadow_triangles). Batches of origins at one height above or below a
// floor of two triangles (from 0 to well beyond the offset a hit on the floor gets, in ulps of
// its size) and tilted triangles, towards point and directional lights on either side, at
// several scales and far from the origin: every answer is the scalar query's.
TEST(PacketTracer, ShadowCullingNeverDropsATriangleARayMeets) {
  REQUIRE_PACKETS();
  int culled_batches_checked = 0;
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1), c(-1, 1);
    const double size = std::pow(10.0, std::uniform_int_distribution<int>(-2, 4)(rng));
    const Vec3 shift = u(rng) < 0.3 ? Vec3(3e4, -2e4, 1e4) * size : Vec3(0);
    Scene s;
    s.materials = {Material{}};
    const Vec3 a = Vec3(-1, 0, -1) * size + shift, b = Vec3(1, 0, -1) * size + shift;
    const Vec3 cc = Vec3(1, 0, 1) * size + shift, d = Vec3(-1, 0, 1) * size + shift;
    s.triangles.push_back(Triangle{a, d, cc, 0});
    s.triangles.push_back(Triangle{a, cc, b, 0});
    const Vec3 tilt = Vec3(c(rng), 0.3 * c(rng), c(rng)) * size * 0.3;
    s.triangles.push_back(Triangle{shift + tilt, shift + Vec3(0.2, 0.5, 0) * size, shift + Vec3(0, 0.1, 0.4) * size, 0});
    Light light;
    if (seed % 2 == 0) {
      light.type = LightType::kDirectional;
      light.direction = glm::normalize(Vec3(c(rng), seed % 4 == 0 ? -1.0 : 1.0, c(rng)));
    } else {
      light.position = Vec3(c(rng), seed % 3 == 0 ? -2.0 : 2.0, c(rng)) * size + shift;
    }
    s.lights = {light};
    const PreparedScene p(std::move(s));
    const Light& l = p.scene().lights[0];
    PacketTracer& tracer = packet_tracer_for(p);
    const double ulp = std::ldexp(1.0, -52) * (std::abs(shift.x) + size);
    for (const double h : {0.0, ulp, 16 * ulp, 1024 * ulp, 0x1p-42 * size, 0x1p-41 * size, 0x1p-40 * size, 1e-9 * size,
                           1e-6 * size, 0.3 * size}) {
      for (const double sign : {1.0, -1.0}) {
        std::vector<double> ox, oy, oz, dx, dy, dz, t_max;
        for (int i = 0; i < 8; ++i) {
          const Vec3 o = shift + Vec3(c(rng) * 0.9 * size, sign * h, c(rng) * 0.9 * size);
          Vec3 dir;
          double t = std::numeric_limits<double>::infinity();
          if (l.type == LightType::kPoint) {
            dir = glm::normalize(l.position - o);
            t = glm::length(l.position - o) * (1 - 1e-9);
          } else {
            dir = -l.direction;
          }
          ox.push_back(o.x), oy.push_back(o.y), oz.push_back(o.z);
          dx.push_back(dir.x), dy.push_back(dir.y), dz.push_back(dir.z);
          t_max.push_back(t);
        }
        std::vector<std::uint8_t> blocked(8);
        tracer.occluded_towards(l, ox.data(), oy.data(), oz.data(), dx.data(), dy.data(), dz.data(), t_max.data(), 8,
                                blocked.data());
        for (int i = 0; i < 8; ++i) {
          const Ray ray = make_ray(Vec3(ox[i], oy[i], oz[i]), Vec3(dx[i], dy[i], dz[i]));
          ASSERT_EQ(blocked[i] != 0, occluded(p, ray, t_max[i])) << "height " << sign * h << ", ray " << i;
        }
        ++culled_batches_checked;
      }
    }
  }
  EXPECT_EQ(culled_batches_checked, 40 * 20);
}

// The kernels' bounds pass over NaN coordinates on every instance (minpd's rule, which not every
// instruction set's own min follows).
TEST(PacketTracer, KernelBoundsPassOverNaN) {
  REQUIRE_PACKETS();
  test::for_each_simd_target([&] { EXPECT_EQ(test::nan_bounds_failures(), ""); });
}

TEST(PacketTracer, TheImageDoesNotDependOnTheThreadCount) {
  REQUIRE_PACKETS();
  const PreparedScene scene = load_prepared("glass");
  EXPECT_TRUE(same_bits(render(scene, 200, 120, 2, true, 1), render(scene, 200, 120, 2, true, 3)));
}

TEST(PacketTracer, ServesOnlyWhatItCanTraceExactly) {
  const Scene loaded = load_scene_or_fail("lecture");
  const PreparedScene scene(loaded);
  // The debug views stay with the scalar renderer (render() checks PassStats::packets).
  EXPECT_FALSE(PacketTracer::draws(Term::kNormal));
  EXPECT_FALSE(PacketTracer::draws(Term::kDepth));
  EXPECT_FALSE(PacketTracer::draws(Term::kRays));
  render(scene, 8, 8, 1, true, 1, 0, Term::kRays);
  EXPECT_EQ(packet_tracing_applies(scene), packet_cpu_supported());
  const PreparedScene with_bvh(loaded, forced_bvh);
  EXPECT_EQ(packet_tracing_applies(with_bvh), packet_cpu_supported());  // it walks the SceneBvh
  // Any other accelerator (Embree's) is queried ray by ray.
  struct Other final : Accelerator {
    std::optional<Hit> intersect(const Scene& s, const Ray& r, double t_max) const override { return intersect_all(s, r, t_max); }
    bool occluded(const Scene& s, const Ray& r, double t_max) const override { return occluded_all(s, r, t_max); }
    bool matches(const Scene&) const override { return true; }
  };
  const PreparedScene other(loaded, [](const Scene&) { return std::make_shared<Other>(); });
  EXPECT_FALSE(packet_tracing_applies(other));
  NumericsVariant schlick;
  schlick.schlick_fresnel = true;
  PreparedScene variant = prepare_variant(loaded, schlick);
  EXPECT_FALSE(packet_tracing_applies(variant));
  NumericsVariant fixed;
  fixed.fixed_offset = 1e-4;
  variant = prepare_variant(loaded, fixed);
  EXPECT_FALSE(packet_tracing_applies(variant));
  EXPECT_EQ(packet_tracing_applies(load_prepared("cornell")), packet_cpu_supported());  // a mesh, through the SceneBvh
}

}  // namespace
