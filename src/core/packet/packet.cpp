// The packet tracer's driver: batches, culling, and the scalar steps between the AVX2 kernels.
#include "core/packet/packet.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "core/accel/accel.h"
#include "core/geometry/geometry.h"
#include "core/packet/packet_batches.h"
#include "core/packet/packet_kernels.h"

namespace phonglab {

bool packet_cpu_supported() {
#if defined(PHONGLAB_PACKET_AVX2)
  static const bool supported = __builtin_cpu_supports("avx2");
  return supported;
#else
  return false;
#endif
}

bool packet_tracing_applies(const PreparedScene& prepared) {
  const Accelerator* accel = prepared.accel();
  const bool walkable = accel ? dynamic_cast<const SceneBvh*>(accel) != nullptr : prepared.scene().meshes.empty();
  return !prepared.experiment() && walkable && packet_cpu_supported();
}

namespace {

// The kernels read BVH nodes and triangles in place, through plain structs of their own (the
// AVX2 unit sees no glm): the layouts must agree.
static_assert(std::is_standard_layout_v<BvhNode> && std::is_standard_layout_v<Aabb> && std::is_standard_layout_v<Vec3>);
static_assert(sizeof(Vec3) == 3 * sizeof(double) && offsetof(Aabb, lo) == 0 && offsetof(Aabb, hi) == sizeof(Vec3));
static_assert(sizeof(BvhNode) == sizeof(packet::Node) && offsetof(BvhNode, box) == offsetof(packet::Node, box) &&
              offsetof(BvhNode, first) == offsetof(packet::Node, first) &&
              offsetof(BvhNode, count) == offsetof(packet::Node, count) &&
              offsetof(BvhNode, axis) == offsetof(packet::Node, axis));
static_assert(std::is_standard_layout_v<Triangle> && offsetof(Triangle, v1) == offsetof(Triangle, v0) + sizeof(Vec3) &&
              offsetof(Triangle, v2) == offsetof(Triangle, v1) + sizeof(Vec3) && sizeof(Triangle) % sizeof(double) == 0);

const packet::Node* kernel_nodes(const Bvh& bvh) {
  return bvh.nodes.empty() ? nullptr : reinterpret_cast<const packet::Node*>(bvh.nodes.data());
}
const double* kernel_vertices(const std::vector<Triangle>& tris) { return tris.empty() ? nullptr : &tris[0].v0.x; }

using namespace packet_driver;  // RayBatch, Level, MaterialInfo (packet_batches.h)

}  // namespace

struct PacketTracer::Impl {
  const PreparedScene& prepared;
  const Scene& scene;
  TraceLimits limits;
  // The scene's spheres and planes as arrays for the kernels.
  std::vector<double> cx, cy, cz, radius, sphere_offset;
  std::vector<double> plx, ply, plz, pnx, pny, pnz, plane_size;
  std::vector<int> prim_material;  // by kernel id (spheres, then planes, then triangles)
  std::vector<std::int32_t> every_sphere, primary_tested, shadow_tested;
  std::vector<std::int32_t> every_triangle, triangles_tested;  // loose triangles, as the spheres'
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

  explicit Impl(const PreparedScene& p) : prepared(p), scene(p.scene()), limits{scene.max_depth, scene.min_weight} {
    for (const Sphere& sp : scene.spheres) {
      cx.push_back(sp.center.x);
      cy.push_back(sp.center.y);
      cz.push_back(sp.center.z);
      radius.push_back(sp.radius);
      sphere_offset.push_back(kCoordinateMargin * (max_abs(sp.center) + sp.radius));
      prim_material.push_back(sp.material);
    }
    for (const Plane& pl : scene.planes) {
      plx.push_back(pl.point.x);
      ply.push_back(pl.point.y);
      plz.push_back(pl.point.z);
      pnx.push_back(pl.normal.x);
      pny.push_back(pl.normal.y);
      pnz.push_back(pl.normal.z);
      plane_size.push_back(max_abs(pl.point));
      prim_material.push_back(pl.material);
    }
    for (const Triangle& tri : scene.triangles) prim_material.push_back(tri.material);
    for (std::size_t k = 0; k < cx.size(); ++k) every_sphere.push_back(static_cast<std::int32_t>(k));
    spheres = {cx.data(), cy.data(), cz.data(), radius.data(), sphere_offset.data(), every_sphere.data(),
               static_cast<int>(cx.size()), static_cast<int>(cx.size())};
    planes = {plx.data(), ply.data(), plz.data(), pnx.data(), pny.data(), pnz.data(), plane_size.data(),
              static_cast<int>(plx.size())};
    for (const Material& m : scene.materials) {
      MaterialInfo mi;
      mi.specular = !is_zero(m.ks);
      mi.lit = is_lit(m);
      mi.bounces = has_children(m);
      mi.n = m.n;
      mi.ior = m.ior;
      mi.ambient = m.ka * scene.ambient;
      info.push_back(mi);
      ambient.push(mi.ambient);
    }
    for (const Light& light : scene.lights) {
      for (const Material& m : scene.materials) {
        const LightProducts products = light_products(light, m);
        light_kd.push(products.kd);
        light_ks.push(products.ks);
      }
    }
    levels.resize(at(std::max(0, limits.max_depth)) + 1);
    mesh_id = static_cast<int>(prim_material.size());
    if (const auto* bvh = dynamic_cast<const SceneBvh*>(prepared.accel())) set_up_hierarchy(*bvh);
    for (const Triangle& tri : scene.triangles) {
      every_triangle.push_back(static_cast<std::int32_t>(loose_normal.size()));
      loose_normal.push_back(triangle_normal(tri));
      loose_magnitude.push_back(triangle_magnitude(tri));
      loose_flat.push_back(!tri.has_vertex_normals);
    }
    static_assert(sizeof(Vec3) == 3 * sizeof(double));
    loose_records = {kernel_vertices(scene.triangles), static_cast<long>(sizeof(Triangle) / sizeof(double)),
                     loose_normal.empty() ? nullptr : &loose_normal[0].x, loose_magnitude.data(), loose_flat.data(),
                     static_cast<int>(loose_normal.size()), spheres.count + planes.count};
    loose = {kernel_vertices(scene.triangles), static_cast<long>(sizeof(Triangle) / sizeof(double)),
             static_cast<int>(scene.triangles.size()), spheres.count + planes.count, every_triangle.data(),
             static_cast<int>(every_triangle.size())};
  }

