// The illumination equation at hand-computed points (docs/model.md).
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "core/render/render.h"
#include "core/shading/shading.h"

using namespace phonglab;

namespace {

constexpr double kTol = 1e-12;

// A unit sphere at the origin seen from +z, one material, no lights yet.
Scene unit_sphere_scene(const Material& m) {
  Scene s;
  s.materials = {m};
  s.spheres = {Sphere{{0, 0, 0}, 1, 0}};
  s.sphere_object = {0};
  s.background = Color(0.25, 0.5, 0.75);
  s.ambient = Color(1, 1, 1);
  return s;
}

Light point_light(Vec3 pos, Color intensity) {
  Light l;
  l.type = LightType::kPoint;
  l.position = pos;
  l.intensity = intensity;
  return l;
}

// Terms of the ray from (0, 0, 5) straight down -z, which hits (0, 0, 1) with N = V = +z.
Terms terms_at_pole(Scene scene, RayCounts* counts_out = nullptr) {
  const PreparedScene p(std::move(scene));
  const Scene& s = p.scene();
  const Ray ray = make_ray({0, 0, 5}, {0, 0, -1});
  const auto hit = intersect(p, ray);
  EXPECT_TRUE(hit.has_value());
  RayCounts counts;
  Terms t = shade(p, TraceLimits{s.max_depth, s.min_weight}, ray, *hit, 0, 1.0, counts);
  if (counts_out) *counts_out = counts;
  return t;
}

void expect_color(const Color& got, const Color& want, double tol = kTol) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

Material plastic() {
  Material m;
  m.name = "plastic";
  m.ka = Color(0.1, 0.2, 0.3);
  m.kd = Color(0.5);
  m.ks = Color(0.25);
  m.n = 2;
  return m;
}

}  // namespace

TEST(PhongShading, AmbientIsKaTimesIa) {
  Scene s = unit_sphere_scene(plastic());
  s.ambient = Color(0.5, 1, 2);
  expect_color(terms_at_pole(s).ambient, Color(0.05, 0.2, 0.6));
}

TEST(PhongShading, DiffuseAndSpecularAt45Degrees) {
  // Light at (0, 1, 2): L = (0, 1, 1)/sqrt2, N.L = 1/sqrt2; R = (0, -1, 1)/sqrt2, R.V = 1/sqrt2.
  Scene s = unit_sphere_scene(plastic());
  s.lights = {point_light({0, 1, 2}, Color(1, 2, 4))};
  const Terms t = terms_at_pole(s);
  const double c = 1 / std::sqrt(2.0);
  expect_color(t.diffuse, Color(1, 2, 4) * 0.5 * c);
  expect_color(t.specular, Color(1, 2, 4) * 0.25 * 0.5);  // (1/sqrt2)^2 = 1/2
  expect_color(t.reflection, Color(0));
  expect_color(t.refraction, Color(0));
}

TEST(PhongShading, BlinnUsesHalfVector) {
  // H = normalize(L + V) makes 22.5 degrees with N: N.H = cos(pi/8).
  Scene s = unit_sphere_scene(plastic());
  s.specular_model = SpecularModel::kBlinn;
  s.lights = {point_light({0, 1, 2}, Color(1))};
  const double nh = std::cos(M_PI / 8);
  expect_color(terms_at_pole(s).specular, Color(0.25 * nh * nh));
}

TEST(PhongShading, SpecularIsZeroWhenLightIsBehindSurface) {
  Material m = plastic();
  m.n = 0;  // pow(0, 0) = 1 must not light the dark side
  Scene s = unit_sphere_scene(m);
  s.lights = {point_light({0, 0, -10}, Color(1))};
  RayCounts counts;
  const Terms t = terms_at_pole(s, &counts);
  expect_color(t.diffuse, Color(0));
  expect_color(t.specular, Color(0));
  EXPECT_EQ(counts.shadow, 0u) << "no shadow ray towards a light behind the surface";
}

