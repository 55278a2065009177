// Wavefront OBJ/MTL meshes (through tinyobjloader) as triangles and lecture materials.
// Part of the phonglab_io library. The MTL mapping is documented in docs/scene-format.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "io/diagnostic.h"

namespace phonglab {

// Reads a file named relative to the OBJ's folder (an MTL); nullopt and `error` when it cannot.
using FileReader = std::function<std::optional<std::string>(const std::string& path, std::string& error)>;


// An emissive MTL material (Ke > 0): phonglab has point lights only, so it is a hint.
struct Emitter {
  std::string material;  // MTL material name
  Color ke{0};           // its emission
  Vec3 centroid{0};      // area-weighted centre of its faces, in the OBJ's coordinates
  int faces = 0;
};

// A triangle of an ObjIndexedMesh: indices of its corners in `vertices` and of their normals in
// `normals` (all three -1 for a flat face).
struct ObjIndexedTriangle {
  std::array<std::uint32_t, 3> v{};
  std::array<std::int32_t, 3> n{-1, -1, -1};
  int material = 0;  // index into `materials`
  int face = 0;      // the face it comes from (0-based, file order)
};

// An OBJ's mesh with its triangles indexed: shared vertices and normals and 32 bytes a
// triangle instead of 152. Scene loading places the vertices once and makes each Triangle once,
// in its BVH leaf slot.
struct ObjIndexedMesh {
  std::vector<Vec3> vertices;  // OBJ coordinates
  std::vector<Vec3> normals;
  std::vector<ObjIndexedTriangle> triangles;
  std::vector<Material> materials;
  std::vector<Emitter> emitters;
  int skipped_degenerate = 0;
  std::vector<Diagnostic> warnings;
  std::vector<Diagnostic> errors;
  Triangle triangle(std::size_t i) const;  // triangles[i] spelled out, in OBJ coordinates
};

// Called on the prescan's thread, while tinyobjloader still parses the file on the caller's, with
// the most triangles its faces can give (a fan for every face of 3 or more vertices; none when
// the prescan finds errors): callers can make room for them there, off the parse's path.
using TriangleCountHook = std::function<void(std::size_t max_triangles)>;

// Parses OBJ text; `read_mtl` resolves its mtllib names. Quads and n-gons are split into fans,
// negative (relative) indices are honoured, faces without normals are flat.
ObjIndexedMesh load_obj_indexed(const std::string& obj_text, const std::string& obj_name, const FileReader& read_mtl,
                                NsMapping ns = NsMapping::kAsIs, const TriangleCountHook& on_prescan = {});

// The material MTL-less faces get: a neutral grey (ka 0.1, kd 0.7, ks 0.2, n 32).
Material default_mesh_material();

}  // namespace phonglab
