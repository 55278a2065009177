#include "experiments/numerics_variants.h"

#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "core/accel/accel.h"
#include "core/render/render.h"
#include "core/base/threads.h"
#include "core/shading/experiment.h"

namespace phonglab {

namespace {

// Vectors in the variant's precision (float or double).
template <typename R>
using V3 = glm::vec<3, R, glm::defaultp>;

// A distance limit in precision R: finite doubles beyond float's range become infinity.
template <typename R>
R limit_in(double t) {
  if (t >= static_cast<double>(std::numeric_limits<R>::max())) return std::numeric_limits<R>::infinity();
  return static_cast<R>(t);
}

// Nearest of two roots in (t_min, t_max), or 0 for none.
template <typename R>
R pick_root(R t0, R t1, R t_min, R t_max) {
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > t_min) return t0 < t_max ? t0 : 0;
  if (t1 > t_min) return t1 < t_max ? t1 : 0;
  return 0;
}

// The production sphere test (Haines et al.) with every operation in R.
template <typename R>
R sphere_robust(const V3<R>& c, R r, const V3<R>& o, const V3<R>& d, R t_min, R t_max) {
  const V3<R> f = o - c;
  const R b = glm::dot(f, d);
  const R r2 = r * r;
  const R cf = glm::dot(f, f) - r2;
  const V3<R> perp = f - b * d;
  const R disc = r2 - glm::dot(perp, perp);
  if (!(disc >= 0)) return 0;
  const R q = -(b + std::copysign(std::sqrt(disc), b));
  if (q == 0) return 0;
  return pick_root(cf / q, q, t_min, t_max);
}

// The textbook quadratic a t^2 + b t + c = 0: b^2 - 4ac cancels catastrophically for a small
// sphere far away (b^2 and 4ac are both about 4|f|^2), and -b + sqrt(disc) cancels for the far
// root.
template <typename R>
R sphere_textbook(const V3<R>& c, R r, const V3<R>& o, const V3<R>& d, R t_min, R t_max) {
  const V3<R> f = o - c;
  const R a = glm::dot(d, d);
  const R b = R(2) * glm::dot(f, d);
  const R cf = glm::dot(f, f) - r * r;
  const R disc = b * b - R(4) * a * cf;
  if (!(disc >= 0)) return 0;
  const R sq = std::sqrt(disc);
  return pick_root((-b - sq) / (R(2) * a), (-b + sq) / (R(2) * a), t_min, t_max);
}

template <typename R>
R plane_root(const V3<R>& p0, const V3<R>& n, const V3<R>& o, const V3<R>& d, R t_max) {
  const R denom = glm::dot(d, n);
  if (denom == 0) return 0;
  const R t = glm::dot(p0 - o, n) / denom;
  return (t > 0 && t < t_max) ? t : 0;
}

// Watertight triangle test (Woop, Benthin, Wald 2013) in precision R; b1, b2 the barycentric
// weights of v1 and v2.
template <typename R>
R triangle_root(const Triangle& tri, const V3<R>& o, const V3<R>& d, R t_max, R& b1, R& b2) {
  const R ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  const int kz = (ax >= ay) ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
  int kx = (kz + 1) % 3;
  int ky = (kx + 1) % 3;
  if (d[kz] < 0) std::swap(kx, ky);
  const R sz = R(1) / d[kz];
  const R sx = d[kx] * sz;
  const R sy = d[ky] * sz;
  const V3<R> a = V3<R>(tri.v0) - o;
  const V3<R> b = V3<R>(tri.v1) - o;
  const V3<R> c = V3<R>(tri.v2) - o;
  const R ex = a[kx] - sx * a[kz], ey = a[ky] - sy * a[kz];
  const R fx = b[kx] - sx * b[kz], fy = b[ky] - sy * b[kz];
  const R gx = c[kx] - sx * c[kz], gy = c[ky] - sy * c[kz];
  const R u = gx * fy - gy * fx;
  const R v = ex * gy - ey * gx;
  const R w = fx * ey - fy * ex;
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return 0;
  const R det = u + v + w;
  if (det == 0) return 0;
  const R t = (u * (sz * a[kz]) + v * (sz * b[kz]) + w * (sz * c[kz])) / det;
  if (!(t > 0) || !(t < t_max)) return 0;
  b1 = v / det;
  b2 = w / det;
  return t;
}

template <typename R>
R sphere_root(const Sphere& s, bool textbook, const V3<R>& o, const V3<R>& d, R t_max) {
  const V3<R> c(s.center);
  const R r = static_cast<R>(s.radius);
  return textbook ? sphere_textbook(c, r, o, d, R(0), t_max) : sphere_robust(c, r, o, d, R(0), t_max);
}

template <typename R>
std::optional<Hit> nearest(const Scene& scene, bool textbook, const Ray& ray, double t_max) {
  const V3<R> o(ray.origin), d(ray.dir);
  R best = limit_in<R>(t_max);
  R best_b1 = 0, best_b2 = 0;
  ObjectRef obj;
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    if (const R t = sphere_root(scene.spheres[i], textbook, o, d, best); t > 0) {
      best = t;
      obj = {ObjectRef::Kind::kSphere, static_cast<int>(i)};
    }
  }
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    const Plane& pl = scene.planes[i];
    if (const R t = plane_root(V3<R>(pl.point), V3<R>(pl.normal), o, d, best); t > 0) {
      best = t;
      obj = {ObjectRef::Kind::kPlane, static_cast<int>(i)};
    }
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    R b1 = 0, b2 = 0;
    if (const R t = triangle_root(scene.triangles[i], o, d, best, b1, b2); t > 0) {
      best = t;
      best_b1 = b1;
      best_b2 = b2;
      obj = {ObjectRef::Kind::kTriangle, static_cast<int>(i)};
    }
  }
  if (obj.kind == ObjectRef::Kind::kNone) return std::nullopt;
  // Material, shading normal and magnitude as in production; then the point (and a sphere's
  // normal, which follows from it) from the variant's own arithmetic.
  Hit hit = make_hit(scene, ray, obj, static_cast<double>(best), static_cast<double>(best_b1),
                     static_cast<double>(best_b2));
  switch (obj.kind) {
    case ObjectRef::Kind::kSphere: {
      const Sphere& s = scene.spheres[static_cast<std::size_t>(obj.index)];
      const V3<R> c(s.center);
      V3<R> p = o + best * d;
      if (!textbook) {  // the robust test re-projects onto the sphere, in R
        const V3<R> radial = p - c;
        const R len = glm::length(radial);
        if (len > 0) p = c + static_cast<R>(s.radius) * (radial / len);
      }
      hit.p = Vec3(p);
      const Vec3 radial = hit.p - s.center;
      const double len = glm::length(radial);
      hit.ng = len > 0 ? radial / len : Vec3(0, 1, 0);
      hit.ns = hit.ng;
      break;
    }
    case ObjectRef::Kind::kPlane:
      hit.p = Vec3(o + best * d);
      break;
    case ObjectRef::Kind::kTriangle: {
      const Triangle& tri = scene.triangles[static_cast<std::size_t>(obj.index)];
      const R b0 = R(1) - best_b1 - best_b2;
      hit.p = Vec3(b0 * V3<R>(tri.v0) + best_b1 * V3<R>(tri.v1) + best_b2 * V3<R>(tri.v2));
      break;
    }
    case ObjectRef::Kind::kMesh:  // the variants test no meshes (see the header)
    case ObjectRef::Kind::kNone:
      break;
  }
  return hit;
}

