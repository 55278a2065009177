// The hot loops of the packet tracer (src/core/packet/packet.cpp): its kernels, many rays at a
// time, over the data declared here. The kernels themselves are declared in packet_kernel_list.h.
//
// One kernel source, many instances. The kernels are written once (packet_kernels_hits.cpp:
// intersections; packet_kernels_shading.cpp: hit records, camera rays, lights and their sums,
// bounces; packet_kernels_powers.cpp: whole specular powers) over a lane type and its operations
// (packet_simd_ops.h). Each instruction set builds them as one instance, in a namespace of its
// own: `avx2` (4 lanes) and `avx512` (8 lanes) on x86-64, `simd128` (4 lanes in two SIMD128
// registers) in the web page, `neon` (4 lanes in two NEON registers) on aarch64. The program
// calls the kernels in namespace packet, and packet_dispatch.cpp forwards each call to the
// instance chosen once for the CPU (packet_simd_target, packet.h). The instances' translation
// units must not define any inline or template function they share with the rest of the program
// (the linker could otherwise keep, say, its AVX-512 copy for everyone): they see only this
// header, which declares plain data and functions, and packet_simd_ops.h (operations with
// internal linkage, for them alone). A test checks their object files.
//
// Every kernel repeats, operation for operation, the scalar code it stands for (sphere_root,
// intersect_plane, camera_ray, the light loop of shade), with no fused multiply-add, so the
// packet tracer's image is bit-identical to the scalar renderer's on every instance.
#pragma once

#include <cstdint>

#include "core/packet/packet_lanes.h"

