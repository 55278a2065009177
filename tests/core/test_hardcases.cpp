// The numerical hard cases of docs/accuracy.md (S, O, N, T, R, L), each with its pass criterion.
// Every expected value is computed here, independently and in long double, from the scene's
// input numbers: ray-sphere and ray-plane hits, the camera rays of docs/model.md, camera and samples, the local Phong
// term of docs/model.md, Snell's law and the exact Fresnel equations. Random cases are seeded and
// print their seed on failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/scene/camera.h"
#include "core/accel/accel.h"
#include "core/geometry/geometry.h"
#include "tests/support/test_support.h"
#include "core/scene/math.h"
#include "experiments/numerics_variants.h"
#include "core/render/render.h"
#include "core/scene/scene.h"
#include "io/scene/scene_io.h"
#include "core/shading/shading.h"
#include "tests/support/hardcase_reference.h"

using namespace phonglab;
using namespace phonglab::reference;

namespace {

std::string seed_trace(std::uint64_t seed) { return "seed = " + std::to_string(seed); }

// A unit vector uniformly distributed on the sphere.
Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  for (;;) {
    const Vec3 v(g(rng), g(rng), g(rng));
    const double len = glm::length(v);
    if (len > 1e-3) return v / len;
  }
}

// Two unit vectors completing `w` (unit) to an orthonormal frame.
void complete_frame(const Vec3& w, Vec3& e1, Vec3& e2) {
  const Vec3 helper = std::abs(w.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  e1 = glm::normalize(glm::cross(w, helper));
  e2 = glm::cross(w, e1);
}

// One glass sphere (kt 1, nothing else) alone in an empty scene, unpruned, prepared.
PreparedScene bare_glass_sphere(const Vec3& c, double r, double ior, bool fresnel, int max_depth) {
  Scene scene;
  Material glass;
  glass.kt = Color(1);
  glass.ior = ior;
  glass.fresnel = fresnel;
  scene.materials = {glass};
  scene.spheres = {Sphere{c, r, 0}};
  scene.max_depth = max_depth;
  scene.min_weight = 0;
  return PreparedScene(std::move(scene));
}

// ---------------------------------------------------------------------------------------------
// Rendering and comparing.

struct Rendered {
  int width = 0, height = 0;
  std::vector<Color> px;
  PassStats stats;
  Color at(int x, int y) const { return px[static_cast<std::size_t>(y) * width + x]; }
};

// Renders `passes` samples per pixel (pass 1 is the pixel-centre image).
Rendered render_image(const PreparedScene& prepared, Term term = Term::kFull, std::uint32_t passes = 1) {
  const Scene& scene = prepared.scene();
  Accumulator acc;
  acc.reset(scene.width, scene.height);
  RenderOptions options;
  options.term = term;
  Rendered out;
  out.width = scene.width;
  out.height = scene.height;
  for (std::uint32_t i = 0; i < passes; ++i) {
    const PassStats s = render_pass(prepared, options, acc);
    out.stats.rays += s.rays;
    out.stats.nan_count += s.nan_count;
  }
  out.px.resize(static_cast<std::size_t>(scene.width) * scene.height);
  for (int y = 0; y < scene.height; ++y) {
    for (int x = 0; x < scene.width; ++x) out.px[static_cast<std::size_t>(y) * scene.width + x] = acc.mean(x, y);
  }
  return out;
}

struct ImageCheck {
  int compared = 0;
  int darker = 0;      // pixels with a channel below the reference beyond the tolerance (acne)
  int mismatched = 0;  // pixels with a channel off by more than the tolerance either way
  LD max_rel = 0;
  std::string first_bad;
};

// Compares an image with expected(x, y, out) (which returns false to skip a pixel).
// A channel matches when |got - exp| <= tol * max(|exp|, floor).
ImageCheck check_image(const Rendered& img, LD tol, LD floor,
                       const std::function<bool(int, int, LV&)>& expected) {
  ImageCheck check;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      LV exp;
      if (!expected(x, y, exp)) continue;
      ++check.compared;
      const Color got = img.at(x, y);
      bool darker = false, bad = false;
      for (int c = 0; c < 3; ++c) {
        const LD e = exp.at(c);
        const LD g = got[c];
        const LD scale = std::max(std::abs(e), floor);
        const LD rel = std::abs(g - e) / scale;
        if (!(rel <= check.max_rel)) check.max_rel = rel;  // also records NaN
        if (!(rel <= tol)) bad = true;
        if (!(g >= e - tol * scale)) darker = true;
      }
      check.darker += darker ? 1 : 0;
      check.mismatched += bad ? 1 : 0;
      if (bad && check.first_bad.empty()) {
        check.first_bad = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): got " +
                          str(got) + ", expected " + str(exp);
      }
    }
  }
  return check;
}

// Expected full image of a scene of spheres and planes whose lit points all see their lights.
std::function<bool(int, int, LV&)> local_reference(const Scene& scene) {
  const RefCamera cam = ref_camera(scene.camera, scene.width, scene.height);
  return [&scene, cam](int x, int y, LV& out) {
    const LV d = ref_pixel_dir(cam, x, y);
    const RefHit h = ref_intersect(scene, cam.origin, d);
    out = h.hit ? ref_local(scene, h, d).sum() : to_ld(scene.background);
    return true;
  };
}

Material phong_material(double ka, double kd, double ks, double n) {
  Material m;
  m.ka = Color(ka);
  m.kd = Color(kd);
  m.ks = Color(ks);
  m.n = n;
  return m;
}

Light point_light(const Vec3& position, const Color& intensity) {
  Light l;
  l.type = LightType::kPoint;
  l.position = position;
  l.intensity = intensity;
  return l;
}

Light directional_light(const Vec3& direction, const Color& intensity) {
  Light l;
  l.type = LightType::kDirectional;
  l.direction = direction;
  l.intensity = intensity;
  return l;
}

Triangle make_triangle(const Vec3& v0, const Vec3& v1, const Vec3& v2, int material = 0) {
  Triangle tri;
  tri.v0 = v0;
  tri.v1 = v1;
  tri.v2 = v2;
  tri.material = material;
  return tri;
}

bool hit_is_finite(const Hit& h) {
  return std::isfinite(h.t) && all_finite(h.p) && all_finite(h.ng) && all_finite(h.ns);
}

bool terms_are_finite(const Terms& t) {
  return all_finite(t.ambient) && all_finite(t.diffuse) && all_finite(t.specular) &&
         all_finite(t.reflection) && all_finite(t.refraction);
}

// The whole ray tree of one ray, traced with the scene's limits.
struct Probed {
  ProbeNode root;
  RayCounts counts;
  Color radiance{0};
};
void probe_ray(const PreparedScene& prepared, const Ray& ray, Probed& out) {
  const TraceLimits limits{prepared.scene().max_depth, prepared.scene().min_weight};
  out.radiance = trace(prepared, limits, ray, 0, 1.0, out.counts, &out.root);
}

// A plane with normal (1,2,3)/sqrt(14) through (s,s,s) seen by a camera 10 above it looking
// 63 degrees down (fov 60, 4:3), so every pixel sees the plane and none its horizon.
struct TiltedPlane {
  Scene scene;
  Vec3 p0, n, t1, t2;  // point, unit normal, unit tangents
};
TiltedPlane tilted_plane(double s, const Material& m) {
  TiltedPlane tp;
  tp.p0 = Vec3(s, s, s);
  tp.n = glm::normalize(Vec3(1, 2, 3));
  tp.t1 = glm::normalize(glm::cross(tp.n, Vec3(0, 0, 1)));
  tp.t2 = glm::cross(tp.n, tp.t1);
  Scene& scene = tp.scene;
  scene.width = 96;
  scene.height = 72;
  scene.ambient = Color(1);
  scene.background = Color(0);
  scene.max_depth = 0;
  scene.materials = {m};
  scene.planes.push_back(Plane{tp.p0, Vec3(1, 2, 3), 0});
  scene.camera = Camera{tp.p0 + 10.0 * tp.n, tp.p0 + 5.0 * tp.t1, tp.n, 60};
  return tp;
}

}  // namespace

// =============================================================================================
// S. Ray-sphere

// A unit sphere at distance D = 10..1e6 along two axes; rays from the origin aimed at a disk of
// radius 1.02 around it, plus rays aimed within 8 ulp(D) of the silhouette. Any hit/miss that
// disagrees with the long double reference lies within 1 ulp(D) of tangency; the median
// relative error of t is <= 1e-6. Both intersect_sphere and the scene query intersect() are held
// to it. (Measured: at D = 1e5..1e6 a few rays of the 8-ulp band disagree, all within 0.43 ulp.)
TEST(HardCases, S1_DistantSphereHitMissAndDistance) {
  const std::uint64_t seed = 1001;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  const Vec3 axes[] = {{0, 0, 1}, {0.48, 0.6, 0.64}};
  for (const Vec3& axis : axes) {
    for (const double dist : {10.0, 1e2, 1e3, 1e4, 1e5, 1e6}) {
      SCOPED_TRACE("axis " + str(axis) + ", D = " + std::to_string(dist));
      Scene scene;
      scene.materials = {phong_material(0, 1, 0, 1)};
      scene.spheres = {Sphere{dist * axis, 1.0, 0}};
      const Sphere& sphere = scene.spheres[0];
      Vec3 e1, e2;
      complete_frame(axis, e1, e2);
      const double ulp = std::nextafter(dist, 2 * dist) - dist;
      // Path 0: intersect_sphere; path 1: the nearest-hit query over the scene, as the renderer uses it.
      int disagreements[2] = {0, 0};
      int far_disagreements[2] = {0, 0};
      LD worst_margin[2] = {0, 0};
      std::vector<LD> rel_errors[2];
      auto shoot = [&](double rho, double phi, bool record_t) {
        const Vec3 target = sphere.center + rho * (std::cos(phi) * e1 + std::sin(phi) * e2);
        const Vec3 d = glm::normalize(target);
        const Ray ray = make_ray(Vec3(0), d);
        const LD d_len = length(to_ld(d));
        const LV du = (1 / d_len) * to_ld(d);
        const LD miss_distance = ref_line_distance(to_ld(sphere.center), LV{}, du);
        const bool ref_hit = miss_distance <= 1;
        const std::optional<Hit> hit = intersect_all(scene, ray);
        const std::optional<double> ts[2] = {intersect_sphere(sphere, ray),
                                             hit ? std::optional<double>(hit->t) : std::nullopt};
        for (int path = 0; path < 2; ++path) {
          const std::optional<double>& t = ts[path];
          if (t.has_value() != ref_hit) {
            ++disagreements[path];
            const LD margin = std::abs(miss_distance - 1) / ulp;
            worst_margin[path] = std::max(worst_margin[path], margin);
            if (margin > 1) ++far_disagreements[path];
          }
          if (t && !std::isfinite(*t)) ADD_FAILURE() << "non-finite t for direction " << str(d);
          if (t && ref_hit && record_t) {
            const LD t_ref = *ref_sphere_t(to_ld(sphere.center), 1, LV{}, du) / d_len;
            rel_errors[path].push_back(std::abs(*t - t_ref) / t_ref);
          }
        }
      };
      for (int i = 0; i < 20000; ++i) shoot(1.02 * std::sqrt(uni(rng)), 2 * kPi * uni(rng), true);
      for (int i = 0; i < 2000; ++i) shoot(1 + (2 * uni(rng) - 1) * 8 * ulp, 2 * kPi * uni(rng), false);

      for (int path = 0; path < 2; ++path) {
        SCOPED_TRACE(path == 0 ? "intersect_sphere" : "intersect(scene)");
        EXPECT_EQ(far_disagreements[path], 0)
            << disagreements[path] << " hit/miss disagreements, the worst "
            << static_cast<double>(worst_margin[path]) << " ulp(D) from tangency";
        std::vector<LD>& errors = rel_errors[path];
        ASSERT_FALSE(errors.empty());
        std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2), errors.end());
        EXPECT_LE(static_cast<double>(errors[errors.size() / 2]), 1e-6) << "median relative error of t";
      }
    }
  }
}

// Spheres of radius 10^+-4, scaled by 10^+-4 and translated up to 1e8. Rays leaving a hit point
// outwards never hit the same sphere again; rays leaving it inwards (refraction) hit the far
// side at the reference distance where the sphere is resolvable (r >= 1e-6 of its coordinates:
// the surface offset is 1e-9 of them) and are never re-hits (t below half the chord) elsewhere.
TEST(HardCases, S4_NoReHitsOfTheSameSphereAtAnyScale) {
  const std::uint64_t seed = 1004;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  const Vec3 axis(0.48, 0.6, 0.64);
  for (const double radius : {1e-4, 1.0, 1e4}) {
    for (const double scale : {1e-4, 1.0, 1e4}) {
      for (const double shift : {0.0, 1e4, 1e8}) {
        const double r = radius * scale;
        const Vec3 c = shift * axis;
        const double coords = std::max(max_abs(c), r);
        if (r < 1e-9 * coords) continue;  // below the offset's resolution: not a modelled scene
        const bool resolvable = r >= 1e-6 * coords;
        SCOPED_TRACE("r = " + std::to_string(r) + ", centre " + str(c));
        Scene scene;
        scene.materials = {phong_material(0, 1, 0, 1)};
        scene.spheres = {Sphere{c, r, 0}};
        int primary_misses = 0, outward_rehits = 0, inward_rehits = 0, inward_wrong = 0;
        std::string example;
        for (int i = 0; i < 300; ++i) {
          const Vec3 w = random_unit(rng);
          const Vec3 origin = c + 4 * r * w;
          Vec3 u = random_unit(rng);
          if (glm::dot(u, w) < 0.3) u = glm::normalize(u + w);
          if (glm::dot(u, w) < 0.3) continue;
          const Vec3 dir = glm::normalize(c + r * u - origin);
          const std::optional<Hit> hit = intersect_all(scene, make_ray(origin, dir));
          if (!hit) {
            ++primary_misses;
            continue;
          }
          ASSERT_TRUE(hit_is_finite(*hit));
          const Vec3 ng = hit->ng;  // outward: the ray came from outside
          const double offset = surface_offset(hit->p, hit->t);
          // Outward: any direction with a positive normal component, grazing ones included.
          Vec3 e = random_unit(rng);
          double en = glm::dot(e, ng);
          if (en < 0) e -= 2 * en * ng;
          if (i % 3 == 0) e = glm::normalize(e - glm::dot(e, ng) * ng + 1e-3 * ng);
          const Ray out_ray = make_ray(offset_origin(hit->p, ng, e, offset), e);
          if (auto t = intersect_sphere(scene.spheres[0], out_ray)) {
            ++outward_rehits;
            if (example.empty()) example = "outward re-hit at t = " + std::to_string(*t);
          }
          if (occluded_all(scene, out_ray, std::numeric_limits<double>::infinity())) {
            ++outward_rehits;
            if (example.empty()) example = "outward re-hit by the any-hit query";
          }
          // Inward, at least 0.1 from the tangent plane.
          Vec3 g = random_unit(rng);
          if (glm::dot(g, ng) > 0) g -= 2 * glm::dot(g, ng) * ng;
          if (glm::dot(g, ng) > -0.1) g = glm::normalize(g - 0.2 * ng);
          const double chord = 2 * r * -glm::dot(g, ng);
          const Ray in_ray = make_ray(offset_origin(hit->p, ng, g, offset), g);
          const std::optional<double> t_in = intersect_sphere(scene.spheres[0], in_ray);
          const std::optional<Hit> hit_in = intersect_all(scene, in_ray);
          if (hit_in.has_value() != t_in.has_value() || (t_in && hit_in->t != *t_in)) {
            ++inward_wrong;
            if (example.empty()) example = "intersect_sphere and intersect(scene) differ on an inward ray";
          }
          if (t_in && *t_in < 0.5 * chord) {
            ++inward_rehits;
            if (example.empty()) example = "inward re-hit at t = " + std::to_string(*t_in);
          }
          if (resolvable) {
            const std::optional<LD> t_ref = ref_sphere_t(to_ld(c), r, to_ld(in_ray.origin), to_ld(g));
            if (!t_in || !t_ref || std::abs(*t_in - *t_ref) > 1e-6L * *t_ref) {
              ++inward_wrong;
              if (example.empty()) {
                example = "inward ray: t = " + (t_in ? std::to_string(*t_in) : std::string("miss")) +
                          ", expected " + (t_ref ? std::to_string(static_cast<double>(*t_ref)) : "miss");
              }
            }
          }
        }
        if (resolvable) { EXPECT_EQ(primary_misses, 0); }
        EXPECT_EQ(outward_rehits, 0) << example;
        EXPECT_EQ(inward_rehits, 0) << example;
        EXPECT_EQ(inward_wrong, 0) << example;
      }
    }
  }
}