TEST(PhongShading, ShininessZeroGivesFullSpecularOnLitSide) {
  // n = 0: max(0, R.V)^0 = 1 wherever N.L > 0, even when R.V <= 0 (pow(0, 0) = 1).
  Material m = plastic();
  m.n = 0;
  Scene s = unit_sphere_scene(m);
  s.lights = {point_light({0, 100, 1.0001}, Color(1))};  // grazing light: R points away from V
  expect_color(terms_at_pole(s).specular, Color(0.25));
}

TEST(PhongShading, DirectionalLightUsesNegatedDirection) {
  Scene s = unit_sphere_scene(plastic());
  Light l;
  l.type = LightType::kDirectional;
  l.direction = Vec3(0, -3, -3);  // not unit: PreparedScene normalises it
  l.intensity = Color(1);
  s.lights = {l};
  const double c = 1 / std::sqrt(2.0);
  expect_color(terms_at_pole(s).diffuse, Color(0.5 * c));
}

TEST(PhongShading, NoDistanceFalloff) {
  Scene near_scene = unit_sphere_scene(plastic());
  near_scene.lights = {point_light({0, 0, 2}, Color(1))};
  Scene far_scene = unit_sphere_scene(plastic());
  far_scene.lights = {point_light({0, 0, 2000}, Color(1))};
  expect_color(terms_at_pole(near_scene).diffuse, terms_at_pole(far_scene).diffuse);
  expect_color(terms_at_pole(near_scene).diffuse, Color(0.5));
}

TEST(PhongShading, OccluderBlocksDiffuseAndSpecularButNotAmbient) {
  Scene s = unit_sphere_scene(plastic());
  s.lights = {point_light({0, 0, 10}, Color(1))};
  s.spheres.push_back(Sphere{{0, 0, 3}, 0.5, 0});  // between P = (0,0,1) and the light
  s.sphere_object.push_back(1);
  const PreparedScene shade_scene(s);  // the primary ray starts in the gap, below the occluder
  const Ray ray = make_ray({0, 0, 1.5}, {0, 0, -1});
  const auto hit = intersect(shade_scene, ray);
  ASSERT_TRUE(hit.has_value());
  RayCounts counts;
  const Terms t = shade(shade_scene, TraceLimits{}, ray, *hit, 0, 1.0, counts);
  expect_color(t.ambient, Color(0.1, 0.2, 0.3));
  expect_color(t.diffuse, Color(0));
  expect_color(t.specular, Color(0));
  EXPECT_EQ(counts.shadow, 1u);
}

TEST(PhongShading, LightsAddUp) {
  Scene one = unit_sphere_scene(plastic());
  one.lights = {point_light({0, 1, 2}, Color(1, 0, 0))};
  Scene two = one;
  two.lights.push_back(point_light({1, 0, 2}, Color(0, 1, 0)));
  const Terms t1 = terms_at_pole(one);
  const Terms t2 = terms_at_pole(two);
  EXPECT_NEAR(t2.diffuse.x, t1.diffuse.x, kTol);
  EXPECT_NEAR(t2.diffuse.y, 0.5 / std::sqrt(2.0), kTol);
}

TEST(Recursion, MirrorReflectsBackgroundWeightedByKr) {
  Material m;
  m.kr = Color(0.5, 0.25, 1);
  Scene s = unit_sphere_scene(m);
  // At the pole the mirror direction is +z, which leaves to the background.
  const Terms t = terms_at_pole(s);
  expect_color(t.reflection, Color(0.5 * 0.25, 0.25 * 0.5, 1 * 0.75));
}

TEST(Recursion, MaxDepthZeroMeansLocalShadingOnly) {
  Material m;
  m.kr = Color(1);
  Scene s = unit_sphere_scene(m);
  s.max_depth = 0;
  RayCounts counts;
  expect_color(terms_at_pole(s, &counts).reflection, Color(0));
  EXPECT_EQ(counts.reflection, 0u);
}

