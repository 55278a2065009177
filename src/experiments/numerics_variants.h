// The numerics the production renderer does not use, kept to measure what its choices buy
// (phonglab-cli bench: the precision and savings tables): intersection tests in float, the
// textbook ray-sphere quadratic, fixed ray offsets, Schlick's Fresnel approximation, and the
// work the production renderer spares. They reach the renderer through its two doors for
// experiments: an accelerator of their own for the geometry, and an Experiment
// (core/shading/experiment.h) for the shading. Nothing in the programs but the bench links them.
#pragma once

#include <cstdint>
#include <optional>

#include "core/accel/prepared_scene.h"
#include "core/geometry/geometry.h"
#include "core/scene/scene.h"

namespace phonglab {

// What an experiment changes. All off is the production renderer.
struct NumericsVariant {
  bool float_geometry = false;   // intersection tests and hit points in float (shading stays double)
  bool textbook_sphere = false;  // b^2 - 4ac with (-b -+ sqrt)/2a roots, hit point not re-projected
  // Ablations of work the production renderer skips; the image stays the same, only rays grow.
  bool nearest_hit_shadows = false;    // shadow rays as nearest-hit queries, not any-hit
  bool shadow_rays_behind = false;     // cast shadow rays also to lights with N.L <= 0
  bool refraction_for_opaque = false;  // trace a refraction ray for opaque materials (kt = 0) too
  bool schlick_fresnel = false;  // Schlick's approximation, cos(theta_i) on both sides
  double fixed_offset = 0;       // > 0: secondary rays start this far (world units) along the normal
  bool geometry() const { return float_geometry || textbook_sphere; }
  bool production() const {
    return !geometry() && !nearest_hit_shadows && !shadow_rays_behind && !refraction_for_opaque &&
           !schlick_fresnel && !(fixed_offset > 0);
  }
};

// The scene prepared for rendering under `variant`: the production PreparedScene when every
// switch is off, else one whose accelerator answers with the variant's geometry and whose
// Experiment applies the variant's shading (the packet tracer then stands aside).
PreparedScene prepare_variant(Scene scene, const NumericsVariant& variant);

// Nearest hit with t in (0, t_max) with the variant's geometry (float and/or textbook). The
// Hit's point comes from the variant's own arithmetic; normals, material and the offset
// magnitude are then derived from that point as in make_hit.
std::optional<Hit> intersect_variant(const Scene& scene, const NumericsVariant& variant, const Ray& ray, double t_max);

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
AcneCount count_acne(const PreparedScene& prepared, int width, int height, int threads = 0);

// The scene with every position and length mapped by p -> s p + shift (directions, colours and
// coefficients unchanged): the same image, ideally, at another scale and place.
Scene transformed_scene(Scene scene, double s, const Vec3& shift);

// Schlick's approximation R0 + (1 - R0)(1 - cos_i)^5, R0 = ((1 - eta) / (1 + eta))^2, with the
// incident cosine on both sides of the interface (the common shortcut); 1 under total internal
// reflection is left to the caller, as for fresnel_exact.
double fresnel_schlick(double cos_i, double eta);

}  // namespace phonglab