  void set_up_hierarchy(const SceneBvh& bvh) {
    walk_hierarchy = true;
    for (const SceneBvh::TopPrim& p : bvh.prims()) {
      top_kind.push_back(p.kind == ObjectRef::Kind::kSphere ? 0 : p.kind == ObjectRef::Kind::kTriangle ? 1 : 2);
      top_index.push_back(p.index);
    }
    for (const Mesh& m : scene.meshes) {
      mesh_trees.push_back({kernel_nodes(m.geometry->bvh), kernel_vertices(m.geometry->triangles)});
    }
    hierarchy.top = kernel_nodes(bvh.top());
    hierarchy.prim_kind = top_kind.data();
    hierarchy.prim_index = top_index.data();
    hierarchy.cx = cx.data(), hierarchy.cy = cy.data(), hierarchy.cz = cz.data(), hierarchy.r = radius.data();
    hierarchy.triangles = kernel_vertices(scene.triangles);
    hierarchy.meshes = mesh_trees.data();
    hierarchy.triangle_stride = static_cast<long>(sizeof(Triangle) / sizeof(double));
    hierarchy.triangle_id = spheres.count + planes.count;
    hierarchy.mesh_id = mesh_id;
    hierarchy.far_widen = kBoxFarWiden;
    hierarchy.t_max_slack = kBoxTmaxSlack;
  }

  // The spheres the brute-force kernels test themselves: none when the hierarchy holds them.
  packet::Spheres no_spheres() const {
    packet::Spheres view = spheres;
    view.tested_count = 0;
    return view;
  }

  int material_of(std::int32_t id, std::int32_t prim) const {
    if (id < mesh_id) return prim_material[at(id)];
    return scene.meshes[at(id - mesh_id)].geometry->triangles[at(prim)].material;
  }

  ObjectRef object_of(std::int32_t id, std::int32_t prim) const {
    const int s = spheres.count, p = planes.count;
    if (id < s) return {ObjectRef::Kind::kSphere, id};
    if (id < s + p) return {ObjectRef::Kind::kPlane, id - s};
    if (id < mesh_id) return {ObjectRef::Kind::kTriangle, id - s - p};
    return {ObjectRef::Kind::kMesh, id - mesh_id, prim};
  }

  // The spheres the primary rays of image region [x0, x1] x [y0, y1] can meet: the rays share
  // the eye and lie in the cone of the region's corner rays (axis a, half-angle theta); a sphere
  // of angular radius alpha whose centre is more than theta + alpha off the axis meets none.
  // The margin (1e-6 rad) is far beyond rounding, so culling never changes a hit.
  packet::Spheres primary_spheres(const CameraFrame& f, int x0, int y0, int x1, int y1) {
    if (walk_hierarchy) return no_spheres();
    Vec3 corner[4];
    Vec3 sum(0);
    for (int c = 0; c < 4; ++c) {
      const double sx = 2.0 * (c & 1 ? x1 : x0) / f.width - 1;
      const double sy = 1 - 2.0 * (c & 2 ? y1 : y0) / f.height;
      corner[c] = glm::normalize(f.forward + sx * f.right + sy * f.up);
      sum += corner[c];
    }
    const Vec3 axis = glm::normalize(sum);
    double cos_theta = 1;
    for (const Vec3& c : corner) cos_theta = std::min(cos_theta, glm::dot(axis, c));
    const double theta = std::acos(clamp_unit(cos_theta));
    if (!(theta < 1.0)) return spheres;  // a wide region: no cone worth testing
    primary_tested.clear();
    for (std::size_t k = 0; k < scene.spheres.size(); ++k) {
      const Sphere& sp = scene.spheres[k];
      const Vec3 v = sp.center - f.origin;
      const double dist = glm::length(v);
      bool keep = !(dist > sp.radius * (1 + 1e-6));  // the eye inside or on the sphere
      if (!keep) {
        const double off_axis = std::acos(clamp_unit(glm::dot(axis, v) / dist));
        keep = !(off_axis > theta + std::asin(sp.radius / dist) + 1e-6);
      }
      if (keep) primary_tested.push_back(static_cast<std::int32_t>(k));
    }
    packet::Spheres view = spheres;
    view.tested = primary_tested.data();
    view.tested_count = static_cast<int>(primary_tested.size());
    return view;
  }

