// The numerics the production renderer does not use, kept to measure what its choices buy
// (phonglab-cli bench: the precision table) : intersection tests in float, the textbook
// ray-sphere quadratic, and Schlick's Fresnel approximation. Scene::numerics selects them;
// intersect() and occluded() delegate here through one branch at their top, so the production
// path pays one predictable test per query.
#pragma once

#include <cstdint>
#include <optional>

#include "core/geometry/geometry.h"
#include "core/scene/scene.h"

namespace phonglab {

// Nearest hit with t in (0, t_max) under scene.numerics (float and/or textbook geometry).
// The Hit's point comes from the variant's own arithmetic; normals, material and the offset
// magnitude are then derived from that point as in make_hit.
std::optional<Hit> intersect_variant(const Scene& scene, const Ray& ray, double t_max);

// Whether anything lies on the ray with t in (0, t_max) under scene.numerics: the variant
// geometry, and/or a nearest-hit query instead of the any-hit one (nearest_hit_shadows).
bool occluded_variant(const Scene& scene, const Ray& ray, double t_max);

// Ray-sphere distance t > t_min of the nearest hit, or nothing: the textbook quadratic
// (discriminant b^2 - 4ac, roots (-b -+ sqrt(disc)) / 2a) in double, or in float.
std::optional<double> intersect_sphere_textbook(const Sphere& s, const Ray& ray, double t_min = 0);
std::optional<double> intersect_sphere_textbook_float(const Sphere& s, const Ray& ray, double t_min = 0);
// The production (Haines et al.) test with every operation in float.
std::optional<double> intersect_sphere_robust_float(const Sphere& s, const Ray& ray, double t_min = 0);

// Self-intersection ("acne"), counted on the pixel-centre ray trees of a width x height image.
// An acne ray is a shadow, reflection or refraction ray that leaves a primitive towards a side
// from which it cannot meet that primitive again (either side of a plane or triangle, the
// outside of a sphere) and still reports that primitive as its occluder or nearest hit. An
// acne pixel is one whose ray tree holds at least one acne ray.
struct AcneCount {
  std::uint64_t pixels = 0;  // pixels with at least one acne ray
  std::uint64_t rays = 0;    // acne rays in all the trees
};
AcneCount count_acne(const Scene& scene, int width, int height, int threads = 0);

// The scene with every position and length mapped by p -> s p + shift (directions, colours and
// coefficients unchanged): the same image, ideally, at another scale and place.
Scene transformed_scene(Scene scene, double s, const Vec3& shift);

// Schlick's approximation R0 + (1 - R0)(1 - cos_i)^5, R0 = ((1 - eta) / (1 + eta))^2, with the
// incident cosine on both sides of the interface (the common shortcut); 1 under total internal
// reflection is left to the caller, as for fresnel_exact.
double fresnel_schlick(double cos_i, double eta);

}  // namespace phonglab
