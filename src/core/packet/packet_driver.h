// The packet tracer's driver (internal to src/core/packet): PacketTracer::Impl, its batch
// buffers and the scene's data as the kernels read it. Its stages are defined in packet.cpp (set-up,
// the levels, hits, children) and packet_lights.cpp (the light loop, the shadow queries and the
// culling of what both test).
#pragma once

#include <cstdint>
#include <vector>

#include "core/accel/accel.h"
#include "core/geometry/geometry.h"
#include "core/packet/packet.h"
#include "core/packet/packet_batches.h"
#include "core/packet/packet_kernels.h"

namespace phonglab {

struct PacketTracer::Impl {
  using Level = packet_driver::Level;
  using RayBatch = packet_driver::RayBatch;
  using MaterialInfo = packet_driver::MaterialInfo;
  using MaterialColors = packet_driver::MaterialColors;

  const PreparedScene& prepared;
  const Scene& scene;
  TraceLimits limits;
  // The scene's spheres and planes as arrays for the kernels.
  std::vector<double> cx, cy, cz, radius, sphere_offset;
  std::vector<double> plx, ply, plz, pnx, pny, pnz, plane_size;
  std::vector<int> prim_material;  // by kernel id (spheres, then planes, then triangles)
  std::vector<std::int32_t> every_sphere, primary_tested, shadow_tested;
  std::vector<std::int32_t> every_triangle, triangles_tested;  // loose triangles, as the spheres'
  std::vector<std::int32_t> primary_triangles_tested;
  packet::LooseTriangles primary_loose{};  // the loose triangles the tile's primary rays can meet
  packet::Spheres spheres{};
  packet::Planes planes{};
  // With a SceneBvh: the spheres, loose triangles and meshes are found through it (planes are
  // tested before it, as SceneBvh does), and no sphere is culled.
  bool walk_hierarchy = false;
  packet::Hierarchy hierarchy{};
  // Without one: the loose triangles, tested four rays at a time after the spheres and planes.
  packet::LooseTriangles loose{};
  std::vector<Vec3> loose_normal;        // triangle_normal of each loose triangle, computed once
  std::vector<double> loose_magnitude;   // and its triangle_magnitude
  std::vector<std::uint8_t> loose_flat;  // 1: no vertex normals (its hit record is the kernel's)
  packet::TriangleRecords loose_records{};
  std::vector<std::uint8_t> top_kind;
  std::vector<std::int32_t> top_index;
  std::vector<packet::MeshTree> mesh_trees;
  int mesh_id = 0;  // id of mesh 0
  std::vector<MaterialInfo> info;
  // packet::specular_powers' exponent by material (whole_power_exponent; 0 without ks, -1 for
  // std::pow); empty where the CPU has no FMA.
  std::vector<int> power;
  MaterialColors light_kd, light_ks;  // I_l * kd and I_l * ks, per light and material
  MaterialColors ambient;             // ka * Ia per material
  std::vector<Level> levels;
  RayBatch primary;
  std::vector<double> x_plus_u, y_plus_v;
  // What the primary hits give (render_tile's term), what they must compute for it, and the eye
  // V points to there (null: -D).
  Term primary_term = Term::kFull;
  TermsWanted primary_wanted;
  const Vec3* shading_eye = nullptr;
  Terms* primary_terms = nullptr;  // where the primary hits' five terms go (render_tile's terms_out)
  PacketTreeSink* sink = nullptr;  // recording the trees (record_tile)
  // The primary rays and nearest hits of the last find_surfaces, by lane, for shade_found; and
  // the spheres those rays can meet.
  struct Found {
    std::vector<double> ox, oy, oz, dx, dy, dz, weight, t, b1, b2;
    std::vector<std::int32_t> id, prim;
    packet::Spheres tested{};
    int n = 0;
  } found;

  explicit Impl(const PreparedScene& p);

  void set_up_hierarchy(const SceneBvh& bvh);

  // The spheres the brute-force kernels test themselves: none when the hierarchy holds them.
  packet::Spheres no_spheres() const;

  int material_of(std::int32_t id, std::int32_t prim) const;

  ObjectRef object_of(std::int32_t id, std::int32_t prim) const;

  // The spheres the primary rays of image region [x0, x1] x [y0, y1] can meet: the rays share
  // the eye and lie in the cone of the region's corner rays (axis a, half-angle theta); a sphere
  // of angular radius alpha whose centre is more than theta + alpha off the axis meets none.
  // The margin (1e-6 rad) is far beyond rounding, so culling never changes a hit.
  packet::Spheres primary_spheres(const CameraFrame& f, int x0, int y0, int x1, int y1);

  // The loose triangles the primary rays of image region [x0, x1] x [y0, y1] can meet: the rays
  // share the eye and their directions lie in the convex hull of the region's corner rays (before
  // normalising), so a triangle is passed over when that hull lies strictly outside one of the
  // planes through the eye and its edges, or when every corner leaves its plane. The margins
  // dwarf rounding, so culling never changes a hit.
  packet::LooseTriangles primary_triangles(const CameraFrame& f, int x0, int y0, int x1, int y1);

  // The spheres shadow rays from points within the ball (b, ball) towards `light` can meet:
  // the rays lie within `ball` of the segment from b to a point light (of the ray from b along
  // L for a directional one), so a sphere farther than its radius + `ball` from that segment
  // meets none. The margins dwarf rounding, so culling never changes an answer.
  packet::Spheres shadow_spheres(const Vec3& b, double ball, const Light& light, const Vec3& l);