  // The spheres shadow rays from points within the ball (b, ball) towards `light` can meet:
  // the rays lie within `ball` of the segment from b to a point light (of the ray from b along
  // L for a directional one), so a sphere farther than its radius + `ball` from that segment
  // meets none. The margins dwarf rounding, so culling never changes an answer.
  packet::Spheres shadow_spheres(const Vec3& b, double ball, const Light& light, const Vec3& l) {
    if (walk_hierarchy) return no_spheres();
    shadow_tested.clear();
    const bool point = light.type == LightType::kPoint;
    const Vec3 w = point ? light.position - b : l;
    const double ww = glm::dot(w, w);
    const double reach = point ? glm::length(w) : 0.0;
    for (std::size_t k = 0; k < scene.spheres.size(); ++k) {
      const Sphere& sp = scene.spheres[k];
      const Vec3 cb = sp.center - b;
      double s = ww > 0 ? glm::dot(cb, w) / ww : 0.0;
      s = point ? std::clamp(s, 0.0, 1.0) : std::max(s, 0.0);
      const double dist = glm::length(cb - s * w);
      const double margin = 1e-6 * (sp.radius + ball) + 1e-9 * (glm::length(cb) + reach + max_abs(b));
      if (!(dist > sp.radius + ball + margin)) shadow_tested.push_back(static_cast<std::int32_t>(k));
    }
    packet::Spheres view = spheres;
    view.tested = shadow_tested.data();
    view.tested_count = static_cast<int>(shadow_tested.size());
    return view;
  }

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
                                       const Aabb* origins = nullptr) {
    packet::LooseTriangles view = loose;
    if (loose.count == 0) return view;
    triangles_tested.clear();
    // The batch's origins and directions as boxes, once for every triangle: over a box a plane's
    // signed distance (or a direction's cosine) lies within the centre's plus or minus |n|·half.
    double box[12];
    if (light && origins) {  // only the origins' box is read
      for (int c = 0; c < 3; ++c) box[c] = origins->lo[c], box[3 + c] = origins->hi[c];
    } else {
      packet::ray_bounds(rays, t_max, lanes, box);
    }
    const Vec3 olo(box[0], box[1], box[2]), ohi(box[3], box[4], box[5]);
    const Vec3 dlo(box[6], box[7], box[8]), dhi(box[9], box[10], box[11]);
    view.tested = triangles_tested.data();
    view.tested_count = 0;
    if (!(olo.x <= ohi.x)) return view;  // no ray
    const Vec3 centre = 0.5 * (olo + ohi), half = 0.5 * (ohi - olo);
    const Vec3 dcentre = 0.5 * (dlo + dhi), dhalf = 0.5 * (dhi - dlo);
    const double origins_size = std::max(max_abs(olo), max_abs(ohi));
    const bool point = light && light->type == LightType::kPoint;
    for (int k = 0; k < loose.count; ++k) {
      const Vec3& n = loose_normal[at(k)];
      const Vec3 an = glm::abs(n);
      const double d = glm::dot(n, centre - scene.triangles[at(k)].v0), spread = glm::dot(an, half);
      const double size = std::max(loose_magnitude[at(k)], origins_size);
      const double margin = 0x1p-42 * size;
      // The far ends' side: a point light's, the direction L from the plane, or the rays'.
      double end_lo = 0, end_hi = 0, end_margin = 1e-12;
      if (light) {
        end_lo = end_hi = point ? glm::dot(n, light->position - scene.triangles[at(k)].v0) : glm::dot(n, -light->direction);
        if (point) end_margin = 0x1p-42 * std::max(size, max_abs(light->position));
      } else {
        const double cosine = glm::dot(n, dcentre), cosine_spread = glm::dot(an, dhalf);
        end_lo = cosine - cosine_spread, end_hi = cosine + cosine_spread;
      }
      const bool above = d - spread > margin && end_lo > end_margin;
      const bool below = d + spread < -margin && end_hi < -end_margin;
      if (!above && !below) triangles_tested.push_back(k);
    }
    view.tested = triangles_tested.data();
    view.tested_count = static_cast<int>(triangles_tested.size());
    return view;
  }

  // The nearest hit of every ray: spheres and planes in the kernel, then the scene's few loose
  // triangles, in intersect_all's order.
  void find_hits(Level& lv, const RayBatch& rays, const packet::Spheres& tested) {
    lv.fit_lanes(rays.n);
    for (int i = 0; i < rays.n; ++i) {
      lv.t[at(i)] = kInf;
      lv.id[at(i)] = -1;
    }
    packet::nearest(tested, planes, rays.view(), padded(rays.n), lv.t.data(), lv.id.data());
    if (walk_hierarchy) {
      packet::hierarchy_nearest(hierarchy, rays.view(), rays.n,
                                {lv.t.data(), lv.id.data(), lv.prim.data(), lv.b1.data(), lv.b2.data()});
      return;
    }
    if (scene.triangles.empty()) return;
    packet::triangles_nearest(triangles_met(rays.view(), nullptr, rays.n, nullptr), rays.view(), rays.n,
                              {lv.t.data(), lv.id.data(), lv.prim.data(), lv.b1.data(), lv.b2.data()});
  }

