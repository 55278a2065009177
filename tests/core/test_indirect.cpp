// The indirect light (docs/model.md, "What the ambient term stands in for"): the two cases with
// exact answers, the sampler's stratification, and the invariants of every image (thread count,
// term sums, misses, NaN).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "core/render/indirect_probe.h"
#include "core/render/render.h"
#include "core/teaching/heat_map.h"

using namespace phonglab;

namespace {

Accumulator render(const PreparedScene& prepared, int w, int h, int spp, Term term = Term::kFull,
                   Ambient ambient = Ambient::kIndirect, int threads = 2) {
  RenderOptions options;
  options.term = term;
  options.ambient = ambient;
  options.threads = threads;
  Accumulator accum;
  accum.reset(w, h);
  render_passes(prepared, options, accum, spp);
  return accum;
}

// A sphere of material kd under a background, no lights, seen whole by the camera.
Scene convex_scene(const Color& kd, const Color& background) {
  Scene s;
  s.camera.position = Vec3(0, 0, 4);
  s.camera.look_at = Vec3(0, 0, 0);
  s.background = background;
  Material m;
  m.ka = Color(0.3);  // replaced by the indirect term: must not show
  m.kd = kd;
  s.materials = {m};
  s.spheres = {Sphere{{0, 0, 0}, 1, 0}};
  s.indirect_bounces = 1;
  return s;
}

// The camera inside a closed sphere of albedo a, a point light of intensity I at its centre.
Scene closed_sphere(double a, const Color& intensity, int bounces) {
  Scene s;
  s.camera.position = Vec3(0.2, -0.1, 0.3);
  s.camera.look_at = Vec3(-1, 0.2, -2);
  s.camera.fov_y_deg = 90;
  Material m;
  m.kd = Color(a);
  s.materials = {m};
  s.spheres = {Sphere{{0, 0, 0}, 2, 0}};
  Light light;
  light.position = Vec3(0);
  light.intensity = intensity;
  s.lights = {light};
  s.indirect_bounces = bounces;
  return s;
}

}  // namespace

// SPEC case 1: a convex object alone under a background B shows kd ⊙ B with one bounce: every
// gather ray leaves it and meets the sky, whatever its direction, so at any spp.
TEST(Indirect, ConvexObjectUnderTheSkyIsKdTimesBackground) {
  const Color kd(0.7, 0.4, 0.2), sky(0.5, 0.8, 1.2);
  const PreparedScene prepared(convex_scene(kd, sky));
  for (const int spp : {1, 5}) {
    const Accumulator full = render(prepared, 24, 16, spp);
    const Accumulator term = render(prepared, 24, 16, spp, Term::kIndirect, Ambient::kConstant);
    int hits = 0;
    for (int y = 0; y < 16; ++y) {
      for (int x = 0; x < 24; ++x) {
        // A pixel on the silhouette mixes the sphere and the sky: only the pixels whose samples
        // all hit, or all miss, are checked (the centre one decides which).
        const Color f = full.mean(x, y), t = term.mean(x, y);
        const bool hit = glm::length(t) > 0;
        const bool inner = std::abs(glm::length(Vec3(x - 11.5, y - 7.5, 0))) < 4;
        const bool outer = std::abs(glm::length(Vec3(x - 11.5, y - 7.5, 0))) > 10;
        if (inner) {
          ++hits;
          for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(f[c], kd[c] * sky[c], 1e-9) << x << "," << y;
            EXPECT_NEAR(t[c], kd[c] * sky[c], 1e-9) << x << "," << y;
          }
        }
        if (outer) {
          EXPECT_FALSE(hit);
          EXPECT_EQ(f, sky);
          EXPECT_EQ(t, Color(0));  // the indirect term image is 0 where the primary ray misses
        }
      }
    }
    EXPECT_GT(hits, 20);
  }
}