template <typename R>
bool any_hit(const Scene& scene, bool textbook, const Ray& ray, double t_max) {
  const V3<R> o(ray.origin), d(ray.dir);
  const R limit = limit_in<R>(t_max);
  for (const Sphere& s : scene.spheres) {
    if (sphere_root(s, textbook, o, d, limit) > 0) return true;
  }
  for (const Plane& pl : scene.planes) {
    if (plane_root(V3<R>(pl.point), V3<R>(pl.normal), o, d, limit) > 0) return true;
  }
  for (const Triangle& tri : scene.triangles) {
    R b1 = 0, b2 = 0;
    if (triangle_root(tri, o, d, limit, b1, b2) > 0) return true;
  }
  return false;
}

template <typename R>
std::optional<double> as_optional(R t) {
  if (t > 0) return static_cast<double>(t);
  return std::nullopt;
}

}  // namespace

std::optional<Hit> intersect_variant(const Scene& scene, const NumericsVariant& variant, const Ray& ray,
                                     double t_max) {
  return variant.float_geometry ? nearest<float>(scene, variant.textbook_sphere, ray, t_max)
                                : nearest<double>(scene, variant.textbook_sphere, ray, t_max);
}

namespace {

// The variant's geometry behind the Accelerator interface; queries it does not change go to
// the production accelerator (`base`, null: brute force).
class VariantAccelerator final : public Accelerator {
 public:
  VariantAccelerator(const NumericsVariant& variant, std::shared_ptr<const Accelerator> base)
      : variant_(variant), base_(std::move(base)) {}