  // occluded() for the shadow rays of the lanes marked kTest (the others have t_max = 0).
  void test_shadows(Level& lv, int lanes, const packet::Spheres& tested, const Light& light) {
    std::fill_n(lv.blocked.begin(), padded(lanes), std::uint8_t{0});
    const packet::Rays rays{lv.sox.data(), lv.soy.data(), lv.soz.data(), lv.sdx.data(), lv.sdy.data(), lv.sdz.data()};
    any_hits(rays, lv.st_max.data(), padded(lanes), tested, lv.blocked.data(), &light);
  }

  // Sets blocked[i] = 1 for the lanes that something blocks within (0, t_max[i]); for shadow
  // rays towards `light`, only the loose triangles they can meet are tested (`origins`: a box
  // known to hold their origins, or null).
  void any_hits(const packet::Rays& rays, const double* t_max, int lanes, const packet::Spheres& tested,
                std::uint8_t* blocked, const Light* light = nullptr, const Aabb* origins = nullptr) {
    packet::occluded(tested, planes, rays, t_max, lanes, blocked);
    if (walk_hierarchy) {
      packet::hierarchy_occluded(hierarchy, rays, t_max, lanes, blocked);
      return;
    }
    if (scene.triangles.empty()) return;
    packet::triangles_occluded(light ? triangles_met(rays, t_max, lanes, light, origins) : loose, rays, t_max, lanes,
                               blocked);
  }

  // The light loop of shade() for every hit of the level, one light at a time. The light kernel
  // writes each lane's Shadow as the byte it is (0, 1, 2).
  static_assert(sizeof(Shadow) == 1 && static_cast<int>(Shadow::kNone) == 0 && static_cast<int>(Shadow::kVisible) == 1 &&
                static_cast<int>(Shadow::kTest) == 2);
  void shade_lights(Level& lv, int lanes, RayCounts& counts) {
    const packet::ShadedPoints pts{lv.px.data(), lv.py.data(), lv.pz.data(), lv.nx.data(), lv.ny.data(),
                                   lv.nz.data(), lv.gx.data(), lv.gy.data(), lv.gz.data(), lv.vx.data(),
                                   lv.vy.data(), lv.vz.data(), lv.offset.data(), lv.active.data()};
    const packet::LightOut out{lv.n_dot_l.data(), lv.cos_spec.data(), lv.sox.data(), lv.soy.data(), lv.soz.data(),
                               lv.sdx.data(),     lv.sdy.data(),      lv.sdz.data(), lv.st_max.data(),
                               reinterpret_cast<std::uint8_t*>(lv.shadow.data())};
    const bool blinn = scene.specular_model == SpecularModel::kBlinn;
    const std::size_t materials = scene.materials.size();
    for (std::size_t li = 0; li < scene.lights.size(); ++li) {
      const Light& light = scene.lights[li];
      if (!light.enabled && sink == nullptr) continue;
      packet::LightIn in{};
      in.point = light.type == LightType::kPoint;
      const Vec3 l = in.point ? light.position : -light.direction;
      in.x = l.x, in.y = l.y, in.z = l.z;
      in.shrink = in.point ? surface_offset(light.position, 0) : 0.0;
      in.blinn = blinn;
      // Lit points (N.L > 0, a material with kd or ks) cast a shadow ray, except where the
      // light is within rounding distance (visible without one). N.L is NaN for a point light
      // exactly at P.
      const packet::ShadowCounts shadows = packet::light(in, pts, padded(lanes), out);
      counts.shadow += static_cast<std::uint64_t>(shadows.lit);
      if (shadows.tested > 0) {
        // The rays start within max_offset of the hit points' bounding box.
        const double ball = (0.5 * glm::length(lv.hi - lv.lo) + lv.max_offset) * (1 + 1e-9);
        test_shadows(lv, lanes, shadow_spheres(0.5 * (lv.lo + lv.hi), ball, light, l), light);
      }
      if (sink != nullptr) record_light(lv, lanes, static_cast<int>(li));
      if (!light.enabled) continue;
      // The light's terms where it is seen. The specular factor (pow) is computed only there:
      // a blocked light's would be multiplied by vis = 0.
      if (mark_seen(lv, lanes) == 0) continue;
      packet::add_light(light_kd.from(li * materials), light_ks.from(li * materials), lv.material.data(),
                        lv.seen.data(), lv.n_dot_l.data(), lv.spec.data(), padded(lanes), lv.diffuse.lanes(),
                        lv.specular.lanes());
    }
  }

