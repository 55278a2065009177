#include "core/accel/accel.h"

namespace phonglab {

std::optional<Hit> intersect_all(const Scene& scene, const Ray& ray, double t_max) {
  double best = t_max;
  ObjectRef obj;
  double best_b1 = 0, best_b2 = 0;
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    if (const double t = sphere_root(scene.spheres[i], ray.origin, ray.dir, 0, best); t > 0) {
      best = t;
      obj = {ObjectRef::Kind::kSphere, static_cast<int>(i)};
    }
  }
  if (const int i = nearest_plane(scene.planes, ray, best); i >= 0) obj = {ObjectRef::Kind::kPlane, i};
  if (scene.triangles.empty() && scene.meshes.empty()) {
    if (obj.kind == ObjectRef::Kind::kNone) return std::nullopt;
    return make_hit(scene, ray, obj, best, 0, 0);
  }
  const TriangleShear shear = make_shear(ray.dir);
  const auto test_triangles = [&](const std::vector<Triangle>& tris, ObjectRef::Kind kind, int index) {
    if (const int i = nearest_triangle(tris, ray, shear, best, best_b1, best_b2); i >= 0) {
      obj = kind == ObjectRef::Kind::kMesh ? ObjectRef{kind, index, i} : ObjectRef{kind, i};
    }
  };
  test_triangles(scene.triangles, ObjectRef::Kind::kTriangle, -1);
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    test_triangles(scene.meshes[m].geometry->triangles, ObjectRef::Kind::kMesh, static_cast<int>(m));
  }
  if (obj.kind == ObjectRef::Kind::kNone) return std::nullopt;
  return make_hit(scene, ray, obj, best, best_b1, best_b2);
}

bool occluded_all(const Scene& scene, const Ray& ray, double t_max) {
  for (const Sphere& s : scene.spheres) {
    if (sphere_root(s, ray.origin, ray.dir, 0, t_max) > 0) return true;
  }
  if (any_plane(scene.planes, ray, t_max)) return true;
  if (scene.triangles.empty() && scene.meshes.empty()) return false;
  const TriangleShear shear = make_shear(ray.dir);
  if (any_triangle(scene.triangles, ray, shear, t_max)) return true;
  for (const Mesh& mesh : scene.meshes) {
    if (any_triangle(mesh.geometry->triangles, ray, shear, t_max)) return true;
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
    case ObjectRef::Kind::kTriangle:
    case ObjectRef::Kind::kMesh: {
      const Triangle& tri = triangle_of(scene, obj);
      triangle_hit_record(tri, triangle_normal(tri), triangle_magnitude(tri), b1, b2, hit);
      break;
    }
    case ObjectRef::Kind::kNone:
      break;
  }
  return hit;
}

}  // namespace phonglab
