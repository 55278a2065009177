// The hot loops of the packet tracer (src/core/packet/packet.cpp), four rays at a time with AVX2.
//
// They live in their own translation units (packet_avx2.cpp: intersections; packet_avx2_shading.cpp:
// hit records, camera rays, lights and their sums, bounces), compiled with -mavx2 and called only after a
// runtime check of the CPU, so the default build still runs on any x86-64 machine. Those units
// must not define any inline or template function they share with the rest of the program (the
// linker could otherwise keep its AVX2 copy for everyone): they see only this header, which
// declares plain data and functions, <immintrin.h> and packet_avx2_ops.h (operations with
// internal linkage, for them alone). A test checks their object files.
//
// Every kernel repeats, operation for operation, the scalar code it stands for (sphere_root,
// intersect_plane, camera_ray, the light loop of shade), with no fused multiply-add, so the
// packet tracer's image is bit-identical to the scalar renderer's.
#pragma once

#include <cstdint>

namespace phonglab::packet {

// Structure-of-arrays views. Lane counts are multiples of 4; lanes past the live ones hold
// finite padding and their results are ignored.
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

// Nearest sphere or plane with t in (0, t_best) for each lane, in the order of intersect_all
// (spheres, then planes). On entry t_best holds each lane's limit (+inf for a plain query); on
// return the nearest t, and id the sphere index, spheres.count + the plane index, or is left
// unchanged when nothing is nearer.
void nearest(const Spheres& spheres, const Planes& planes, const Rays& rays, int lanes, double* t_best,
             std::int32_t* id);

// Any sphere or plane with t in (0, t_max) (occluded_all): sets occluded[i] = 1 for those
// lanes and leaves the others as they are. Lanes whose t_max is not > 0 hold no ray.
void occluded(const Spheres& spheres, const Planes& planes, const Rays& rays, const double* t_max, int lanes,
              std::uint8_t* occluded);

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
void hit_records(const Spheres& spheres, const Planes& planes, const OffsetMargins& margins, const Rays& rays,
                 const double* t, const std::int32_t* id, int lanes, const HitRecords& out);

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
void triangle_records(const TriangleRecords& tris, const OffsetMargins& margins, const Rays& rays, const double* t,
                      const std::int32_t* id, const double* b1, const double* b2, int lanes, const HitRecords& out);

// camera_ray for pixels (x + u, y + v): directions only (the origin is the eye).
struct CameraIn {
  double fx, fy, fz;  // forward
  double rx, ry, rz;  // right, scaled
  double ux, uy, uz;  // up, scaled
  double width, height;
};
void camera_dirs(const CameraIn& cam, const double* x_plus_u, const double* y_plus_v, int lanes, double* dx,
                 double* dy, double* dz);

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
ShadowCounts light(const LightIn& light, const ShadedPoints& pts, int lanes, const LightOut& out);

// Colours as structure of arrays: one per material (read) or one per lane (written).
struct ByMaterial {
  const double *r, *g, *b;
};
struct ColorLanes {
  double *r, *g, *b;
};

// One light's terms added where it is seen (shade()'s light loop after the shadow query): for
// the lanes with seen[i] set, diffuse += (I_l kd) N.L and specular += (I_l ks) spec, with I_l kd
// and I_l ks of the lane's material. Other lanes, and their material entries, are not read.
void add_light(const ByMaterial& kd, const ByMaterial& ks, const std::int32_t* material, const std::uint8_t* seen,
               const double* n_dot_l, const double* spec, int lanes, const ColorLanes& diffuse,
               const ColorLanes& specular);

// The specular factor (specular_factor: max(0, cos)^n) of the lanes where `seen` is set, by
// material: power[m] is a whole n in [1, 4096] that this kernel raises to, 0 for a material
// without ks (factor 0), or -1 (std::pow). Writes spec where the value is certainly std::pow's
// double (packet_pow_fma.cpp says why) and sets pending[i] = 1 on the seen lanes left to the
// caller's std::pow (about one in five of a whole n's, every lane of -1, and lanes of mixed
// materials), 0 elsewhere. Built with FMA: call only where the CPU has it (packet_fma_supported).
void specular_powers(const double* cos_spec, const std::int32_t* material, const int* power,
                     const std::uint8_t* seen, int lanes, double* spec, std::uint8_t* pending);

// The box of the hit points (lanes [0, live) whose id is >= 0; a NaN coordinate is passed
// over) and their largest offset: out = lo x, y, z, hi x, y, z, the offset (+inf, -inf and 0
// with no hit).
void hit_bounds(const double* px, const double* py, const double* pz, const double* offset, const std::int32_t* id,
                int live, double* out);

// Terms::sum of every hit (id >= 0) among lanes [0, live): (((ambient + diffuse) + specular) +
// reflection) + refraction, the ambient of the lane's material, a null reflection or refraction
// standing for zeros. Written as colours (r, g, b of lane i at out[3 i ..]); misses are left.
struct TermLanes {
  ColorLanes diffuse, specular;
  const ColorLanes* reflection;
  const ColorLanes* refraction;
};
void sum_terms(const ByMaterial& ambient, const std::int32_t* material, const std::int32_t* id,
               const TermLanes& terms, int live, double* out);

// The box of the origins, and of the directions, of the rays in lanes [0, live) whose t_max is
// > 0 (every one when t_max is null): out = lo x, y, z, hi x, y, z of the origins, then of the
// directions. With no such ray, lo is +inf and hi -inf.
void ray_bounds(const Rays& rays, const double* t_max, int live, double* out);

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
void bounce(const BounceIn& in, int lanes, const BounceOut& out);

// A bounding volume hierarchy for packets of four rays (the scene's SceneBvh, bvh.h and accel.h).
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
void hierarchy_nearest(const Hierarchy& h, const Rays& rays, int live, const NearestHits& out);

// SceneBvh::occluded without its planes: sets occluded[i] = 1 for the lanes that anything blocks
// within (0, t_max). Lanes whose t_max is not > 0, or that are occluded already, are skipped.
void hierarchy_occluded(const Hierarchy& h, const Rays& rays, const double* t_max, int lanes,
                        std::uint8_t* occluded);

// A brute-force scene's loose triangles (Triangle's layout: v0, v1, v2 from `vertices` on, the
// next triangle `stride` doubles further), tested four rays at a time as nearest_triangle and
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

// nearest_triangle for lanes [0, live): where a triangle is strictly nearer than t (ties go to
// what came first: spheres, planes, then triangles in order), t, id (first_id + k), b1 and b2
// are replaced; prim is left alone.
void triangles_nearest(const LooseTriangles& tris, const Rays& rays, int live, const NearestHits& out);

// any_triangle within (0, t_max): sets occluded[i] = 1 for the lanes a triangle blocks. Lanes
// whose t_max is not > 0, or that are occluded already, are skipped.
void triangles_occluded(const LooseTriangles& tris, const Rays& rays, const double* t_max, int lanes,
                        std::uint8_t* occluded);

}  // namespace phonglab::packet