  // Where the light just tested is seen (lit, and its shadow ray seen or not needed), with the
  // specular factor there (zero for a material without ks); returns how many lanes see it.
  // Four lanes at a time as the bytes of a word: seen = lit & (shadow 1, or shadow 2 and not
  // blocked), every byte 0 or 1 (lit is 0 past the live lanes; blocked is read only where a ray
  // was tested).
  int mark_seen(Level& lv, int lanes) const {
    int count = 0;
    constexpr std::uint32_t kOnes = 0x01010101u;
    for (int h = 0; h < padded(lanes); h += 4) {
      std::uint32_t lit, shadow, blocked;
      std::memcpy(&lit, &lv.lit[at(h)], 4);
      std::memcpy(&shadow, &lv.shadow[at(h)], 4);
      std::memcpy(&blocked, &lv.blocked[at(h)], 4);
      const std::uint32_t seen = lit & ((shadow & kOnes) | ((shadow >> 1) & ~blocked & kOnes));
      std::memcpy(&lv.seen[at(h)], &seen, 4);
      if (seen == 0) continue;
      for (int j = 0; j < 4; ++j) {
        if (!(seen >> (8 * j) & 1)) continue;
        ++count;
        const std::size_t u = at(h + j);
        const MaterialInfo& mi = info[at(lv.material[u])];
        lv.spec[u] = mi.specular ? specular_factor(lv.cos_spec[u], mi.n) : 0.0;
      }
    }
    return count;
  }

  // One light at every hit of the level, as the scalar tracer tells its recorder.
  void record_light(const Level& lv, int lanes, int li) {
    for (int h = 0; h < lanes; ++h) {
      const std::size_t u = at(h);
      if (lv.id[u] < 0) continue;
      const double n_dot_l = lv.n_dot_l[u];
      if (std::isnan(n_dot_l)) {  // a point light exactly at P: no direction
        sink->light(lv.node[u], li, LightSeen::kNoLight, 0, 0, 0);
      } else if (!(n_dot_l > 0)) {
        sink->light(lv.node[u], li, LightSeen::kNoLight, n_dot_l, 0, 0);
      } else {
        // A blocked light's specular factor is never read (every shading sum skips it, and an
        // edit that could unblock it moves the light, which takes the factor again): no pow.
        const bool blocked = lv.shadow[u] == Shadow::kTest && lv.blocked[u];
        const double cos_spec = lv.cos_spec[u];
        sink->light(lv.node[u], li, blocked ? LightSeen::kBlocked : LightSeen::kVisible, n_dot_l, cos_spec,
                    blocked ? 0.0 : specular_factor(cos_spec, info[at(lv.material[u])].n));
      }
    }
  }

  // The level's rays that missed and its hits, told to the sink (record_tile).
  void record_hits(Level& lv, const RayBatch& rays, int depth, TraceRecorder::Child kind) {
    for (int i = 0; i < rays.n; ++i) {
      const std::size_t u = at(i);
      const int pixel = depth == 0 ? i : rays.pixel[u];
      const std::int32_t parent = depth == 0 ? -1 : rays.parent[u];
      if (lv.id[u] < 0) {
        sink->missed(pixel, parent, kind);
        continue;
      }
      lv.node[u] = sink->hit(pixel, parent, kind, depth, lv.material[u], lv.entering[u] != 0,
                             Vec3(lv.px[u], lv.py[u], lv.pz[u]), Vec3(lv.nx[u], lv.ny[u], lv.nz[u]),
                             Vec3(lv.gx[u], lv.gy[u], lv.gz[u]), rays.dir(i), lv.offset[u]);
    }
  }