// Glass sphere (ior 1.5, no Fresnel): a ray entering at impact parameter b travels a chord of
// 2 r cos(theta_t) inside, with sin(theta_t) = (b / r) / 1.5.
TEST(HardCases, S5_GlassSphereChordLength) {
  struct Case {
    Vec3 c;
    double r;
  };
  const Case cases[] = {{{0, 0, 0}, 1}, {{3, -2, 5}, 0.5}, {{100, 200, -50}, 10}, {{1e-3, 2e-3, 0}, 1e-3}};
  const Vec3 w = glm::normalize(Vec3(0.3, -0.5, 0.8));
  Vec3 u, v;
  complete_frame(w, u, v);
  for (const Case& cs : cases) {
    const PreparedScene scene = bare_glass_sphere(cs.c, cs.r, 1.5, false, 2);
    for (const double b_over_r : {0.0, 0.5, 0.9, 0.999}) {
      SCOPED_TRACE("centre " + str(cs.c) + ", r = " + std::to_string(cs.r) + ", b/r = " + std::to_string(b_over_r));
      const Vec3 origin = cs.c - 3 * cs.r * w + b_over_r * cs.r * u;
      Probed pr;
      probe_ray(scene, make_ray(origin, w), pr);
      ASSERT_TRUE(pr.root.hit);
      ASSERT_TRUE(pr.root.entering);
      ASSERT_NE(pr.root.refraction, nullptr);
      const ProbeNode& inside = *pr.root.refraction;
      ASSERT_TRUE(inside.hit) << "the exit point was skipped";
      EXPECT_FALSE(inside.entering);
      const LD b = ref_line_distance(to_ld(cs.c), to_ld(origin), to_ld(w));
      const LD sin_t = b / cs.r / 1.5L;
      const LD chord = 2 * cs.r * std::sqrt(1 - sin_t * sin_t);
      EXPECT_LE(static_cast<double>(std::abs(inside.t - chord) / chord), 1e-6)
          << "chord " << inside.t << ", expected " << static_cast<double>(chord);
    }
  }
}

// Rays tangent to a sphere, b = r (1 +- 1e-7) and b = r: no NaN in t, P or N; the ray at
// r (1 - 1e-7) hits near the tangent point, the one at r (1 + 1e-7) misses; shading is finite.
TEST(HardCases, S6_TangentRaysGiveNoNaN) {
  const std::uint64_t seed = 1006;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  struct Case {
    Vec3 c;
    double r;
  };
  const Case cases[] = {{{0, 0, 0}, 1}, {{3, -2, 5}, 1e-3}, {{1e3, -2e3, 5e2}, 1e3}, {{1e5, 1e5, -1e5}, 1}};
  for (const Case& cs : cases) {
    SCOPED_TRACE("centre " + str(cs.c) + ", r = " + std::to_string(cs.r));
    Scene scene;
    Material glass = phong_material(0.1, 0.5, 0.5, 10.5);
    glass.kt = Color(0.8);
    glass.kr = Color(0.1);
    glass.fresnel = true;
    scene.materials = {glass};
    scene.spheres = {Sphere{cs.c, cs.r, 0}};
    scene.lights = {point_light(cs.c + Vec3(0, 3 * cs.r, 0), Color(1)),
                    directional_light(Vec3(1, -1, 0.5), Color(0.5))};
    scene.max_depth = 4;
    scene.min_weight = 0;
    const PreparedScene prepared(scene);
    const TraceLimits limits{scene.max_depth, scene.min_weight};
    int wrong = 0;
    std::string example;
    for (int i = 0; i < 300; ++i) {
      const Vec3 w = random_unit(rng);
      Vec3 u, v;
      complete_frame(w, u, v);
      for (const double factor : {1 - 1e-7, 1.0, 1 + 1e-7}) {
        const Vec3 origin = cs.c - 10 * cs.r * w + factor * cs.r * u;
        const Ray ray = make_ray(origin, w);
        const std::optional<double> t = intersect_sphere(scene.spheres[0], ray);
        if (t) { ASSERT_TRUE(std::isfinite(*t)) << "factor " << factor; }
        const std::optional<Hit> hit = intersect(prepared, ray);
        if (hit) { ASSERT_TRUE(hit_is_finite(*hit)) << "factor " << factor; }
        ASSERT_EQ(t.has_value(), hit.has_value()) << "intersect_sphere vs intersect(scene), factor " << factor;
        RayCounts counts;
        const Color c = trace(prepared, limits, ray, 0, 1.0, counts);
        ASSERT_TRUE(all_finite(c)) << "factor " << factor;
        const LD miss_distance = ref_line_distance(to_ld(cs.c), to_ld(origin), to_ld(w));
        if (factor == 1.0) continue;  // exactly tangent: either answer is right
        const bool ref_hit = miss_distance < cs.r;
        if (hit.has_value() != ref_hit) {
          ++wrong;
          if (example.empty()) example = "factor " + std::to_string(factor) + ": hit " + std::to_string(hit.has_value());
          continue;
        }
        if (hit) {
          // The tangent point: where the line passes closest to the centre.
          const LV foot = to_ld(origin) + dot(to_ld(cs.c) - to_ld(origin), to_ld(w)) * to_ld(w);
          if (length(to_ld(hit->p) - foot) > 1e-3L * cs.r) {
            ++wrong;
            if (example.empty()) example = "hit point " + str(hit->p) + " far from the tangent point " + str(foot);
          }
        }
      }
    }
    EXPECT_EQ(wrong, 0) << example;
  }
}

// =============================================================================================
// O. Self-intersection and scale

// Lights "10 above" a plane far from the origin: every plane pixel equals its unshadowed Phong
// value (no acne).
TEST(HardCases, O1_LitPlaneFarFromOrigin) {
  for (const double s : {1e5, 1e6}) {
    SCOPED_TRACE("s = " + std::to_string(s));
    TiltedPlane tp = tilted_plane(s, phong_material(0.05, 0.6, 0.4, 30));
    Scene& scene = tp.scene;
    scene.lights = {point_light(tp.p0 + 10.0 * tp.n + 7.0 * tp.t2 - 3.0 * tp.t1, Color(0.6)),
                    point_light(tp.p0 + 10.0 * tp.n + 5.0 * tp.t1 + 5.0 * tp.t2, Color(0.3)),
                    directional_light(-tp.n - 0.3 * tp.t1, Color(0.2))};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    EXPECT_EQ(img.stats.nan_count, 0u);
    const ImageCheck check = check_image(img, 1e-6L, 1e-9L, local_reference(prepared.scene()));
    EXPECT_EQ(check.compared, scene.width * scene.height);
    EXPECT_EQ(check.darker, 0) << "acne: " << check.first_bad;
    EXPECT_EQ(check.mismatched, 0) << check.first_bad << " (max relative error "
                                   << static_cast<double>(check.max_rel) << ")";
  }
}

// The same plane at s = 10..1e4: no acne, and the offsets stay <= 1e-3 of the smallest feature
// (the camera's and lights' height of 10).
TEST(HardCases, O2_LitPlaneAtModerateDistances) {
  for (const double s : {10.0, 1e2, 1e3, 1e4}) {
    SCOPED_TRACE("s = " + std::to_string(s));
    TiltedPlane tp = tilted_plane(s, phong_material(0.05, 0.6, 0.4, 30));
    Scene& scene = tp.scene;
    scene.lights = {point_light(tp.p0 + 10.0 * tp.n + 7.0 * tp.t2 - 3.0 * tp.t1, Color(0.6)),
                    directional_light(-tp.n - 0.3 * tp.t1, Color(0.3))};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    const ImageCheck check = check_image(img, 1e-6L, 1e-9L, local_reference(prepared.scene()));
    EXPECT_EQ(check.darker, 0) << "acne: " << check.first_bad;
    EXPECT_EQ(check.mismatched, 0) << check.first_bad;
    // The largest offset of the image: its farthest hit (a corner).
    const RefCamera cam = ref_camera(scene.camera, scene.width, scene.height);
    double worst = 0;
    const std::pair<int, int> corners[] = {
        {0, 0}, {scene.width - 1, 0}, {0, scene.height - 1}, {scene.width - 1, scene.height - 1}};
    for (const auto& [x, y] : corners) {
      const LV d = ref_pixel_dir(cam, x, y);
      const RefHit h = ref_intersect(prepared.scene(), cam.origin, d);
      ASSERT_TRUE(h.hit);
      worst = std::max(worst, surface_offset(to_d(h.p), static_cast<double>(h.t)));
    }
    EXPECT_LE(worst, 1e-3 * 10);
  }
}

// Plane, and a sphere of radius 0.5 s resting 0.02 s above it, lit from above: the image at
// scale s = 1e-5..1e5 matches the one at s = 1 within 1/255 (contact shadows keep their size).
TEST(HardCases, O3_TinyAndHugeScenesMatchUnitScale) {
  auto make = [](double s) {
    Scene scene;
    scene.width = 96;
    scene.height = 72;
    scene.ambient = Color(1);
    scene.background = Color(0.1, 0.2, 0.3);
    scene.max_depth = 3;
    Material floor = phong_material(0.05, 0.7, 0.2, 20);
    Material ball = phong_material(0.05, 0.5, 0.5, 50);
    ball.kr = Color(0.3);
    scene.materials = {floor, ball};
    scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
    scene.spheres = {Sphere{s * Vec3(0, 0.52, 0), 0.5 * s, 1}};
    scene.lights = {point_light(s * Vec3(0.3, 4, 0.2), Color(0.8)),
                    directional_light(Vec3(-0.2, -1, -0.3), Color(0.3))};
    scene.camera = Camera{s * Vec3(0, 0.8, 1.6), s * Vec3(0, 0.1, 0), Vec3(0, 1, 0), 50};
    return PreparedScene(std::move(scene));
  };
  const PreparedScene unit_scene = make(1);
  const Rendered unit = render_image(unit_scene);
  for (const double s : {1e-5, 1e-4, 1e-3, 1e-2, 0.1, 10.0, 1e3, 1e5}) {
    SCOPED_TRACE("s = " + std::to_string(s));
    const PreparedScene scaled_scene = make(s);
    const Rendered scaled = render_image(scaled_scene);
    EXPECT_EQ(scaled.stats.nan_count, 0u);
    int differing = 0;
    std::string example;
    for (int y = 0; y < unit.height; ++y) {
      for (int x = 0; x < unit.width; ++x) {
        const Color diff = glm::abs(scaled.at(x, y) - unit.at(x, y));
        if (max_channel(diff) > 1.0 / 255) {
          if (example.empty()) {
            example = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): " +
                      str(scaled.at(x, y)) + " vs unit " + str(unit.at(x, y));
          }
          ++differing;
        }
      }
    }
    EXPECT_EQ(differing, 0) << example;
  }
}

// Grazing light, down to 0.1 degrees above the plane (directional, and a far point light), at
// the origin and 1e5 away: no acne.
TEST(HardCases, O4_GrazingShadowRays) {
  for (const double s : {0.0, 1e5}) {
    for (const double elevation_deg : {0.1, 0.2, 0.5, 1.0, 2.0, 5.0}) {
      for (const double azimuth_deg : {0.0, 100.0, 225.0}) {
        SCOPED_TRACE("s = " + std::to_string(s) + ", elevation " + std::to_string(elevation_deg) +
                     " deg, azimuth " + std::to_string(azimuth_deg) + " deg");
        TiltedPlane tp = tilted_plane(s, phong_material(0, 1, 0.5, 10));
        Scene& scene = tp.scene;
        const double e = elevation_deg * kPi / 180;
        const double a = azimuth_deg * kPi / 180;
        const Vec3 horizontal = std::cos(a) * tp.t1 + std::sin(a) * tp.t2;
        const Vec3 towards_light = std::cos(e) * horizontal + std::sin(e) * tp.n;
        scene.lights = {directional_light(-towards_light, Color(1))};
        const PreparedScene prepared(scene);
        {
          const Rendered img = render_image(prepared);
          const ImageCheck check = check_image(img, 1e-6L, 1e-12L, local_reference(prepared.scene()));
          EXPECT_EQ(check.darker, 0) << "directional light, acne: " << check.first_bad;
          EXPECT_EQ(check.mismatched, 0) << check.first_bad;
        }
        // A point light 2000 away in the same direction (elevation about the same from the
        // viewed part of the plane).
        scene.lights = {point_light(tp.p0 + 5.0 * tp.t1 + 2000.0 * towards_light, Color(1))};
        const PreparedScene relit(scene);
        {
          const Rendered img = render_image(relit);
          const ImageCheck check = check_image(img, 1e-6L, 1e-12L, local_reference(relit.scene()));
          EXPECT_EQ(check.darker, 0) << "point light, acne: " << check.first_bad;
          EXPECT_EQ(check.mismatched, 0) << check.first_bad;
        }
      }
    }
  }
}

// A ray starting 1e-4..1e-2 outside a sphere and aimed at it gets the near hit, not the far one.
TEST(HardCases, O6_RayJustOutsideSphereGetsNearHit) {
  const std::uint64_t seed = 1016;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  struct Case {
    Vec3 c;
    double r;
  };
  const Case cases[] = {{{0, 0, 0}, 1}, {{5, -3, 2}, 10}, {{1e3, 2e3, -1e3}, 100}, {{0.5, 0.25, 0}, 0.01}};
  for (const Case& cs : cases) {
    for (const double gap : {1e-4, 1e-3, 1e-2}) {
      SCOPED_TRACE("centre " + str(cs.c) + ", r = " + std::to_string(cs.r) + ", gap " + std::to_string(gap));
      Scene scene;
      scene.materials = {phong_material(0, 1, 0, 1)};
      scene.spheres = {Sphere{cs.c, cs.r, 0}};
      int wrong = 0;
      std::string example;
      const double max_angle = std::asin(cs.r / (cs.r + gap));
      for (int i = 0; i < 400; ++i) {
        const Vec3 u = random_unit(rng);
        Vec3 p, q;
        complete_frame(u, p, q);
        const Vec3 origin = cs.c + (cs.r + gap) * u;
        const double alpha = (i == 0 ? 0.0 : 0.95 * max_angle * uni(rng));
        const double phi = 2 * kPi * uni(rng);
        const Vec3 dir = glm::normalize(-std::cos(alpha) * u + std::sin(alpha) * (std::cos(phi) * p + std::sin(phi) * q));
        const RefRoots ref = ref_sphere_roots(to_ld(cs.c), cs.r, to_ld(origin), to_ld(dir));
        if (!ref.hit || !(ref.t0 > 0)) continue;  // aimed past the sphere by rounding
        const std::optional<double> t = intersect_sphere(scene.spheres[0], make_ray(origin, dir));
        const std::optional<Hit> hit = intersect_all(scene, make_ray(origin, dir));
        auto near = [&](double t_got) { return std::abs(t_got - ref.t0) <= 1e-6L * ref.t0; };
        const bool ok = t && hit && near(*t) && near(hit->t);
        if (!ok) {
          ++wrong;
          if (example.empty()) {
            example = "t = " + (t ? std::to_string(*t) : std::string("miss")) + ", near root " +
                      std::to_string(static_cast<double>(ref.t0)) + ", far root " +
                      std::to_string(static_cast<double>(ref.t1));
          }
        }
      }
      EXPECT_EQ(wrong, 0) << example;
    }
  }
}