namespace phonglab::packet {

// Structure-of-arrays views. Lane counts are multiples of kBatchLanes; lanes past the live ones
// hold finite padding and their results are ignored.
struct Rays {
  const double *ox, *oy, *oz;
  const double *dx, *dy, *dz;
};

struct Spheres {
  const double *cx, *cy, *cz, *r;  // every sphere of the scene, by index
  const double* offset_base;  // the coordinate part of surface_offset: margin (max|c| + r)
  // The spheres a query tests, in increasing order: all, or those a batch's rays can meet.
  const std::int32_t* tested;
  int tested_count;
  int count;  // all spheres
};

struct Planes {
  const double *px, *py, *pz;  // stored point
  const double *nx, *ny, *nz;  // unit normal
  const double* point_size;    // max|point|
  int count;
};

// Hit records (make_hit, hit_side and surface_offset) of the lanes whose nearest hit is a
// sphere or a plane (id as `nearest` leaves it); other lanes are left as they are.
struct HitRecords {
  double *px, *py, *pz;  // P
  double *nx, *ny, *nz;  // N, facing the ray
  double *gx, *gy, *gz;  // geometric normal, facing the ray
  double *vx, *vy, *vz;  // V = -D
  double* offset;        // surface_offset(scene, hit)
  std::uint8_t* entering;
};
struct OffsetMargins {
  double coordinate, size;  // kCoordinateMargin, kSizeMargin (geometry.h)
};

// triangle_hit_record, hit_side and surface_offset of the lanes whose nearest hit is one of a
// brute-force scene's loose triangles without vertex normals (id in [first_id, first_id + count)
// and `flat` set): P interpolated from the vertices, Ng = N = its unit normal facing the ray,
// V = -D, offset kCoordinateMargin * magnitude + kSizeMargin * t. Other lanes are left as they are.
struct TriangleRecords {
  const double* vertices;    // the first triangle's v0.x (Triangle's layout)
  long stride;
  const double* normal;      // triangle_normal of triangle k at normal[3 k .. 3 k + 2]
  const double* magnitude;   // triangle_magnitude of each
  const std::uint8_t* flat;  // 1: no vertex normals (these lanes are the kernel's)
  int count;
  int first_id;
};

// camera_ray for pixels (x + u, y + v): directions only (the origin is the eye).
struct CameraIn {
  double fx, fy, fz;  // forward
  double rx, ry, rz;  // right, scaled
  double ux, uy, uz;  // up, scaled
  double width, height;
};

// One light at a batch of shaded points: the light loop of shade() up to the shadow query.
struct LightIn {
  bool point;            // point light at (x, y, z); otherwise L = (x, y, z) = -direction
  double x, y, z;
  double shrink;         // point lights: surface_offset(position, 0), taken off the far end
  bool blinn;            // specular model: Blinn's N.H instead of Phong's R.V
};
struct ShadedPoints {
  const double *px, *py, *pz;  // P
  const double *nx, *ny, *nz;  // N, facing the incoming ray
  const double *gx, *gy, *gz;  // geometric normal on the same side
  const double *vx, *vy, *vz;  // V
  const double* offset;        // surface_offset of each point
  const std::uint8_t* active;  // lanes to compute (others' outputs are left as they are)
};
struct LightOut {
  double* n_dot_l;   // N.L; NaN where a point light sits exactly on P (no direction)
  double* cos_spec;  // R.V (Phong) or N.H (Blinn), before clamping
  double *ox, *oy, *oz, *dx, *dy, *dz;  // the shadow ray
  double* t_max;     // its far end; not > 0: the light is within rounding distance (visible)
  // Optional (null: not written): each lane's shadow ray, 0 where the light gives no term (an
  // inactive lane, N.L not > 0), 1 where it is seen without a ray, 2 where the ray is to be
  // tested. With it, t_max is set to 0 wherever no ray is to be tested, inactive lanes included.
  std::uint8_t* shadow = nullptr;
};
// With `out.shadow`: how many lanes the light gives a term (shadow 1 or 2), and how many of them
// have a ray to test (2); zeros without it.
struct ShadowCounts {
  int lit = 0, tested = 0;
};

// Colours as structure of arrays: one per material (read) or one per lane (written).
struct ByMaterial {
  const double *r, *g, *b;
};
struct ColorLanes {
  double *r, *g, *b;
};

// Terms::sum of every hit (id >= 0) among lanes [0, live): (((ambient + diffuse) + specular) +
// reflection) + refraction, the ambient of the lane's material, a null reflection or refraction
// standing for zeros. Written as colours (r, g, b of lane i at out[3 i ..]); misses are left.
struct TermLanes {
  ColorLanes diffuse, specular;
  const ColorLanes* reflection;
  const ColorLanes* refraction;
};

// bounce() at a batch of mirror and glass hits: the geometry of the children and the exact
// Fresnel reflectance (the weights kr', kt' are left to the caller).
struct BounceIn {
  const double *dx, *dy, *dz;  // the incoming ray's direction D
  const double *nx, *ny, *nz;  // N, facing D
  const double* ior;           // the material's index of refraction
  const std::uint8_t* entering;
  const std::uint8_t* active;  // lanes to compute (others' outputs are left as they are)
};
struct BounceOut {
  double* eta;        // n_incident / n_transmitted
  double* fresnel;    // fresnel_exact(cos_i, eta), 1 under total internal reflection
  std::uint8_t* tir;  // total internal reflection
  double *mx, *my, *mz;  // reflected direction
  double *tx, *ty, *tz;  // transmitted direction (the reflected one under TIR)
};

// A bounding volume hierarchy for packets of rays (the scene's SceneBvh, bvh.h and accel.h).
// Node is BvhNode's layout (box lo, box hi, first, count, axis); packet.cpp checks that it is.
struct Node {
  double box[6];  // lo x, y, z, then hi x, y, z
  std::uint32_t first, count, axis;
};
struct MeshTree {
  const Node* nodes;       // the mesh's BVH; its leaves index its triangles directly
  const double* vertices;  // the first triangle's v0.x; v1 and v2 follow v0, as in Triangle
};
struct Hierarchy {
  const Node* top;                  // the top level over spheres, loose triangles and meshes
  const std::uint8_t* prim_kind;    // by top-level leaf slot: 0 sphere, 1 loose triangle, 2 mesh
  const std::int32_t* prim_index;   // by top-level leaf slot: index among its kind
  const double *cx, *cy, *cz, *r;   // spheres, by index
  const double* triangles;          // the first loose triangle's v0.x
  const MeshTree* meshes;           // by mesh index
  long triangle_stride;             // doubles from one Triangle's v0.x to the next's
  int triangle_id;                  // id of loose triangle 0 (spheres + planes); mesh m: mesh_id + m
  int mesh_id;
  double far_widen, t_max_slack;    // hits_box's kBoxFarWiden and kBoxTmaxSlack
};

// SceneBvh::intersect without its planes, for lanes [0, live) (the others are skipped): each
// lane walks the hierarchy in the order its own traversal would (near child first by its signs,
// lanes of different signs in turn) and tests exactly the primitives it would. On entry t, id
// hold each lane's nearest plane hit (+inf, -1 for none); on return the nearest hit (ties
// between triangles to the first in the scene's order), with a mesh's triangle in `prim` and a
// triangle's barycentric weights of v1 and v2 in b1, b2. Lanes whose answer is unchanged keep
// their id and prim.
struct NearestHits {
  double* t;
  std::int32_t* id;
  std::int32_t* prim;
  double *b1, *b2;
};

// A brute-force scene's loose triangles (Triangle's layout: v0, v1, v2 from `vertices` on, the
// next triangle `stride` doubles further), tested many rays at a time as nearest_triangle and
// any_triangle test them one ray at a time.
struct LooseTriangles {
  const double* vertices;  // the first triangle's v0.x
  long stride;
  int count;
  int first_id;            // id of triangle 0 (spheres + planes)
  // The triangles a query tests, in increasing order: all, or those a batch's rays can meet.
  const std::int32_t* tested;
  int tested_count;
};

}  // namespace phonglab::packet

// The kernels as the program calls them (packet_dispatch.cpp) and, in a kernel translation unit,
// as its instance defines them.
namespace phonglab::packet {
#include "core/packet/packet_kernel_list.h"
}  // namespace phonglab::packet
#if defined(PHONGLAB_SIMD_NS)
namespace phonglab::packet::PHONGLAB_SIMD_NS {
#include "core/packet/packet_kernel_list.h"
}  // namespace phonglab::packet::PHONGLAB_SIMD_NS
#endif