// SPEC case 2: inside a closed sphere of albedo a lit from its centre, the direct light is a·I
// everywhere and every gather brings back the same radiance: the full image is
// I·(a + a² + ... + a^(B+1)) at any spp.
TEST(Indirect, ClosedSphereLitFromItsCentreSumsTheBounces) {
  const double a = 0.6;
  const Color intensity(1.0, 0.5, 2.0);
  for (const int bounces : {1, 2, 4, 16}) {
    const PreparedScene prepared(closed_sphere(a, intensity, bounces));
    double series = 0;
    for (int k = 2; k <= bounces + 1; ++k) series += std::pow(a, k);
    for (const int spp : {1, 3}) {
      const Accumulator full = render(prepared, 12, 8, spp);
      const Accumulator term = render(prepared, 12, 8, spp, Term::kIndirect);
      for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 12; ++x) {
          for (int c = 0; c < 3; ++c) {
            ASSERT_NEAR(full.mean(x, y)[c], intensity[c] * (a + series), 1e-9) << "B=" << bounces;
            ASSERT_NEAR(term.mean(x, y)[c], intensity[c] * series, 1e-9) << "B=" << bounces;
          }
        }
      }
    }
    // The probe's estimate is exact too, with no spread.
    const IndirectProbe probe = probe_indirect(prepared, 12, 8, 5, 4, 16);
    ASSERT_TRUE(probe.hit);
    EXPECT_NEAR(probe.mean.z, intensity.z * series, 1e-9);
    EXPECT_LT(probe.standard_error.z, 1e-9);
    EXPECT_NEAR(probe.fitted_ka.x, series, 1e-9);  // Ia = 1: ka is the estimate itself
  }
}

// Every gather's points over the sample indices are stratified: the first 2^k samples put one
// point in each cell of every 2^i x 2^(k-i) grid (a (0,k,2)-net), for each of the tree's gathers.
TEST(Indirect, GatherPointsAreStratifiedForEveryGather) {
  for (const std::uint32_t key : {indirect_pixel_key(0, 0, 0), indirect_pixel_key(17, 3, 9)}) {
    for (int k = 2; k <= 8; k += 2) {
      const std::uint32_t n = 1U << k;
      constexpr int kGathers = 5;
      std::vector<std::vector<std::pair<double, double>>> points(kGathers);
      for (std::uint32_t i = 0; i < n; ++i) {
        IndirectSampler sampler(8, key, i);
        for (int g = 0; g < kGathers; ++g) {
          double u1, u2;
          sampler.next_point(u1, u2);
          ASSERT_TRUE(u1 >= 0 && u1 < 1 && u2 >= 0 && u2 < 1);
          points[static_cast<std::size_t>(g)].emplace_back(u1, u2);
        }
      }
      for (int g = 0; g < kGathers; ++g) {
        for (int i = 0; i <= k; ++i) {
          std::set<std::pair<int, int>> cells;
          for (const auto& [u1, u2] : points[static_cast<std::size_t>(g)]) {
            cells.emplace(static_cast<int>(u1 * (1 << i)), static_cast<int>(u2 * (1 << (k - i))));
          }
          ASSERT_EQ(cells.size(), n) << "gather " << g << ", 2^" << i << " x 2^" << (k - i);
        }
      }
    }
  }
}

// Cosine-weighted directions stay in N's hemisphere, and their mean cosine is 2/3 (the mean of
// cos θ under the density cos θ / π).
TEST(Indirect, CosineDirectionsFollowTheCosineDensity) {
  for (const Vec3& n : {Vec3(0, 0, 1), Vec3(0, 0, -1), glm::normalize(Vec3(0.3, -0.8, 0.1))}) {
    IndirectSampler sampler(1, indirect_pixel_key(1, 2, 3), 0);
    double sum = 0;
    constexpr int kCount = 4096;
    for (int i = 0; i < kCount; ++i) {
      IndirectSampler s(1, indirect_pixel_key(1, 2, 3), static_cast<std::uint32_t>(i));
      double u1, u2;
      s.next_point(u1, u2);
      const Vec3 w = cosine_direction(n, u1, u2);
      ASSERT_NEAR(glm::length(w), 1, 1e-12);
      ASSERT_GT(glm::dot(w, n), 0);
      sum += glm::dot(w, n);
    }
    EXPECT_NEAR(sum / kCount, 2.0 / 3.0, 2e-3);
  }
}