// A point light 1e-6 above a plane, and a light on a sphere's surface (its bottom, over a
// plane): no NaN and no self-shadowing; the lit plane matches the reference everywhere.
TEST(HardCases, O7_LightOnOrJustAboveASurface) {
  {
    SCOPED_TRACE("light 1e-6 above a plane");
    Scene scene;
    scene.width = 96;
    scene.height = 72;
    scene.ambient = Color(1);
    scene.materials = {phong_material(0.01, 0.8, 0.3, 5)};
    scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
    scene.lights = {point_light(Vec3(0.25, 1e-6, -0.5), Color(1))};
    scene.camera = Camera{Vec3(0, 3, 4), Vec3(0, 0, 0), Vec3(0, 1, 0), 60};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    EXPECT_EQ(img.stats.nan_count, 0u);
    const ImageCheck check = check_image(img, 1e-6L, 1e-15L, local_reference(prepared.scene()));
    EXPECT_EQ(check.darker, 0) << "self-shadowed: " << check.first_bad;
    EXPECT_EQ(check.mismatched, 0) << check.first_bad;
  }
  {
    SCOPED_TRACE("light on a plane");
    Scene scene;
    scene.width = 64;
    scene.height = 48;
    // ks = 0: N.L is 0 only up to the rounding of the hit point, and Phong's specular term
    // (not weighted by N.L) would then legitimately come and go.
    scene.materials = {phong_material(0.01, 0.8, 0, 5)};
    scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
    scene.lights = {point_light(Vec3(0.25, 0, -0.5), Color(1))};
    scene.camera = Camera{Vec3(0, 3, 4), Vec3(0, 0, 0), Vec3(0, 1, 0), 60};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    EXPECT_EQ(img.stats.nan_count, 0u);
    // N.L = 0 on the whole plane: ambient only.
    const ImageCheck check = check_image(img, 1e-9L, 1e-12L, local_reference(prepared.scene()));
    EXPECT_EQ(check.mismatched, 0) << check.first_bad;
  }
  struct OnSphere {
    Vec3 c;
    double r;
  };
  for (const OnSphere& os : {OnSphere{Vec3(0, 2, 0), 1}, OnSphere{Vec3(0.1, 2.3, -0.7), 1.3}}) {
    SCOPED_TRACE("light at the bottom of the sphere at " + str(os.c) + ", r = " + std::to_string(os.r));
    Scene scene;
    scene.width = 96;
    scene.height = 72;
    scene.ambient = Color(1);
    scene.materials = {phong_material(0.02, 0.8, 0.3, 8), phong_material(0.03, 0.6, 0.2, 4)};
    scene.spheres = {Sphere{os.c, os.r, 1}};
    scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
    // At the sphere's lowest point (up to rounding): every plane point sees it unblocked (the
    // segment stays below the sphere's horizontal tangent plane); every sphere point has N.L <= 0.
    scene.lights = {point_light(os.c - Vec3(0, os.r, 0), Color(1))};
    scene.camera = Camera{Vec3(0.5, 2.5, 5), Vec3(0, 0.8, 0), Vec3(0, 1, 0), 60};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    EXPECT_EQ(img.stats.nan_count, 0u);
    const ImageCheck check = check_image(img, 1e-6L, 1e-9L, local_reference(prepared.scene()));
    EXPECT_EQ(check.darker, 0) << "self-shadowed: " << check.first_bad;
    EXPECT_EQ(check.mismatched, 0) << check.first_bad;
  }
}

// Total internal reflection inside a glass sphere (other objects nearby): every internal
// reflection hits the same sphere again, at the far side of its actual ray, all the way down
// the ray tree (24 bounces), with or without Fresnel.
TEST(HardCases, O8_TotalInternalReflectionHitsTheSameSphere) {
  struct Case {
    Vec3 c;
    double r;
  };
  const Case cases[] = {{{0, 0, 0}, 1}, {{1e5, -1e5, 1e5}, 1e3}, {{1e-3, 0, 0}, 1e-4}};
  const Vec3 w = glm::normalize(Vec3(-0.2, 0.9, 0.4));
  Vec3 u, v;
  complete_frame(w, u, v);
  for (const bool fresnel : {false, true}) {
    for (const Case& cs : cases) {
      for (const double b_over_r : {0.7, 0.9, 0.99}) {
        SCOPED_TRACE("centre " + str(cs.c) + ", r = " + std::to_string(cs.r) + ", b/r = " +
                     std::to_string(b_over_r) + (fresnel ? ", Fresnel" : ""));
        Scene scene;
        Material glass;
        glass.kt = Color(1);
        glass.ior = 1.5;
        glass.fresnel = fresnel;
        scene.materials = {glass, phong_material(0.1, 0.5, 0, 1)};
        // Other objects nearby: a wrong "skip the last primitive" would find them instead.
        scene.spheres = {Sphere{cs.c, cs.r, 0}, Sphere{cs.c + 3 * cs.r * u, cs.r, 1}};
        scene.planes = {Plane{cs.c - 2 * cs.r * w, w, 1}};
        scene.max_depth = 24;
        scene.min_weight = 0;
        const PreparedScene prepared(scene);
        const Vec3 origin = cs.c + b_over_r * cs.r * u;
        Probed pr;
        probe_ray(prepared, make_ray(origin, w), pr);
        const LD b = ref_line_distance(to_ld(cs.c), to_ld(origin), to_ld(w));
        const ProbeNode* node = &pr.root;
        for (int depth = 0; depth <= scene.max_depth; ++depth) {
          SCOPED_TRACE("depth " + std::to_string(depth));
          ASSERT_TRUE(node->hit);
          ASSERT_EQ(node->object.kind, ObjectRef::Kind::kSphere);
          ASSERT_EQ(node->object.index, 0);
          EXPECT_FALSE(node->entering);
          if (depth < scene.max_depth) { EXPECT_TRUE(node->tir); }  // recorded where it recurses
          // The far side from the actual ray (whose origin each bounce moves inwards by the
          // surface offset, 1e-9 of the coordinates: the chord drifts by that much per bounce).
          const std::optional<LD> t_ref = ref_sphere_t(to_ld(cs.c), cs.r, to_ld(node->origin), to_ld(node->dir));
          ASSERT_TRUE(t_ref);
          EXPECT_LE(static_cast<double>(std::abs(node->t - *t_ref) / *t_ref), 1e-6);
          // The impact parameter (so the incidence angle) is kept by each reflection, up to that
          // drift of at most one offset per bounce.
          const LD b_here = ref_line_distance(to_ld(cs.c), to_ld(node->origin), to_ld(node->dir));
          const LD drift_bound = (depth + 1) * 1e-9L * (max_abs(cs.c) + 3 * cs.r) + 1e-12L * cs.r;
          EXPECT_LE(static_cast<double>(std::abs(b_here - b)), static_cast<double>(drift_bound));
          if (depth == scene.max_depth) break;
          const ProbeNode* next = node->refraction ? node->refraction.get() : node->reflection.get();
          ASSERT_NE(next, nullptr);
          ASSERT_TRUE(node->refraction == nullptr || node->reflection == nullptr);
          node = next;
        }
      }
    }
  }
}

// =============================================================================================
// N. NaN and Inf in shading

// n = 0: specular is 0 wherever N.L <= 0 (pow(0, 0) = 1 must not light the dark side); where
// N.L > 0 it is ks I even with R.V < 0 (docs/model.md: pow(0, 0) is 1).
TEST(HardCases, N1_ZeroShininessDoesNotLightTheDarkSide) {
  {
    SCOPED_TRACE("plane, shade() directly");
    Scene scene;
    Material m = phong_material(0, 0.5, 1, 0);
    scene.materials = {m};
    scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
    const PreparedScene prepared(scene);
    // Hits (0, 0, 0) exactly (t = 0.6 / 0.6), so N.L = 0 is exact for lights in the plane.
    const Ray ray = make_ray(Vec3(0, 0.6, 0.8), Vec3(0, -0.6, -0.8));
    const std::optional<Hit> hit = intersect(prepared, ray);
    ASSERT_TRUE(hit);
    ASSERT_EQ(hit->p, Vec3(0));
    const TraceLimits limits{0, 0};
    struct LightCase {
      const char* what;
      Light light;
      double expected_specular;
    };
    const LightCase lights[] = {
        {"point light below (N.L = -1)", point_light(Vec3(0, -1, 0), Color(1)), 0},
        {"point light in the plane (N.L = 0)", point_light(Vec3(5, 0, 0), Color(1)), 0},
        {"directional light along the plane (N.L = 0)", directional_light(Vec3(-1, 0, 0), Color(1)), 0},
        {"directional light from below", directional_light(Vec3(0.3, 1, 0.2), Color(1)), 0},
        {"lit, R.V < 0", point_light(Vec3(0, 0.2, 1), Color(1)), 1},
    };
    for (const LightCase& lc : lights) {
      SCOPED_TRACE(lc.what);
      Scene s = scene;
      s.lights = {lc.light};
      const PreparedScene s_prepared(s);
      RayCounts counts;
      const Terms t = shade(s_prepared, limits, ray, *hit, 0, 1.0, counts);
      EXPECT_EQ(t.specular, Color(lc.expected_specular));
      if (lc.expected_specular == 0) {
        EXPECT_EQ(t.diffuse, Color(0));
        EXPECT_EQ(counts.shadow, 0u);
      }
    }
  }
  {
    SCOPED_TRACE("sphere lit from the side, specular term image");
    Scene scene;
    scene.width = 80;
    scene.height = 60;
    scene.materials = {phong_material(0, 0, 1, 0)};
    scene.spheres = {Sphere{Vec3(0), 1, 0}};
    scene.lights = {point_light(Vec3(4, 1, 0), Color(0.75))};
    scene.camera = Camera{Vec3(0, 0, 4), Vec3(0), Vec3(0, 1, 0), 40};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared, Term::kSpecular);
    const RefCamera cam = ref_camera(scene.camera, scene.width, scene.height);
    int dark = 0;
    const ImageCheck check = check_image(img, 1e-12L, 1e-12L, [&](int x, int y, LV& out) {
      const LV d = ref_pixel_dir(cam, x, y);
      const RefHit h = ref_intersect(prepared.scene(), cam.origin, d);
      if (!h.hit) {
        out = LV{};
        return true;
      }
      const RefLocal local = ref_local(prepared.scene(), h, d);
      if (local.min_abs_n_dot_l < 1e-9L) return false;  // on the terminator: either is right
      dark += local.lit_lights == 0 ? 1 : 0;
      out = local.specular;
      return true;
    });
    EXPECT_GT(dark, 100);  // the dark side is in view
    EXPECT_EQ(check.mismatched, 0) << check.first_bad;
  }
}

// R.V = -0.5 with N.L > 0: for n in {0.5, 1, 10, 10.5, 1e4} the specular term is exactly 0 (the
// base is clamped before pow: no NaN for n = 10.5, no phantom highlight for n = 10); for n = 0
// it is ks I. A rendered sphere's specular term matches the reference for every n.
TEST(HardCases, N2_NegativeCosineWithFractionalShininess) {
  const double exponents[] = {0, 0.5, 1, 10, 10.5, 1e4};
  {
    SCOPED_TRACE("R.V = -0.5, shade() directly");
    // N = +y, L = (0.6, 0.8, 0) so R = (-0.6, 0.8, 0); V chosen with R.V = -0.5 and V.y > 0.
    const double vy = 0.1;
    const double vx = (0.08 + 0.5) / 0.6;
    const Vec3 v(vx, vy, std::sqrt(1 - vx * vx - vy * vy));
    const Vec3 p(0.25, 0, -0.5);
    const Ray ray = make_ray(p + v, -v);
    for (const double n : exponents) {
      SCOPED_TRACE("n = " + std::to_string(n));
      Scene scene;
      scene.materials = {phong_material(0, 0, 0.5, n)};
      scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
      scene.lights = {point_light(p + 10.0 * Vec3(0.6, 0.8, 0), Color(1))};
      const PreparedScene prepared(scene);
      const std::optional<Hit> hit = intersect(prepared, ray);
      ASSERT_TRUE(hit);
      RayCounts counts;
      ProbeNode probe;
      const Terms t = shade(prepared, TraceLimits{0, 0}, ray, *hit, 0, 1.0, counts, &probe);
      ASSERT_EQ(probe.lights.size(), 1u);
      EXPECT_NEAR(probe.lights[0].r_dot_v, -0.5, 1e-12);
      EXPECT_TRUE(terms_are_finite(t));
      EXPECT_EQ(t.specular, Color(n == 0 ? 0.5 : 0.0));
    }
  }
  for (const double n : exponents) {
    SCOPED_TRACE("sphere, specular term image, n = " + std::to_string(n));
    Scene scene;
    scene.width = 80;
    scene.height = 60;
    scene.materials = {phong_material(0, 0.3, 0.9, n)};
    scene.spheres = {Sphere{Vec3(0), 1, 0}};
    scene.lights = {point_light(Vec3(3, 2, 1), Color(1)), directional_light(Vec3(0.5, -0.2, -1), Color(0.5))};
    scene.camera = Camera{Vec3(0, 0, 4), Vec3(0), Vec3(0, 1, 0), 40};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared, Term::kSpecular);
    EXPECT_EQ(img.stats.nan_count, 0u);
    const RefCamera cam = ref_camera(scene.camera, scene.width, scene.height);
    const ImageCheck check = check_image(img, 1e-6L, 1e-12L, [&](int x, int y, LV& out) {
      const LV d = ref_pixel_dir(cam, x, y);
      const RefHit h = ref_intersect(prepared.scene(), cam.origin, d);
      out = h.hit ? ref_local(prepared.scene(), h, d).specular : LV{};
      return true;
    });
    EXPECT_EQ(check.mismatched, 0) << check.first_bad;
  }
}

// A light exactly at the shaded point, and the camera on a surface: no NaN anywhere.
TEST(HardCases, N3_LightAtShadedPointAndCameraOnSurface) {
  {
    SCOPED_TRACE("light at the centre pixel's hit point");
    Scene scene;
    scene.width = 65;
    scene.height = 49;  // odd: the centre pixel's ray is exactly the view direction
    scene.ambient = Color(1);
    // ks = 0: N.L is 0 only up to the rounding of the hit points (see O7).
    scene.materials = {phong_material(0.125, 0.5, 0, 10.5)};
    scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
    scene.lights = {point_light(Vec3(0), Color(1))};
    scene.camera = Camera{Vec3(0, 1, 0), Vec3(0), Vec3(0, 0, -1), 60};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    EXPECT_EQ(img.stats.nan_count, 0u);
    // The light lies in the plane: N.L = 0 at every other point, so ambient only.
    for (int y = 0; y < scene.height; ++y) {
      for (int x = 0; x < scene.width; ++x) {
        ASSERT_LE(max_channel(glm::abs(img.at(x, y) - Color(0.125))), 1e-12) << x << ", " << y;
      }
    }
    // shade() with the light exactly at the hit point.
    const Ray ray = make_ray(Vec3(0, 1, 0), Vec3(0, -1, 0));
    const std::optional<Hit> hit = intersect(prepared, ray);
    ASSERT_TRUE(hit);
    ASSERT_EQ(hit->p, Vec3(0));
    RayCounts counts;
    ProbeNode probe;
    const Terms t = shade(prepared, TraceLimits{0, 0}, ray, *hit, 0, 1.0, counts, &probe);
    EXPECT_TRUE(terms_are_finite(t));
  }
  {
    SCOPED_TRACE("light at a sphere's hit point");
    Scene scene;
    scene.width = 65;
    scene.height = 49;
    scene.materials = {phong_material(0.125, 0.5, 0.5, 0.5)};
    scene.spheres = {Sphere{Vec3(0, -1, 0), 1, 0}};
    scene.lights = {point_light(Vec3(0), Color(1)), point_light(Vec3(0, 2, 0), Color(0.5))};
    scene.camera = Camera{Vec3(0, 1, 0), Vec3(0), Vec3(0, 0, -1), 60};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    EXPECT_EQ(img.stats.nan_count, 0u);
  }
  // The camera on a plane or a sphere, looking along, into and away from it, with mirrors and
  // glass so that secondary rays start there too.
  Scene base;
  base.width = 48;
  base.height = 36;
  Material glass = phong_material(0.1, 0.3, 0.5, 10.5);
  glass.kr = Color(0.3);
  glass.kt = Color(0.6);
  glass.fresnel = true;
  base.materials = {glass, phong_material(0.1, 0.6, 0.3, 0)};
  base.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 1}};
  base.spheres = {Sphere{Vec3(0, 1, 0), 1, 0}};
  base.lights = {point_light(Vec3(2, 3, 1), Color(1)), directional_light(Vec3(0, -1, 0.3), Color(0.4))};
  base.max_depth = 5;
  base.min_weight = 0;
  const Vec3 camera_spots[] = {Vec3(0.5, 0, 3), Vec3(0, 2, 0), Vec3(1, 1, 0), Vec3(0, 0, 0)};
  const Vec3 targets[] = {Vec3(0.5, 0, -3), Vec3(0, 1, 0), Vec3(3, 3, 3), Vec3(0, -1, 0.5), Vec3(2, 0.5, 0)};
  for (const Vec3& pos : camera_spots) {
    for (const Vec3& target : targets) {
      if (glm::length(glm::cross(glm::normalize(target - pos), Vec3(0, 1, 0))) < 0.1) continue;
      SCOPED_TRACE("camera at " + str(pos) + " looking at " + str(target));
      Scene scene = base;
      scene.camera = Camera{pos, target, Vec3(0, 1, 0), 90};
      const PreparedScene prepared(scene);
      const Rendered img = render_image(prepared);
      EXPECT_EQ(img.stats.nan_count, 0u);
    }
  }
}

