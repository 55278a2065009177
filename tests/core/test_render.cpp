// Whole-image invariants: term images sum to the full image, thread-count independence,
// sample 0 at the pixel centre, the camera formula of docs/model.md, camera and samples.
#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <cstring>
#include <string>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>
#include <utility>

#include "core/packet/packet.h"
#include "core/render/quad_shading.h"
#include "core/render/render.h"
#include "core/base/threads.h"
#include "tests/support/random_scenes.h"

using namespace phonglab;

namespace {

// A small scene with every term present: a mirror, glass with Fresnel, plastic, a floor.
PreparedScene busy_scene() {
  Scene s;
  s.camera.position = Vec3(0, 1.5, 6);
  s.camera.look_at = Vec3(0, 0.8, 0);
  s.background = Color(0.1, 0.2, 0.3);
  s.ambient = Color(1);
  Material floor;
  floor.ka = Color(0.05);
  floor.kd = Color(0.6);
  floor.ks = Color(0.2);
  floor.n = 10;
  Material mirror;
  mirror.kd = Color(0.05);
  mirror.ks = Color(0.5);
  mirror.n = 100;
  mirror.kr = Color(0.8);
  Material glass;
  glass.ks = Color(0.5);
  glass.n = 300;
  glass.kt = Color(0.9);
  glass.fresnel = true;
  Material plastic;
  plastic.ka = Color(0.1, 0.02, 0.02);
  plastic.kd = Color(0.8, 0.2, 0.1);
  plastic.ks = Color(0.5);
  plastic.n = 20;
  s.materials = {floor, mirror, glass, plastic};
  s.planes = {Plane{{0, 0, 0}, {0, 1, 0}, 0}};
  s.spheres = {Sphere{{-1.2, 0.7, 0}, 0.7, 1}, Sphere{{0.4, 0.5, 1}, 0.5, 2}, Sphere{{1.5, 0.6, -0.5}, 0.6, 3}};
  s.triangles = {Triangle{{-3, 0, -2}, {3, 0, -2}, {0, 3, -2.5}, 3}};
  Light a;
  a.position = Vec3(2, 6, 4);
  a.intensity = Color(0.9);
  Light b;
  b.type = LightType::kDirectional;
  b.direction = Vec3(-1, -1, -0.5);
  b.intensity = Color(0.2);
  s.lights = {a, b};
  return PreparedScene(std::move(s));
}

Accumulator render(const PreparedScene& s, int w, int h, int spp, Term term, int threads) {
  Accumulator acc;
  acc.reset(w, h);
  RenderOptions opt;
  opt.term = term;
  opt.threads = threads;
  opt.tile_size = 7;  // odd size: tiles straddle the image edge
  for (int i = 0; i < spp; ++i) {
    const PassStats st = render_pass(s, opt, acc);
    EXPECT_EQ(st.nan_count, 0u);
  }
  return acc;
}

}  // namespace

TEST(TermImages, FiveTermsAddUpToTheFullImage) {
  const PreparedScene prepared = busy_scene();
  const Scene& s = prepared.scene();
  const int w = 64, h = 40;
  const Accumulator full = render(prepared, w, h, 1, Term::kFull, 2);
  std::vector<Accumulator> parts;
  for (Term t : {Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection, Term::kRefraction}) {
    parts.push_back(render(prepared, w, h, 1, t, 2));
  }
  const CameraFrame frame = make_camera_frame(s.camera, w, h);
  int hits = 0, misses = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool hit = intersect(prepared, camera_ray(frame, x, y, 0.5, 0.5)).has_value();
      Color sum(0);
      for (const Accumulator& p : parts) sum += p.mean(x, y);
      if (!hit) {
        ++misses;
        EXPECT_EQ(sum, Color(0)) << "term images are 0 where the primary ray misses";
        EXPECT_EQ(full.mean(x, y), s.background);
        continue;
      }
      ++hits;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], full.mean(x, y)[c], 1e-12) << x << "," << y;
    }
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 10);
}

