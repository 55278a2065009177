// Ray-primitive intersection: robust sphere, plane and watertight triangle tests, the
// nearest-hit query and the any-hit (shadow) query. Pure functions of the scene and a ray.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

#include "core/scene/math.h"
#include "core/scene/scene.h"

namespace phonglab {

// Per-ray constants of the watertight triangle test (Woop et al. 2013): the axis permutation
// that makes the ray's largest direction component z, and the shear onto the z axis.
struct TriangleShear {
  int kx = 0, ky = 1, kz = 2;
  double sx = 0, sy = 0, sz = 1;
};
TriangleShear make_shear(const Vec3& dir);

// Nearest intersection found by a query.
struct Hit {
  double t = 0;      // distance along the ray
  Vec3 p;            // hit point (re-projected onto spheres and planes)
  Vec3 ng;           // unit geometric normal on the outward side (not yet facing the ray)
  Vec3 ns;           // unit shading normal (interpolated vertex normals, else ng)
  int material = 0;  // index into Scene::materials
  ObjectRef object;  // which primitive was hit
  double magnitude = 0;  // coordinate magnitude that sets the rounding error of p (see surface_offset)
};

// Per-primitive tests: distance t > t_min of the nearest hit, or nothing. Never NaN. (Spheres:
// sphere_root below.)
std::optional<double> intersect_plane(const Plane& pl, const Ray& ray, double t_min = 0);
// The watertight triangle test with the ray's shear (make_shear) computed once for many
// triangles; also gives the barycentric weights of v1 and v2.
inline std::optional<double> intersect_triangle(const Triangle& tri, const Ray& ray, const TriangleShear& sh,
                                                double* b1, double* b2, double t_min = 0) {
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

// Nearest root in (t_min, t_max) of the ray-sphere quadratic, or 0 for none.
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

// The nearest of `planes` with t in (0, best), the first in order on a tie: its index, with
// best updated; -1 (nothing changed) when none is nearer. Every nearest-hit query starts here.
int nearest_plane(const std::vector<Plane>& planes, const Ray& ray, double& best);
// Whether any of `planes` lies on the ray with t in (0, t_max).
bool any_plane(const std::vector<Plane>& planes, const Ray& ray, double t_max);

// The nearest of `tris` with t in (0, best), the first in order on a tie: its index, with best
// and the barycentric weights b1, b2 updated; -1 (nothing changed) when none is nearer.
int nearest_triangle(const std::vector<Triangle>& tris, const Ray& ray, const TriangleShear& shear, double& best,
                     double& b1, double& b2);
// Whether any of `tris` lies on the ray with t in (0, t_max).
bool any_triangle(const std::vector<Triangle>& tris, const Ray& ray, const TriangleShear& shear, double t_max);

// Whether a triangle hit at distance t, named `ref`, replaces the nearest hit found so far (`best`,
// `obj`; kind kNone: none yet, `best` is the query's limit): it is nearer, or exactly as near and
// first in the scene's order (by kind, index, triangle), as brute force, which tests in that order,
// would keep it. So a tie (a ray through an edge two triangles share) has one answer whatever order
// a hierarchy visits them in.
inline bool replaces(double t, const ObjectRef& ref, double best, const ObjectRef& obj) {
  if (t < best) return true;
  if (!(t == best) || obj.kind == ObjectRef::Kind::kNone) return false;
  if (ref.kind != obj.kind) return ref.kind < obj.kind;
  if (ref.index != obj.index) return ref.index < obj.index;
  return ref.prim < obj.prim;
}

// Nearest-hit and any-hit queries over a scene's primitives (built by PreparedScene, or by a
// benchmark that compares acceleration structures). Answers must equal the brute-force ones.
class Accelerator {
 public:
  virtual ~Accelerator() = default;
  // Nearest hit with t in (0, t_max).
  virtual std::optional<Hit> intersect(const Scene& scene, const Ray& ray, double t_max) const = 0;
  // Whether anything lies on the ray with t in (0, t_max).
  virtual bool occluded(const Scene& scene, const Ray& ray, double t_max) const = 0;
  // Whether it was built over this scene's primitives as they are now (a cheap check: the
  // tests compare accelerators built apart).
  virtual bool matches(const Scene& scene) const = 0;
};


// A triangle's unit geometric normal Ng = normalize((v1 - v0) x (v2 - v0)), and its coordinate
// magnitude for surface_offset (its largest vertex coordinate).
inline Vec3 triangle_normal(const Triangle& tri) { return glm::normalize(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0)); }
inline double triangle_magnitude(const Triangle& tri) {
  return std::max({max_abs(tri.v0), max_abs(tri.v1), max_abs(tri.v2)});
}

// make_hit's part for a triangle hit at barycentric weights b1, b2 (of v1, v2), given its
// triangle_normal and triangle_magnitude (which a tracer may compute once per triangle): the
// point interpolated from the vertices (more accurate than o + t d for far-away rays), the
// normals (interpolated vertex normals where the triangle has them), the material.
inline void triangle_hit_record(const Triangle& tri, const Vec3& ng, double magnitude, double b1, double b2, Hit& hit) {
  const double b0 = 1 - b1 - b2;
  hit.p = b0 * tri.v0 + b1 * tri.v1 + b2 * tri.v2;
  hit.magnitude = magnitude;
  hit.ng = ng;
  hit.ns = ng;
  if (tri.has_vertex_normals) {
    const Vec3 n = b0 * tri.n0 + b1 * tri.n1 + b2 * tri.n2;
    const double len = glm::length(n);
    if (len > 0 && std::isfinite(len)) hit.ns = n / len;
  }
  hit.material = tri.material;
}


// How far to move a secondary ray's origin off a surface point reached after distance t,
// where `magnitude` is the size of the coordinates the point was computed from (|p|; for a
// sphere |c| + r, for a triangle its largest vertex coordinate). Rounding puts the point within
// a few ulps of (magnitude + t) of the true surface; the offset is 1e7 times that, yet only
// 1e-9 of the scene's coordinates, so contact shadows keep their size.
inline double surface_offset(double magnitude, double t) { return 1e-9 * (magnitude + t); }
inline double surface_offset(const Vec3& p, double t) { return surface_offset(max_abs(p), t); }

// The same for a ray leaving `hit`, from bounds of each primitive's rounding errors rather
// than one magnitude for all. Two kinds of error meet there. (a) Absolute coordinates: P, and
// the differences o - c (sphere), point - o (plane), v - o (triangle) the next test forms from
// the offset origin, are rounded to a few ulps of the coordinates involved (the sphere's centre and radius,
// the plane's stored point, the vertices, P itself); kCoordinateMargin covers 4096 ulps of them.
// (b) Sizes: the next test's own error is relative to what it computes with once those
// differences are formed: the radius, the distance t travelled; kSizeMargin is the 1e-9 of
// surface_offset. Splitting them keeps the offset at 1e-12 of the coordinates far from the
// origin (a unit scene moved 1e5 away: 1e-7, not 1e-4 of its size, docs/accuracy.md O5) while a huge
// sphere still gets 1e-9 of its radius (S3).
inline constexpr double kCoordinateMargin = 0x1p-40;  // 9.1e-13 = 4096 ulps of a coordinate
inline constexpr double kSizeMargin = 1e-9;
inline double surface_offset(const Scene& scene, const Hit& hit) {
  switch (hit.object.kind) {
    case ObjectRef::Kind::kSphere: {  // |P| <= |C| + r
      const Sphere& s = scene.spheres[static_cast<std::size_t>(hit.object.index)];
      return kCoordinateMargin * (max_abs(s.center) + s.radius) + kSizeMargin * (s.radius + hit.t);
    }
    case ObjectRef::Kind::kPlane: {
      const Plane& pl = scene.planes[static_cast<std::size_t>(hit.object.index)];
      return kCoordinateMargin * std::max(max_abs(hit.p), max_abs(pl.point)) + kSizeMargin * hit.t;
    }
    case ObjectRef::Kind::kTriangle:  // magnitude: the largest vertex coordinate, >= |P|
    case ObjectRef::Kind::kMesh:
      return kCoordinateMargin * hit.magnitude + kSizeMargin * hit.t;
    case ObjectRef::Kind::kNone:
      break;
  }
  return surface_offset(hit.magnitude, hit.t);
}

// Origin for a ray leaving the surface with geometric normal ng at p, towards dir.
inline Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir, double offset) {
  return glm::dot(dir, ng) >= 0 ? p + offset * ng : p - offset * ng;
}

}  // namespace phonglab
