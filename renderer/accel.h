// Acceleration: each mesh keeps its own BVH, built once when it is loaded; prepare_scene builds
// a small top-level BVH over the spheres, loose triangles and mesh boxes, so an edit rebuilds
// only that. Planes are infinite and stay outside every box.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "renderer/bvh.h"
#include "renderer/geometry.h"
#include "renderer/scene.h"

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

// The default accelerator: top-level BVH over spheres, triangles and meshes; null (brute force)
// for scenes of a few spheres and triangles and no mesh, unless `force_bvh` (benchmarks).
std::shared_ptr<const Accelerator> build_scene_accel(const Scene& scene, bool force_bvh = false);

// Bounds of everything but planes (empty when there is nothing else).
Aabb scene_bounds(const Scene& scene);

// The triangle an ObjectRef of kind kTriangle or kMesh names.
const Triangle& triangle_of(const Scene& scene, const ObjectRef& obj);

}  // namespace phonglab
