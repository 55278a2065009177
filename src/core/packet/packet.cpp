// The packet tracer's driver: set-up, the recursion levels, their hits and children, the scalar
// steps between the kernels (the light loop and culling: packet_lights.cpp).
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
#include "core/packet/packet_driver.h"
#include "core/packet/packet_kernels.h"

namespace phonglab {

int whole_power_exponent(double n) {
  if (!(n >= 1 && n <= 4096) || n != static_cast<double>(static_cast<int>(n))) return -1;
  const int k = static_cast<int>(n);
  const int steps = (31 - __builtin_clz(static_cast<unsigned>(k))) + __builtin_popcount(static_cast<unsigned>(k)) - 1;
  return steps <= kWholePowerSteps ? k : -1;
}

bool packet_tracing_applies(const PreparedScene& prepared) {
  const Accelerator* accel = prepared.accel();
  const bool walkable = accel ? dynamic_cast<const SceneBvh*>(accel) != nullptr : prepared.scene().meshes.empty();
  return !prepared.experiment() && walkable && packet_cpu_supported();
}

namespace {

// The kernels read BVH nodes and triangles in place, through plain structs of their own (the
// kernels' units see no glm): the layouts must agree.
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

PacketTracer::Impl::Impl(const PreparedScene& p) : prepared(p), scene(p.scene()), limits{scene.max_depth, scene.min_weight} {
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
    if (packet_fma_supported()) power.push_back(!mi.specular ? 0 : whole_power_exponent(m.n));
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

void PacketTracer::Impl::set_up_hierarchy(const SceneBvh& bvh) {
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

packet::Spheres PacketTracer::Impl::no_spheres() const {
  packet::Spheres view = spheres;
  view.tested_count = 0;
  return view;
}

int PacketTracer::Impl::material_of(std::int32_t id, std::int32_t prim) const {
  if (id < mesh_id) return prim_material[at(id)];
  return scene.meshes[at(id - mesh_id)].geometry->triangles[at(prim)].material;
}

ObjectRef PacketTracer::Impl::object_of(std::int32_t id, std::int32_t prim) const {
  const int s = spheres.count, p = planes.count;
  if (id < s) return {ObjectRef::Kind::kSphere, id};
  if (id < s + p) return {ObjectRef::Kind::kPlane, id - s};
  if (id < mesh_id) return {ObjectRef::Kind::kTriangle, id - s - p};
  return {ObjectRef::Kind::kMesh, id - mesh_id, prim};
}

void PacketTracer::Impl::find_hits(Level& lv, const RayBatch& rays, const packet::Spheres& tested,
                                   const packet::LooseTriangles* triangles) {
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
  packet::triangles_nearest(triangles ? *triangles : triangles_met(rays.view(), nullptr, rays.n, nullptr), rays.view(), rays.n,
                            {lv.t.data(), lv.id.data(), lv.prim.data(), lv.b1.data(), lv.b2.data()});
}

void PacketTracer::Impl::record_hits(Level& lv, const RayBatch& rays, int depth, TraceRecorder::Child kind) {
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

packet::Spheres PacketTracer::Impl::primary_rays(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::uint32_t sample_index,
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
  return finish_primary(frame, x0, y0, x1, y1, n);
}

packet::Spheres PacketTracer::Impl::finish_primary(const CameraFrame& frame, int x0, int y0, int x1, int y1, int n) {
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
  primary_loose = primary_triangles(frame, x0, y0, x1, y1);
  return primary_spheres(frame, x0, y0, x1, y1);
}

void PacketTracer::Impl::trace_level(int depth, const RayBatch& rays, const packet::Spheres& tested, Color* out, RayCounts& counts,
                 TraceRecorder::Child kind, bool hits_found) {
  Level& lv = levels[at(depth)];
  if (!hits_found) find_hits(lv, rays, tested, depth == 0 ? &primary_loose : nullptr);
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

void PacketTracer::Impl::children_terms(Level& lv, int lanes) {
  lv.reflection.zero(padded(lanes));
  lv.refraction.zero(padded(lanes));
  for (int i = 0; i < lanes; ++i) {
    const std::size_t u = at(i);
    if (lv.id[u] < 0 || !lv.bounces[u]) continue;
    if (lv.reflected_index[u] >= 0) lv.reflection.set(i, lv.kr[u] * lv.reflected_radiance[at(lv.reflected_index[u])]);
    if (lv.refracted_index[u] >= 0) lv.refraction.set(i, lv.kt[u] * lv.refracted_radiance[at(lv.refracted_index[u])]);
  }
}

void PacketTracer::Impl::primary_terms_out(const Level& lv, int lanes, bool children, Color* out) const {
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

void PacketTracer::Impl::look_from_eye(Level& lv, int i) const {
  const std::size_t u = at(i);
  const std::optional<Vec3> v = towards_eye(Vec3(lv.px[u], lv.py[u], lv.pz[u]), *shading_eye);
  if (v) lv.vx[u] = v->x, lv.vy[u] = v->y, lv.vz[u] = v->z;
}

bool PacketTracer::Impl::kernel_recorded(std::int32_t id) const {
  const int k = id - loose_records.first_id;
  return k < loose_records.count && loose_flat[at(k)];
}

void PacketTracer::Impl::record_triangle_hit(Level& lv, const RayBatch& rays, int i) {
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

void PacketTracer::Impl::send_children(Level& lv, const RayBatch& rays, int lanes, int depth, const TermsWanted& wanted,
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

bool PacketTracer::draws(Term term) { return is_equation_term(term) && term != Term::kIndirect; }

void PacketTracer::Impl::aim_primary(Term term, const Vec3* eye, Terms* terms_out) {
  primary_term = term;
  primary_wanted = terms_out ? TermsWanted{} : terms_wanted(term);
  shading_eye = eye;
  primary_terms = terms_out;
}

void PacketTracer::find_surfaces(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::int64_t* surface,
                                 RayCounts& counts) {
  Impl& im = *impl_;
  im.found.tested = im.primary_rays(frame, x0, y0, x1, y1, 0, 0);
  const int n = im.primary.n;
  counts.primary += static_cast<std::uint64_t>(n);
  Impl::Level& lv = im.levels[0];
  im.find_hits(lv, im.primary, im.found.tested, &im.primary_loose);
  Impl::Found& f = im.found;
  f.n = n;
  for (std::vector<double>* v : {&f.ox, &f.oy, &f.oz, &f.dx, &f.dy, &f.dz, &f.weight, &f.t, &f.b1, &f.b2}) fit(*v, n);
  fit(f.id, n);
  fit(f.prim, n);
  const Impl::RayBatch& rays = im.primary;
  for (int i = 0; i < n; ++i) {
    const std::size_t u = at(i);
    f.ox[u] = rays.ox[u], f.oy[u] = rays.oy[u], f.oz[u] = rays.oz[u];
    f.dx[u] = rays.dx[u], f.dy[u] = rays.dy[u], f.dz[u] = rays.dz[u];
    f.weight[u] = rays.weight[u];
    f.t[u] = lv.t[u], f.id[u] = lv.id[u], f.prim[u] = lv.prim[u], f.b1[u] = lv.b1[u], f.b2[u] = lv.b2[u];
    surface[i] = lv.id[u] < 0 ? -1
                              : static_cast<std::int64_t>(lv.id[u]) << 32 |
                                    static_cast<std::uint32_t>(im.material_of(lv.id[u], lv.prim[u]));
  }
}

void PacketTracer::shade_found(const int* lanes, int m, const Vec3* shading_eye, Color* out, RayCounts& counts) {
  if (m <= 0) return;
  Impl& im = *impl_;
  const Impl::Found& f = im.found;
  Impl::Level& lv = im.levels[0];
  Impl::RayBatch& rays = im.primary;
  rays.reserve_lanes(m);
  for (std::vector<double>* v : {&lv.t, &lv.b1, &lv.b2}) fit(*v, padded(m));
  fit(lv.id, padded(m));
  fit(lv.prim, padded(m));
  // The lanes' rays and hits, in order, at the front of the batch; padding lanes meet nothing.
  for (int j = 0; j < m; ++j) {
    const std::size_t from = at(lanes[j]), to = at(j);
    rays.ox[to] = f.ox[from], rays.oy[to] = f.oy[from], rays.oz[to] = f.oz[from];
    rays.dx[to] = f.dx[from], rays.dy[to] = f.dy[from], rays.dz[to] = f.dz[from];
    rays.weight[to] = f.weight[from];
    lv.t[to] = f.t[from], lv.id[to] = f.id[from], lv.prim[to] = f.prim[from];
    lv.b1[to] = f.b1[from], lv.b2[to] = f.b2[from];
  }
  for (int j = m; j < padded(m); ++j) {
    lv.t[at(j)] = kInf;
    lv.id[at(j)] = -1;
  }
  rays.n = m;
  im.aim_primary(Term::kFull, shading_eye, nullptr);
  im.trace_level(0, rays, f.tested, out, counts, TraceRecorder::Child::kReflection, true);
}

void PacketTracer::render_tile(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::uint32_t sample_index,
                               std::uint32_t seed, Color* out, RayCounts& counts, Term term, const Vec3* shading_eye,
                               Terms* terms_out) {
  Impl& im = *impl_;
  im.aim_primary(term, shading_eye, terms_out);
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
  im.find_hits(lv, im.primary, tested, &im.primary_loose);
  int hits = 0;
  for (int i = 0; i < im.primary.n; ++i) hits += lv.id[at(i)] >= 0;
  return hits;
}

}  // namespace phonglab