  // The primary rays of pixels [x0, x1) x [y0, y1) (sample `sample_index`), row by row; returns
  // the spheres they can meet.
  packet::Spheres primary_rays(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::uint32_t sample_index,
                    std::uint32_t seed) {
    const int w = x1 - x0;
    const int n = w * (y1 - y0);
    primary.reserve_lanes(n);
    primary.n = n;
    fit(x_plus_u, padded(n));
    fit(y_plus_v, padded(n));
    int i = 0;
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x, ++i) {
        double u, v;
        sample_offset(x, y, sample_index, u, v, seed);
        x_plus_u[at(i)] = x + u;
        y_plus_v[at(i)] = y + v;
      }
    }
    const packet::CameraIn cam{frame.forward.x, frame.forward.y, frame.forward.z, frame.right.x,
                               frame.right.y,   frame.right.z,   frame.up.x,      frame.up.y,
                               frame.up.z,      static_cast<double>(frame.width), static_cast<double>(frame.height)};
    packet::camera_dirs(cam, x_plus_u.data(), y_plus_v.data(), padded(n), primary.dx.data(), primary.dy.data(),
                        primary.dz.data());
    for (int k = 0; k < padded(n); ++k) {
      primary.ox[at(k)] = frame.origin.x;
      primary.oy[at(k)] = frame.origin.y;
      primary.oz[at(k)] = frame.origin.z;
      primary.weight[at(k)] = 1.0;
    }
    return primary_spheres(frame, x0, y0, x1, y1);
  }

  // Radiance of every ray of `rays` (at recursion depth `depth`) into out[0 .. rays.n); `tested`:
  // the spheres those rays can meet.
  void trace_level(int depth, const RayBatch& rays, const packet::Spheres& tested, Color* out, RayCounts& counts,
                   TraceRecorder::Child kind = TraceRecorder::Child::kReflection) {
    Level& lv = levels[at(depth)];
    find_hits(lv, rays, tested);
    const int lanes = rays.n;
    packet::hit_records(spheres, planes, {kCoordinateMargin, kSizeMargin}, rays.view(), lv.t.data(), lv.id.data(),
                        padded(lanes), lv.records());
    if (loose_records.count > 0) {
      packet::triangle_records(loose_records, {kCoordinateMargin, kSizeMargin}, rays.view(), lv.t.data(), lv.id.data(),
                               lv.b1.data(), lv.b2.data(), padded(lanes), lv.records());
    }
    bool any_hit = false, any_bounce = false;
    const Color miss = depth == 0 ? miss_value(scene, primary_term) : scene.background;
    const bool recording = sink != nullptr, eye_moved = depth == 0 && shading_eye;
    const int first_triangle = spheres.count + planes.count;
    for (int i = 0; i < lanes; ++i) {
      const std::size_t u = at(i);
      const std::int32_t id = lv.id[u];
      if (i % 4 == 0 && i + 4 <= lanes && id >= 0 && id < first_triangle && !eye_moved && lv.id[u + 1] == id &&
          lv.id[u + 2] == id && lv.id[u + 3] == id) {
        // Four lanes on one sphere or plane (the usual case): its material's flags once.
        const int material = prim_material[at(id)];
        const MaterialInfo& mi = info[at(material)];
        for (std::size_t v = u; v < u + 4; ++v) {
          lv.material[v] = material;
          lv.lit[v] = mi.lit;
          lv.active[v] = mi.lit || recording;
          lv.bounces[v] = mi.bounces;
          lv.ior[v] = mi.ior;
        }
        any_hit = true;
        any_bounce |= mi.bounces;
        i += 3;
        continue;
      }
      if (id < 0) {
        out[i] = miss;
        if (depth == 0 && primary_terms) primary_terms[i] = Terms{};
        lv.lit[u] = lv.active[u] = lv.bounces[u] = 0;
        continue;
      }
      any_hit = true;
      const int material = material_of(id, lv.prim[u]);
      const MaterialInfo& mi = info[at(material)];
      lv.material[u] = material;
      lv.lit[u] = mi.lit;
      lv.active[u] = mi.lit || recording;
      lv.bounces[u] = mi.bounces;
      lv.ior[u] = mi.ior;
      any_bounce |= mi.bounces;
      if (id >= first_triangle && !kernel_recorded(id)) record_triangle_hit(lv, rays, i);
      if (eye_moved) look_from_eye(lv, i);
    }
    for (int i = lanes; i < padded(lanes); ++i) lv.lit[at(i)] = lv.active[at(i)] = lv.bounces[at(i)] = 0;
    if (recording) record_hits(lv, rays, depth, kind);
    if (!any_hit) return;
    double bounds[7];
    packet::hit_bounds(lv.px.data(), lv.py.data(), lv.pz.data(), lv.offset.data(), lv.id.data(), lanes, bounds);
    lv.lo = Vec3(bounds[0], bounds[1], bounds[2]);
    lv.hi = Vec3(bounds[3], bounds[4], bounds[5]);
    lv.max_offset = bounds[6];
    const TermsWanted wanted = depth == 0 ? primary_wanted : TermsWanted{};
    lv.diffuse.zero(padded(lanes));
    lv.specular.zero(padded(lanes));
    if (wanted.lights) shade_lights(lv, lanes, counts);

    const bool children = any_bounce && depth < limits.max_depth;
    if (children) {
      send_children(lv, rays, lanes, depth, wanted, counts);
      children_terms(lv, lanes);
    }
    if (depth == 0 && (primary_term != Term::kFull || primary_terms)) {
      primary_terms_out(lv, lanes, children, out);
      return;
    }
    const packet::ColorLanes reflection = lv.reflection.lanes(), refraction = lv.refraction.lanes();
    packet::sum_terms(ambient.from(0), lv.material.data(), lv.id.data(),
                      {lv.diffuse.lanes(), lv.specular.lanes(), children ? &reflection : nullptr,
                       children ? &refraction : nullptr},
                      lanes, &out[0].x);
  }

  // The reflection and refraction terms of the level's hits: kr' and kt' times what their
  // children brought back, zero where none was traced.
  void children_terms(Level& lv, int lanes) {
    lv.reflection.zero(padded(lanes));
    lv.refraction.zero(padded(lanes));
    for (int i = 0; i < lanes; ++i) {
      const std::size_t u = at(i);
      if (lv.id[u] < 0 || !lv.bounces[u]) continue;
      if (lv.reflected_index[u] >= 0) lv.reflection.set(i, lv.kr[u] * lv.reflected_radiance[at(lv.reflected_index[u])]);
      if (lv.refracted_index[u] >= 0) lv.refraction.set(i, lv.kt[u] * lv.refracted_radiance[at(lv.refracted_index[u])]);
    }
  }

  // The primary hits' values when a term other than the full image is drawn, or the five terms
  // are kept (render_tile's terms_out): lane by lane, through Terms.
  void primary_terms_out(const Level& lv, int lanes, bool children, Color* out) const {
    for (int i = 0; i < lanes; ++i) {
      const std::size_t u = at(i);
      if (lv.id[u] < 0) continue;
      Terms t;
      t.ambient = info[at(lv.material[u])].ambient;
      t.diffuse = lv.diffuse.at_lane(i);
      t.specular = lv.specular.at_lane(i);
      if (children) t.reflection = lv.reflection.at_lane(i), t.refraction = lv.refraction.at_lane(i);
      out[i] = primary_term != Term::kFull ? term_value(t, primary_term) : t.sum();
      if (primary_terms) primary_terms[i] = t;
    }
  }

  // shade()'s V at a primary hit when the eye has moved ("move your head"): towards the eye; an
  // eye exactly at P has no direction and keeps -D.
  void look_from_eye(Level& lv, int i) const {
    const std::size_t u = at(i);
    const std::optional<Vec3> v = towards_eye(Vec3(lv.px[u], lv.py[u], lv.pz[u]), *shading_eye);
    if (v) lv.vx[u] = v->x, lv.vy[u] = v->y, lv.vz[u] = v->z;
  }

  // Whether the kernels wrote the hit record of a hit on triangle-or-mesh `id`: a loose
  // triangle without vertex normals.
  bool kernel_recorded(std::int32_t id) const {
    const int k = id - loose_records.first_id;
    return k < loose_records.count && loose_flat[at(k)];
  }

  // A triangle's hit record (a mesh's, or loose with vertex normals), by the scalar functions;
  // a loose triangle's normal and magnitude come from those computed once.
  void record_triangle_hit(Level& lv, const RayBatch& rays, int i) {
    const std::size_t u = at(i);
    const Vec3 d = rays.dir(i);
    const int first = spheres.count + planes.count;
    Hit hit;
    if (lv.id[u] < mesh_id) {
      const int k = lv.id[u] - first;
      hit.t = lv.t[u];
      hit.object = {ObjectRef::Kind::kTriangle, k};
      triangle_hit_record(scene.triangles[at(k)], loose_normal[at(k)], loose_magnitude[at(k)], lv.b1[u], lv.b2[u], hit);
    } else {
      hit = make_hit(scene, make_ray(rays.origin(i), d), object_of(lv.id[u], lv.prim[u]), lv.t[u], lv.b1[u], lv.b2[u]);
    }
    const HitSide side = hit_side(hit, d);
    lv.entering[u] = side.entering;
    lv.px[u] = hit.p.x, lv.py[u] = hit.p.y, lv.pz[u] = hit.p.z;
    lv.nx[u] = side.n.x, lv.ny[u] = side.n.y, lv.nz[u] = side.n.z;
    lv.gx[u] = side.ng.x, lv.gy[u] = side.ng.y, lv.gz[u] = side.ng.z;
    lv.vx[u] = -d.x, lv.vy[u] = -d.y, lv.vz[u] = -d.z;
    lv.offset[u] = surface_offset(scene, hit);
  }

  // Reflected and refracted rays of the level's mirror and glass hits, traced as the next
  // level's two batches (shade()'s recursion, with its path-weight pruning), for the lanes marked
  // in `bounces` (at the primary hits, only the children whose terms are `wanted`).
  void send_children(Level& lv, const RayBatch& rays, int lanes, int depth, const TermsWanted& wanted,
                     RayCounts& counts) {
    lv.reflected.n = 0;
    lv.refracted.n = 0;
    packet::bounce({rays.dx.data(), rays.dy.data(), rays.dz.data(), lv.nx.data(), lv.ny.data(), lv.nz.data(),
                    lv.ior.data(), lv.entering.data(), lv.bounces.data()},
                   padded(lanes),
                   {lv.eta.data(), lv.fresnel.data(), lv.tir.data(), lv.mx.data(), lv.my.data(), lv.mz.data(),
                    lv.tx.data(), lv.ty.data(), lv.tz.data()});
    lv.reflected.reserve_lanes(lanes);
    lv.refracted.reserve_lanes(lanes);
    for (int k = 0; k < lanes; ++k) {
      const std::size_t u = at(k);
      if (!lv.bounces[u]) continue;
      lv.reflected_index[u] = lv.refracted_index[u] = -1;
      const Material& m = scene.materials[at(lv.material[u])];
      const Vec3 ng(lv.gx[u], lv.gy[u], lv.gz[u]);
      const Vec3 p(lv.px[u], lv.py[u], lv.pz[u]);
      // bounce(), from the kernel's geometry and Fresnel reflectance.
      Bounce bn;
      bn.eta = lv.eta[u];
      bn.tir = lv.tir[u] != 0;
      if (uses_fresnel(m)) bn.fresnel = lv.fresnel[u];
      set_bounce_weights(m, bn);
      bn.mirror = Vec3(lv.mx[u], lv.my[u], lv.mz[u]);
      bn.refracted = Vec3(lv.tx[u], lv.ty[u], lv.tz[u]);
      lv.kr[u] = bn.kr;
      lv.kt[u] = bn.kt;
      if (sink != nullptr) sink->bounced(lv.node[u], bn.fresnel);
      const double weight = rays.weight[u];
      const double offset = lv.offset[u];
      const auto send = [&](const Color& kw, const Vec3& dir, RayBatch& batch, int& index, std::uint64_t& count) {
        const std::optional<double> w = child_weight(kw, weight, limits.min_weight);
        if (!w) return;
        ++count;
        index = batch.n;
        batch.push(offset_origin(p, ng, dir, offset), dir, *w);
        if (sink != nullptr) batch.tag_last(depth == 0 ? k : rays.pixel[u], lv.node[u]);
      };
      if (wanted.reflection) send(bn.kr, bn.mirror, lv.reflected, lv.reflected_index[u], counts.reflection);
      if (wanted.refraction && !is_zero(bn.kt)) {
        send(bn.kt, bn.refracted, lv.refracted, lv.refracted_index[u], counts.refraction);
      }
    }
    fit(lv.reflected_radiance, lv.reflected.n);
    fit(lv.refracted_radiance, lv.refracted.n);
    using Child = TraceRecorder::Child;
    if (lv.reflected.n > 0) {
      trace_level(depth + 1, lv.reflected, spheres, lv.reflected_radiance.data(), counts, Child::kReflection);
    }
    if (lv.refracted.n > 0) {
      trace_level(depth + 1, lv.refracted, spheres, lv.refracted_radiance.data(), counts, Child::kRefraction);
    }
  }
};

