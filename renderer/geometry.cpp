#include "renderer/geometry.h"

#include <utility>

#include "renderer/numerics_variants.h"

namespace phonglab {

TriangleShear make_shear(const Vec3& dir) {
  TriangleShear sh;
  // The axis where the direction is largest becomes z; x and y follow cyclically, swapped
  // when d_z < 0 so the triangle's winding is preserved (Woop et al. 2013, section 3).
  const double ax = std::abs(dir.x), ay = std::abs(dir.y), az = std::abs(dir.z);
  sh.kz = (ax >= ay) ? (ax >= az ? 0 : 2) : (ay >= az ? 1 : 2);
  sh.kx = (sh.kz + 1) % 3;
  sh.ky = (sh.kx + 1) % 3;
  if (dir[sh.kz] < 0) std::swap(sh.kx, sh.ky);
  sh.sz = 1.0 / dir[sh.kz];
  sh.sx = dir[sh.kx] * sh.sz;
  sh.sy = dir[sh.ky] * sh.sz;
  return sh;
}

namespace {

// Nearest root of the ray-sphere quadratic in (t_min, t_max), or 0 for none.
// Haines et al., Ray Tracing Gems ch. 7: the discriminant from the perpendicular distance
// r^2 - |f - (f.d)d|^2 avoids the cancellation of b^2 - c, and the roots come from
// q = -(b + sign(b) sqrt(disc)) so neither is a difference of near-equal numbers.
inline double sphere_root(const Sphere& s, const Vec3& o, const Vec3& d, double t_min, double t_max) {
  const Vec3 f = o - s.center;
  const double b = glm::dot(f, d);
  const double r2 = s.radius * s.radius;
  const double c = glm::dot(f, f) - r2;
  // Outside and moving away (the usual case for a ray leaving the sphere's surface), or the
  // nearest possible root -b - r already beyond t_max: no sqrt or division needed.
  if (c > 0 && (b > 0 || -b - s.radius > t_max)) return 0;
  const Vec3 perp = f - b * d;
  const double disc = r2 - glm::dot(perp, perp);
  if (!(disc >= 0)) return 0;  // also rejects NaN
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  if (q == 0) return 0;  // tangent at the origin itself: nothing ahead
  double t0 = c / q;
  double t1 = q;
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > t_min) return t0 < t_max ? t0 : 0;
  if (t1 > t_min) return t1 < t_max ? t1 : 0;
  return 0;
}

}  // namespace

std::optional<double> intersect_sphere(const Sphere& s, const Ray& ray, double t_min) {
  const double t = sphere_root(s, ray.origin, ray.dir, t_min, std::numeric_limits<double>::infinity());
  if (t > 0) return t;
  return std::nullopt;
}

std::optional<double> intersect_plane(const Plane& pl, const Ray& ray, double t_min) {
  const double denom = glm::dot(ray.dir, pl.normal);
  if (denom == 0) return std::nullopt;  // parallel: no gap guard, so no horizon gap
  const double t = glm::dot(pl.point - ray.origin, pl.normal) / denom;
  if (t > t_min && t < std::numeric_limits<double>::infinity()) return t;
  return std::nullopt;
}

std::optional<double> intersect_triangle(const Triangle& tri, const Ray& ray, double* b1, double* b2,
                                         double t_min) {
  return intersect_triangle(tri, ray, make_shear(ray.dir), b1, b2, t_min);
}

std::optional<double> intersect_triangle(const Triangle& tri, const Ray& ray, const TriangleShear& sh,
                                         double* b1, double* b2, double t_min) {
  // Watertight test (Woop, Benthin, Wald, JCGT 2013): vertices are moved into a space where
  // the ray is the +z axis; the 2D edge functions of a shared edge are then computed from the
  // same numbers by both triangles, so a ray through an edge or vertex cannot slip between.
  const Vec3 a = tri.v0 - ray.origin;
  const Vec3 b = tri.v1 - ray.origin;
  const Vec3 c = tri.v2 - ray.origin;
  const double ax = a[sh.kx] - sh.sx * a[sh.kz];
  const double ay = a[sh.ky] - sh.sy * a[sh.kz];
  const double bx = b[sh.kx] - sh.sx * b[sh.kz];
  const double by = b[sh.ky] - sh.sy * b[sh.kz];
  const double cx = c[sh.kx] - sh.sx * c[sh.kz];
  const double cy = c[sh.ky] - sh.sy * c[sh.kz];
  const double u = cx * by - cy * bx;
  const double v = ax * cy - ay * cx;
  const double w = bx * ay - by * ax;
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return std::nullopt;
  const double det = u + v + w;
  if (det == 0) return std::nullopt;  // degenerate or edge-on: no area seen from the ray
  const double t_scaled = u * (sh.sz * a[sh.kz]) + v * (sh.sz * b[sh.kz]) + w * (sh.sz * c[sh.kz]);
  const double t = t_scaled / det;
  if (!(t > t_min) || !(t < std::numeric_limits<double>::infinity())) return std::nullopt;
  // A zero-area triangle has no normal: never hit it (rounding can leave det != 0 for one).
  const Vec3 cross = glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0);
  if (!(glm::dot(cross, cross) > 0)) return std::nullopt;
  if (b1) *b1 = v / det;
  if (b2) *b2 = w / det;
  return t;
}

