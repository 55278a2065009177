// The numerics variants and ablations of NumericsVariant do what they say: the textbook and
// float sphere tests lose a far small sphere, a fixed offset gives acne in float far out and
// loses contact shadows in a tiny scene, Schlick differs from exact Fresnel by its known amount,
// and the "model only what a scene needs" ablations cast more rays for a bit-identical image.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "experiments/numerics_variants.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"
#include "core/shading/shading.h"
#include "tests/support/test_support.h"

namespace phonglab {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The lecture scene at width x height, unprepared (prepare_variant or PreparedScene prepares it).
Scene lecture(int width, int height) {
  Scene scene = load_scene_or_fail("lecture");
  scene.width = width;
  scene.height = height;
  return scene;
}

struct Image {
  std::vector<Color> sum;
  PassStats stats;
};

Image render_centres(const PreparedScene& prepared) {
  const Scene& scene = prepared.scene();
  Accumulator acc;
  acc.reset(scene.width, scene.height);
  Image img;
  img.stats = render_pass(prepared, RenderOptions{}, acc);
  img.sum = acc.sum;
  return img;
}

int pixels_off(const Image& a, const Image& b, double tol) {
  int n = 0;
  for (std::size_t i = 0; i < a.sum.size(); ++i) n += max_channel(glm::abs(a.sum[i] - b.sum[i])) > tol ? 1 : 0;
  return n;
}

// Wrong hit/miss decisions on rays from the origin to a unit sphere at distance `dist`, aimed
// at points of its centre plane at 0.5..0.9 (hits) and 1.1..1.5 (misses) radii: well clear of
// tangency, so an exact test gets every one right.
template <typename Test>
int wrong_decisions(double dist, Test test) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(0, 1);
  const Vec3 axis = glm::normalize(Vec3(0.48, 0.6, 0.64));
  const Vec3 e1 = glm::normalize(glm::cross(axis, Vec3(0, 0, 1)));
  const Vec3 e2 = glm::cross(axis, e1);
  const Sphere sphere{dist * axis, 1, 0};
  int wrong = 0;
  for (int i = 0; i < 2000; ++i) {
    const bool inside = i % 2 == 0;
    const double rho = inside ? 0.5 + 0.4 * uni(rng) : 1.1 + 0.4 * uni(rng);
    const double phi = 2 * kPi * uni(rng);
    const Vec3 target = sphere.center + rho * (std::cos(phi) * e1 + std::sin(phi) * e2);
    const Ray ray = make_ray(Vec3(0), glm::normalize(target));
    if (test(sphere, ray).has_value() != inside) ++wrong;
  }
  return wrong;
}

}  // namespace

TEST(NumericsVariants, TextbookSphereLosesAFarSmallSphereWhereTheRobustOneDoesNot) {
  // In double: at 1e8, b^2 and 4ac are both about 4e16 and their difference (at most 4) is
  // below their rounding error.
  EXPECT_EQ(wrong_decisions(1e8, [](const Sphere& s, const Ray& r) { return intersect_sphere(s, r); }), 0);
  EXPECT_GT(wrong_decisions(1e8, [](const Sphere& s, const Ray& r) { return intersect_sphere_textbook(s, r); }), 200);
  // The textbook test is fine in double where the scene is not that far.
  EXPECT_EQ(wrong_decisions(1e4, [](const Sphere& s, const Ray& r) { return intersect_sphere_textbook(s, r); }), 0);
  // In float the same happens a thousand times closer; the robust test in float holds there.
  EXPECT_EQ(wrong_decisions(1e4, [](const Sphere& s, const Ray& r) { return intersect_sphere_robust_float(s, r); }), 0);
  EXPECT_GT(wrong_decisions(1e4, [](const Sphere& s, const Ray& r) { return intersect_sphere_textbook_float(s, r); }), 200);
}

TEST(NumericsVariants, TextbookSphereHitPointsLeaveTheSphereFarAway) {
  // A unit sphere 1e4 away: the textbook roots carry the discriminant's cancellation into t,
  // and without re-projection the hit point lies that far off the surface; the production
  // point is within a few ulps of 1e4.
  Scene scene;
  scene.materials = {Material{}};
  const Vec3 axis = glm::normalize(Vec3(0.48, 0.6, 0.64));
  scene.spheres = {Sphere{1e4 * axis, 1, 0}};
  const PreparedScene production(scene);
  NumericsVariant variant;
  variant.textbook_sphere = true;
  const PreparedScene textbook = prepare_variant(scene, variant);
  const Vec3 e1 = glm::normalize(glm::cross(axis, Vec3(0, 0, 1)));
  const Vec3 e2 = glm::cross(axis, e1);
  double worst_production = 0, worst_textbook = 0;
  for (int i = 0; i < 200; ++i) {
    const double rho = 0.99 * i / 200, phi = 0.1 * i;
    const Vec3 target = scene.spheres[0].center + rho * (std::cos(phi) * e1 + std::sin(phi) * e2);
    const Ray ray = make_ray(Vec3(0), glm::normalize(target));
    const auto a = intersect(production, ray);
    const auto b = intersect(textbook, ray);
    ASSERT_TRUE(a && b);
    worst_production = std::max(worst_production, std::abs(glm::length(a->p - scene.spheres[0].center) - 1));
    worst_textbook = std::max(worst_textbook, std::abs(glm::length(b->p - scene.spheres[0].center) - 1));
  }
  EXPECT_LT(worst_production, 1e-11);
  EXPECT_GT(worst_textbook, 1e-9);
}