PacketTracer::PacketTracer(const PreparedScene& prepared) : impl_(std::make_unique<Impl>(prepared)) {}
PacketTracer::PacketTracer(const PreparedScene& prepared, PacketTracer&& recycled)
    : impl_(std::make_unique<Impl>(prepared)) {
  if (!recycled.impl_) return;
  // Buffers only: every lane is written before it is read, in any tile of any scene.
  Impl& old = *recycled.impl_;
  const std::size_t depth = impl_->levels.size();
  impl_->levels = std::move(old.levels);
  impl_->levels.resize(depth);
  impl_->primary = std::move(old.primary);
  impl_->x_plus_u = std::move(old.x_plus_u);
  impl_->y_plus_v = std::move(old.y_plus_v);
  recycled.impl_.reset();
}
PacketTracer::~PacketTracer() = default;

bool PacketTracer::draws(Term term) { return is_equation_term(term); }

void PacketTracer::render_tile(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::uint32_t sample_index,
                               std::uint32_t seed, Color* out, RayCounts& counts, Term term, const Vec3* shading_eye,
                               Terms* terms_out) {
  Impl& im = *impl_;
  im.primary_term = term;
  im.primary_wanted = terms_out ? TermsWanted{} : terms_wanted(term);
  im.shading_eye = shading_eye;
  im.primary_terms = terms_out;
  const packet::Spheres tested = im.primary_rays(frame, x0, y0, x1, y1, sample_index, seed);
  counts.primary += static_cast<std::uint64_t>(im.primary.n);
  im.trace_level(0, im.primary, tested, out, counts);
}