// Cosines a rounding step outside [-1, 1] are clamped: Fresnel at cos_i = 1 + ulp is the
// normal-incidence value; R.V = 1 + ulp never makes the specular factor exceed 1; glass hit
// head-on with such a cosine shades to finite values.
TEST(HardCases, N4_OutOfRangeCosinesAreClamped) {
  const double above_one = std::nextafter(1.0, 2.0);
  for (const double eta : {1 / 1.33, 1.33, 1 / 1.5, 1.5, 1 / 2.42, 2.42}) {
    SCOPED_TRACE("eta = " + std::to_string(eta));
    const double f = fresnel_exact(above_one, eta);
    const double normal = (1 - eta) * (1 - eta) / ((1 + eta) * (1 + eta));
    EXPECT_NEAR(f, normal, 1e-12);
    const double f_grazing = fresnel_exact(-1e-17, eta);
    EXPECT_TRUE(f_grazing >= 0 && f_grazing <= 1) << f_grazing;
  }
  // Unit vectors whose rounded self-dot product exceeds 1.
  const std::uint64_t seed = 1024;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  int found = 0;
  for (int i = 0; i < 200000 && found < 40; ++i) {
    const Vec3 a = random_unit(rng);
    if (!(glm::dot(a, a) > 1)) continue;
    ++found;
    SCOPED_TRACE("normal " + str(a));
    // Camera and light on the normal: R = V up to rounding, so R.V may round above 1.
    Scene scene;
    Material glass = phong_material(0.1, 0.5, 0.5, 1e4);
    glass.kt = Color(0.5);
    glass.kr = Color(0.25);
    glass.fresnel = (found % 2) == 0;
    scene.materials = {glass};
    scene.planes = {Plane{Vec3(0), a, 0}};
    scene.lights = {point_light(a, Color(1))};
    scene.max_depth = 1;
    scene.min_weight = 0;
    const PreparedScene prepared(scene);
    const Plane& plane = prepared.scene().planes[0];  // its normal normalised, as the renderer takes it
    const Ray ray = make_ray(plane.normal, -plane.normal);
    const std::optional<Hit> hit = intersect(prepared, ray);
    ASSERT_TRUE(hit);
    RayCounts counts;
    ProbeNode probe;
    const Terms t = shade(prepared, TraceLimits{1, 0}, ray, *hit, 0, 1.0, counts, &probe);
    EXPECT_TRUE(terms_are_finite(t));
    ASSERT_EQ(probe.lights.size(), 1u);
    EXPECT_LE(probe.lights[0].spec_factor, 1.0);
    EXPECT_LE(t.specular.x, 0.5);
    ASSERT_NE(probe.refraction, nullptr);
    EXPECT_NEAR(glm::length(probe.refraction->dir), 1.0, 1e-15);
    // The same with the ray leaving the glass (from below the plane).
    const Ray up = make_ray(-plane.normal, plane.normal);
    const std::optional<Hit> hit_up = intersect(prepared, up);
    ASSERT_TRUE(hit_up);
    const Terms t_up = shade(prepared, TraceLimits{1, 0}, up, *hit_up, 0, 1.0, counts);
    EXPECT_TRUE(terms_are_finite(t_up));
  }
  EXPECT_GT(found, 0);
}

namespace {

// A random scene within the valid ranges of docs/scene-format.md, including the awkward values: n in
// {0, 0.5, 1, 10, 10.5, 1e4}, ior in (0.1, 3), Fresnel, lights and the camera on surfaces.
PreparedScene random_scene(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0, 1);
  auto range = [&](double a, double b) { return a + (b - a) * uni(rng); };
  auto coin = [&](double p) { return uni(rng) < p; };
  auto pick = [&](int n) { return std::min(n - 1, static_cast<int>(uni(rng) * n)); };
  auto colour = [&](double hi) { return Color(range(0, hi), range(0, hi), range(0, hi)); };
  auto point = [&](double extent) { return Vec3(range(-extent, extent), range(-extent, extent), range(-extent, extent)); };

  Scene s;
  s.width = 24;
  s.height = 18;
  s.ambient = colour(1);
  s.background = colour(1);
  s.max_depth = pick(6);
  const double weights[] = {0, 1e-4, 1e-2};
  s.min_weight = weights[pick(3)];
  if (s.max_depth > 3 && s.min_weight == 0) s.min_weight = 1e-3;
  s.specular_model = coin(0.5) ? SpecularModel::kPhong : SpecularModel::kBlinn;

  const double exponents[] = {0, 0.5, 1, 10, 10.5, 1e4};
  const int material_count = 1 + pick(4);
  for (int i = 0; i < material_count; ++i) {
    Material m;
    m.ka = colour(1);
    m.kd = colour(1);
    m.ks = colour(1);
    m.n = coin(0.7) ? exponents[pick(6)] : range(0, 300);
    m.kr = coin(0.5) ? colour(1) : Color(0);
    m.kt = coin(0.5) ? colour(1) : Color(0);
    m.ior = range(0.1, 3);
    if (m.ior <= 0.1) m.ior = 0.2;
    m.fresnel = coin(0.5);
    s.materials.push_back(m);
  }
  for (int i = pick(5); i > 0; --i) s.spheres.push_back(Sphere{point(4), range(0.05, 2), pick(material_count)});
  for (int i = pick(3); i > 0; --i) s.planes.push_back(Plane{point(4), random_unit(rng), pick(material_count)});
  for (int i = pick(5); i > 0; --i) {
    Triangle tri;
    do {
      tri.v0 = point(4);
      tri.v1 = point(4);
      tri.v2 = point(4);
    } while (glm::length(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0)) < 1e-2);
    tri.material = pick(material_count);
    s.triangles.push_back(tri);
  }
  if (s.spheres.empty() && s.planes.empty() && s.triangles.empty()) {
    s.spheres.push_back(Sphere{Vec3(0), 1, 0});
  }
  // A point on some surface (for lights and cameras placed on one).
  auto surface_point = [&]() {
    if (!s.spheres.empty() && coin(0.6)) {
      const Sphere& sp = s.spheres[static_cast<std::size_t>(pick(static_cast<int>(s.spheres.size())))];
      return sp.center + sp.radius * random_unit(rng);
    }
    if (!s.planes.empty()) {
      const Plane& pl = s.planes[static_cast<std::size_t>(pick(static_cast<int>(s.planes.size())))];
      const Vec3 q = point(3);
      return q - glm::dot(q - pl.point, pl.normal) * pl.normal;
    }
    return point(4);
  };
  for (int i = 1 + pick(4); i > 0; --i) {
    Light l;
    if (coin(0.7)) {
      l.type = LightType::kPoint;
      l.position = coin(0.3) ? surface_point() : point(6);
    } else {
      l.type = LightType::kDirectional;
      l.direction = random_unit(rng);
    }
    l.intensity = colour(2);
    l.enabled = coin(0.9);
    s.lights.push_back(l);
  }
  for (;;) {
    const double where = uni(rng);
    if (where < 0.2) {
      s.camera.position = surface_point();
    } else if (where < 0.3 && !s.spheres.empty()) {
      s.camera.position = s.spheres[0].center;
    } else {
      s.camera.position = point(6);
    }
    s.camera.look_at = point(3);
    s.camera.up = random_unit(rng);
    s.camera.fov_y_deg = range(10, 150);
    const Vec3 view = s.camera.look_at - s.camera.position;
    if (glm::length(view) < 1e-3) continue;
    if (glm::length(glm::cross(glm::normalize(view), s.camera.up)) < 0.2) continue;
    break;
  }
  return PreparedScene(std::move(s));
}

}  // namespace

// 200 seeded random scenes: the per-pass NaN/Inf counter stays 0 for the full image (2 samples)
// and, in every fourth scene, each term and debug image. The counter itself is live: a NaN
// light or an infinite background is counted.
TEST(HardCases, N5_NoNaNOrInfInRandomScenes) {
  {
    SCOPED_TRACE("the counter counts");
    Scene scene;
    scene.width = 16;
    scene.height = 12;
    scene.materials = {phong_material(0.1, 0.5, 0.5, 10)};
    scene.spheres = {Sphere{Vec3(0), 1, 0}};
    scene.lights = {point_light(Vec3(0, 0, 5), Color(std::numeric_limits<double>::quiet_NaN()))};
    scene.camera = Camera{Vec3(0, 0, 5), Vec3(0), Vec3(0, 1, 0), 10};  // the sphere fills the view
    const PreparedScene prepared(scene);
    EXPECT_EQ(render_image(prepared).stats.nan_count, 16u * 12u);
    scene.lights.clear();
    scene.camera.fov_y_deg = 90;
    scene.background = Color(std::numeric_limits<double>::infinity());
    const Rendered img = render_image(PreparedScene(scene));
    EXPECT_GT(img.stats.nan_count, 0u);
    EXPECT_LT(img.stats.nan_count, 16u * 12u);
  }
  const Term terms[] = {Term::kAmbient, Term::kDiffuse,    Term::kSpecular, Term::kReflection,
                        Term::kRefraction, Term::kNormal, Term::kDepth};
  for (std::uint64_t seed = 5000; seed < 5200; ++seed) {
    SCOPED_TRACE(seed_trace(seed));
    std::mt19937_64 rng(seed);
    const PreparedScene scene = random_scene(rng);
    const Rendered full = render_image(scene, Term::kFull, 2);
    ASSERT_EQ(full.stats.nan_count, 0u);
    if (seed % 4 == 0) {
      for (const Term term : terms) {
        SCOPED_TRACE(std::string(term_name(term)));
        ASSERT_EQ(render_image(scene, term).stats.nan_count, 0u);
      }
    }
  }
}

// =============================================================================================
// T. Planes and triangles

// Rays parallel to a plane (d.n = 0, +-1e-30, +-1e-8), from above, below and in the plane: no
// NaN, and the answer is right (t = -h / (d.n) when that is ahead, else a miss). A camera 1
// above a plane looking at its horizon: every pixel below the horizon hits (depth out to 2e4,
// no gap) at the reference distance.
TEST(HardCases, T1_RaysParallelToAPlane) {
  const std::uint64_t seed = 2001;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  Scene scene;
  scene.materials = {phong_material(0.1, 0.5, 0.5, 10.5)};
  scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 0}};
  scene.lights = {point_light(Vec3(1, 1, 1), Color(1))};
  const PreparedScene prepared(scene);
  const TraceLimits limits{2, 0};
  for (const double height : {1.0, 0.0, -1.0, 1e-300}) {
    for (const double dn : {0.0, 1e-30, -1e-30, 1e-8, -1e-8, 1e-300, -1e-300}) {
      SCOPED_TRACE("height " + std::to_string(height) + ", d.n = " + std::to_string(dn));
      for (int i = 0; i < 20; ++i) {
        const double phi = 2 * kPi * uni(rng);
        const Vec3 dir(std::cos(phi), dn, std::sin(phi));  // unit to within rounding
        const Vec3 origin(0.25 * i - 2, height, 0.5 * i);
        const Ray ray = make_ray(origin, dir);
        const std::optional<double> t = intersect_plane(prepared.scene().planes[0], ray);
        const bool expect_hit = ((height > 0 && dn < 0) || (height < 0 && dn > 0)) && std::isfinite(-height / dn);
        ASSERT_EQ(t.has_value(), expect_hit);
        if (t) {
          ASSERT_TRUE(std::isfinite(*t));
          EXPECT_DOUBLE_EQ(*t, -height / dn);
        }
        const std::optional<Hit> hit = intersect(prepared, ray);
        if (hit) { ASSERT_TRUE(hit_is_finite(*hit)); }
        RayCounts counts;
        ASSERT_TRUE(all_finite(trace(prepared, limits, ray, 0, 1.0, counts)));
      }
    }
  }
  // The horizon: fov 1 degree, so the rows next to it hit 2.3e4 away.
  struct HorizonCase {
    Vec3 p0, n;
  };
  const HorizonCase cases[] = {{Vec3(0), Vec3(0, 1, 0)}, {Vec3(1e3, 1e3, 1e3), glm::normalize(Vec3(1, 2, 3))}};
  for (const HorizonCase& hc : cases) {
    SCOPED_TRACE("plane through " + str(hc.p0));
    Scene s2 = scene;
    s2.planes = {Plane{hc.p0, hc.n, 0}};
    s2.width = 32;
    s2.height = 200;
    Vec3 t1, t2;
    complete_frame(hc.n, t1, t2);
    s2.camera = Camera{hc.p0 + hc.n, hc.p0 + hc.n + t1, hc.n, 1};
    const PreparedScene s2_prepared(s2);
    const Rendered depth = render_image(s2_prepared, Term::kDepth);
    const RefCamera cam = ref_camera(s2.camera, s2.width, s2.height);
    int gaps = 0, below = 0;
    LD farthest = 0;
    const ImageCheck check = check_image(depth, 1e-6L, 1e-12L, [&](int x, int y, LV& out) {
      const LV d = ref_pixel_dir(cam, x, y);
      const RefHit h = ref_intersect(s2_prepared.scene(), cam.origin, d);
      out = h.hit ? LV{h.t, h.t, h.t} : LV{};
      if (h.hit) {
        ++below;
        farthest = std::max(farthest, h.t);
        if (depth.at(x, y).x == 0) ++gaps;
      }
      return true;
    });
    EXPECT_EQ(below, s2.width * s2.height / 2);
    EXPECT_GT(static_cast<double>(farthest), 1e4);
    EXPECT_EQ(gaps, 0);
    EXPECT_EQ(check.mismatched, 0) << check.first_bad;
  }
}

// A closed fan of 7 triangles around a shared vertex, and a closed octahedron: rays through the
// shared edges and the shared vertex never slip through (0 leaks).
TEST(HardCases, T2_WatertightFanAndClosedMesh) {
  const std::uint64_t seed = 2002;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  const Vec3 centres[] = {Vec3(0), Vec3(120.5, -30.25, 47.0), Vec3(1e4, 2e4, -3e4)};
  for (const Vec3& c : centres) {
    SCOPED_TRACE("fan centre " + str(c));
    Scene scene;
    scene.materials = {phong_material(0, 1, 0, 1)};
    const Vec3 n = glm::normalize(Vec3(1, 2, 3));
    Vec3 t1, t2;
    complete_frame(n, t1, t2);
    const int kFan = 7;
    const double radius = 5;
    std::vector<Vec3> rim;
    for (int i = 0; i < kFan; ++i) {
      const double a = 2 * kPi * i / kFan;
      rim.push_back(c + radius * (std::cos(a) * t1 + std::sin(a) * t2));
    }
    for (int i = 0; i < kFan; ++i) {
      Triangle tri;
      tri.v0 = c;
      tri.v1 = rim[static_cast<std::size_t>(i)];
      tri.v2 = rim[static_cast<std::size_t>((i + 1) % kFan)];
      scene.triangles.push_back(tri);
    }
    int leaks = 0, rays = 0;
    std::string example;
    for (int i = 0; i < 8000; ++i) {
      // Origin on either side of the fan, 0.5..20 away.
      Vec3 origin = c + 20.0 * Vec3(2 * uni(rng) - 1, 2 * uni(rng) - 1, 2 * uni(rng) - 1);
      const double h = glm::dot(origin - c, n);
      if (std::abs(h) < 0.5) origin += (h < 0 ? -1.0 : 1.0) * 0.5 * n;
      Vec3 target = c;  // the shared vertex, one ray in 8
      if (i % 8 != 0) {
        const int edge = i % kFan;
        target = c + (0.02 + 0.96 * uni(rng)) * (rim[static_cast<std::size_t>(edge)] - c);
      }
      const Vec3 dir = glm::normalize(target - origin);
      ++rays;
      if (!intersect_all(scene, make_ray(origin, dir))) {
        ++leaks;
        if (example.empty()) example = "origin " + str(origin) + " towards " + str(target);
      }
    }
    EXPECT_EQ(leaks, 0) << "of " << rays << " rays; first: " << example;
  }
  // Closed octahedron, rays from inside towards its vertices, edge midpoints and anywhere.
  for (const Vec3& c : centres) {
    SCOPED_TRACE("octahedron centre " + str(c));
    Scene scene;
    scene.materials = {phong_material(0, 1, 0, 1)};
    const double a = 3;
    const Vec3 vx[] = {c + Vec3(a, 0, 0), c + Vec3(-a, 0, 0), c + Vec3(0, a, 0),
                       c + Vec3(0, -a, 0), c + Vec3(0, 0, a), c + Vec3(0, 0, -a)};
    const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (const auto& f : faces) {
      Triangle tri;
      tri.v0 = vx[f[0]];
      tri.v1 = vx[f[1]];
      tri.v2 = vx[f[2]];
      scene.triangles.push_back(tri);
    }
    std::vector<Vec3> targets(std::begin(vx), std::end(vx));
    for (const auto& f : faces) {
      for (int e = 0; e < 3; ++e) targets.push_back(0.5 * (vx[f[e]] + vx[f[(e + 1) % 3]]));
    }
    int leaks = 0;
    std::string example;
    for (int i = 0; i < 6000; ++i) {
      const Vec3 origin = c + 0.5 * Vec3(2 * uni(rng) - 1, 2 * uni(rng) - 1, 2 * uni(rng) - 1);
      Vec3 dir;
      if (i % 2 == 0) {
        dir = glm::normalize(targets[static_cast<std::size_t>(i / 2) % targets.size()] - origin);
      } else {
        dir = random_unit(rng);
      }
      if (!intersect_all(scene, make_ray(origin, dir))) {
        ++leaks;
        if (example.empty()) example = "origin " + str(origin) + " direction " + str(dir);
      }
    }
    EXPECT_EQ(leaks, 0) << example;
  }
}