// The small multiples' pass: one trace whose primary hits keep all five terms gives each term
// image, and the main image, bit for bit what a pass for that term alone gives; over two samples
// of seeded random scenes, by either tracer, with the full image, a term or a debug view as the
// main image.
TEST(TermImages, OnePassGivesEveryTermImageBitForBit) {
  const std::array<Term, 5>& terms = kFiveTerms;
  const auto& members = kFiveTermMembers;
  const int w = 21, h = 13;
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const PreparedScene scene = random_scene(seed, seed % 3 == 0);
    const Term main = seed % 10 == 0 ? Term::kNormal : seed % 5 == 0 ? Term::kSpecular : Term::kFull;
    for (const bool packets : {false, true}) {
      if (packets && !packet_cpu_supported()) continue;
      RenderOptions options;
      options.packets = packets;
      options.threads = 2;
      options.tile_size = 7;
      options.term = main;
      Accumulator together;
      together.reset(w, h, true);
      ASSERT_TRUE(together.has_terms());
      for (int pass = 0; pass < 2; ++pass) render_pass(scene, options, together);
      const auto alone = [&](Term term) {
        Accumulator a;
        a.reset(w, h);
        options.term = term;
        for (int pass = 0; pass < 2; ++pass) render_pass(scene, options, a);
        options.term = main;
        return a;
      };
      const Accumulator main_alone = alone(main);
      for (std::size_t i = 0; i < together.sum.size(); ++i) {
        ASSERT_EQ(std::memcmp(&together.sum[i], &main_alone.sum[i], sizeof(Color)), 0) << "main image, pixel " << i;
      }
      for (std::size_t k = 0; k < terms.size(); ++k) {
        const Accumulator term_alone = alone(terms[k]);
        for (std::size_t i = 0; i < together.sum.size(); ++i) {
          const Color c = together.terms[i].*members[k];
          ASSERT_EQ(std::memcmp(&c, &term_alone.sum[i], sizeof(Color)), 0)
              << term_name(terms[k]) << ", pixel " << i << (packets ? ", packets" : ", scalar");
        }
      }
    }
  }
}

// A term image computes only what its term needs (no shadow rays for the ambient image, no
// children for diffuse and specular, only the reflected or the refracted child at the primary
// hit for those), and each pixel is still that term of the fully shaded hit, bit for bit; by
// either tracer.
TEST(TermImages, EachCastsOnlyTheRaysItsTermNeedsAndKeepsItsValue) {
  const PreparedScene prepared = busy_scene();
  const Scene& s = prepared.scene();
  const int w = 48, h = 32;
  const CameraFrame frame = make_camera_frame(s.camera, w, h);
  const TraceLimits limits{s.max_depth, s.min_weight};
  for (const bool packets : {false, true}) {
    SCOPED_TRACE(packets ? "packet tracer" : "scalar renderer");
    RayCounts full_rays;
    for (const Term t : {Term::kFull, Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection,
                         Term::kRefraction}) {
      SCOPED_TRACE(std::string(term_name(t)));
      Accumulator acc;
      acc.reset(w, h);
      RenderOptions opt;
      opt.term = t;
      opt.packets = packets;
      const RayCounts rays = render_pass(prepared, opt, acc).rays;
      if (t == Term::kFull) full_rays = rays;
      EXPECT_EQ(rays.primary, static_cast<std::uint64_t>(w * h));
      switch (t) {
        case Term::kAmbient:
          EXPECT_EQ(rays.total(), rays.primary);
          break;
        case Term::kDiffuse:
        case Term::kSpecular:
          EXPECT_GT(rays.shadow, 0u);
          EXPECT_EQ(rays.reflection + rays.refraction, 0u);
          break;
        case Term::kReflection:
          EXPECT_GT(rays.reflection, 0u);
          EXPECT_LT(rays.total(), full_rays.total());
          break;
        case Term::kRefraction:
          EXPECT_GT(rays.refraction, 0u);
          EXPECT_LT(rays.total(), full_rays.total());
          break;
        default:
          break;
      }
      int hits = 0;
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const Ray ray = camera_ray(frame, x, y, 0.5, 0.5);
          const std::optional<Hit> hit = intersect(prepared, ray);
          if (!hit) continue;
          ++hits;
          RayCounts counts;
          const Color want = term_value(shade(prepared, limits, ray, *hit, 0, 1.0, counts), t);
          ASSERT_EQ(acc.mean(x, y), want) << x << "," << y;
        }
      }
      EXPECT_GT(hits, 500);
    }
  }
}

