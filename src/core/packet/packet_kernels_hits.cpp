// The packet tracer's kernels, intersections: spheres and planes, loose triangles, the hierarchy
// walk. One source for every instance (packet_kernels.h): built once per instruction set, in the
// namespace PHONGLAB_SIMD_NS, over the vocabulary of packet_simd_ops.h.
#include "core/packet/packet_kernels.h"
#include "core/packet/packet_simd_ops.h"

namespace phonglab::packet::PHONGLAB_SIMD_NS {

namespace {

// sphere_root(s, o, d, 0, t_max) for kLanes rays: the root, or 0 where there is none.
inline V sphere_root(V ox, V oy, V oz, V dx, V dy, V dz, double cx, double cy, double cz, double radius,
                     V t_max) {
  const V zero = zeros();
  const V fx = ox - splat(cx), fy = oy - splat(cy), fz = oz - splat(cz);
  const V b = dot(fx, fy, fz, dx, dy, dz);
  const double r2 = radius * radius;
  const V c = dot(fx, fy, fz, fx, fy, fz) - splat(r2);
  const M early = both(gt(c, zero), either(gt(b, zero), gt(negate(b) - splat(radius), t_max)));
  const V px = fx - b * dx, py = fy - b * dy, pz = fz - b * dz;
  const V disc = splat(r2) - dot(px, py, pz, px, py, pz);
  const M candidates = and_not(early, ge(disc, zero));
  if (lanes_set(candidates) == 0) return zero;  // the usual case: the sphere is missed by every lane
  const V root = sqrt(disc);
  const V signed_root = copysign(root, b);
  const V q = negate(b + signed_root);
  const V t0 = c / q;
  const M swap = gt(t0, q);
  const V lo = pick(swap, q, t0), hi = pick(swap, t0, q);
  const V lo_t = keep(lt(lo, t_max), lo);
  const V hi_t = keep(lt(hi, t_max), hi);
  const V t = pick(gt(lo, zero), lo_t, keep(gt(hi, zero), hi_t));
  return keep(both(candidates, ne(q, zero)), t);
}

// intersect_plane's distance, and whether it counts (t in (0, inf), the plane not parallel).
inline V plane_t(V ox, V oy, V oz, V dx, V dy, V dz, const Planes& pl, int k, M* valid) {
  const V nx = splat(pl.nx[k]), ny = splat(pl.ny[k]), nz = splat(pl.nz[k]);
  const V denom = dot(dx, dy, dz, nx, ny, nz);
  const V wx = splat(pl.px[k]) - ox, wy = splat(pl.py[k]) - oy, wz = splat(pl.pz[k]) - oz;
  const V t = dot(wx, wy, wz, nx, ny, nz) / denom;
  const V zero = zeros();
  *valid = both(ne(denom, zero), both(gt(t, zero), lt(t, splat(kInf))));
  return t;
}

}  // namespace

void nearest(const Spheres& spheres, const Planes& planes, const Rays& rays, int lanes, double* t_best,
             std::int32_t* id) {
  for (int i = 0; i < lanes; i += kLanes) {
    const V ox = load(rays.ox + i), oy = load(rays.oy + i), oz = load(rays.oz + i);
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    V best = load(t_best + i);
    V best_id = splat(-1);
    for (int j = 0; j < spheres.tested_count; ++j) {
      const int k = spheres.tested[j];
      const V t = sphere_root(ox, oy, oz, dx, dy, dz, spheres.cx[k], spheres.cy[k], spheres.cz[k], spheres.r[k], best);
      const M hit = gt(t, zeros());
      best = pick(hit, t, best);
      best_id = pick(hit, splat(k), best_id);
    }
    for (int k = 0; k < planes.count; ++k) {
      M valid;
      const V t = plane_t(ox, oy, oz, dx, dy, dz, planes, k, &valid);
      const M hit = both(valid, lt(t, best));
      best = pick(hit, t, best);
      best_id = pick(hit, splat(spheres.count + k), best_id);
    }
    store(t_best + i, best);
    double ids[kLanes];
    store(ids, best_id);
    for (int j = 0; j < kLanes; ++j) {
      if (ids[j] >= 0) id[i + j] = static_cast<std::int32_t>(ids[j]);
    }
  }
}

void occluded(const Spheres& spheres, const Planes& planes, const Rays& rays, const double* t_max, int lanes,
              std::uint8_t* occluded_out) {
  for (int i = 0; i < lanes; i += kLanes) {
    const V ox = load(rays.ox + i), oy = load(rays.oy + i), oz = load(rays.oz + i);
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    const V limit = load(t_max + i);
    const M idle = not_gt(limit, zeros());  // !(t_max > 0): no ray
    if (lanes_set(idle) == kAll) continue;
    M blocked = no_lanes();
    for (int j = 0; j < spheres.tested_count && lanes_set(either(blocked, idle)) != kAll; ++j) {
      const int k = spheres.tested[j];
      const V t = sphere_root(ox, oy, oz, dx, dy, dz, spheres.cx[k], spheres.cy[k], spheres.cz[k], spheres.r[k], limit);
      blocked = either(blocked, gt(t, zeros()));
    }
    for (int k = 0; k < planes.count && lanes_set(either(blocked, idle)) != kAll; ++k) {
      M valid;
      const V t = plane_t(ox, oy, oz, dx, dy, dz, planes, k, &valid);
      blocked = either(blocked, both(valid, lt(t, limit)));
    }
    blocked = and_not(idle, blocked);
    const int bits = lanes_set(blocked);
    for (int j = 0; j < kLanes; ++j) {
      if (bits & (1 << j)) occluded_out[i + j] = 1;
    }
  }
}

namespace {

// kLanes rays with what the box test (BoxRay) and the watertight triangle test (make_shear) need.
struct Packet {
  V o[3], d[3];
  V inv[3];             // 1 / d
  int sign[3];          // bit j set when lane j's d[a] has its sign bit set
  int octant(int j) const { return ((sign[0] >> j) & 1) | (((sign[1] >> j) & 1) << 1) | (((sign[2] >> j) & 1) << 2); }
  // The shear of each lane: its axis permutation as masks, its origin permuted, sx, sy, sz.
  M kx_is0, kx_is1, ky_is0, ky_is1, kz_is0, kz_is1;
  V okx, oky, okz;
  V sx, sy, sz;
  bool uniform;         // all lanes share one permutation, namely kx, ky, kz
  int kx, ky, kz;
};

// kLanes rays of `rays` from lane i with their triangle shear only (inv and sign unset: the loose
// triangles test no boxes); `live`: the lanes that matter (the shear's `uniform` looks at those
// only).
Packet shear_packet(const Rays& rays, int i, int live) {
  Packet p;
  p.o[0] = load(rays.ox + i), p.o[1] = load(rays.oy + i), p.o[2] = load(rays.oz + i);
  p.d[0] = load(rays.dx + i), p.d[1] = load(rays.dy + i), p.d[2] = load(rays.dz + i);
  // make_shear, lane by lane: kz is the axis of the largest |d| (the first of equals), kx and ky
  // follow it cyclically, swapped when d[kz] < 0.
  const V ax = abs(p.d[0]), ay = abs(p.d[1]), az = abs(p.d[2]);
  const M x_ge_y = ge(ax, ay);
  const M kz0 = both(x_ge_y, ge(ax, az));
  const M kz1 = and_not(x_ge_y, ge(ay, az));
  const M kz2 = and_not(either(kz0, kz1), all_lanes());
  const V d_kz = pick(kz0, p.d[0], pick(kz1, p.d[1], p.d[2]));
  const M swap = lt(d_kz, zeros());
  // One permutation for all live lanes (the usual case): kz and the swap agree.
  const int m0 = lanes_set(kz0) & live, m1 = lanes_set(kz1) & live, ms = lanes_set(swap) & live;
  p.uniform = (m0 == 0 || m0 == live) && (m1 == 0 || m1 == live) && (ms == 0 || ms == live);
  const int first = __builtin_ctz(static_cast<unsigned>(live));
  p.kz = (m0 >> first) & 1 ? 0 : (m1 >> first) & 1 ? 1 : 2;
  const bool swapped = (ms >> first) & 1;
  p.kx = swapped ? (p.kz + 2) % 3 : (p.kz + 1) % 3;
  p.ky = swapped ? (p.kz + 1) % 3 : (p.kz + 2) % 3;
  p.sz = splat(1.0) / d_kz;
  if (p.uniform) {  // the same values as the blends below pick, by index
    p.okx = p.o[p.kx], p.oky = p.o[p.ky], p.okz = p.o[p.kz];
    p.sx = p.d[p.kx] * p.sz;
    p.sy = p.d[p.ky] * p.sz;
    return p;
  }
  p.kz_is0 = kz0, p.kz_is1 = kz1;
  p.kx_is0 = choose(swap, kz1, kz2), p.kx_is1 = choose(swap, kz2, kz0);
  p.ky_is0 = choose(swap, kz2, kz1), p.ky_is1 = choose(swap, kz0, kz2);
  const auto select = [](M is0, M is1, const V* v) { return pick(is0, v[0], pick(is1, v[1], v[2])); };
  p.okx = select(p.kx_is0, p.kx_is1, p.o), p.oky = select(p.ky_is0, p.ky_is1, p.o), p.okz = select(kz0, kz1, p.o);
  p.sx = select(p.kx_is0, p.kx_is1, p.d) * p.sz;
  p.sy = select(p.ky_is0, p.ky_is1, p.d) * p.sz;
  return p;
}

// The same with what the box tests need too (1 / d and the sign octants).
Packet make_packet(const Rays& rays, int i, int live) {
  Packet p = shear_packet(rays, i, live);
  for (int a = 0; a < 3; ++a) p.inv[a] = splat(1.0) / p.d[a];
  for (int a = 0; a < 3; ++a) p.sign[a] = sign_lanes(p.d[a]);
  return p;
}

// The sign octant of a walk's lanes, and where each axis's near and far slab planes sit in a
// Node's box: the high plane comes first for a negative direction (sign bit set, -0 included).
struct Octant {
  int bits;  // bit a set when d[a] is negative
  int near[3], far[3];
  explicit Octant(int b) : bits(b) {
    for (int a = 0; a < 3; ++a) {
      const bool negative = (b >> a) & 1;
      near[a] = negative ? 3 + a : a;
      far[a] = negative ? a : 3 + a;
    }
  }
};

// hits_box for the lanes of one octant: whether each meets the box within (0, t_max].
inline M hits_box(const Node& n, const Packet& p, const Octant& o, V t_max, const Hierarchy& h) {
  V t0 = zeros();
  V t1 = t_max * splat(h.t_max_slack);
  for (int a = 0; a < 3; ++a) {
    const V tn = (splat(n.box[o.near[a]]) - p.o[a]) * p.inv[a];
    const V tf = (splat(n.box[o.far[a]]) - p.o[a]) * p.inv[a] * splat(h.far_widen);
    t0 = max_of(tn, t0);  // tn > t0 ? tn : t0
    t1 = min_of(tf, t1);  // tf < t1 ? tf : t1
  }
  return le(t0, t1);
}

// Component k of vertex v for each lane, k being each lane's kx, ky or kz (masks is0, is1).
inline V component(const Packet& p, const double* v, int uniform_k, M is0, M is1) {
  if (p.uniform) return splat(v[uniform_k]);
  return pick(is0, splat(v[0]), pick(is1, splat(v[1]), splat(v[2])));
}

// The watertight test of intersect_triangle for kLanes rays: the lanes with a hit at t in
// (0, inf), its t and (when asked) the barycentric weights.
struct TriangleHit {
  M valid;
  V t, u, v, w, det;
};
inline TriangleHit triangle_hit(const Packet& p, const double* v0) {
  const double* v1 = v0 + 3;
  const double* v2 = v0 + 6;
  const V zero = zeros();
  const V a_x = component(p, v0, p.kx, p.kx_is0, p.kx_is1) - p.okx;
  const V a_y = component(p, v0, p.ky, p.ky_is0, p.ky_is1) - p.oky;
  const V a_z = component(p, v0, p.kz, p.kz_is0, p.kz_is1) - p.okz;
  const V b_x = component(p, v1, p.kx, p.kx_is0, p.kx_is1) - p.okx;
  const V b_y = component(p, v1, p.ky, p.ky_is0, p.ky_is1) - p.oky;
  const V b_z = component(p, v1, p.kz, p.kz_is0, p.kz_is1) - p.okz;
  const V c_x = component(p, v2, p.kx, p.kx_is0, p.kx_is1) - p.okx;
  const V c_y = component(p, v2, p.ky, p.ky_is0, p.ky_is1) - p.oky;
  const V c_z = component(p, v2, p.kz, p.kz_is0, p.kz_is1) - p.okz;
  const V ax = a_x - p.sx * a_z, ay = a_y - p.sy * a_z;
  const V bx = b_x - p.sx * b_z, by = b_y - p.sy * b_z;
  const V cx = c_x - p.sx * c_z, cy = c_y - p.sy * c_z;
  TriangleHit r;
  r.u = cx * by - cy * bx;
  r.v = ax * cy - ay * cx;
  r.w = bx * ay - by * ax;
  const M negative = either(either(lt(r.u, zero), lt(r.v, zero)), lt(r.w, zero));
  const M positive = either(either(gt(r.u, zero), gt(r.v, zero)), gt(r.w, zero));
  const M mixed = both(negative, positive);
  if (lanes_set(mixed) == kAll) {  // every lane passes outside an edge: no t to compute
    r.valid = no_lanes();
    return r;
  }
  r.det = (r.u + r.v) + r.w;
  const V t_scaled = (r.u * (p.sz * a_z) + r.v * (p.sz * b_z)) + r.w * (p.sz * c_z);
  r.t = t_scaled / r.det;
  r.valid = and_not(mixed, both(ne(r.det, zero), both(gt(r.t, zero), lt(r.t, splat(kInf)))));
  return r;
}

// intersect_triangle's last check: a triangle of zero area (|(v1 - v0) x (v2 - v0)|^2 not > 0) is
// never hit. glm's cross and dot, in their order.
bool has_area(const double* v0) {
  const double e1[3] = {v0[3] - v0[0], v0[4] - v0[1], v0[5] - v0[2]};
  const double e2[3] = {v0[6] - v0[0], v0[7] - v0[1], v0[8] - v0[2]};
  const double c[3] = {e1[1] * e2[2] - e2[1] * e1[2], e1[2] * e2[0] - e2[2] * e1[0], e1[0] * e2[1] - e2[0] * e1[1]};
  return (c[0] * c[0] + c[1] * c[1]) + c[2] * c[2] > 0;
}

// What a walk keeps for kLanes lanes. Nearest-hit: the nearest so far (t, id, prim, b1, b2).
// Any-hit: `best` holds each lane's fixed t_max, and `blocked` grows.
struct Walk {
  V best, id, prim, b1, b2;
  M blocked;
};

// Tests one triangle (id, prim) for the lanes of `m`.
template <bool kAny>
inline void test_triangle(const Packet& p, const double* v0, double id, double prim, M m, Walk& w) {
  const TriangleHit hit = triangle_hit(p, v0);
  if constexpr (kAny) {
    const M blocks = both(both(m, hit.valid), lt(hit.t, w.best));
    if (lanes_set(blocks) == 0 || !has_area(v0)) return;
    w.blocked = either(w.blocked, blocks);
  } else {
    // replaces(): nearer, or as near and first in the scene's order (id, then prim).
    const V cand_id = splat(id), cand_prim = splat(prim);
    const M first = either(lt(cand_id, w.id), both(eq(cand_id, w.id), lt(cand_prim, w.prim)));
    const M tie = both(both(eq(hit.t, w.best), ge(w.id, zeros())), first);
    const M take = both(both(m, hit.valid), either(lt(hit.t, w.best), tie));
    if (lanes_set(take) == 0 || !has_area(v0)) return;
    w.best = pick(take, hit.t, w.best);
    w.id = pick(take, cand_id, w.id);
    w.prim = pick(take, cand_prim, w.prim);
    w.b1 = pick(take, hit.v / hit.det, w.b1);
    w.b2 = pick(take, hit.w / hit.det, w.b2);
  }
}

// The lanes still walking: all of `lanes` for a nearest-hit query, the unblocked ones for any-hit.
template <bool kAny>
inline M walking(M lanes, const Walk& w) {
  if constexpr (kAny) return and_not(w.blocked, lanes);
  return lanes;
}

// traverse() over one BVH for the lanes of `lanes` (all of one octant): `leaf(first, count, m)`
// tests a leaf's primitives for the lanes m whose own box test passed.
template <bool kAny, class Leaf>
inline void walk(const Node* nodes, const Packet& p, const Octant& octant, M lanes, Walk& w, const Hierarchy& h, Leaf&& leaf) {
  std::uint32_t stack[128];
  int top = 0;
  std::uint32_t index = 0;
  for (;;) {
    const Node& node = nodes[index];
    const M live = walking<kAny>(lanes, w);
    if constexpr (kAny) {
      if (lanes_set(live) == 0) return;  // every lane blocked
    }
    const M m = both(live, hits_box(node, p, octant, w.best, h));
    if (lanes_set(m) != 0) {
      if (node.count > 0) {
        leaf(node.first, node.count, m);
      } else {
        const bool flip = (octant.bits >> node.axis) & 1;
        stack[top++] = flip ? index + 1 : node.first;
        index = flip ? node.first : index + 1;
        continue;
      }
    }
    if (top == 0) return;
    index = stack[--top];
  }
}

// The whole hierarchy for the lanes of `lanes` (all of one octant).
template <bool kAny>
void walk_scene(const Hierarchy& h, const Packet& p, const Octant& octant, M lanes, Walk& w) {
  const auto top_leaf = [&](std::uint32_t first, std::uint32_t count, M m) {
    for (std::uint32_t slot = first; slot < first + count; ++slot) {
      const std::int32_t k = h.prim_index[slot];
      switch (h.prim_kind[slot]) {
        case 0: {  // sphere
          const V t = sphere_root(p.o[0], p.o[1], p.o[2], p.d[0], p.d[1], p.d[2], h.cx[k], h.cy[k], h.cz[k], h.r[k], w.best);
          const M hit = both(walking<kAny>(m, w), gt(t, zeros()));
          if constexpr (kAny) {
            w.blocked = either(w.blocked, hit);
          } else {
            w.best = pick(hit, t, w.best);
            w.id = pick(hit, splat(k), w.id);
            w.prim = pick(hit, splat(-1), w.prim);
          }
          break;
        }
        case 1:  // loose triangle
          test_triangle<kAny>(p, h.triangles + k * h.triangle_stride, h.triangle_id + k, -1, walking<kAny>(m, w), w);
          break;
        default: {  // mesh
          const MeshTree& mesh = h.meshes[k];
          const double id = h.mesh_id + k;
          walk<kAny>(mesh.nodes, p, octant, m, w, h, [&](std::uint32_t f, std::uint32_t n, M mm) {
            for (std::uint32_t i = f; i < f + n; ++i) {
              test_triangle<kAny>(p, mesh.vertices + static_cast<long>(i) * h.triangle_stride, id, i,
                                  walking<kAny>(mm, w), w);
            }
          });
          break;
        }
      }
    }
  };
  walk<kAny>(h.top, p, octant, lanes, w, h, top_leaf);
}

// Runs walk_scene once for each octant among the lanes of `lanes` (usually one).
template <bool kAny>
void walk_octants(const Hierarchy& h, const Packet& p, int lanes, Walk& w) {
  while (lanes != 0) {
    const int first = __builtin_ctz(static_cast<unsigned>(lanes));
    const int octant = p.octant(first);
    int group = 0;
    for (int j = first; j < kLanes; ++j) {
      if ((lanes >> j) & 1 && p.octant(j) == octant) group |= 1 << j;
    }
    walk_scene<kAny>(h, p, Octant(octant), lane_mask(group), w);
    lanes &= ~group;
  }
}

// The lanes i .. i + kLanes - 1 of a shadow batch that still need a query: a ray (t_max > 0) that
// nothing has occluded yet.
int shadow_lanes(const double* t_max, const std::uint8_t* occluded, int i) {
  int live = lanes_set(gt(load(t_max + i), zeros()));
  for (int j = 0; j < kLanes; ++j) {
    if (occluded[i + j]) live &= ~(1 << j);
  }
  return live;
}

}  // namespace

void hierarchy_nearest(const Hierarchy& h, const Rays& rays, int live, const NearestHits& out) {
  if (h.top == nullptr) return;
  for (int i = 0; i < live; i += kLanes) {
    const int lanes = live_lanes(live - i);
    const Packet p = make_packet(rays, i, lanes);
    Walk w;
    w.best = load(out.t + i);
    w.id = from_int32(out.id + i);
    w.prim = splat(-1);
    w.b1 = w.b2 = zeros();
    w.blocked = no_lanes();
    walk_octants<false>(h, p, lanes, w);
    double t[kLanes], id[kLanes], prim[kLanes], b1[kLanes], b2[kLanes];
    store(t, w.best);
    store(id, w.id);
    store(prim, w.prim);
    store(b1, w.b1);
    store(b2, w.b2);
    // Whatever the hierarchy finds is nearer than the lane's plane hit (a tie goes to the plane,
    // first in the scene's order), so a nearer t is the mark of a new answer.
    const int changed = lanes_set(lt(w.best, load(out.t + i)));
    for (int j = 0; j < kLanes; ++j) {
      if (!((lanes & changed) >> j & 1)) continue;
      out.t[i + j] = t[j];
      out.id[i + j] = static_cast<std::int32_t>(id[j]);
      out.prim[i + j] = static_cast<std::int32_t>(prim[j]);
      out.b1[i + j] = b1[j];
      out.b2[i + j] = b2[j];
    }
  }
}

void hierarchy_occluded(const Hierarchy& h, const Rays& rays, const double* t_max, int lanes, std::uint8_t* occluded_out) {
  if (h.top == nullptr) return;
  for (int i = 0; i < lanes; i += kLanes) {
    const int live = shadow_lanes(t_max, occluded_out, i);
    if (live == 0) continue;
    const Packet p = make_packet(rays, i, live);
    Walk w;
    w.best = load(t_max + i);
    w.id = w.prim = w.b1 = w.b2 = zeros();
    w.blocked = no_lanes();
    walk_octants<true>(h, p, live, w);
    const int bits = lanes_set(w.blocked) & live;
    for (int j = 0; j < kLanes; ++j) {
      if (bits & (1 << j)) occluded_out[i + j] = 1;
    }
  }
}

void triangles_nearest(const LooseTriangles& tris, const Rays& rays, int live, const NearestHits& out) {
  if (tris.tested_count == 0) return;
  for (int i = 0; i < live; i += kLanes) {
    const int lanes = live_lanes(live - i);
    const Packet p = shear_packet(rays, i, lanes);
    const M m = lane_mask(lanes);
    V best = load(out.t + i);
    V id = from_int32(out.id + i);
    V b1 = zeros(), b2 = zeros();
    int changed = 0;
    for (int j = 0; j < tris.tested_count; ++j) {
      const int k = tris.tested[j];
      const double* v0 = tris.vertices + k * tris.stride;
      const TriangleHit hit = triangle_hit(p, v0);
      const M take = both(both(m, hit.valid), lt(hit.t, best));
      const int bits = lanes_set(take);
      if (bits == 0 || !has_area(v0)) continue;
      best = pick(take, hit.t, best);
      id = pick(take, splat(tris.first_id + k), id);
      b1 = pick(take, hit.v / hit.det, b1);
      b2 = pick(take, hit.w / hit.det, b2);
      changed |= bits;
    }
    if (changed == 0) continue;
    double t_out[kLanes], id_out[kLanes], b1_out[kLanes], b2_out[kLanes];
    store(t_out, best);
    store(id_out, id);
    store(b1_out, b1);
    store(b2_out, b2);
    for (int j = 0; j < kLanes; ++j) {
      if (!((changed >> j) & 1)) continue;
      out.t[i + j] = t_out[j];
      out.id[i + j] = static_cast<std::int32_t>(id_out[j]);
      out.b1[i + j] = b1_out[j];
      out.b2[i + j] = b2_out[j];
    }
  }
}

void triangles_occluded(const LooseTriangles& tris, const Rays& rays, const double* t_max, int lanes,
                        std::uint8_t* occluded_out) {
  if (tris.tested_count == 0) return;
  for (int i = 0; i < lanes; i += kLanes) {
    const int live = shadow_lanes(t_max, occluded_out, i);
    if (live == 0) continue;
    const Packet p = shear_packet(rays, i, live);
    const V limit = load(t_max + i);
    M open = lane_mask(live);
    for (int j = 0; j < tris.tested_count && lanes_set(open) != 0; ++j) {
      const int k = tris.tested[j];
      const double* v0 = tris.vertices + k * tris.stride;
      const TriangleHit hit = triangle_hit(p, v0);
      const M blocks = both(both(open, hit.valid), lt(hit.t, limit));
      if (lanes_set(blocks) == 0 || !has_area(v0)) continue;
      open = and_not(blocks, open);
    }
    const int bits = live & ~lanes_set(open);
    for (int j = 0; j < kLanes; ++j) {
      if (bits & (1 << j)) occluded_out[i + j] = 1;
    }
  }
}

}  // namespace phonglab::packet::PHONGLAB_SIMD_NS