// Sliver triangles (height 1e-9..1e-6 of their length): rays aimed clearly inside hit, rays
// aimed clearly outside miss, no NaN barycentrics, finite unit normals.
TEST(HardCases, T4_SliverTrianglesHaveNoFalseHitsAndNoNaN) {
  const std::uint64_t seed = 2004;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  for (const double height : {1e-6, 1e-8, 1e-9}) {
    for (const Vec3& shift : {Vec3(0), Vec3(3.5, -1.25, 2)}) {
      SCOPED_TRACE("sliver height " + std::to_string(height) + ", at " + str(shift));
      Scene scene;
      scene.materials = {phong_material(0.1, 0.5, 0.5, 10)};
      Triangle tri;
      tri.v0 = shift + Vec3(0, 0, 0);
      tri.v1 = shift + Vec3(1, 0, 0);
      tri.v2 = shift + Vec3(0.5, height, 0);
      scene.triangles = {tri};
      scene.lights = {point_light(shift + Vec3(0.5, 1, 1), Color(1))};
      const PreparedScene prepared(scene);
      int wrong = 0;
      std::string example;
      for (int i = 0; i < 4000; ++i) {
        const Vec3 origin = shift + Vec3(2 * uni(rng) - 0.5, 2 * uni(rng) - 1, 0.2 + 2 * uni(rng)) *
                                        (uni(rng) < 0.5 ? 1.0 : -1.0);
        // Barycentric target: inside (all weights >= 0.05) or outside (one weight <= -0.05).
        double w1 = uni(rng), w2 = uni(rng);
        const bool inside = i % 2 == 0;
        if (inside) {
          w1 = 0.05 + 0.45 * w1;
          w2 = 0.05 + 0.45 * w2;
        } else {
          w2 = -0.05 - w2;
        }
        const Vec3 target = tri.v0 + w1 * (tri.v1 - tri.v0) + w2 * (tri.v2 - tri.v0);
        const Vec3 dir = glm::normalize(target - origin);
        double b1 = 0, b2 = 0;
        const std::optional<double> t = intersect_triangle(tri, make_ray(origin, dir), &b1, &b2);
        if (t.has_value() != inside) {
          ++wrong;
          if (example.empty()) example = std::string(inside ? "missed" : "false hit") + " towards " + str(target);
        }
        if (t) {
          ASSERT_TRUE(std::isfinite(*t) && std::isfinite(b1) && std::isfinite(b2));
          const std::optional<Hit> hit = intersect(prepared, make_ray(origin, dir));
          ASSERT_TRUE(hit);
          ASSERT_TRUE(hit_is_finite(*hit));
          EXPECT_NEAR(glm::length(hit->ng), 1.0, 1e-12);
        }
      }
      EXPECT_EQ(wrong, 0) << example;
    }
  }
}

// Zero-area triangles (collinear or repeated vertices, as OBJ files often contain) are never
// hit and never produce NaN. The scene-file loader rejects them, but meshes will not all be
// clean and in-memory scenes can hold them.
TEST(HardCases, T4_ZeroAreaTrianglesAreNeverHit) {
  const std::uint64_t seed = 2044;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  const Triangle degenerate[] = {
      make_triangle(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2)),  // collinear, exactly
      make_triangle(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0)),  // collinear along an axis
      make_triangle(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(4, 5, 6)),  // two vertices the same
      make_triangle(Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)),  // a point
  };
  for (const Triangle& tri : degenerate) {
    SCOPED_TRACE("triangle " + str(tri.v0) + " " + str(tri.v1) + " " + str(tri.v2));
    Scene scene;
    scene.width = 32;
    scene.height = 24;
    scene.materials = {phong_material(0.1, 0.5, 0.5, 10)};
    scene.triangles = {tri};
    scene.lights = {point_light(Vec3(3, 3, 3), Color(1))};
    const PreparedScene prepared(scene);
    int hits = 0, nan_hits = 0;
    std::string example;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 origin = 5.0 * random_unit(rng);
      const double s = uni(rng);
      const Vec3 target = tri.v0 + s * (tri.v1 - tri.v0) + (1 - s) * uni(rng) * (tri.v2 - tri.v0);
      const Vec3 to = target - origin;
      if (glm::length(to) == 0) continue;
      const Ray ray = make_ray(origin, glm::normalize(to));
      double b1 = 0, b2 = 0;
      if (auto t = intersect_triangle(tri, ray, &b1, &b2)) {
        ++hits;
        if (example.empty()) {
          example = "hit at t = " + std::to_string(*t) + " from " + str(origin) + " towards " + str(target);
        }
      }
      if (auto hit = intersect(prepared, ray); hit && !hit_is_finite(*hit)) ++nan_hits;
    }
    EXPECT_EQ(hits, 0) << example;
    EXPECT_EQ(nan_hits, 0) << "hits with a NaN normal";
    // Looking straight at it.
    scene.camera = Camera{tri.v0 + Vec3(0.3, -0.2, 4), 0.5 * (tri.v0 + tri.v2), Vec3(0, 1, 0), 30};
    const PreparedScene looking(scene);
    EXPECT_EQ(render_image(looking).stats.nan_count, 0u);
  }
}

// =============================================================================================
// R. Refraction and Fresnel

namespace {

// A ray from inside a glass sphere (ior 1.5, no Fresnel) meeting the surface at `theta` from the
// normal: the probed ray tree (its root is the hit on the way out).
struct InsideRay {
  Vec3 c, origin, dir;
  double r = 1;
};
InsideRay inside_ray(const Vec3& c, double r, double theta_rad) {
  InsideRay ir;
  ir.c = c;
  ir.r = r;
  ir.dir = glm::normalize(Vec3(0.2, -0.3, 0.9));
  Vec3 u, v;
  complete_frame(ir.dir, u, v);
  ir.origin = c + r * std::sin(theta_rad) * u;
  return ir;
}

}  // namespace

// Inside rays at 41.80 and 41.82 degrees (critical angle 41.8103) and sweeps either side:
// below, Snell's law holds to 1e-6 rad; above, every ray is totally reflected to the mirror
// direction.
TEST(HardCases, R1_CriticalAngleSnellAndTotalInternalReflection) {
  std::vector<double> below, above;
  below.push_back(41.80);
  above.push_back(41.82);
  for (double a = 0; a < 41.8; a += 0.5) below.push_back(a);
  for (double a = 42; a < 90; a += 0.5) above.push_back(a);
  above.push_back(89.99);
  struct Case {
    Vec3 c;
    double r;
  };
  const Case cases[] = {{{0, 0, 0}, 1}, {{10, -20, 30}, 2.5}};
  for (const Case& cs : cases) {
    const PreparedScene scene = bare_glass_sphere(cs.c, cs.r, 1.5, false, 1);
    for (const bool is_above : {false, true}) {
      for (const double theta_deg : is_above ? above : below) {
        SCOPED_TRACE("centre " + str(cs.c) + ", theta " + std::to_string(theta_deg) + " deg");
        const InsideRay ir = inside_ray(cs.c, cs.r, theta_deg * kPi / 180);
        Probed pr;
        probe_ray(scene, make_ray(ir.origin, ir.dir), pr);
        ASSERT_TRUE(pr.root.hit);
        ASSERT_FALSE(pr.root.entering);
        EXPECT_NEAR(pr.root.eta, 1.5, 1e-15);
        ASSERT_NE(pr.root.refraction, nullptr);
        const LV out_dir = to_ld(pr.root.refraction->dir);
        // The reference geometry: exact incidence angle and outward normal at the hit.
        const LV o = to_ld(ir.origin), d = to_ld(ir.dir), c = to_ld(cs.c);
        const LD b = ref_line_distance(c, o, d);
        const LD theta_i = std::asin(b / cs.r);
        const LV p = o + *ref_sphere_t(c, cs.r, o, d) * d;
        const LV n_out = normalized(p - c);
        const LD sin_t = 1.5L * std::sin(theta_i);
        EXPECT_EQ(pr.root.tir, sin_t > 1);
        ASSERT_EQ(is_above, sin_t > 1);
        // The tangential part of the new direction keeps the incoming one's orientation.
        const LV tangential = d - dot(d, n_out) * n_out;
        if (!is_above) {
          const LD theta_t = std::asin(sin_t);
          EXPECT_LE(static_cast<double>(std::abs(angle_between(out_dir, n_out) - theta_t)), 1e-6);
          if (theta_deg > 0) { EXPECT_GT(static_cast<double>(dot(out_dir, tangential)), 0); }
        } else {
          EXPECT_LE(static_cast<double>(std::abs(angle_between(out_dir, -n_out) - theta_i)), 1e-6);
          EXPECT_GT(static_cast<double>(dot(out_dir, tangential)), 0);
        }
      }
    }
  }
}

// Through a glass sphere at b/r = 0..0.99: the total deviation is 2 (theta_i - theta_t) within
// 1e-6 rad (the normal is flipped on the way out).
TEST(HardCases, R3_DeviationThroughASphere) {
  struct Case {
    Vec3 c;
    double r;
  };
  const Case cases[] = {{{0, 0, 0}, 1}, {{100, 200, -50}, 10}};
  const Vec3 w = glm::normalize(Vec3(0.3, -0.5, 0.8));
  Vec3 u, v;
  complete_frame(w, u, v);
  for (const Case& cs : cases) {
    const PreparedScene scene = bare_glass_sphere(cs.c, cs.r, 1.5, false, 2);
    for (int i = 0; i < 100; ++i) {
      const double b_over_r = i / 100.0;
      SCOPED_TRACE("centre " + str(cs.c) + ", b/r = " + std::to_string(b_over_r));
      const Vec3 origin = cs.c - 3 * cs.r * w + b_over_r * cs.r * u;
      Probed pr;
      probe_ray(scene, make_ray(origin, w), pr);
      ASSERT_TRUE(pr.root.hit);
      ASSERT_NE(pr.root.refraction, nullptr);
      ASSERT_TRUE(pr.root.refraction->hit);
      ASSERT_NE(pr.root.refraction->refraction, nullptr);
      const ProbeNode& out = *pr.root.refraction->refraction;
      EXPECT_FALSE(pr.root.refraction->tir);
      const LD b = ref_line_distance(to_ld(cs.c), to_ld(origin), to_ld(w));
      const LD theta_i = std::asin(b / cs.r);
      const LD theta_t = std::asin(std::sin(theta_i) / 1.5L);
      const LD deviation = angle_between(to_ld(w), to_ld(out.dir));
      EXPECT_LE(static_cast<double>(std::abs(deviation - 2 * (theta_i - theta_t))), 1e-6);
    }
  }
}


// Exact Fresnel for n = 1.33, 1.5, 2.42 on both sides: within 1e-6 of the reference, 1 under
// TIR, in [0, 1] at grazing; and the probe's F at a sphere's entry and exit points agrees.
TEST(HardCases, R4_ExactFresnelBothSides) {
  for (const double ior : {1.33, 1.5, 2.42}) {
    for (const bool entering : {true, false}) {
      SCOPED_TRACE("ior " + std::to_string(ior) + (entering ? ", entering" : ", leaving"));
      const LD n1 = entering ? 1.0L : ior;
      const LD n2 = entering ? static_cast<LD>(ior) : 1.0L;
      const double eta = entering ? 1 / ior : ior;
      int wrong = 0, tir = 0;
      std::string example;
      std::vector<double> cosines;
      for (int i = 0; i <= 100000; ++i) cosines.push_back(i / 100000.0);
      if (!entering) {
        // Densely around the critical angle.
        const double cos_c = std::sqrt(1 - 1 / (ior * ior));
        for (int i = -1000; i <= 1000; ++i) cosines.push_back(cos_c * (1 + i * 1e-9));
      }
      for (const double cos_i : cosines) {
        const double f = fresnel_exact(cos_i, eta);
        LD sin_t2 = 0;
        const LD ref = ref_fresnel(cos_i, n1, n2, &sin_t2);
        // Under TIR (clear of the boundary by more than rounding) F must be exactly 1.
        const bool clear_tir = sin_t2 > 1 + 1e-12L;
        if (clear_tir) ++tir;
        const bool in_range = f >= 0 && f <= 1;
        if (!in_range || std::abs(f - ref) > 1e-6L || (clear_tir && f != 1)) {
          ++wrong;
          if (example.empty()) {
            example = "cos_i " + std::to_string(cos_i) + ": F = " + std::to_string(f) + ", expected " +
                      std::to_string(static_cast<double>(ref));
          }
        }
      }
      EXPECT_EQ(wrong, 0) << example;
      EXPECT_EQ(fresnel_exact(0, eta), 1.0) << "grazing";
      if (!entering) { EXPECT_GT(tir, 0); }
    }
  }
  // Through the renderer: F at the entry and at the exit of a sphere.
  const Vec3 w = glm::normalize(Vec3(0.3, -0.5, 0.8));
  Vec3 u, v;
  complete_frame(w, u, v);
  for (const double ior : {1.33, 1.5, 2.42}) {
    const PreparedScene scene = bare_glass_sphere(Vec3(1, 2, 3), 2, ior, true, 2);
    for (const double b_over_r : {0.0, 0.3, 0.6, 0.9, 0.99, 0.999}) {
      SCOPED_TRACE("ior " + std::to_string(ior) + ", b/r = " + std::to_string(b_over_r));
      const Vec3 origin = scene.scene().spheres[0].center - 6.0 * w + b_over_r * 2.0 * u;
      Probed pr;
      probe_ray(scene, make_ray(origin, w), pr);
      ASSERT_TRUE(pr.root.hit);
      const LD b = ref_line_distance(to_ld(scene.scene().spheres[0].center), to_ld(origin), to_ld(w));
      const LD sin_i = b / 2;
      const LD cos_i = std::sqrt(1 - sin_i * sin_i);
      EXPECT_NEAR(pr.root.fresnel, static_cast<double>(ref_fresnel(cos_i, 1, ior)), 1e-6);
      ASSERT_NE(pr.root.refraction, nullptr);
      const ProbeNode& inside = *pr.root.refraction;
      ASSERT_TRUE(inside.hit);
      const LD sin_t = sin_i / ior;
      const LD cos_t = std::sqrt(1 - sin_t * sin_t);
      EXPECT_NEAR(inside.fresnel, static_cast<double>(ref_fresnel(cos_t, ior, 1)), 1e-6);
    }
  }
}

// =============================================================================================
// L. Exact answers

// Camera inside a sphere of radius 2 with a point light at its centre, kd 0.5, I 1, ka 0:
// N.L = 1 everywhere, so every pixel is 0.5 (1e-6 relative).
TEST(HardCases, L1_InsideSphereWithLightAtCentre) {
  const Vec3 centres[] = {Vec3(0), Vec3(1, 2, 3), Vec3(1e5, -1e5, 1e5)};
  const Vec3 eyes[] = {Vec3(0), Vec3(0.3, -0.2, 0.5), Vec3(-1.5, 0.9, 0.2)};
  for (const Vec3& c : centres) {
    for (const Vec3& eye : eyes) {
      SCOPED_TRACE("centre " + str(c) + ", eye at centre + " + str(eye));
      Scene scene;
      scene.width = 64;
      scene.height = 48;
      scene.materials = {phong_material(0, 0.5, 0, 32)};
      scene.spheres = {Sphere{c, 2, 0}};
      scene.lights = {point_light(c, Color(1))};
      scene.camera = Camera{c + eye, c + Vec3(1, 0.5, -1), Vec3(0, 1, 0), 120};
      const PreparedScene prepared(scene);
      const Rendered img = render_image(prepared);
      EXPECT_EQ(img.stats.nan_count, 0u);
      const ImageCheck check = check_image(img, 1e-6L, 1e-6L, [](int, int, LV& out) {
        out = LV{0.5L, 0.5L, 0.5L};
        return true;
      });
      EXPECT_EQ(check.mismatched, 0) << check.first_bad;
    }
  }
}