TEST(TermImages, EveryTermIsNonZeroSomewhereInTheBusyScene) {
  const PreparedScene s = busy_scene();
  for (Term t : {Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection, Term::kRefraction}) {
    const Accumulator a = render(s, 48, 32, 1, t, 1);
    double total = 0;
    for (const Color& c : a.sum) total += c.x + c.y + c.z;
    EXPECT_GT(total, 0) << term_name(t);
  }
}

TEST(Threads, ImageIsBitIdenticalForAnyThreadCount) {
  const PreparedScene s = busy_scene();
  for (int spp : {1, 3}) {
    const Accumulator one = render(s, 37, 23, spp, Term::kFull, 1);
    for (int threads : {2, 3, 8}) {
      const Accumulator many = render(s, 37, 23, spp, Term::kFull, threads);
      ASSERT_EQ(one.sum.size(), many.sum.size());
      for (std::size_t i = 0; i < one.sum.size(); ++i) {
        ASSERT_EQ(one.sum[i], many.sum[i]) << "pixel " << i << ", " << threads << " threads, spp " << spp;
      }
    }
  }
}

// A first pass writes each pixel's mean as float too, tile by tile (what a viewer converts after
// the pass, the same bits); a later pass leaves that image alone. Both tracers, the quad-shaded
// rung too.
TEST(Threads, AFirstPassWritesItsImageAsFloatsAsItGoes) {
  const PreparedScene s = busy_scene();
  constexpr int kW = 37, kH = 23;
  const glm::vec3 untouched(-7.0f);
  for (const bool packets : {false, true}) {
    for (const bool quads : {false, true}) {
      SCOPED_TRACE(std::string(packets ? "packets" : "scalar") + (quads ? ", quads" : ""));
      std::vector<glm::vec3> floats(static_cast<std::size_t>(kW * kH), untouched);
      RenderOptions options;
      options.threads = 2;
      options.packets = packets;
      options.first_sample_image = floats.data();
      Accumulator a;
      a.reset(kW, kH);
      if (quads) render_quad_shaded(s, options, a);
      else render_pass(s, options, a);
      for (std::size_t i = 0; i < floats.size(); ++i) {
        ASSERT_EQ(floats[i], glm::vec3(a.sum[i] * (1.0 / a.samples))) << "pixel " << i;
      }
      std::fill(floats.begin(), floats.end(), untouched);
      render_pass(s, options, a);  // a second sample: not a first pass
      for (const glm::vec3& f : floats) ASSERT_EQ(f, untouched);
    }
  }
}

TEST(Sampling, SampleZeroIsThePixelCentre) {
  for (int y = 0; y < 50; y += 7) {
    for (int x = 0; x < 50; x += 3) {
      double u, v;
      sample_offset(x, y, 0, u, v);
      EXPECT_EQ(u, 0.5);
      EXPECT_EQ(v, 0.5);
    }
  }
}

TEST(Sampling, LaterSamplesStayInsideThePixelAndCoverIt) {
  // The first 64 samples of a pixel fall in [0,1)^2 and hit each of a 4x4 grid's cells.
  for (int pixel = 0; pixel < 20; ++pixel) {
    int cells[16] = {};
    for (std::uint32_t i = 1; i <= 64; ++i) {
      double u, v;
      sample_offset(pixel * 13, pixel * 7, i, u, v);
      ASSERT_GE(u, 0.0);
      ASSERT_LT(u, 1.0);
      ASSERT_GE(v, 0.0);
      ASSERT_LT(v, 1.0);
      ++cells[static_cast<int>(u * 4) + 4 * static_cast<int>(v * 4)];
    }
    for (int c : cells) EXPECT_GT(c, 0);
  }
}