TEST(Recursion, ChildBelowMinWeightIsNotTraced) {
  Material m;
  m.kr = Color(0.01);
  Scene s = unit_sphere_scene(m);
  s.min_weight = 0.02;
  RayCounts counts;
  expect_color(terms_at_pole(s, &counts).reflection, Color(0));
  EXPECT_EQ(counts.reflection, 0u);
  s.min_weight = 0.01;  // weight 0.01 >= min_weight: traced
  expect_color(terms_at_pole(s, &counts).reflection, 0.01 * s.background);
  EXPECT_EQ(counts.reflection, 1u);
}

TEST(Recursion, RayThroughCentreOfGlassSphereGoesStraight) {
  // Without Fresnel, normal incidence: kt at entry, kt at exit, then the background.
  Material m;
  m.kt = Color(0.5);
  m.ior = 1.5;
  Scene s = unit_sphere_scene(m);
  RayCounts counts;
  const Terms t = terms_at_pole(s, &counts);
  expect_color(t.refraction, 0.25 * s.background);
  EXPECT_EQ(counts.refraction, 2u);
}

TEST(Fresnel, NormalIncidenceMatchesClosedForm) {
  // F = ((n1 - n2) / (n1 + n2))^2 on both sides of the interface.
  EXPECT_NEAR(fresnel_exact(1, 1 / 1.5), 0.04, 1e-15);
  EXPECT_NEAR(fresnel_exact(1, 1.5), 0.04, 1e-15);
}

TEST(Fresnel, IsOneUnderTotalInternalReflection) {
  const double critical = std::asin(1 / 1.5);
  EXPECT_EQ(fresnel_exact(std::cos(critical + 1e-6), 1.5), 1.0);
  EXPECT_LT(fresnel_exact(std::cos(critical - 1e-3), 1.5), 1.0);
}

TEST(Fresnel, MatchesSAndPFormulasAtAnAngle) {
  // 45 degrees into n = 1.5: sin_t = sin45/1.5.
  const double ci = std::cos(M_PI / 4), st = std::sin(M_PI / 4) / 1.5, ct = std::sqrt(1 - st * st);
  const double rs = (ci - 1.5 * ct) / (ci + 1.5 * ct), rp = (1.5 * ci - ct) / (1.5 * ci + ct);
  EXPECT_NEAR(fresnel_exact(ci, 1 / 1.5), 0.5 * (rs * rs + rp * rp), 1e-15);
}

TEST(Recursion, FresnelMovesWeightFromTransmissionToReflection) {
  Material m;
  m.kt = Color(1);
  m.fresnel = true;
  Scene s = unit_sphere_scene(m);
  s.max_depth = 1;  // the reflected ray sees the background; the refracted one ends at the
                    // far wall, whose local term is 0 (no ka, kd, ks)
  const Terms t = terms_at_pole(s);
  expect_color(t.reflection, 0.04 * s.background);
}

TEST(Recursion, TotalInternalReflectionSendsKtAlongMirrorDirection) {
  // Inside a glass sphere, a ray hitting the wall at 60 degrees (> 41.8) is totally reflected.
  Material m;
  m.kt = Color(1);
  m.ior = 1.5;
  Scene s = unit_sphere_scene(m);
  s.max_depth = 1;
  const PreparedScene p(s);
  // A chord from A to B on the sphere meets the normal at B at (pi - angle AOB) / 2.
  const double aob = M_PI - 2 * (M_PI / 3);  // angle with the normal 60 degrees
  const Vec3 A(0, 0, 1);
  const Vec3 B(std::sin(aob), 0, std::cos(aob));
  const Vec3 d = glm::normalize(B - A);
  const Ray ray = make_ray(A + 1e-6 * d, d);
  RayCounts counts;
  ProbeNode probe;
  trace(p, TraceLimits{s.max_depth, s.min_weight}, ray, 0, 1.0, counts, &probe);
  ASSERT_TRUE(probe.hit);
  EXPECT_FALSE(probe.entering);
  EXPECT_TRUE(probe.tir);
  ASSERT_TRUE(probe.refraction);
  const Vec3 mirror = d - 2 * glm::dot(d, probe.n) * probe.n;
  EXPECT_NEAR(glm::length(probe.refraction->dir - mirror), 0, 1e-12);
}