// One light of intensity I against 4 coincident lights of I/4 (point and directional, with
// shadows, mirrors and glass): per-pixel relative difference <= 1e-6.
TEST(HardCases, L2_OneLightEqualsFourQuarterLights) {
  Scene scene;
  scene.width = 120;
  scene.height = 90;
  scene.ambient = Color(0.5);
  scene.background = Color(0.02, 0.03, 0.05);
  scene.max_depth = 4;
  Material red = phong_material(0.05, 0.6, 0.4, 20);
  red.kd = Color(0.7, 0.3, 0.2);
  Material mirror = phong_material(0, 0.1, 0.5, 200);
  mirror.kr = Color(0.6);
  Material glass = phong_material(0, 0, 0.5, 300);
  glass.kt = Color(0.8);
  glass.fresnel = true;
  Material floor = phong_material(0.05, 0.5, 0.2, 10.5);
  scene.materials = {red, mirror, glass, floor};
  scene.spheres = {Sphere{Vec3(0, 1, 0), 1, 0}, Sphere{Vec3(1.8, 0.6, 0.8), 0.6, 1}, Sphere{Vec3(-1.5, 0.7, 1), 0.7, 2}};
  scene.planes = {Plane{Vec3(0), Vec3(0, 1, 0), 3}};
  Triangle tri;
  tri.v0 = Vec3(-2, 0, -2);
  tri.v1 = Vec3(2, 0, -2.5);
  tri.v2 = Vec3(0, 2.5, -2.2);
  tri.material = 0;
  scene.triangles = {tri};
  scene.camera = Camera{Vec3(0, 1.8, 6), Vec3(0, 0.8, 0), Vec3(0, 1, 0), 45};
  const Light lights[] = {point_light(Vec3(2, 5, 3), Color(0.9, 0.6, 0.3)),
                          directional_light(Vec3(-1, -1, -0.5), Color(0.5, 0.7, 0.25))};
  for (const Light& light : lights) {
    SCOPED_TRACE(light.type == LightType::kPoint ? "point light" : "directional light");
    Scene one = scene;
    one.lights = {light};
    const PreparedScene one_prepared(one);
    Scene four = scene;
    Light quarter = light;
    quarter.intensity = light.intensity / 4.0;
    four.lights = {quarter, quarter, quarter, quarter};
    const PreparedScene four_prepared(four);
    const Rendered a = render_image(one_prepared);
    const Rendered b = render_image(four_prepared);
    int differing = 0;
    double worst = 0;
    for (std::size_t i = 0; i < a.px.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const double x = a.px[i][c], y = b.px[i][c];
        const double scale = std::max(std::abs(x), std::abs(y));
        const double rel = scale > 0 ? std::abs(x - y) / scale : 0;
        worst = std::max(worst, rel);
        if (!(rel <= 1e-6)) ++differing;
      }
    }
    EXPECT_EQ(differing, 0) << "worst relative difference " << worst;
    EXPECT_EQ(b.stats.rays.shadow, 4 * a.stats.rays.shadow);
  }
}

// Shadow rays are cast only for lights on the lit side (N.L > 0): a sphere lit from several
// sides casts exactly as many as the reference counts (fewer than lights x hits), and the image
// equals an independent per-pixel Phong evaluation (a lone convex sphere shadows nothing).
TEST(HardCases, L3_ShadowRaysOnlyForLitSideLights) {
  Scene scene;
  scene.width = 96;
  scene.height = 96;
  scene.ambient = Color(1);
  scene.background = Color(0.1, 0.2, 0.3);
  scene.max_depth = 0;
  Material m = phong_material(0.1, 0.6, 0.4, 16);
  m.kd = Color(0.6, 0.5, 0.4);
  scene.materials = {m};
  scene.spheres = {Sphere{Vec3(0), 1, 0}};
  scene.lights = {point_light(Vec3(3, 0, 0), Color(0.5)), point_light(Vec3(-3, 1, 0), Color(0.3, 0.4, 0.5)),
                  point_light(Vec3(0, 3, -2), Color(0.6)), point_light(Vec3(0.5, -0.5, 5), Color(0.2)),
                  directional_light(Vec3(0, 0, 1), Color(1))};  // from behind: never on the lit side
  scene.camera = Camera{Vec3(0, 0, 4), Vec3(0), Vec3(0, 1, 0), 40};
  const PreparedScene prepared(scene);
  const Rendered img = render_image(prepared);
  const RefCamera cam = ref_camera(scene.camera, scene.width, scene.height);
  std::uint64_t expected_shadow = 0, hits = 0, ambiguous = 0;
  for (int y = 0; y < scene.height; ++y) {
    for (int x = 0; x < scene.width; ++x) {
      const LV d = ref_pixel_dir(cam, x, y);
      const RefHit h = ref_intersect(prepared.scene(), cam.origin, d);
      if (!h.hit) continue;
      ++hits;
      const RefLocal local = ref_local(prepared.scene(), h, d);
      expected_shadow += static_cast<std::uint64_t>(local.lit_lights);
      if (local.min_abs_n_dot_l < 1e-9L) ++ambiguous;
    }
  }
  const std::uint64_t lights = scene.lights.size();
  EXPECT_GT(hits, 1000u);
  EXPECT_LT(img.stats.rays.shadow, lights * hits);
  EXPECT_LE(img.stats.rays.shadow, expected_shadow + ambiguous);
  EXPECT_GE(img.stats.rays.shadow + ambiguous, expected_shadow);
  EXPECT_EQ(img.stats.rays.primary, static_cast<std::uint64_t>(scene.width * scene.height));
  const ImageCheck check = check_image(img, 1e-6L, 1e-9L, local_reference(prepared.scene()));
  EXPECT_EQ(check.mismatched, 0) << check.first_bad;
}

// =============================================================================================
// Remaining cases of docs/accuracy.md: S2 S3 S7 O5 R2 R5 R6 T3 T5 L4.

// A unit sphere at D = 1e4 (and 1e5, 1e6) filling a disk of 200 px, 1 spp, seen from the origin
// (the depth image, 0 on a miss): no isolated miss pixel inside the disk; every pixel whose
// centre ray passes clearly inside (1e-9 of r) or outside the silhouette agrees with the long
// double reference, and inside pixels have the reference depth to 1e-6.
TEST(HardCases, S2_DistantSphereSilhouetteHasNoHoles) {
  const Vec3 axes[] = {{0, 0, 1}, {0.48, 0.6, 0.64}};
  for (const Vec3& axis : axes) {
    for (const double dist : {1e4, 1e5, 1e6}) {
      SCOPED_TRACE("axis " + str(axis) + ", D = " + std::to_string(dist));
      Scene scene;
      scene.width = 240;
      scene.height = 240;
      scene.materials = {phong_material(0.1, 0.5, 0.5, 10)};
      scene.spheres = {Sphere{dist * axis, 1.0, 0}};
      scene.lights = {point_light(Vec3(0, 1, 0), Color(1))};
      // The sphere's angular radius asin(1 / D) spans 100 of the 240 rows.
      const double h = std::tan(std::asin(1 / dist)) * scene.height / 200.0;
      scene.camera = Camera{Vec3(0), dist * axis, Vec3(0, 1, 0), 2 * std::atan(h) * 180 / kPi};
      const PreparedScene prepared(scene);
      const Rendered depth = render_image(prepared, Term::kDepth);
      EXPECT_EQ(depth.stats.nan_count, 0u);
      const RefCamera cam = ref_camera(scene.camera, scene.width, scene.height);
      auto hits = [&](int x, int y) { return depth.at(x, y).x > 0; };
      int inside = 0, isolated = 0, wrong = 0, bad_depth = 0;
      std::string example;
      for (int y = 0; y < scene.height; ++y) {
        for (int x = 0; x < scene.width; ++x) {
          const LV d = ref_pixel_dir(cam, x, y);
          const LD miss = ref_line_distance(to_ld(scene.spheres[0].center), cam.origin, d);
          if (miss < 1) ++inside;
          if (x > 0 && y > 0 && x + 1 < scene.width && y + 1 < scene.height && !hits(x, y) &&
              hits(x - 1, y) && hits(x + 1, y) && hits(x, y - 1) && hits(x, y + 1)) {
            ++isolated;
            if (example.empty()) example = "isolated miss at (" + std::to_string(x) + ", " + std::to_string(y) + ")";
          }
          if (std::abs(miss - 1) < 1e-9L) continue;  // on the silhouette: either answer is right
          if (hits(x, y) != (miss < 1)) {
            ++wrong;
            if (example.empty()) {
              example = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") " +
                        (hits(x, y) ? "hits" : "misses") + ", line distance " +
                        std::to_string(static_cast<double>(miss));
            }
          } else if (miss < 1) {
            const LD t_ref = *ref_sphere_t(to_ld(scene.spheres[0].center), 1, cam.origin, d);
            if (!(std::abs(depth.at(x, y).x - t_ref) <= 1e-6L * t_ref)) ++bad_depth;
          }
        }
      }
      // pi 100^2 pixels, give or take the silhouette's rows.
      EXPECT_GT(inside, 30000);
      EXPECT_LT(inside, 33000);
      EXPECT_EQ(isolated, 0) << example;
      EXPECT_EQ(wrong, 0) << example;
      EXPECT_EQ(bad_depth, 0);
    }
  }
}

// A huge ground sphere, R = 1e3..1e6, its top at the origin (along +y and along (1,2,3)), camera
// 1 above looking 35 degrees down. The renderer models it as a sphere, not a plane: hit points
// (re-projected onto the sphere) satisfy ||p - C| - R| <= 1e-6 (measured: at most 1.7e-10, about
// an ulp of R) and lie within 1e-6 (relative to t + 1) of the reference hit, from straight down
// to 0.1 degrees below the horizon; the lit image equals the unshadowed Phong reference (no acne).
// Over the 4x4 units in view, the sphere departs from its tangent plane by up to 8e-3 at
// R = 1e3 (d^2 / 2R), so a plane is not an equivalent model there; at R = 1e6 it is (8e-6).
TEST(HardCases, S3_HugeGroundSphere) {
  const std::uint64_t seed = 1003;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  for (const Vec3& up : {Vec3(0, 1, 0), glm::normalize(Vec3(1, 2, 3))}) {
    for (const double radius : {1e3, 1e4, 1e5, 1e6}) {
      SCOPED_TRACE("up " + str(up) + ", R = " + std::to_string(radius));
      Vec3 t1, t2;
      complete_frame(up, t1, t2);
      Scene scene;
      scene.width = 96;
      scene.height = 72;
      scene.ambient = Color(1);
      scene.materials = {phong_material(0.05, 0.6, 0.4, 30)};
      scene.spheres = {Sphere{-radius * up, radius, 0}};
      scene.lights = {point_light(10.0 * up + 3.0 * t1 - 2.0 * t2, Color(0.7)),
                      directional_light(-up - 0.4 * t2, Color(0.3))};
      // 35 degrees down; the image's top edge is 15 degrees down, well below the horizon (whose
      // dip is at most sqrt(2 / R) = 2.6 degrees).
      const double down = 35 * kPi / 180;
      scene.camera = Camera{up, up + std::cos(down) * t1 - std::sin(down) * up, up, 40};
      const PreparedScene prepared(scene);
      const LV c = to_ld(scene.spheres[0].center);
      int off_sphere = 0, off_ray = 0, misses = 0;
      LD worst_radial = 0;
      for (int i = 0; i < 4000; ++i) {
        // From straight down to 0.1 degrees below the horizon (whose dip is acos(R / (R + 1))).
        const double dip = std::acos(radius / (radius + 1));
        const double elev = -(dip + 0.1 * kPi / 180 + (89 * kPi / 180 - dip) * uni(rng));
        const double az = 2 * kPi * uni(rng);
        const Vec3 dir = glm::normalize(std::cos(elev) * (std::cos(az) * t1 + std::sin(az) * t2) + std::sin(elev) * up);
        const Ray ray = make_ray(scene.camera.position, dir);
        const std::optional<Hit> hit = intersect(prepared, ray);
        const std::optional<LD> t_ref = ref_sphere_t(c, radius, to_ld(ray.origin), to_ld(dir));
        ASSERT_TRUE(t_ref);
        if (!hit) {
          ++misses;
          continue;
        }
        ASSERT_TRUE(hit_is_finite(*hit));
        const LD radial = std::abs(length(to_ld(hit->p) - c) - radius);
        worst_radial = std::max(worst_radial, radial);
        if (!(radial <= 1e-6L)) ++off_sphere;
        const LV p_ref = to_ld(ray.origin) + *t_ref * to_ld(dir);
        if (!(length(to_ld(hit->p) - p_ref) <= 1e-6L * (*t_ref + 1))) ++off_ray;
      }
      EXPECT_EQ(misses, 0);
      EXPECT_EQ(off_sphere, 0) << "worst ||p - C| - R| = " << static_cast<double>(worst_radial);
      EXPECT_EQ(off_ray, 0);
      const Rendered img = render_image(prepared);
      EXPECT_EQ(img.stats.nan_count, 0u);
      const ImageCheck check = check_image(img, 1e-6L, 1e-9L, local_reference(prepared.scene()));
      EXPECT_EQ(check.darker, 0) << "acne: " << check.first_bad;
      EXPECT_EQ(check.mismatched, 0) << check.first_bad;
    }
  }
}

namespace {

// A scene file with one sphere (and the camera, which must see it) for the loader cases.
std::string sphere_scene_json(const std::string& center, const std::string& radius, const std::string& eye) {
  return R"({"camera": {"position": )" + eye + R"(, "look_at": )" + center +
         R"(, "up": [0, 1, 0.001], "fov_y": 60}, "image": {"width": 32, "height": 24}, "max_depth": 3,
  "lights": [{"type": "point", "position": [0, 5, 5], "intensity": 1},
             {"type": "directional", "direction": [-1, -1, -0.5], "intensity": 0.5}],
  "materials": {"glass": {"ka": 0.1, "kd": 0.5, "ks": 0.5, "n": 10, "kr": 0.2, "kt": 0.7, "fresnel": true}},
  "objects": [{"type": "sphere", "center": )" + center + R"(, "radius": )" + radius + R"(, "material": "glass"}]})";
}

}  // namespace

// Radius 0, 1e-30, 1e30, centre at 1e30. The loader rejects radius <= 0 and magnitudes above
// 1e100 (naming objects[0].radius / .center); the others load, and then every query is NaN-free
// and consistent: intersect_sphere, intersect(scene) and occluded agree, and any disagreement
// with the long double reference lies within rounding of tangency (1e-15 of |o - C| + r, where
// spheres far below their coordinates' resolution, like r = 1 at 1e30, are simply missed).
TEST(HardCases, S7_DegenerateAndExtremeSpheres) {
  for (const char* radius : {"0", "-1", "-0", "1e101"}) {
    SCOPED_TRACE(std::string("radius ") + radius);
    const LoadResult r = load_scene_text(sphere_scene_json("[0, 0, 0]", radius, "[0, 0, 5]"), "s7.json");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error_text().find("objects[0].radius"), std::string::npos) << r.error_text();
  }
  {
    const LoadResult r = load_scene_text(sphere_scene_json("[1e101, 0, 0]", "1", "[0, 0, 5]"), "s7.json");
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.error_text().find("objects[0].center"), std::string::npos) << r.error_text();
  }
  struct Case {
    const char* center;
    const char* radius;
    const char* eye;
  };
  const Case cases[] = {
      {"[0, 0, 0]", "1e-30", "[0, 0, 5]"},       {"[0.5, -0.25, 2]", "1e-30", "[0, 0, 5]"},
      {"[0, 0, 0]", "1e30", "[0, 0, 5]"},        {"[0, 0, 0]", "1e30", "[3e29, 1e29, -2e29]"},
      {"[1e30, 0, 0]", "1", "[0, 0, 5]"},        {"[1e30, 1e30, -1e30]", "1e-30", "[0, 0, 5]"},
      {"[1e30, 0, 0]", "1e30", "[0, 0, 5]"},     {"[1e30, 0, 0]", "1e30", "[-1e30, 0, 0]"},
      {"[1e30, 2e30, 0]", "1e29", "[1e30, 2e30, 5e29]"},
  };
  const std::uint64_t seed = 1007;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  for (const Case& cs : cases) {
    SCOPED_TRACE(std::string("centre ") + cs.center + ", radius " + cs.radius + ", eye " + cs.eye);
    LoadResult r = load_scene_text(sphere_scene_json(cs.center, cs.radius, cs.eye), "s7.json");
    ASSERT_TRUE(r.ok()) << r.error_text();
    Scene scene = *r.scene;
    const PreparedScene prepared(scene);
    ASSERT_EQ(scene.spheres.size(), 1u);
    const Sphere& sphere = scene.spheres[0];
    const LV c = to_ld(sphere.center);
    const LD radius = sphere.radius;
    const Vec3 eye = scene.camera.position;
    const TraceLimits limits{scene.max_depth, 0};
    int inconsistent = 0, far_wrong = 0, hits = 0;
    std::string example;
    for (int i = 0; i < 2000; ++i) {
      // Aimed at the centre, at the silhouette (+- a relative 1e-3) or anywhere.
      Vec3 dir;
      const int kind = i % 4;
      const Vec3 to_c = sphere.center - eye;
      if (kind == 3 || glm::length(to_c) == 0) {
        dir = random_unit(rng);
      } else {
        const Vec3 w = glm::normalize(to_c);
        Vec3 e1, e2;
        complete_frame(w, e1, e2);
        const double rho = kind == 0 ? 0.0 : (kind == 1 ? 1 - 1e-3 * uni(rng) : 1 + 1e-3 * uni(rng));
        const double phi = 2 * kPi * uni(rng);
        const Vec3 target = sphere.center + rho * sphere.radius * (std::cos(phi) * e1 + std::sin(phi) * e2);
        const Vec3 to = target - eye;
        dir = glm::length(to) > 0 ? glm::normalize(to) : random_unit(rng);
      }
      if (!all_finite(dir)) dir = random_unit(rng);
      const Ray ray = make_ray(eye, dir);
      const std::optional<double> t = intersect_sphere(sphere, ray);
      const std::optional<Hit> hit = intersect(prepared, ray);
      const bool blocked = occluded(prepared, ray, std::numeric_limits<double>::infinity());
      if (t) { ASSERT_TRUE(std::isfinite(*t) && *t > 0) << "t = " << *t; }
      if (hit) { ASSERT_TRUE(hit_is_finite(*hit)) << "direction " << str(dir); }
      if (t.has_value() != hit.has_value() || blocked != t.has_value() || (t && hit->t != *t)) {
        ++inconsistent;
        if (example.empty()) example = "queries disagree for direction " + str(dir);
      }
      hits += t ? 1 : 0;
      RayCounts counts;
      ASSERT_TRUE(all_finite(trace(prepared, limits, ray, 0, 1.0, counts))) << "direction " << str(dir);
      // The reference: a hit when the line passes within r of the centre and the sphere is ahead.
      const LV o = to_ld(eye), d = normalized(to_ld(dir));
      const bool ref_hit = ref_sphere_t(c, radius, o, d).has_value();
      if (ref_hit != t.has_value()) {
        const LD margin = std::abs(ref_line_distance(c, o, d) - radius);
        if (margin > 1e-15L * (length(o - c) + radius)) {
          ++far_wrong;
          if (example.empty()) {
            example = std::string(t ? "hit" : "miss") + " for direction " + str(dir) + ", line distance - r = " +
                      std::to_string(static_cast<double>(margin));
          }
        }
      }
    }
    EXPECT_EQ(inconsistent, 0) << example;
    EXPECT_EQ(far_wrong, 0) << example << " (" << hits << " hits)";
    const Rendered img = render_image(prepared, Term::kFull, 2);
    EXPECT_EQ(img.stats.nan_count, 0u);
  }
}