  std::optional<Hit> intersect(const Scene& scene, const Ray& ray, double t_max) const override {
    if (variant_.geometry()) return intersect_variant(scene, variant_, ray, t_max);
    return base_ ? base_->intersect(scene, ray, t_max) : intersect_all(scene, ray, t_max);
  }
  bool occluded(const Scene& scene, const Ray& ray, double t_max) const override {
    if (variant_.nearest_hit_shadows) return intersect(scene, ray, t_max).has_value();
    if (variant_.geometry()) {
      return variant_.float_geometry ? any_hit<float>(scene, variant_.textbook_sphere, ray, t_max)
                                     : any_hit<double>(scene, variant_.textbook_sphere, ray, t_max);
    }
    return base_ ? base_->occluded(scene, ray, t_max) : occluded_all(scene, ray, t_max);
  }
  bool matches(const Scene& scene) const override { return !base_ || base_->matches(scene); }

 private:
  NumericsVariant variant_;
  std::shared_ptr<const Accelerator> base_;
};

// The variant's shading behind the Experiment interface.
class VariantShading final : public Experiment {
 public:
  explicit VariantShading(const NumericsVariant& variant) : variant_(variant) {}
  double fresnel(double cos_i, double eta) const override {
    return variant_.schlick_fresnel ? fresnel_schlick(cos_i, eta) : fresnel_exact(cos_i, eta);
  }
  double offset(const Scene& scene, const Hit& hit) const override {
    return variant_.fixed_offset > 0 ? variant_.fixed_offset : surface_offset(scene, hit);
  }
  bool shadow_rays_behind() const override { return variant_.shadow_rays_behind; }
  bool refraction_for_opaque() const override { return variant_.refraction_for_opaque; }

 private:
  NumericsVariant variant_;
};

}  // namespace

PreparedScene prepare_variant(Scene scene, const NumericsVariant& variant) {
  if (variant.production()) return PreparedScene(std::move(scene));
  const auto make_accel = [&variant](const Scene& s) -> std::shared_ptr<const Accelerator> {
    return std::make_shared<VariantAccelerator>(variant, build_scene_accel(s));
  };
  return PreparedScene(std::move(scene), make_accel, std::make_shared<VariantShading>(variant));
}

std::optional<double> intersect_sphere_textbook(const Sphere& s, const Ray& ray, double t_min) {
  return as_optional(sphere_textbook(s.center, s.radius, ray.origin, ray.dir, t_min,
                                     std::numeric_limits<double>::infinity()));
}

std::optional<double> intersect_sphere_textbook_float(const Sphere& s, const Ray& ray, double t_min) {
  return as_optional(sphere_textbook(V3<float>(s.center), static_cast<float>(s.radius), V3<float>(ray.origin),
                                     V3<float>(ray.dir), limit_in<float>(t_min),
                                     std::numeric_limits<float>::infinity()));
}

