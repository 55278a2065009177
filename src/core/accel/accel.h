// Acceleration: each mesh keeps its own BVH, built once when it is loaded; PreparedScene builds
// a small top-level BVH over the spheres, loose triangles and mesh boxes, so an edit rebuilds
// only that. Planes are infinite and stay outside every box.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <memory>
#include <vector>

#include "core/accel/bvh.h"
#include "core/geometry/geometry.h"
#include "core/scene/scene.h"

namespace phonglab {

struct MeshGeometry {
  std::vector<Triangle> triangles;  // world space, in BVH leaf order
  std::vector<int> source_face;     // each triangle's face in the OBJ (0-based, file order; a polygon's fan shares it)
  Bvh bvh;                          // over `triangles`; bvh.order is the identity
  Aabb bounds;                      // of all triangles
  double build_seconds = 0;         // wall-clock time make_mesh_geometry took
  std::size_t memory_bytes() const;
};

// Builds a mesh's BVH and puts its triangles in leaf order. `source_face[i]` names triangle i.
std::shared_ptr<const MeshGeometry> make_mesh_geometry(std::vector<Triangle> triangles,
                                                       std::vector<int> source_face);

// The same for triangles made on demand: `make(i)` gives triangle i (it is called from two
// threads at once for large meshes, in its leaf slot, and for its box unless `box_of` gives
// that), `source_face[i]` names it. No array of the triangles in any other order is made.
// `room`, when it holds `count` triangles or more, becomes the array of triangles (so that it can
// be allocated and first touched ahead, on another thread: 0.15 s for 1.3M triangles).
// `box_of(i)`, when given, must equal triangle_bounds(make(i)) bit for bit, cheaper.
std::shared_ptr<const MeshGeometry> make_mesh_geometry(std::size_t count, const std::function<Triangle(std::size_t)>& make,
                                                       std::vector<int> source_face, std::vector<Triangle> room = {},
                                                       const std::function<Aabb(std::size_t)>& box_of = {});

// The default accelerator: a BVH over the spheres, the loose triangles and the meshes' boxes, whose
// mesh leaves lead into each mesh's own BVH. Planes are tested before it, each in turn.
class SceneBvh final : public Accelerator {
 public:
  // A top-level primitive: what kind it is and its index in the scene's vector of that kind.
  struct TopPrim {
    ObjectRef::Kind kind;
    int index;
  };

  explicit SceneBvh(const Scene& scene);
  std::optional<Hit> intersect(const Scene& scene, const Ray& ray, double t_max) const override;
  bool occluded(const Scene& scene, const Ray& ray, double t_max) const override;
  bool matches(const Scene& scene) const override;

  // The top level, for tracers that walk it themselves (the packet tracer).
  const Bvh& top() const { return top_; }
  const std::vector<TopPrim>& prims() const { return prims_; }  // by top-level leaf slot

 private:
  // Boxes of the spheres, then the loose triangles, as matches() compares them.
  static std::vector<Aabb> top_level_boxes(const Scene& scene);

  std::vector<Aabb> boxes_;
  std::vector<const MeshGeometry*> meshes_;
  Bvh top_;
  std::vector<TopPrim> prims_;  // in leaf-slot order
  bool has_triangles_ = false;
};

// The default accelerator: top-level BVH over spheres, triangles and meshes; null (brute force)
// for scenes of a few spheres and triangles and no mesh, unless `force_bvh` (benchmarks).
std::shared_ptr<const Accelerator> build_scene_accel(const Scene& scene, bool force_bvh = false);

// Bounds of everything but planes (empty when there is nothing else).
Aabb scene_bounds(const Scene& scene);

// The triangle an ObjectRef of kind kTriangle or kMesh names.
const Triangle& triangle_of(const Scene& scene, const ObjectRef& obj);

// The nearest-hit and any-hit queries testing every primitive (mesh triangles one by one): the
// brute force of scenes without an accelerator, and the reference the acceleration structures
// are tested against. The queries of a prepared scene are in core/accel/prepared_scene.h.
std::optional<Hit> intersect_all(const Scene& scene, const Ray& ray,
                                 double t_max = std::numeric_limits<double>::infinity());
bool occluded_all(const Scene& scene, const Ray& ray, double t_max);

// Fills a Hit for the primitive `obj` hit at distance t (used after the nearest-hit loop).
Hit make_hit(const Scene& scene, const Ray& ray, ObjectRef obj, double t, double b1, double b2);

}  // namespace phonglab