namespace {

// A box of two-sided walls with a sphere and a mirror in it: gathers meet walls, the sphere and
// the mirror, and some leave through the open front.
PreparedScene room() {
  Scene s;
  s.camera.position = Vec3(0, 1, 3.5);
  s.camera.look_at = Vec3(0, 1, 0);
  s.background = Color(0.2, 0.3, 0.5);
  Material white, red, mirror;
  white.ka = Color(0.1);
  white.kd = Color(0.7);
  white.ks = Color(0.2);
  white.n = 20;
  red.kd = Color(0.7, 0.1, 0.1);
  mirror.kd = Color(0.1);
  mirror.kr = Color(0.8);
  s.materials = {white, red, mirror};
  s.planes = {Plane{{0, 0, 0}, {0, 1, 0}, 0}, Plane{{-1.5, 0, 0}, {1, 0, 0}, 1}, Plane{{0, 0, -1.5}, {0, 0, 1}, 0}};
  s.spheres = {Sphere{{0.5, 0.5, -0.3}, 0.5, 2}, Sphere{{-0.6, 0.4, 0.2}, 0.4, 0}};
  Light light;
  light.position = Vec3(0.3, 2.5, 1);
  s.lights = {light};
  s.indirect_bounces = 3;
  return PreparedScene(s);
}

}  // namespace

// The same bits for one and two threads, no NaN, and the term images (the indirect term in the
// ambient's place) add up to the full image with indirect light.
TEST(Indirect, ThreadCountIndependentAndTermsSumToTheFullImage) {
  const PreparedScene prepared = room();
  RenderOptions options;
  options.ambient = Ambient::kIndirect;
  Accumulator one, two;
  one.reset(40, 30, true);
  two.reset(40, 30, true);
  options.threads = 1;
  PassStats a = render_passes(prepared, options, one, 3);
  options.threads = 2;
  PassStats b = render_passes(prepared, options, two, 3);
  EXPECT_EQ(a.nan_count, 0u);
  EXPECT_EQ(b.nan_count, 0u);
  EXPECT_GT(a.rays.indirect, 0u);
  EXPECT_EQ(a.rays.indirect, b.rays.indirect);
  ASSERT_EQ(one.sum, two.sum);
  const Accumulator plain = render(prepared, 40, 30, 3, Term::kFull, Ambient::kIndirect, 2);
  ASSERT_EQ(plain.sum, one.sum);  // with or without the term sums: the same samples
  for (std::size_t i = 0; i < one.sum.size(); ++i) {
    const Color sum = one.terms[i].sum();
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(sum[c], one.sum[i][c], 1e-12 * (1 + std::abs(sum[c])));
  }
  const Accumulator indirect = render(prepared, 40, 30, 3, Term::kIndirect, Ambient::kConstant, 1);
  for (std::size_t i = 0; i < one.sum.size(); ++i) ASSERT_EQ(indirect.sum[i], one.terms[i].ambient);
}

// The lecture's image is untouched by the indirect light's settings: the constant ambient renders
// the same bits whatever the bounces, and differs from the indirect image.
TEST(Indirect, TheLecturesImageIgnoresTheBounces) {
  PreparedScene prepared = room();
  Scene other = prepared.scene();
  other.indirect_bounces = 17;
  const PreparedScene bounced(other);
  const Accumulator a = render(prepared, 20, 15, 2, Term::kFull, Ambient::kConstant);
  const Accumulator b = render(bounced, 20, 15, 2, Term::kFull, Ambient::kConstant);
  EXPECT_EQ(a.sum, b.sum);
  const Accumulator c = render(prepared, 20, 15, 2, Term::kFull, Ambient::kIndirect);
  EXPECT_NE(a.sum, c.sum);
}