TEST(NumericsVariants, FloatGeometryWithFixedOffsetHasAcneFarOutProductionHasNone) {
  // The lecture scaled by 1e4: float coordinates of 1e4 are rounded to about 1e-3, ten times
  // the common 1e-4 offset, so surfaces shadow themselves. Double with the production offsets
  // has no acne there.
  const Scene big_scene = transformed_scene(lecture(96, 54), 1e4, Vec3(0));
  const PreparedScene big(big_scene);
  EXPECT_EQ(count_acne(big, 96, 54).pixels, 0u);
  NumericsVariant variant;
  variant.float_geometry = true;
  variant.fixed_offset = 1e-4;
  const PreparedScene naive = prepare_variant(big_scene, variant);
  const AcneCount acne = count_acne(naive, 96, 54);
  EXPECT_GT(acne.pixels, 100u) << acne.rays << " acne rays";
}

TEST(NumericsVariants, FixedOffsetLosesContactShadowsInATinyScene) {
  // The lecture scaled by 1e-4 (spheres of radius 0.5e-4): a shadow ray moved 1e-3 off the floor
  // starts above the spheres, so their shadows vanish. The production offset keeps the image.
  const Scene unit = lecture(160, 90);
  const Image reference = render_centres(PreparedScene(unit));
  const Scene tiny_scene = transformed_scene(unit, 1e-4, Vec3(0));
  const PreparedScene tiny(tiny_scene);
  EXPECT_EQ(pixels_off(render_centres(tiny), reference, 1.0 / 255), 0);
  NumericsVariant variant;
  variant.fixed_offset = 1e-3;
  const PreparedScene fixed = prepare_variant(tiny_scene, variant);
  EXPECT_GT(pixels_off(render_centres(fixed), reference, 1.0 / 255), 500);
  EXPECT_EQ(count_acne(fixed, 160, 90).pixels, 0u);  // too far off the surface, never onto it
}

TEST(NumericsVariants, SchlickDiffersFromExactFresnelByItsKnownAmount) {
  // Glass (n = 1.5) at 60 degrees from outside: R0 = 0.04, Schlick 0.04 + 0.96 / 32 = 0.07;
  // exact (rs^2 + rp^2) / 2 = 0.08919.
  const double eta = 1 / 1.5;
  EXPECT_NEAR(fresnel_schlick(0.5, eta), 0.07, 1e-15);
  EXPECT_NEAR(fresnel_exact(0.5, eta), 0.0891867, 1e-7);
  EXPECT_NEAR(fresnel_exact(0.5, eta) - fresnel_schlick(0.5, eta), 0.0191867, 1e-7);
  // At normal incidence they agree; from inside, 0.1 degree below the critical angle (41.81),
  // the exact F is 0.69 while Schlick with cos(theta_i) stays near R0 (docs/accuracy.md R4).
  EXPECT_NEAR(fresnel_schlick(1, eta), fresnel_exact(1, eta), 1e-15);
  const double cos_i = std::cos(41.7 * kPi / 180);
  EXPECT_NEAR(fresnel_exact(cos_i, 1.5), 0.68966, 1e-5);
  EXPECT_LT(fresnel_schlick(cos_i, 1.5), 0.05);
}

TEST(NumericsVariants, SchlickChangesOnlyFresnelMaterials) {
  const Scene scene = lecture(96, 54);
  const Image exact = render_centres(PreparedScene(scene));
  NumericsVariant variant;
  variant.schlick_fresnel = true;
  const Image schlick = render_centres(prepare_variant(scene, variant));
  EXPECT_GT(pixels_off(schlick, exact, 0), 0);  // the glass sphere changes
  EXPECT_EQ(schlick.stats.nan_count, 0u);
}

TEST(ModelOnlyWhatIsNeeded, AblationsCastMoreRaysForABitIdenticalImage) {
  for (const char* name : {"lecture", "glass", "mirrors"}) {
    SCOPED_TRACE(name);
    LoadResult loaded = load_scene_arg(name);
    ASSERT_TRUE(loaded.ok());
    Scene scene = *loaded.scene;
    scene.width = 96;
    scene.height = 54;
    const Image base = render_centres(PreparedScene(scene));

    NumericsVariant behind;
    behind.shadow_rays_behind = true;
    const Image b = render_centres(prepare_variant(scene, behind));
    EXPECT_EQ(b.sum, base.sum);
    EXPECT_GT(b.stats.rays.shadow, base.stats.rays.shadow);
    EXPECT_EQ(b.stats.rays.primary, base.stats.rays.primary);

    NumericsVariant opaque;
    opaque.refraction_for_opaque = true;
    const Image o = render_centres(prepare_variant(scene, opaque));
    EXPECT_EQ(o.sum, base.sum);
    EXPECT_GT(o.stats.rays.refraction, base.stats.rays.refraction);

    NumericsVariant nearest;
    nearest.nearest_hit_shadows = true;
    const Image n = render_centres(prepare_variant(scene, nearest));
    EXPECT_EQ(n.sum, base.sum);
    EXPECT_EQ(n.stats.rays.total(), base.stats.rays.total());
  }
}

TEST(NumericsVariants, FloatGeometryWithAFloatSizedOffsetStaysCloseAtUnitScale) {
  // Near the origin, float geometry with the usual 1e-3 offset is a working renderer: no NaN
  // and under 2 % of the pixels visibly different (edges, contact shadows).
  const Scene scene = lecture(96, 54);
  const Image base = render_centres(PreparedScene(scene));
  NumericsVariant variant;
  variant.float_geometry = true;
  variant.fixed_offset = 1e-3;
  const Image f = render_centres(prepare_variant(scene, variant));
  EXPECT_EQ(f.stats.nan_count, 0u);
  EXPECT_LT(pixels_off(f, base, 1.0 / 255), 96 * 54 / 50);
}

}  // namespace phonglab
