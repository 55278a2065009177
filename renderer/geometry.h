// Ray-primitive intersection: robust sphere, plane and watertight triangle tests, the
// nearest-hit query and the any-hit (shadow) query. Pure functions of the scene and a ray.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>

#include "renderer/math.h"
#include "renderer/scene.h"

namespace phonglab {

// A ray with unit direction.
struct Ray {
  Vec3 origin;
  Vec3 dir;  // unit length
};

// Makes a ray; `dir` must be unit length and finite.
inline Ray make_ray(const Vec3& origin, const Vec3& dir) { return Ray{origin, dir}; }

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

// Per-primitive tests: distance t > t_min of the nearest hit, or nothing. Never NaN.
std::optional<double> intersect_sphere(const Sphere& s, const Ray& ray, double t_min = 0);
std::optional<double> intersect_plane(const Plane& pl, const Ray& ray, double t_min = 0);
// Also gives the barycentric weights of v1 and v2.
std::optional<double> intersect_triangle(const Triangle& tri, const Ray& ray, double* b1 = nullptr,
                                         double* b2 = nullptr, double t_min = 0);
// The same with the ray's shear computed once for many triangles.
std::optional<double> intersect_triangle(const Triangle& tri, const Ray& ray, const TriangleShear& shear,
                                         double* b1, double* b2, double t_min = 0);

// Nearest hit with t in (0, t_max).
std::optional<Hit> intersect(const Scene& scene, const Ray& ray,
                             double t_max = std::numeric_limits<double>::infinity());

// Whether anything lies on the ray with t in (0, t_max). Stops at the first hit found.
bool occluded(const Scene& scene, const Ray& ray, double t_max);

// Fills a Hit for the primitive `obj` hit at distance t (used after the nearest-hit loop).
Hit make_hit(const Scene& scene, const Ray& ray, ObjectRef obj, double t, double b1, double b2);

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
// origin (a unit scene moved 1e5 away: 1e-7, not 1e-4 of its size, HARDCASES O5) while a huge
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