// The probe's standard error falls as 1/sqrt(samples): from 64 to 1,024 samples by 4, within
// 10 %, averaged over pixels of the room (one pixel's estimate of its spread is itself noisy).
TEST(Indirect, StandardErrorFallsAsOneOverRootSamples) {
  const PreparedScene prepared = room();
  double se64 = 0, se1024 = 0;
  int pixels = 0;
  for (int y = 2; y < 30; y += 4) {
    for (int x = 2; x < 40; x += 4) {
      const IndirectProbe a = probe_indirect(prepared, 40, 30, x, y, 64);
      const IndirectProbe b = probe_indirect(prepared, 40, 30, x, y, 1024);
      if (!a.hit || glm::length(b.standard_error) == 0) continue;
      se64 += glm::length(a.standard_error);
      se1024 += glm::length(b.standard_error);
      ++pixels;
    }
  }
  ASSERT_GT(pixels, 30);
  EXPECT_NEAR(se64 / se1024, 4.0, 0.4);
}

// The indirect term with the term images: the value is the indirect term, bit for bit as without
// them, and the terms are the lecture's (ka·Ia), bit for bit as a constant-ambient render's: the
// two images "side by side" come from one pass.
TEST(Indirect, TheIndirectTermComesWithTheLecturesTermsBesideIt) {
  const PreparedScene prepared = room();
  RenderOptions options;
  options.term = Term::kIndirect;
  Accumulator with_terms;
  with_terms.reset(30, 20, true);
  render_passes(prepared, options, with_terms, 2);
  const Accumulator plain = render(prepared, 30, 20, 2, Term::kIndirect, Ambient::kConstant);
  ASSERT_EQ(with_terms.sum, plain.sum);
  RenderOptions lecture;
  lecture.packets = false;
  Accumulator constant;
  constant.reset(30, 20, true);
  render_passes(prepared, lecture, constant, 2);
  for (std::size_t i = 0; i < constant.terms.size(); ++i) {
    ASSERT_EQ(with_terms.terms[i].ambient, constant.terms[i].ambient);
    ASSERT_EQ(with_terms.terms[i].diffuse, constant.terms[i].diffuse);
    ASSERT_EQ(with_terms.terms[i].reflection, constant.terms[i].reflection);
  }
}

// The best constant ambient for a view: per material, the mean indirect term over its hits, and
// the ka that makes ka·Ia equal to it. Exact for the sphere under the sky (kd ⊙ B / Ia); the same
// for any thread count; a material with no hit keeps its ka.
TEST(Indirect, FittedAmbientIsTheMeanIndirectTermOverAMaterialsHits) {
  Scene s = convex_scene(Color(0.7, 0.4, 0.2), Color(0.5, 0.8, 1.2));
  s.ambient = Color(0.5, 1, 2);
  Material unseen;
  unseen.ka = Color(0.3);
  s.materials.push_back(unseen);
  const PreparedScene prepared(s);
  const AmbientFit fit = fit_ambient(prepared, 24, 16, 3, 2);
  ASSERT_EQ(fit.fitted_ka.size(), 2u);
  EXPECT_GT(fit.hits[0], 100u);
  EXPECT_EQ(fit.hits[1], 0u);
  const Color expected = Color(0.7, 0.4, 0.2) * Color(0.5, 0.8, 1.2) / Color(0.5, 1, 2);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(fit.fitted_ka[0][c], expected[c], 1e-12);
  EXPECT_EQ(fit.fitted_ka[1], Color(0.3));
  // The scene's Iₐ with the materials' ka (0.3 here): ka·Iₐ = kd ⊙ B exactly, the unseen
  // material not counted.
  const Color sky_light = Color(0.7, 0.4, 0.2) * Color(0.5, 0.8, 1.2);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(fit.fitted_ia[c], sky_light[c] / 0.3, 1e-12);

  // A dim Iₐ: the ka a material would need is over 1; it is offered clamped, the wish kept.
  s.ambient = Color(0.1);
  const AmbientFit dim = fit_ambient(PreparedScene(s), 24, 16, 3, 2);
  EXPECT_TRUE(ka_over_one(dim.wanted_ka[0]));
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(dim.wanted_ka[0][c], sky_light[c] / 0.1, 1e-12);
    EXPECT_EQ(dim.fitted_ka[0][c], std::min(sky_light[c] / 0.1, 1.0));
  }

  const PreparedScene busy = room();
  const AmbientFit one = fit_ambient(busy, 20, 15, 2, 1);
  const AmbientFit two = fit_ambient(busy, 20, 15, 2, 2);
  EXPECT_EQ(one.mean_indirect, two.mean_indirect);
  EXPECT_EQ(one.hits, two.hits);
}

