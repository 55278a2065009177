#include "core/geometry/geometry.h"

#include <utility>


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


std::optional<double> intersect_plane(const Plane& pl, const Ray& ray, double t_min) {
  const double denom = glm::dot(ray.dir, pl.normal);
  if (denom == 0) return std::nullopt;  // parallel: no gap guard, so no horizon gap
  const double t = glm::dot(pl.point - ray.origin, pl.normal) / denom;
  if (t > t_min && t < std::numeric_limits<double>::infinity()) return t;
  return std::nullopt;
}

int nearest_plane(const std::vector<Plane>& planes, const Ray& ray, double& best) {
  int nearest = -1;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    if (auto t = intersect_plane(planes[i], ray); t && *t < best) {
      best = *t;
      nearest = static_cast<int>(i);
    }
  }
  return nearest;
}

bool any_plane(const std::vector<Plane>& planes, const Ray& ray, double t_max) {
  for (const Plane& pl : planes) {
    if (auto t = intersect_plane(pl, ray); t && *t < t_max) return true;
  }
  return false;
}

int nearest_triangle(const std::vector<Triangle>& tris, const Ray& ray, const TriangleShear& shear, double& best,
                     double& b1, double& b2) {
  int nearest = -1;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    double u = 0, v = 0;
    if (auto t = intersect_triangle(tris[i], ray, shear, &u, &v); t && *t < best) {
      best = *t;
      b1 = u;
      b2 = v;
      nearest = static_cast<int>(i);
    }
  }
  return nearest;
}

bool any_triangle(const std::vector<Triangle>& tris, const Ray& ray, const TriangleShear& shear, double t_max) {
  for (const Triangle& tri : tris) {
    if (auto t = intersect_triangle(tri, ray, shear, nullptr, nullptr); t && *t < t_max) return true;
  }
  return false;
}

}  // namespace phonglab