std::optional<Hit> intersect(const Scene& scene, const Ray& ray, double t_max) {
  if (scene.numerics.geometry()) [[unlikely]] return intersect_variant(scene, ray, t_max);  // bench only
  double best = t_max;
  ObjectRef obj;
  double best_b1 = 0, best_b2 = 0;
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    if (const double t = sphere_root(scene.spheres[i], ray.origin, ray.dir, 0, best); t > 0) {
      best = t;
      obj = {ObjectRef::Kind::kSphere, static_cast<int>(i)};
    }
  }
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    if (auto t = intersect_plane(scene.planes[i], ray); t && *t < best) {
      best = *t;
      obj = {ObjectRef::Kind::kPlane, static_cast<int>(i)};
    }
  }
  const TriangleShear shear = scene.triangles.empty() ? TriangleShear{} : make_shear(ray.dir);
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    double b1 = 0, b2 = 0;
    if (auto t = intersect_triangle(scene.triangles[i], ray, shear, &b1, &b2); t && *t < best) {
      best = *t;
      best_b1 = b1;
      best_b2 = b2;
      obj = {ObjectRef::Kind::kTriangle, static_cast<int>(i)};
    }
  }
  if (obj.kind == ObjectRef::Kind::kNone) return std::nullopt;
  return make_hit(scene, ray, obj, best, best_b1, best_b2);
}

bool occluded(const Scene& scene, const Ray& ray, double t_max) {
  if (scene.numerics.occlusion()) [[unlikely]] return occluded_variant(scene, ray, t_max);  // bench only
  for (const Sphere& s : scene.spheres) {
    if (sphere_root(s, ray.origin, ray.dir, 0, t_max) > 0) return true;
  }
  for (const Plane& pl : scene.planes) {
    if (auto t = intersect_plane(pl, ray); t && *t < t_max) return true;
  }
  if (scene.triangles.empty()) return false;
  const TriangleShear shear = make_shear(ray.dir);
  for (const Triangle& tri : scene.triangles) {
    if (auto t = intersect_triangle(tri, ray, shear, nullptr, nullptr); t && *t < t_max) return true;
  }
  return false;
}

Hit make_hit(const Scene& scene, const Ray& ray, ObjectRef obj, double t, double b1, double b2) {
  Hit hit;
  hit.t = t;
  hit.object = obj;
  hit.p = ray.origin + t * ray.dir;
  switch (obj.kind) {
    case ObjectRef::Kind::kSphere: {
      const Sphere& s = scene.spheres[obj.index];
      // Re-project onto the sphere: the radial error of o + t d is then a few ulps of |c| + r.
      Vec3 radial = hit.p - s.center;
      const double len = glm::length(radial);
      hit.ng = len > 0 ? radial / len : Vec3(0, 1, 0);
      hit.p = s.center + s.radius * hit.ng;
      hit.ns = hit.ng;
      hit.material = s.material;
      hit.magnitude = std::max(max_abs(hit.p), max_abs(s.center) + s.radius);
      break;
    }
    case ObjectRef::Kind::kPlane: {
      const Plane& pl = scene.planes[obj.index];
      hit.ng = pl.normal;
      hit.ns = pl.normal;
      hit.material = pl.material;
      hit.magnitude = max_abs(hit.p);
      break;
    }
    case ObjectRef::Kind::kTriangle: {
      const Triangle& tri = scene.triangles[obj.index];
      const double b0 = 1 - b1 - b2;
      // Interpolating the vertices is more accurate than o + t d for far-away rays.
      hit.p = b0 * tri.v0 + b1 * tri.v1 + b2 * tri.v2;
      hit.magnitude = std::max({max_abs(tri.v0), max_abs(tri.v1), max_abs(tri.v2)});
      hit.ng = glm::normalize(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0));
      hit.ns = hit.ng;
      if (tri.has_vertex_normals) {
        const Vec3 n = b0 * tri.n0 + b1 * tri.n1 + b2 * tri.n2;
        const double len = glm::length(n);
        if (len > 0 && std::isfinite(len)) hit.ns = n / len;
      }
      hit.material = tri.material;
      break;
    }
    case ObjectRef::Kind::kNone:
      break;
  }
  return hit;
}

}  // namespace phonglab