namespace {

// Inside a closed sphere (ior 1: a refracted ray leaves it straight for the sky), lit from its
// centre, every hit sees the same: direct kd·I, and its ways on (a gather, the mirror child, the
// refracted child to the sky) bring the same radiance from wherever they start. The radiance of a
// ray at depth d, path weight w, with b bounces left, by the definition's rules (the depth and
// path-weight limits of TraceLimits' defaults).
Color closed_sphere_radiance(const Material& m, const Color& light, const Color& sky, int b, int depth, double w) {
  const TraceLimits limits;
  Color l = m.kd * light;
  if (b > 0) l += m.kd * closed_sphere_radiance(m, light, sky, b - 1, 0, 1.0);
  if (depth < limits.max_depth) {
    if (const auto wr = child_weight(m.kr, w, limits.min_weight)) {
      l += m.kr * closed_sphere_radiance(m, light, sky, b, depth + 1, *wr);
    }
    if (child_weight(m.kt, w, limits.min_weight)) l += m.kt * sky;
  }
  return l;
}

}  // namespace

// A gather follows one way at each hit, chosen by its coefficient and divided by its chance: the
// estimate stays unbiased. Inside a closed sphere that is a mirror and glass as well as diffuse,
// the probe's mean over 4,096 samples lies within 4.5 standard errors of the definition's value
// (the exhaustive tree), and its spread is not zero (the choices are random).
TEST(Indirect, GathersFollowingOneWayAHitStayUnbiased) {
  struct Coefficients {
    double kd;
    Color kr, kt;
  };
  // Bright ways (they always go on), and dim ones (their sum under the roulette's 0.25: a path
  // also ends there, and the tree's own gather is taken by chance).
  for (const Coefficients& k : {Coefficients{0.45, Color(0.3, 0.25, 0.2), Color(0.1, 0.2, 0.15)},
                                Coefficients{0.12, Color(0.05, 0.04, 0.03), Color(0.02, 0.05, 0.01)}}) {
    Scene s = closed_sphere(k.kd, Color(1.0, 0.5, 2.0), 3);
    s.background = Color(0.2, 0.4, 0.6);
    s.materials[0].kr = k.kr;
    s.materials[0].kt = k.kt;
    s.materials[0].ior = 1.0;
    const PreparedScene prepared(s);
    const Material& m = s.materials[0];
    const Color expected = m.kd * closed_sphere_radiance(m, Color(1.0, 0.5, 2.0), s.background, 2, 0, 1.0);
    for (const auto& [x, y] : {std::pair{3, 2}, std::pair{9, 6}}) {
      const IndirectProbe probe = probe_indirect(prepared, 12, 8, x, y, 4096);
      ASSERT_TRUE(probe.hit);
      for (int c = 0; c < 3; ++c) {
        EXPECT_GT(probe.standard_error[c], 1e-6);
        EXPECT_NEAR(probe.mean[c], expected[c], 4.5 * probe.standard_error[c]) << "kd " << k.kd << ", channel " << c;
      }
    }
  }
}