void PacketTracer::record_tile(const CameraFrame& frame, int x0, int y0, int x1, int y1, const Vec3* shading_eye,
                               PacketTreeSink& sink, Color* out, RayCounts& counts) {
  Impl& im = *impl_;
  im.sink = &sink;
  render_tile(frame, x0, y0, x1, y1, 0, 0, out, counts, Term::kFull, shading_eye);
  im.sink = nullptr;
}

void PacketTracer::occluded(const double* ox, const double* oy, const double* oz, const double* dx, const double* dy,
                            const double* dz, const double* t_max, int n, std::uint8_t* blocked) {
  Impl& im = *impl_;
  std::fill_n(blocked, padded(n), std::uint8_t{0});
  const packet::Rays rays{ox, oy, oz, dx, dy, dz};
  im.any_hits(rays, t_max, padded(n), im.spheres, blocked);
}

void PacketTracer::occluded_towards(const Light& light, const double* ox, const double* oy, const double* oz,
                                    const double* dx, const double* dy, const double* dz, const double* t_max, int n,
                                    std::uint8_t* blocked) {
  Impl& im = *impl_;
  std::fill_n(blocked, padded(n), std::uint8_t{0});
  if (n <= 0) return;
  Vec3 lo(kInf), hi(-kInf);
  for (int i = 0; i < n; ++i) {
    const Vec3 o(ox[i], oy[i], oz[i]);
    lo = glm::min(lo, o);
    hi = glm::max(hi, o);
  }
  const double ball = 0.5 * glm::length(hi - lo) * (1 + 1e-9);  // every origin lies within it
  const Vec3 l = light.type == LightType::kPoint ? light.position : -light.direction;
  const packet::Rays rays{ox, oy, oz, dx, dy, dz};
  const Aabb origins{lo, hi};
  im.any_hits(rays, t_max, padded(n), im.shadow_spheres(0.5 * (lo + hi), ball, light, l), blocked, &light, &origins);
}

PacketTracer& packet_tracer_for(const PreparedScene& prepared) {
  struct Kept {
    const PreparedScene* scene = nullptr;
    std::uint64_t id = 0;
    std::unique_ptr<PacketTracer> tracer;
  };
  thread_local Kept kept;
  if (!kept.tracer || kept.scene != &prepared || kept.id != prepared.id()) {
    kept.tracer = kept.tracer ? std::make_unique<PacketTracer>(prepared, std::move(*kept.tracer))
                              : std::make_unique<PacketTracer>(prepared);
    kept.scene = &prepared;
    kept.id = prepared.id();
  }
  return *kept.tracer;
}

int PacketTracer::cast_primary(const CameraFrame& frame, int x0, int y0, int x1, int y1) {
  Impl& im = *impl_;
  const packet::Spheres tested = im.primary_rays(frame, x0, y0, x1, y1, 0, 0);
  Level& lv = im.levels[0];
  im.find_hits(lv, im.primary, tested);
  int hits = 0;
  for (int i = 0; i < im.primary.n; ++i) hits += lv.id[at(i)] >= 0;
  return hits;
}

}  // namespace phonglab
