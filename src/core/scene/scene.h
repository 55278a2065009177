// The scene as plain data: what a scene file says, with the defaults of docs/scene-format.md,
// and nothing derived from it (the accelerator lives in PreparedScene, core/accel). Objects refer
// to materials by index. Copying a Scene is a cheap snapshot (meshes are shared).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/math.h"

namespace phonglab {

// Pinhole camera (docs/model.md, camera and samples).
struct Camera {
  Vec3 position{0, 1.5, 6};  // eye, world units
  Vec3 look_at{0, 0.8, 0};   // point the view centre passes through
  Vec3 up{0, 1, 0};          // roughly up; must not be parallel to the view direction
  double fov_y_deg = 40;     // full vertical field of view, degrees, in (0, 180)
  bool operator==(const Camera&) const = default;
};

enum class LightType : std::uint8_t { kPoint, kDirectional };

// A light without distance fall-off: its intensity arrives undiminished.
struct Light {
  LightType type = LightType::kPoint;
  Vec3 position{0, 0, 0};    // point lights: world position
  Vec3 direction{0, -1, 0};  // directional lights: unit direction the light travels in
  Color intensity{1, 1, 1};  // I_l, linear RGB
  bool enabled = true;       // previewer "mute"; a disabled light adds nothing and casts no rays
  bool operator==(const Light&) const = default;
};

// The lecture's coefficients. All colours are linear RGB, per channel.
struct Material {
  std::string name;        // key in the scene file's "materials" object
  Color ka{0, 0, 0};       // ambient reflectance
  Color kd{0, 0, 0};       // diffuse reflectance
  Color ks{0, 0, 0};       // specular reflectance
  double n = 32;           // Phong shininess exponent, >= 0
  Color kr{0, 0, 0};       // mirror reflection weight
  Color kt{0, 0, 0};       // transmission weight
  double ior = 1.5;        // index of refraction inside the object (outside is 1)
  bool fresnel = false;    // weight kr/kt by the exact unpolarised Fresnel reflectance
  std::string source{};    // empty: the scene file's; else the mesh file whose MTL made it
                           // (not written back by scene_to_json: the MTL holds it)
  bool operator==(const Material&) const = default;
};

enum class SpecularModel : std::uint8_t { kPhong, kBlinn };

// Bounces of the indirect light (the scene file's "indirect": {"bounces"}): default and range 1..max.
inline constexpr int kDefaultIndirectBounces = 4;
inline constexpr int kMaxIndirectBounces = 64;

struct Sphere {
  Vec3 center{0, 0, 0};
  double radius = 1;  // > 0
  int material = 0;   // index into Scene::materials
  bool operator==(const Sphere&) const = default;
};

// Infinite, two-sided plane; its outward side is the one `normal` points to.
struct Plane {
  Vec3 point{0, 0, 0};
  Vec3 normal{0, 1, 0};  // unit
  int material = 0;
  bool operator==(const Plane&) const = default;
};

// Two-sided triangle; Ng = normalize((v1-v0)x(v2-v0)).
struct Triangle {
  Vec3 v0{0}, v1{0}, v2{0};
  int material = 0;
  // Optional per-vertex shading normals (meshes with vertex normals).
  bool has_vertex_normals = false;
  Vec3 n0{0}, n1{0}, n2{0};
  bool operator==(const Triangle&) const = default;
};

// Where a mesh's OBJ coordinates go: scale, then rotations about x, then y, then z (degrees,
// right-handed), then translation.
struct MeshTransform {
  Vec3 scale{1, 1, 1};
  Vec3 rotate_deg{0, 0, 0};
  Vec3 translate{0, 0, 0};
  bool operator==(const MeshTransform&) const = default;
};

// A loaded mesh's world-space triangles and their bounding volume hierarchy: immutable and
// shared by every snapshot of the scene, so editing anything else never copies or rebuilds it.
struct MeshGeometry;

// How MTL's Ns becomes the lecture's n. MTL's highlight is Blinn's (N.H)^Ns; (R.V)^n with
// n = Ns / 4 gives about the same highlight under the Phong model.
enum class NsMapping : std::uint8_t { kAsIs, kBlinnToPhong };

// A "mesh" object of the scene file.
struct Mesh {
  std::string file;               // OBJ path as written in the scene file (relative to it)
  std::string resolved_path;      // absolute path it was read from; empty for embedded files
  std::string material_override;  // material name replacing the MTL's; empty: the MTL's
  MeshTransform transform;
  NsMapping ns = NsMapping::kAsIs;
  std::shared_ptr<const MeshGeometry> geometry;  // never null in a loaded scene
  bool operator==(const Mesh&) const = default;
};

// Which scene object a primitive came from (for picking and error messages).
struct ObjectRef {
  enum class Kind : std::uint8_t { kSphere, kPlane, kTriangle, kMesh, kNone };
  Kind kind = Kind::kNone;
  int index = -1;  // index into the matching Scene vector
  int prim = -1;   // kMesh: the triangle's index in its MeshGeometry
};

struct Scene {
  Camera camera;
  int width = 960;                    // image width, pixels
  int height = 540;                   // image height, pixels
  Color ambient{1, 1, 1};             // Ia
  Color background{0, 0, 0};          // radiance of rays that hit nothing
  int max_depth = 5;                  // recursion depth limit; 0 = local shading only
  double min_weight = 0.001;          // prune child rays whose path weight is below this
  SpecularModel specular_model = SpecularModel::kPhong;
  int indirect_bounces = kDefaultIndirectBounces;  // of the indirect light, 1..kMaxIndirectBounces
  std::vector<Light> lights;
  std::vector<Material> materials;
  std::vector<Sphere> spheres;
  std::vector<Plane> planes;
  std::vector<Triangle> triangles;
  std::vector<Mesh> meshes;
  // Index of the scene-file object each sphere/plane/triangle/mesh came from ("objects[i]").
  std::vector<int> sphere_object, plane_object, triangle_object, mesh_object;
  // objects[i]'s optional "name", by that index (the vector may be shorter: the rest have none).
  std::vector<std::string> object_names;
};

}  // namespace phonglab