  // The loose triangles a batch of rays can meet: a triangle whose plane has every ray's origin
  // and far end strictly on one side meets none of them. The far end is `light` for shadow rays
  // towards it; without a light, each ray's whole half-line (its direction leaves the plane).
  // The origins of rays leaving the triangle itself lie surface_offset off its plane, at least
  // 2^-40 of its largest coordinate; the margin, 2^-42 of the coordinates involved, is half that
  // and still hundreds of ulps above the rounding of the side test and of the triangle test, and a
  // direction leaves the plane only with a cosine above 1e-12 (its rounding is 1e-15), so culling
  // never changes an answer. Shadow rays may bring a box of their origins known beforehand
  // (`origins`, holding every origin; the rays' own bounds are taken otherwise).
  packet::LooseTriangles triangles_met(const packet::Rays& rays, const double* t_max, int lanes, const Light* light,
                                       const Aabb* origins = nullptr);

  // The nearest hit of every ray: spheres and planes in the kernel, then the scene's few loose
  // triangles, in intersect_all's order.
  // `triangles`: the loose triangles the rays can meet when known (the primary rays'), else
  // triangles_met finds them.
  void find_hits(Level& lv, const RayBatch& rays, const packet::Spheres& tested,
                 const packet::LooseTriangles* triangles = nullptr);

  // occluded() for the shadow rays of the lanes marked kTest (the others have t_max = 0).
  void test_shadows(Level& lv, int lanes, const packet::Spheres& tested, const Light& light);

  // Sets blocked[i] = 1 for the lanes that something blocks within (0, t_max[i]); for shadow
  // rays towards `light`, only the loose triangles they can meet are tested (`origins`: a box
  // known to hold their origins, or null).
  void any_hits(const packet::Rays& rays, const double* t_max, int lanes, const packet::Spheres& tested,
                std::uint8_t* blocked, const Light* light = nullptr, const Aabb* origins = nullptr);

  // The light loop of shade() for every hit of the level, one light at a time. The light kernel
  // writes each lane's Shadow as the byte it is (0, 1, 2).
  void shade_lights(Level& lv, int lanes, RayCounts& counts);

  // Where the light just tested is seen (lit, and its shadow ray seen or not needed), with the
  // specular factor there (zero for a material without ks); returns how many lanes see it.
  // Four lanes at a time as the bytes of a word: seen = lit & (shadow 1, or shadow 2 and not
  // blocked), every byte 0 or 1 (lit is 0 past the live lanes; blocked is read only where a ray
  // was tested).
  int mark_seen(Level& lv, int lanes) const;

  // One light at every hit of the level, as the scalar tracer tells its recorder.
  void record_light(const Level& lv, int lanes, int li);

  // The level's rays that missed and its hits, told to the sink (record_tile).
  void record_hits(Level& lv, const RayBatch& rays, int depth, TraceRecorder::Child kind);

  // The primary rays of pixels [x0, x1) x [y0, y1) (sample `sample_index`), row by row; returns
  // the spheres they can meet.
  packet::Spheres primary_rays(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::uint32_t sample_index,
                    std::uint32_t seed);
  // The camera rays of the lanes' x + u, y + v, and what the region's primary rays can meet.
  packet::Spheres finish_primary(const CameraFrame& frame, int x0, int y0, int x1, int y1, int n);
  // What the primary hits give: `term`'s value, and with `terms_out` their five terms; V towards
  // `eye` (null: -D).
  void aim_primary(Term term, const Vec3* eye, Terms* terms_out);
  // Radiance of every ray of `rays` (at recursion depth `depth`) into out[0 .. rays.n); `tested`:
  // the spheres those rays can meet.
  // `hits_found`: the level's nearest hits are already in place (shade_found's batch).
  void trace_level(int depth, const RayBatch& rays, const packet::Spheres& tested, Color* out, RayCounts& counts,
                   TraceRecorder::Child kind = TraceRecorder::Child::kReflection, bool hits_found = false);

  // The reflection and refraction terms of the level's hits: kr' and kt' times what their
  // children brought back, zero where none was traced.
  void children_terms(Level& lv, int lanes);

  // The primary hits' values when a term other than the full image is drawn, or the five terms
  // are kept (render_tile's terms_out): lane by lane, through Terms.
  void primary_terms_out(const Level& lv, int lanes, bool children, Color* out) const;

  // shade()'s V at a primary hit when the eye has moved ("move your head"): towards the eye; an
  // eye exactly at P has no direction and keeps -D.
  void look_from_eye(Level& lv, int i) const;

  // Whether the kernels wrote the hit record of a hit on triangle-or-mesh `id`: a loose
  // triangle without vertex normals.
  bool kernel_recorded(std::int32_t id) const;

  // A triangle's hit record (a mesh's, or loose with vertex normals), by the scalar functions;
  // a loose triangle's normal and magnitude come from those computed once.
  void record_triangle_hit(Level& lv, const RayBatch& rays, int i);

  // Reflected and refracted rays of the level's mirror and glass hits, traced as the next
  // level's two batches (shade()'s recursion, with its path-weight pruning), for the lanes marked
  // in `bounces` (at the primary hits, only the children whose terms are `wanted`).
  void send_children(Level& lv, const RayBatch& rays, int lanes, int depth, const TermsWanted& wanted,
                     RayCounts& counts);
};

}  // namespace phonglab