std::optional<double> intersect_sphere_robust_float(const Sphere& s, const Ray& ray, double t_min) {
  return as_optional(sphere_robust(V3<float>(s.center), static_cast<float>(s.radius), V3<float>(ray.origin),
                                   V3<float>(ray.dir), limit_in<float>(t_min),
                                   std::numeric_limits<float>::infinity()));
}

namespace {

bool same_object(const ObjectRef& a, const ObjectRef& b) { return a.kind == b.kind && a.index == b.index; }

// Acne rays in the tree below `node` (see count_acne).
std::uint64_t acne_rays(const ProbeNode& node) {
  if (!node.hit) return 0;
  // Which rays leave towards a side the primitive cannot be met from again: on a plane or a
  // triangle every ray; on a sphere, rays leaving its outside. Shadow and reflection rays leave
  // on the side N faces (the outside when the ray arrived from outside, `entering`); a refracted
  // ray crosses to the other side (the outside when leaving), unless it is totally reflected.
  const bool flat = node.object.kind != ObjectRef::Kind::kSphere;
  const bool n_side_outward = flat || node.entering;
  std::uint64_t rays = 0;
  if (n_side_outward) {
    for (const ProbeLight& l : node.lights) {
      if (l.lit_side && !l.visible && same_object(l.occluder, node.object)) ++rays;
    }
  }
  if (const ProbeNode* r = node.reflection.get()) {
    if (r->hit && n_side_outward && same_object(r->object, node.object)) ++rays;
    rays += acne_rays(*r);
  }
  if (const ProbeNode* r = node.refraction.get()) {
    const bool outward = flat || (node.tir ? node.entering : !node.entering);
    if (r->hit && outward && same_object(r->object, node.object)) ++rays;
    rays += acne_rays(*r);
  }
  return rays;
}

}  // namespace

AcneCount count_acne(const PreparedScene& prepared, int width, int height, int threads) {
  const int n = std::max(1, std::min(resolve_thread_count(threads), height));
  std::vector<AcneCount> parts(static_cast<std::size_t>(n));
  run_workers(n, [&](int part) {
    AcneCount& c = parts[static_cast<std::size_t>(part)];
    for (int y = part; y < height; y += n) {
      for (int x = 0; x < width; ++x) {
        const std::uint64_t rays = acne_rays(probe_pixel(prepared, width, height, x, y).root);
        c.rays += rays;
        c.pixels += rays > 0 ? 1 : 0;
      }
    }
  });
  AcneCount total;
  for (const AcneCount& c : parts) {
    total.pixels += c.pixels;
    total.rays += c.rays;
  }
  return total;
}

Scene transformed_scene(Scene scene, double s, const Vec3& shift) {
  auto move = [&](Vec3& p) { p = s * p + shift; };
  move(scene.camera.position);
  move(scene.camera.look_at);
  for (Light& l : scene.lights) {
    if (l.type == LightType::kPoint) move(l.position);
  }
  for (Sphere& sp : scene.spheres) {
    move(sp.center);
    sp.radius *= s;
  }
  for (Plane& pl : scene.planes) move(pl.point);
  for (Triangle& tri : scene.triangles) {
    move(tri.v0);
    move(tri.v1);
    move(tri.v2);
  }
  // A mesh's triangles are shared and immutable: a moved copy gets its own, and its own BVH.
  for (Mesh& mesh : scene.meshes) {
    std::vector<Triangle> tris = mesh.geometry->triangles;
    for (Triangle& tri : tris) {
      move(tri.v0);
      move(tri.v1);
      move(tri.v2);
    }
    mesh.geometry = make_mesh_geometry(std::move(tris), mesh.geometry->source_face);
  }
  return scene;
}

double fresnel_schlick(double cos_i, double eta) {
  const double r0 = (1 - eta) / (1 + eta);
  const double x = 1 - clamp_positive(clamp_unit(cos_i));
  return r0 * r0 + (1 - r0 * r0) * (x * x * x * x * x);
}

}  // namespace phonglab