namespace {

// The scene with every position and length mapped by p -> s p + shift (directions, colours and
// coefficients unchanged).
Scene transformed(const Scene& scene, double s, const Vec3& shift) { return transformed_scene(scene, s, shift); }

// Pixels whose largest channel differs by more than tol.
int pixels_differing(const Rendered& a, const Rendered& b, double tol, std::string* example = nullptr) {
  int differing = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      if (max_channel(glm::abs(a.at(x, y) - b.at(x, y))) > tol) {
        if (example && example->empty()) {
          *example = "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): " + str(a.at(x, y)) +
                     " vs " + str(b.at(x, y));
        }
        ++differing;
      }
    }
  }
  return differing;
}

}  // namespace

// The embedded `lecture` scene (mirror, glass, shadows, 5 bounces) scaled by 1e-4 and 1e4 and
// translated by 1e5 (and both, and the intermediate scales): >= 99.99 % of the 320x180 pixels
// (all but 5) are within 1/255 of the unit image, with no NaN. (docs/accuracy.md. A scene of size
// 1e-4 placed 1e5 away is outside it: its coordinates' ulps are 1e-7 of the scene.)
// Measured with the per-primitive offsets (surface_offset(scene, hit)): 0 differing pixels in
// every case, at 320x180 and at 1280x720. With the former single 1e-9 x (|P| + t) offset, the
// scene moved 1e5 away had 5 of 57600 (the limit) and 119 of 921600 (0.013 %) differing, all
// seen through the glass sphere: that offset was 1e-4 of the unit scene there, and refraction
// carried the shift onto nearby edges.
TEST(HardCases, O5_LectureSceneAtAnyScaleAndPlace) {
  LoadResult loaded = load_scene_arg("lecture");
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  Scene unit_scene = *loaded.scene;
  unit_scene.width = 320;
  unit_scene.height = 180;
  const PreparedScene unit_scene_prepared(unit_scene);
  const Rendered unit = render_image(unit_scene_prepared);
  ASSERT_EQ(unit.stats.nan_count, 0u);
  struct Case {
    double s;
    Vec3 shift;
  };
  const Vec3 far(1e5, 1e5, 1e5);
  const Case cases[] = {{1e-4, Vec3(0)}, {1e-2, Vec3(0)}, {1e2, Vec3(0)}, {1e4, Vec3(0)},
                        {1, far},        {1, Vec3(-1e5, 0, 0)}, {1e4, far}, {1e-2, Vec3(0, 0, 1e2)}};
  const int allowed = static_cast<int>(1e-4 * unit.width * unit.height);
  for (const Case& cs : cases) {
    SCOPED_TRACE("scale " + std::to_string(cs.s) + ", shift " + str(cs.shift));
    const PreparedScene scene(transformed(unit_scene, cs.s, cs.shift));
    const Rendered img = render_image(scene);
    EXPECT_EQ(img.stats.nan_count, 0u);
    std::string example;
    const int differing = pixels_differing(img, unit, 1.0 / 255, &example);
    EXPECT_LE(differing, allowed) << example;
  }
}

// O5 at 1280x720, and further away than docs/accuracy.md promises: the lecture moved 1e5 and 1e6
// from the origin keeps >= 99.99 % of its pixels within 1/255 of the unit image. Measured: 0
// differing pixels at 1e5, 1 at 1e6 (5 at 3e6, 11 at 1e7, 95 at 1e8, the limit: there the
// camera's own rays are rounded to ulp(1e8) = 1.5e-8).
TEST(HardCases, O5_LectureSceneFarAwayAtHighResolution) {
  LoadResult loaded = load_scene_arg("lecture");
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  Scene unit_scene = *loaded.scene;
  unit_scene.width = 1280;
  unit_scene.height = 720;
  const PreparedScene unit_scene_prepared(unit_scene);
  const Rendered unit = render_image(unit_scene_prepared);
  const int allowed = static_cast<int>(1e-4 * unit.width * unit.height);
  for (const double shift : {1e5, 1e6}) {
    SCOPED_TRACE("shift " + std::to_string(shift));
    const Rendered img = render_image(PreparedScene(transformed(unit_scene, 1, Vec3(shift))));
    EXPECT_EQ(img.stats.nan_count, 0u);
    std::string example;
    EXPECT_LE(pixels_differing(img, unit, 1.0 / 255, &example), allowed) << example;
  }
}

// The camera inside a glass sphere (ior 1.5, Fresnel), with lit objects outside: no NaN, an image
// that is not black, and at every node of probed ray trees that hits the glass, `entering`
// matches the long double geometry, eta is 1/1.5 entering and 1.5 leaving, total internal
// reflection happens exactly where eta sin(theta_i) > 1, and otherwise the refracted direction
// obeys Snell's law to 1e-6 rad.
TEST(HardCases, R2_CameraInsideGlassSphere) {
  Scene scene;
  scene.width = 96;
  scene.height = 72;
  scene.ambient = Color(1);
  scene.background = Color(0.1, 0.15, 0.2);
  scene.max_depth = 6;
  scene.min_weight = 0;
  Material glass = phong_material(0, 0, 0.5, 300);
  glass.kt = Color(0.95);
  glass.ior = 1.5;
  glass.fresnel = true;
  scene.materials = {glass, phong_material(0.05, 0.6, 0.2, 20), phong_material(0.1, 0.5, 0.4, 50)};
  const Vec3 c(0, 1, 0);
  const double r = 1;
  scene.spheres = {Sphere{c, r, 0}, Sphere{Vec3(-2.5, 0.8, -2), 0.8, 2}, Sphere{Vec3(2, 0.5, -1), 0.5, 2}};
  scene.planes = {Plane{Vec3(0, -0.3, 0), Vec3(0, 1, 0), 1}};
  scene.lights = {point_light(Vec3(2, 5, 3), Color(0.9)), directional_light(Vec3(-1, -1, -0.5), Color(0.3))};
  const Vec3 eyes[] = {c, c + Vec3(0.3, 0.2, 0.1), c + Vec3(-0.1, -0.5, 0.6)};
  for (const Vec3& eye : eyes) {
    SCOPED_TRACE("eye " + str(eye));
    scene.camera = Camera{eye, Vec3(0, 0.3, -3), Vec3(0, 1, 0), 90};
    const PreparedScene prepared(scene);
    const Rendered img = render_image(prepared);
    EXPECT_EQ(img.stats.nan_count, 0u);
    int lit = 0;
    for (const Color& p : img.px) lit += max_channel(p) > 0.05 ? 1 : 0;
    EXPECT_GT(lit, scene.width * scene.height / 2) << "mostly black";
    int nodes = 0, leaving = 0, entering = 0, tir = 0, wrong = 0;
    std::string example;
    auto fail = [&](const std::string& what) {
      ++wrong;
      if (example.empty()) example = what;
    };
    std::function<void(const ProbeNode&)> walk = [&](const ProbeNode& node) {
      if (node.hit && node.object.kind == ObjectRef::Kind::kSphere && node.object.index == 0) {
        ++nodes;
        const LV o = to_ld(node.origin), d = normalized(to_ld(node.dir));
        const std::optional<LD> t = ref_sphere_t(to_ld(c), r, o, d);
        if (!t) {
          fail("the reference misses the glass at depth " + std::to_string(node.depth));
          return;
        }
        const LV n_out = normalized(o + *t * d - to_ld(c));
        const bool ref_entering = dot(n_out, d) < 0;
        (ref_entering ? entering : leaving) += 1;
        if (node.entering != ref_entering) fail("entering wrong at depth " + std::to_string(node.depth));
        if (node.depth == scene.max_depth) return;  // no recursion there: eta and TIR not evaluated
        if (node.eta != (ref_entering ? 1 / 1.5 : 1.5)) fail("eta " + std::to_string(node.eta));
        const LV n = ref_entering ? n_out : -n_out;  // facing the ray
        const LD sin_i = length(cross(d, n));
        const LD sin_t = static_cast<LD>(ref_entering ? 1 / 1.5 : 1.5) * sin_i;
        if (std::abs(sin_t - 1) > 1e-9L) {
          if (node.tir != (sin_t > 1)) fail("TIR flag wrong, sin_t = " + std::to_string(static_cast<double>(sin_t)));
          tir += sin_t > 1 ? 1 : 0;
          if (sin_t < 1 && node.refraction) {
            const LD theta_t = angle_between(to_ld(node.refraction->dir), -n);
            if (std::abs(theta_t - std::asin(sin_t)) > 1e-6L) {
              fail("Snell: refracted at " + std::to_string(static_cast<double>(theta_t)) + " rad, expected " +
                   std::to_string(static_cast<double>(std::asin(sin_t))));
            }
          }
        }
      }
      if (node.reflection) walk(*node.reflection);
      if (node.refraction) walk(*node.refraction);
    };
    for (int y = 1; y < scene.height; y += 6) {
      for (int x = 2; x < scene.width; x += 6) {
        const PixelProbe probe = probe_pixel(prepared, scene.width, scene.height, x, y);
        EXPECT_FALSE(probe.root.entering);
        EXPECT_EQ(probe.root.eta, 1.5);
        walk(probe.root);
      }
    }
    EXPECT_GT(leaving, 100);
    if (glm::length(eye - c) > r / 1.5) { EXPECT_GT(tir, 0); }  // rays can meet the wall beyond 41.8 degrees
    EXPECT_EQ(wrong, 0) << example << " (" << nodes << " glass hits)";
  }
}

// reflect_dir with normals of length 1.01 (and 0.99, 1 + 1e-8, 100, 1e-3), on either side of the
// surface: the result is unit to 1e-6 and the mirror image of d about the normal's direction to
// 1e-6 rad (against the long double reflection about the normalised normal).
TEST(HardCases, R5_ReflectWithNonUnitNormal) {
  const std::uint64_t seed = 3005;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  for (const double len : {1.01, 0.99, 1 + 1e-8, 1.0, 100.0, 1e-3}) {
    SCOPED_TRACE("normal length " + std::to_string(len));
    int wrong = 0;
    LD worst_angle = 0, worst_len = 0;
    for (int i = 0; i < 10000; ++i) {
      const Vec3 d = random_unit(rng);
      const Vec3 n = len * random_unit(rng);
      const Vec3 out = reflect_dir(d, n);
      const LV nl = normalized(to_ld(n)), dl = to_ld(d);
      const LV ref = dl - 2 * dot(dl, nl) * nl;
      const LD len_err = std::abs(length(to_ld(out)) - 1);
      const LD angle = angle_between(to_ld(out), ref);
      worst_angle = std::max(worst_angle, angle);
      worst_len = std::max(worst_len, len_err);
      if (!(len_err <= 1e-6L) || !(angle <= 1e-6L)) ++wrong;
    }
    EXPECT_EQ(wrong, 0) << "worst angle " << static_cast<double>(worst_angle) << " rad, worst |len - 1| "
                        << static_cast<double>(worst_len);
  }
}

// The TIR trap: a camera inside a glass sphere (ior 1.5, kt 1, Fresnel, no local term). The
// documented terminal value of the ray tree is 0 (docs/model.md): seen from the centre with only
// the background B outside, every pixel is exactly B (1 - F0^max_depth), F0 = 0.04 (each bounce
// returns 0.96 B and reflects 0.04 back through the centre). Off-centre, with lit objects
// outside, every contribution is >= 0, so each pixel grows with max_depth towards the depth-64
// image and the error against it (max and RMS) is non-increasing over max_depth 2..32.
TEST(HardCases, R6_TotalInternalReflectionTrapConvergesWithDepth) {
  Material glass;
  glass.kt = Color(1);
  glass.ior = 1.5;
  glass.fresnel = true;
  {
    SCOPED_TRACE("camera at the centre, background only");
    Scene scene;
    scene.width = 32;
    scene.height = 24;
    scene.background = Color(0.2, 0.5, 1);
    scene.min_weight = 0;
    scene.materials = {glass};
    scene.spheres = {Sphere{Vec3(0.5, -1, 2), 1.5, 0}};
    scene.camera = Camera{Vec3(0.5, -1, 2), Vec3(0, 0, 0), Vec3(0, 1, 0), 100};
    const LD f0 = (0.5L / 2.5L) * (0.5L / 2.5L);
    for (int depth = 0; depth <= 32; ++depth) {
      SCOPED_TRACE("max_depth " + std::to_string(depth));
      scene.max_depth = depth;
      const Rendered img = render_image(PreparedScene(scene));
      const LD factor = 1 - std::pow(f0, static_cast<LD>(depth));
      const ImageCheck check = check_image(img, 1e-9L, 1e-12L, [&](int, int, LV& out) {
        out = factor * to_ld(scene.background);
        return true;
      });
      EXPECT_EQ(check.mismatched, 0) << check.first_bad;
    }
  }
  SCOPED_TRACE("camera off-centre, lit objects outside");
  Scene scene;
  scene.width = 96;
  scene.height = 72;
  scene.ambient = Color(1);
  scene.background = Color(0.1, 0.15, 0.25);
  scene.min_weight = 0;
  scene.materials = {glass, phong_material(0.05, 0.6, 0.3, 20), phong_material(0.1, 0.7, 0.5, 40)};
  scene.materials[2].kd = Color(0.8, 0.3, 0.1);
  scene.spheres = {Sphere{Vec3(0, 1, 0), 1, 0}, Sphere{Vec3(-2.5, 0.8, -2), 0.8, 2}, Sphere{Vec3(2.2, 0.6, 1), 0.6, 2}};
  scene.planes = {Plane{Vec3(0, -0.2, 0), Vec3(0, 1, 0), 1}};
  scene.lights = {point_light(Vec3(2, 5, 3), Color(0.9)), directional_light(Vec3(-1, -1, -0.5), Color(0.3))};
  scene.camera = Camera{Vec3(0.55, 1.2, 0.3), Vec3(-1, 0.9, -3), Vec3(0, 1, 0), 100};
  scene.max_depth = 64;
  const Rendered reference = render_image(PreparedScene(scene));
  EXPECT_EQ(reference.stats.nan_count, 0u);
  double previous_max = std::numeric_limits<double>::infinity();
  double previous_rms = std::numeric_limits<double>::infinity();
  double first_max = 0;
  const Rendered* previous = nullptr;
  std::vector<Rendered> images;
  images.reserve(5);
  for (const int depth : {2, 4, 8, 16, 32}) {
    SCOPED_TRACE("max_depth " + std::to_string(depth));
    scene.max_depth = depth;
    images.push_back(render_image(PreparedScene(scene)));
    const Rendered& img = images.back();
    EXPECT_EQ(img.stats.nan_count, 0u);
    double max_err = 0, sum_sq = 0;
    int decreasing = 0;
    for (std::size_t i = 0; i < img.px.size(); ++i) {
      for (int ch = 0; ch < 3; ++ch) {
        const double e = reference.px[i][ch] - img.px[i][ch];
        max_err = std::max(max_err, std::abs(e));
        sum_sq += e * e;
        // Monotone in depth, up to rounding of the sums.
        if (e < -1e-12) ++decreasing;
        if (previous && img.px[i][ch] < previous->px[i][ch] - 1e-12) ++decreasing;
      }
    }
    const double rms = std::sqrt(sum_sq / (3.0 * static_cast<double>(img.px.size())));
    EXPECT_EQ(decreasing, 0) << "a pixel lost radiance with more depth";
    EXPECT_LE(max_err, previous_max);
    EXPECT_LE(rms, previous_rms);
    if (depth == 2) first_max = max_err;
    if (depth == 32) { EXPECT_LT(max_err, 1e-2 * first_max) << "max error " << max_err; }
    previous_max = max_err;
    previous_rms = rms;
    previous = &img;
  }
  EXPECT_GT(first_max, 0.05) << "the trap should matter at max_depth 2";
}