TEST(Camera, RayFollowsTheSpecFormula) {
  Camera cam;
  cam.position = Vec3(1, 2, 3);
  cam.look_at = Vec3(-1, 0.5, -2);
  cam.up = Vec3(0.1, 1, 0);
  cam.fov_y_deg = 55;
  const int w = 320, h = 200;
  const CameraFrame f = make_camera_frame(cam, w, h);
  const Vec3 F = glm::normalize(cam.look_at - cam.position);
  const Vec3 R = glm::normalize(glm::cross(F, cam.up));
  const Vec3 U = glm::cross(R, F);
  const double th = std::tan(55 * M_PI / 360);
  for (auto [x, y, u, v] : {std::tuple{0, 0, 0.5, 0.5}, {319, 199, 0.25, 0.75}, {160, 100, 0.0, 0.0}}) {
    const Vec3 want = glm::normalize(F + (2 * (x + u) / w - 1) * th * (double(w) / h) * R + (1 - 2 * (y + v) / h) * th * U);
    const Ray r = camera_ray(f, x, y, u, v);
    EXPECT_NEAR(glm::length(r.dir - want), 0, 1e-14);
    EXPECT_EQ(r.origin, cam.position);
  }
}

TEST(Camera, TopLeftPixelLooksUpAndLeft) {
  Camera cam;  // default: looking down -z-ish with +y up
  const CameraFrame f = make_camera_frame(cam, 100, 50);
  const Ray r = camera_ray(f, 0, 0, 0.5, 0.5);
  const Vec3 F = glm::normalize(cam.look_at - cam.position);
  EXPECT_LT(r.dir.x, 0);               // left
  EXPECT_GT(r.dir.y, F.y);             // up
}

TEST(Progressive, MeanOfSamplesIsSumOverCount) {
  const PreparedScene s = busy_scene();
  const Accumulator a = render(s, 16, 16, 4, Term::kFull, 2);
  EXPECT_EQ(a.samples, 4u);
  EXPECT_EQ(a.mean(3, 3), a.sum[3 * 16 + 3] / 4.0);
}

TEST(Progressive, CancelledPassDoesNotCountAsASample) {
  const PreparedScene s = busy_scene();
  Accumulator acc;
  acc.reset(32, 32);
  std::atomic<bool> cancel{true};
  const PassStats st = render_pass(s, RenderOptions{}, acc, &cancel);
  EXPECT_FALSE(st.completed);
  EXPECT_EQ(acc.samples, 0u);
}

TEST(Sampling, SeedsGiveIndependentSampleSetsButTheSameCentre) {
  double u0, v0, u1, v1;
  sample_offset(5, 9, 0, u0, v0, 0);
  sample_offset(5, 9, 0, u1, v1, 17);
  EXPECT_EQ(u0, u1);
  EXPECT_EQ(v0, v1);
  int differ = 0;
  for (std::uint32_t i = 1; i < 50; ++i) {
    sample_offset(5, 9, i, u0, v0, 0);
    sample_offset(5, 9, i, u1, v1, 17);
    differ += (u0 != u1 || v0 != v1);
  }
  EXPECT_EQ(differ, 49);
}

// run_workers keeps its helper threads between calls: every worker index runs exactly once per
// call whatever the sequence of sizes, two callers at once each get their own helpers, and an
// exception on the caller's share comes back after the helpers are done with the work.
TEST(Workers, EveryIndexRunsOncePerCallAndCallersDoNotShareHelpers) {
  const auto check = [](int seed) {
    for (int call = 0; call < 200; ++call) {
      const int n = 1 + (call * 7 + seed) % 5;
      std::vector<std::atomic<int>> runs(static_cast<std::size_t>(n));
      run_workers(n, [&](int i) { runs[static_cast<std::size_t>(i)].fetch_add(1); });
      for (int i = 0; i < n; ++i) ASSERT_EQ(runs[static_cast<std::size_t>(i)].load(), 1) << "call " << call << ", n " << n;
    }
  };
  std::thread other([&] { check(3); });
  check(1);
  other.join();
  std::atomic<int> helpers_done{0};
  EXPECT_THROW(run_workers(3,
                           [&](int i) {
                             if (i == 0) throw std::runtime_error("worker 0");
                             helpers_done.fetch_add(1);
                           }),
               std::runtime_error);
  EXPECT_EQ(helpers_done.load(), 2);
}