// A gather's work is its path's: each gather meets at most one gather further, so a sample's
// gathers are at most (the rays of its Whitted tree) x bounces, and their children at most
// max_depth for each gather, with mirrors and glass everywhere (the exhaustive tree would take
// 2^depth children at every level, and gathers again at each of their hits).
TEST(Indirect, AGathersWorkIsItsPath) {
  Scene s;
  s.camera.position = Vec3(0, 1, 3.5);
  s.camera.look_at = Vec3(0, 1, 0);
  s.background = Color(0.3);
  Material wall, mirror, glass;
  wall.kd = Color(0.6);
  wall.kr = Color(0.3);
  mirror.kd = Color(0.05);
  mirror.kr = Color(0.9);
  glass.kd = Color(0.05);
  glass.kt = Color(0.9);
  glass.fresnel = true;
  s.materials = {wall, mirror, glass};
  s.planes = {Plane{{0, 0, 0}, {0, 1, 0}, 0}, Plane{{0, 3, 0}, {0, -1, 0}, 0}, Plane{{-1.5, 0, 0}, {1, 0, 0}, 0},
              Plane{{1.5, 0, 0}, {-1, 0, 0}, 0}, Plane{{0, 0, -1.5}, {0, 0, 1}, 0}, Plane{{0, 0, 4}, {0, 0, -1}, 0}};
  s.spheres = {Sphere{{0.6, 0.6, -0.3}, 0.5, 1}, Sphere{{-0.6, 0.5, 0.2}, 0.45, 2}};
  Light light;
  light.position = Vec3(0.3, 2.5, 1);
  s.lights = {light};
  constexpr int kBounces = 4;
  s.indirect_bounces = kBounces;
  const PreparedScene prepared(s);
  RenderOptions options;
  options.threads = 2;
  options.packets = false;
  Accumulator lecture, indirect;
  lecture.reset(16, 12);
  indirect.reset(16, 12);
  const PassStats whitted = render_passes(prepared, options, lecture, 2);
  options.ambient = Ambient::kIndirect;
  const PassStats gathered = render_passes(prepared, options, indirect, 2);
  const std::uint64_t tree = whitted.rays.primary + whitted.rays.reflection + whitted.rays.refraction;
  EXPECT_GT(gathered.rays.indirect, tree);  // every hit of a closed room gathers
  EXPECT_LE(gathered.rays.indirect, tree * kBounces);
  const TraceLimits limits;
  EXPECT_LE(gathered.rays.reflection + gathered.rays.refraction,
            whitted.rays.reflection + whitted.rays.refraction +
                gathered.rays.indirect * static_cast<std::uint64_t>(limits.max_depth));
  EXPECT_EQ(gathered.nan_count, 0u);
}

// The signed gap's ramp: black where ka·Ia is right, orange (red over blue) where more light
// arrives, blue where less, brighter with the gap on either side, clamped past the scale.
TEST(Indirect, TheGapRampShowsTheSign) {
  EXPECT_EQ(ambient_gap_srgb(0), Color(0));
  for (const double t : {0.1, 0.5, 0.9, 1.0}) {
    const Color up = ambient_gap_srgb(t), down = ambient_gap_srgb(-t);
    EXPECT_GT(up.x, up.z) << t;
    EXPECT_GT(down.z, down.x) << t;
  }
  const auto luma = [](const Color& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; };
  for (double t = 0.05; t <= 1.0; t += 0.05) {
    EXPECT_GT(luma(ambient_gap_srgb(t)), luma(ambient_gap_srgb(t - 0.05)));
    EXPECT_GT(luma(ambient_gap_srgb(-t)), luma(ambient_gap_srgb(-t + 0.05)));
  }
  EXPECT_EQ(ambient_gap_srgb(3), ambient_gap_srgb(1));
  const std::vector<glm::vec3> indirect = {glm::vec3(0.3f), glm::vec3(0.1f), glm::vec3(0.2f)};
  const std::vector<glm::vec3> ambient = {glm::vec3(0.1f), glm::vec3(0.3f), glm::vec3(0.2f)};
  const std::vector<glm::vec3> gap = ambient_gap_pixels(indirect, ambient);
  ASSERT_EQ(gap.size(), 3u);
  EXPECT_GT(gap[0].x, gap[0].z);
  EXPECT_GT(gap[1].z, gap[1].x);
  EXPECT_EQ(gap[2], glm::vec3(0));
}