// Triangles of size 1e-8..1e8 at distances 0..1e8 (a lone triangle, a coplanar neighbour making
// a quad, and a convex ridge): rays leaving a hit point from its surface offset, to either side
// of a flat quad and to the outer side of the ridge, grazing ones included, never hit either
// triangle again (0 re-hits), by the nearest-hit, any-hit and per-triangle queries.
TEST(HardCases, T3_NoReHitsOfTrianglesAtAnyScale) {
  const std::uint64_t seed = 2003;
  SCOPED_TRACE(seed_trace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0, 1);
  const Vec3 axis(0.48, 0.6, 0.64);
  const Vec3 n = glm::normalize(Vec3(1, 2, 3));
  Vec3 t1, t2;
  complete_frame(n, t1, t2);
  for (const double size : {1e-8, 1e-4, 1.0, 1e4, 1e8}) {
    for (const double shift : {0.0, 1e4, 1e8}) {
      const Vec3 c = shift * axis;
      const double coords = std::max(shift, size);
      if (size < 1e-9 * coords) continue;  // below the coordinates' resolution: not a modelled scene
      const bool resolvable = size >= 1e-6 * coords;
      for (const bool ridge : {false, true}) {
        SCOPED_TRACE("size " + std::to_string(size) + ", centre " + str(c) + (ridge ? ", ridge" : ", quad"));
        auto at = [&](double a, double b, double h) { return c + size * (a * t1 + b * t2 + h * n); };
        const Triangle tri_a = make_triangle(at(-0.5, -0.4, 0), at(0.7, -0.2, 0), at(0.1, 0.6, 0));
        // Shares the edge v1-v2: coplanar (a quad), or bent away from +n (a convex ridge).
        const Triangle tri_b = make_triangle(tri_a.v2, tri_a.v1, at(0.9, 0.8, ridge ? -0.3 : 0));
        Scene scene;
        scene.materials = {phong_material(0, 1, 0, 1)};
        scene.triangles = {tri_a, tri_b};
        int primary_wrong = 0, rehits = 0, rays = 0;
        std::string example;
        for (int i = 0; i < 400; ++i) {
          // A point of triangle A, one in four within 1e-4 of the shared edge (b0 small).
          double b0 = uni(rng), b1 = uni(rng);
          if (i % 4 == 0) b0 = 1e-4 * uni(rng);
          b0 = std::max(b0, 1e-6);
          b1 = (1 - b0) * std::max(0.02, std::min(0.98, b1));
          const double b2 = 1 - b0 - b1;
          const Vec3 target = b0 * tri_a.v0 + b1 * tri_a.v1 + b2 * tri_a.v2;
          // Arrive from the +n side (the ridge's outer side) or, for the quad, from either side.
          const double side = (!ridge && i % 2 == 1) ? -1.0 : 1.0;
          Vec3 w = random_unit(rng);
          if (side * glm::dot(w, n) < 0.2) w = glm::normalize(w + (0.2 - side * glm::dot(w, n) + 0.1) * side * n);
          const Vec3 origin = target + 3 * size * w;
          const Ray ray = make_ray(origin, glm::normalize(target - origin));
          const std::optional<Hit> hit = intersect_all(scene, ray);
          if (!hit || hit->object.index != 0) {
            if (resolvable && b0 > 1e-5) {
              ++primary_wrong;
              if (example.empty()) example = "primary ray towards " + str(target) + (hit ? " hit B" : " missed");
            }
            if (!hit) continue;
          }
          ASSERT_TRUE(hit_is_finite(*hit));
          const Vec3 ng_facing = glm::dot(hit->ng, ray.dir) < 0 ? hit->ng : -hit->ng;
          const double offset = surface_offset(hit->p, hit->t);
          for (int k = 0; k < 4; ++k) {
            // Back to the side it came from (k = 0, 1; k = 1 grazing) or through (k = 2, 3; quad only).
            const bool through = k >= 2;
            if (through && ridge) continue;
            Vec3 e = random_unit(rng);
            const double en = glm::dot(e, ng_facing);
            if ((en < 0) != through) e -= 2 * en * ng_facing;
            if (k % 2 == 1) {
              const Vec3 tangential = e - glm::dot(e, ng_facing) * ng_facing;
              e = glm::normalize(tangential + (through ? -1e-4 : 1e-4) * glm::length(tangential) * ng_facing);
            }
            const Ray out = make_ray(offset_origin(hit->p, hit->ng, e, offset), e);
            ++rays;
            const std::optional<double> ta = intersect_triangle(tri_a, out);
            const std::optional<double> tb = intersect_triangle(tri_b, out);
            const std::optional<Hit> again = intersect_all(scene, out);
            const bool blocked = occluded_all(scene, out, std::numeric_limits<double>::infinity());
            if (ta || tb || again || blocked) {
              ++rehits;
              if (example.empty()) {
                example = std::string(ta ? "A" : (tb ? "B" : "scene")) + " re-hit by a ray leaving " + str(hit->p) +
                          " along " + str(e);
              }
            }
          }
        }
        EXPECT_EQ(primary_wrong, 0) << example;
        EXPECT_EQ(rehits, 0) << "of " << rays << " rays: " << example;
        EXPECT_GT(rays, 600);
      }
    }
  }
}

// No bounding boxes yet, so the closest cases: rays with one or two zero direction components
// whose origins lie exactly on a triangle's coordinate slabs (through its vertices and edges),
// exactly on its plane, and exactly on a plane primitive. Coordinates are dyadic so the
// expected answers are exact: a ray through the closed triangle hits (vertices and edges
// included: no false culls), any other misses; an origin on the surface finds nothing beyond
// rounding distance (t <= 1e-15); nothing is NaN.
TEST(HardCases, T5_ZeroDirectionComponentsAndOriginsOnSurfaces) {
  // The 6 axis directions and the 12 with one zero component.
  std::vector<Vec3> dirs;
  for (int a = 0; a < 3; ++a) {
    for (const double s : {1.0, -1.0}) {
      Vec3 d(0);
      d[a] = s;
      dirs.push_back(d);
      for (int b = a + 1; b < 3; ++b) {
        for (const double s2 : {1.0, -1.0}) {
          Vec3 e(0);
          e[a] = s;
          e[b] = s2;
          dirs.push_back(e);
        }
      }
    }
  }
  ASSERT_EQ(dirs.size(), 18u);
  Material glass = phong_material(0.1, 0.4, 0.5, 10.5);
  glass.kr = Color(0.3);
  glass.kt = Color(0.6);
  glass.fresnel = true;
  int checked = 0, wrong = 0, nan = 0;
  std::string example;
  auto fail = [&](int& counter, const std::string& what) {
    ++counter;
    if (example.empty()) example = what;
  };
  // Triangles in the planes x = 0.75, y = 0.75 and z = 0.75 (legs 2 along the other two axes),
  // alone and as half of a square split along its diagonal.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    auto point = [&](double u, double v, double w) {
      Vec3 p;
      p[i] = u;
      p[j] = v;
      p[k] = w;
      return p;
    };
    const Triangle tri = make_triangle(point(0.5, -0.25, 0.75), point(2.5, -0.25, 0.75), point(0.5, 1.75, 0.75));
    const Triangle other = make_triangle(point(2.5, -0.25, 0.75), point(2.5, 1.75, 0.75), point(0.5, 1.75, 0.75));
    Scene scene;
    scene.materials = {glass};
    scene.triangles = {tri};
    scene.lights = {point_light(Vec3(3, 3, 3), Color(1)), directional_light(Vec3(0, 0, -1), Color(0.5))};
    scene.max_depth = 3;
    scene.min_weight = 0;
    const PreparedScene prepared(scene);
    Scene square = scene;
    square.triangles = {tri, other};
    const PreparedScene square_prepared(square);  // its acceleration structure must hold both halves
    const TraceLimits limits{scene.max_depth, 0};
    // Targets in the triangle's (u, v) = (coord i - 0.5, coord j + 0.25): vertices, edge points,
    // inside, outside; inside means u >= 0, v >= 0, u + v <= 2.
    const double targets[][2] = {{0, 0},    {2, 0},     {0, 2},      {1, 0},   {0, 1},   {1, 1},    {0.5, 1.5},
                                 {0.5, 0.5}, {0.25, 1}, {1.75, 0.125}, {-0.25, 1}, {1, -0.25}, {1.25, 1}, {2.25, 0},
                                 {0, 2.25}, {-0.125, -0.125}, {3, 3}};
    for (const auto& tg : targets) {
      const double u = tg[0], v = tg[1];
      const bool inside = u >= 0 && v >= 0 && u + v <= 2;
      const bool in_square = u >= 0 && v >= 0 && u <= 2 && v <= 2;
      const Vec3 target = point(u + 0.5, v - 0.25, 0.75);
      for (const Vec3& d_raw : dirs) {
        const Vec3 dir = glm::normalize(d_raw);
        const std::string what = "plane " + std::to_string(k) + ", target (" + std::to_string(u) + ", " +
                                 std::to_string(v) + "), direction " + str(d_raw);
        // From 4 units back along d_raw (exact); then from the target itself (on the plane).
        for (const bool on_plane : {false, true}) {
          const Vec3 origin = on_plane ? target : target - 4.0 * d_raw;
          const Ray ray = make_ray(origin, dir);
          const bool crosses = !on_plane && d_raw[k] != 0;  // not edge-on, not starting on it
          ++checked;
          double b1 = 0, b2 = 0;
          const std::optional<double> t = intersect_triangle(tri, ray, &b1, &b2);
          if (t && !(std::isfinite(*t) && std::isfinite(b1) && std::isfinite(b2))) fail(nan, "NaN: " + what);
          // From the plane itself, a "hit" at a rounding-level t (the shear's products need not
          // cancel exactly: measured 2.8e-17) touches the surface at the origin: accepted.
          const bool touch = on_plane && t && *t <= 1e-15;
          if (t.has_value() != (crosses && inside) && !touch) {
            fail(wrong, std::string(t ? "false hit: " : "false miss: ") + what +
                            (on_plane ? " (origin on the plane)" : ""));
          } else if (t && !touch && std::abs(*t - 4 * glm::length(d_raw)) > 1e-14 * *t) {
            fail(wrong, "t = " + std::to_string(*t) + ": " + what);
          }
          const std::optional<Hit> hit = intersect(square_prepared, ray);
          if (hit && !hit_is_finite(*hit)) fail(nan, "NaN hit: " + what);
          const bool touch_square = on_plane && hit && hit->t <= 1e-15;
          if (hit.has_value() != (crosses && in_square) && !touch_square) {
            fail(wrong, std::string(hit ? "false hit (square): " : "false miss (square): ") + what);
          }
          if (occluded(square_prepared, ray, std::numeric_limits<double>::infinity()) != hit.has_value()) {
            fail(wrong, "any-hit disagrees: " + what);
          }
          RayCounts counts;
          if (!all_finite(trace(square_prepared, limits, ray, 0, 1.0, counts))) fail(nan, "NaN radiance: " + what);
        }
      }
    }
  }
  // Plane primitives: y = 0.75, and a tilted one through a dyadic point. From origins exactly on
  // the plane: no hit (t = 0) and no NaN; from 1.5 above or below: a hit exactly where d.n
  // points towards the plane, at t = h / |d.n|.
  const Plane planes[] = {{Vec3(0.5, 0.75, -0.25), Vec3(0, 1, 0), 0}, {Vec3(0.5, 0.25, 1), Vec3(1, 2, 3), 0}};
  for (const Plane& pl_in : planes) {
    Scene scene;
    scene.materials = {glass};
    scene.planes = {pl_in};
    scene.lights = {point_light(Vec3(3, 3, 3), Color(1))};
    scene.max_depth = 3;
    scene.min_weight = 0;
    const PreparedScene prepared(scene);
    const Plane& pl = prepared.scene().planes[0];  // its normal normalised, as the renderer takes it
    const TraceLimits limits{scene.max_depth, 0};
    Vec3 e1, e2;
    complete_frame(pl.normal, e1, e2);
    for (const double h : {0.0, 1.5, -1.5}) {
      for (const Vec3& d_raw : dirs) {
        const Vec3 dir = glm::normalize(d_raw);
        const Vec3 origin = pl.point + h * pl.normal;
        const std::string what =
            "plane normal " + str(pl.normal) + ", height " + std::to_string(h) + ", direction " + str(d_raw);
        const Ray ray = make_ray(origin, dir);
        const LD dn = dot(to_ld(dir), to_ld(pl.normal));
        const bool expect = h != 0 && std::abs(dn) > 1e-12L && (h > 0) == (dn < 0);
        ++checked;
        const std::optional<double> t = intersect_plane(pl, ray);
        if (t.has_value() != expect) {
          fail(wrong, std::string(t ? "false hit: " : "false miss: ") + what);
        } else if (t) {
          const LD t_ref = std::abs(h / dn);
          if (!(std::abs(*t - t_ref) <= 1e-12L * t_ref)) fail(wrong, "t = " + std::to_string(*t) + ": " + what);
        }
        const std::optional<Hit> hit = intersect(prepared, ray);
        if (hit && !hit_is_finite(*hit)) fail(nan, "NaN hit: " + what);
        RayCounts counts;
        if (!all_finite(trace(prepared, limits, ray, 0, 1.0, counts))) fail(nan, "NaN radiance: " + what);
      }
    }
  }
  EXPECT_EQ(nan, 0) << example;
  EXPECT_EQ(wrong, 0) << example;
  EXPECT_GT(checked, 1800);
}

// Mirror corridors (two facing mirrors, kr 0.9) at max_depth 64 with min_weight 0, 1e-3, 1e-2:
// the embedded `mirrors` scene, and a camera looking across a corridor (every ray that does not
// reach the floor or the sphere bounces 64 times). Each camera ray's tree is a chain (only the
// mirrors recurse), so pruning drops one tail of path weight < min_weight, whose radiance is at
// most the scene's maximum radiance, taken as the max channel of the min_weight-0 image. Pixel
// error <= min_weight x that; pruning traces fewer rays (at 1e-3 none is pruned: 0.9^64 = 1.2e-3).
TEST(HardCases, L4_MirrorCorridorPruningErrorBound) {
  LoadResult loaded = load_scene_arg("mirrors");
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  Scene mirrors = *loaded.scene;
  mirrors.width = 160;
  mirrors.height = 90;
  Scene across = mirrors;
  across.camera = Camera{Vec3(0.3, 1.2, 0.5), Vec3(-2, 0.9, 0.1), Vec3(0, 1, 0), 60};
  for (Scene* scene : {&mirrors, &across}) {
    SCOPED_TRACE(scene == &mirrors ? "mirrors scene" : "looking across the corridor");
    scene->max_depth = 64;
    scene->min_weight = 0;
    const Rendered exact = render_image(PreparedScene(*scene));
    EXPECT_EQ(exact.stats.nan_count, 0u);
    double max_radiance = 0;
    for (const Color& p : exact.px) max_radiance = std::max(max_radiance, max_channel(p));
    ASSERT_GT(max_radiance, 0.1);
    EXPECT_GT(exact.stats.rays.reflection, 20u * exact.px.size()) << "the corridor should recurse deeply";
    for (const double min_weight : {1e-3, 1e-2}) {
      SCOPED_TRACE("min_weight " + std::to_string(min_weight));
      scene->min_weight = min_weight;
      const Rendered pruned = render_image(PreparedScene(*scene));
      EXPECT_EQ(pruned.stats.nan_count, 0u);
      double worst = 0;
      for (std::size_t i = 0; i < pruned.px.size(); ++i) {
        worst = std::max(worst, max_channel(glm::abs(pruned.px[i] - exact.px[i])));
      }
      EXPECT_LE(worst, min_weight * max_radiance) << "bound " << min_weight * max_radiance;
      if (min_weight == 1e-3) {
        EXPECT_EQ(pruned.stats.rays.total(), exact.stats.rays.total());
      } else {
        EXPECT_LT(pruned.stats.rays.total(), exact.stats.rays.total());
        EXPECT_GT(worst, 0.0);
      }
    }
  }
}
