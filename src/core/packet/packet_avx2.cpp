// AVX2 kernels of the packet tracer; see packet_kernels.h for the rules this file follows
// (only plain data, intrinsics and functions with internal linkage: no header with inline code).
#include "core/packet/packet_kernels.h"

#include <immintrin.h>

namespace phonglab::packet {

namespace {

using V = __m256d;  // four doubles; + - * / on it are the plain IEEE operations, lane by lane

inline V load(const double* p) { return _mm256_loadu_pd(p); }
inline void store(double* p, V v) { _mm256_storeu_pd(p, v); }
inline V splat(double x) { return _mm256_set1_pd(x); }
inline V gt(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_GT_OQ); }   // a > b, false with NaN
inline V lt(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_LT_OQ); }   // a < b
inline V ge(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_GE_OQ); }   // a >= b
inline V ne(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_NEQ_UQ); }  // !(a == b)
inline V both(V a, V b) { return _mm256_and_pd(a, b); }
inline V either(V a, V b) { return _mm256_or_pd(a, b); }
inline V and_not(V mask, V a) { return _mm256_andnot_pd(mask, a); }  // a where mask is clear
inline V pick(V mask, V if_set, V if_clear) { return _mm256_blendv_pd(if_clear, if_set, mask); }
inline V sign_bit() { return splat(-0.0); }
inline V negate(V a) { return _mm256_xor_pd(a, sign_bit()); }
inline V sqrt(V a) { return _mm256_sqrt_pd(a); }
inline V dot(V ax, V ay, V az, V bx, V by, V bz) { return (ax * bx + ay * by) + az * bz; }  // glm's order
inline int lanes_set(V mask) { return _mm256_movemask_pd(mask); }

constexpr double kInf = __builtin_huge_val();

// Four byte flags from p on: bit j set where p[j] is not 0.
inline int byte_lanes(const std::uint8_t* p) {
  int word;
  __builtin_memcpy(&word, p, 4);
  const __m128i bytes = _mm_cvtsi32_si128(word);
  return ~_mm_movemask_epi8(_mm_cmpeq_epi8(bytes, _mm_setzero_si128())) & 0xF;
}
// Bit j of `bits` as byte j (0 or 1) of a word, and four such bytes stored from p on.
inline std::uint32_t spread_bits(int bits) {
  return (bits & 1) | (bits & 2) << 7 | (bits & 4) << 14 | static_cast<std::uint32_t>(bits & 8) << 21;
}
inline void put_byte_lanes(std::uint8_t* p, std::uint32_t word) { __builtin_memcpy(p, &word, 4); }

inline V lane_mask(int bits) {  // lane j all ones where bit j is set
  return _mm256_castsi256_pd(_mm256_set_epi64x(bits & 8 ? -1 : 0, bits & 4 ? -1 : 0, bits & 2 ? -1 : 0, bits & 1 ? -1 : 0));
}

// sphere_root(s, o, d, 0, t_max) for four rays: the root, or 0 where there is none.
inline V sphere_root(V ox, V oy, V oz, V dx, V dy, V dz, double cx, double cy, double cz, double radius,
                     V t_max) {
  const V zero = _mm256_setzero_pd();
  const V fx = ox - splat(cx), fy = oy - splat(cy), fz = oz - splat(cz);
  const V b = dot(fx, fy, fz, dx, dy, dz);
  const double r2 = radius * radius;
  const V c = dot(fx, fy, fz, fx, fy, fz) - splat(r2);
  const V early = both(gt(c, zero), either(gt(b, zero), gt(negate(b) - splat(radius), t_max)));
  const V px = fx - b * dx, py = fy - b * dy, pz = fz - b * dz;
  const V disc = splat(r2) - dot(px, py, pz, px, py, pz);
  const V candidates = and_not(early, ge(disc, zero));
  if (lanes_set(candidates) == 0) return zero;  // the usual case: the sphere is missed by all four
  const V root = sqrt(disc);
  const V signed_root = either(and_not(sign_bit(), root), both(sign_bit(), b));  // copysign(root, b)
  const V q = negate(b + signed_root);
  const V t0 = c / q;
  const V swap = gt(t0, q);
  const V lo = pick(swap, q, t0), hi = pick(swap, t0, q);
  const V lo_t = both(lt(lo, t_max), lo);
  const V hi_t = both(lt(hi, t_max), hi);
  const V t = pick(gt(lo, zero), lo_t, both(gt(hi, zero), hi_t));
  return both(both(candidates, ne(q, zero)), t);
}

// intersect_plane's distance, and whether it counts (t in (0, inf), the plane not parallel).
inline V plane_t(V ox, V oy, V oz, V dx, V dy, V dz, const Planes& pl, int k, V* valid) {
  const V nx = splat(pl.nx[k]), ny = splat(pl.ny[k]), nz = splat(pl.nz[k]);
  const V denom = dot(dx, dy, dz, nx, ny, nz);
  const V wx = splat(pl.px[k]) - ox, wy = splat(pl.py[k]) - oy, wz = splat(pl.pz[k]) - oz;
  const V t = dot(wx, wy, wz, nx, ny, nz) / denom;
  const V zero = _mm256_setzero_pd();
  *valid = both(ne(denom, zero), both(gt(t, zero), lt(t, splat(kInf))));
  return t;
}

}  // namespace

void nearest(const Spheres& spheres, const Planes& planes, const Rays& rays, int lanes, double* t_best,
             std::int32_t* id) {
  for (int i = 0; i < lanes; i += 4) {
    const V ox = load(rays.ox + i), oy = load(rays.oy + i), oz = load(rays.oz + i);
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    V best = load(t_best + i);
    V best_id = splat(-1);
    for (int j = 0; j < spheres.tested_count; ++j) {
      const int k = spheres.tested[j];
      const V t = sphere_root(ox, oy, oz, dx, dy, dz, spheres.cx[k], spheres.cy[k], spheres.cz[k], spheres.r[k], best);
      const V hit = gt(t, _mm256_setzero_pd());
      best = pick(hit, t, best);
      best_id = pick(hit, splat(k), best_id);
    }
    for (int k = 0; k < planes.count; ++k) {
      V valid;
      const V t = plane_t(ox, oy, oz, dx, dy, dz, planes, k, &valid);
      const V hit = both(valid, lt(t, best));
      best = pick(hit, t, best);
      best_id = pick(hit, splat(spheres.count + k), best_id);
    }
    store(t_best + i, best);
    alignas(32) double ids[4];
    _mm256_store_pd(ids, best_id);
    for (int j = 0; j < 4; ++j) {
      if (ids[j] >= 0) id[i + j] = static_cast<std::int32_t>(ids[j]);
    }
  }
}

void occluded(const Spheres& spheres, const Planes& planes, const Rays& rays, const double* t_max, int lanes,
              std::uint8_t* occluded_out) {
  for (int i = 0; i < lanes; i += 4) {
    const V ox = load(rays.ox + i), oy = load(rays.oy + i), oz = load(rays.oz + i);
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    const V limit = load(t_max + i);
    const V idle = _mm256_cmp_pd(limit, _mm256_setzero_pd(), _CMP_NGT_UQ);  // !(t_max > 0): no ray
    if (lanes_set(idle) == 0xF) continue;
    V blocked = _mm256_setzero_pd();
    for (int j = 0; j < spheres.tested_count && lanes_set(either(blocked, idle)) != 0xF; ++j) {
      const int k = spheres.tested[j];
      const V t = sphere_root(ox, oy, oz, dx, dy, dz, spheres.cx[k], spheres.cy[k], spheres.cz[k], spheres.r[k], limit);
      blocked = either(blocked, gt(t, _mm256_setzero_pd()));
    }
    for (int k = 0; k < planes.count && lanes_set(either(blocked, idle)) != 0xF; ++k) {
      V valid;
      const V t = plane_t(ox, oy, oz, dx, dy, dz, planes, k, &valid);
      blocked = either(blocked, both(valid, lt(t, limit)));
    }
    blocked = and_not(idle, blocked);
    const int bits = lanes_set(blocked);
    for (int j = 0; j < 4; ++j) {
      if (bits & (1 << j)) occluded_out[i + j] = 1;
    }
  }
}

void hit_records(const Spheres& spheres, const Planes& planes, const OffsetMargins& margins, const Rays& rays,
                 const double* t_in, const std::int32_t* id, int lanes, const HitRecords& out) {
  const V zero = _mm256_setzero_pd();
  const V abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7FFFFFFFFFFFFFFF));
  const auto max_abs = [&](V x, V y, V z) {  // std::max of non-negative values: the same as maxpd
    return _mm256_max_pd(_mm256_max_pd(_mm256_and_pd(x, abs_mask), _mm256_and_pd(y, abs_mask)),
                         _mm256_and_pd(z, abs_mask));
  };
  const int s_count = spheres.count, p_count = planes.count;
  for (int i = 0; i < lanes; i += 4) {
    // Gather each lane's primitive (index 0 stands in where the lane has another kind).
    alignas(32) double cx[4] = {}, cy[4] = {}, cz[4] = {}, r[4] = {}, base[4] = {}, sph[4] = {};
    alignas(32) double nx[4] = {}, ny[4] = {}, nz[4] = {}, size[4] = {};
    int kinds = 0;
    for (int j = 0; j < 4; ++j) {
      const std::int32_t k = id[i + j];
      if (k >= 0 && k < s_count) {
        cx[j] = spheres.cx[k], cy[j] = spheres.cy[k], cz[j] = spheres.cz[k], r[j] = spheres.r[k];
        base[j] = spheres.offset_base[k];
        sph[j] = -1.0;  // all bits set: a mask
        kinds |= 1;
      } else if (k >= s_count && k < s_count + p_count) {
        const int q = k - s_count;
        nx[j] = planes.nx[q], ny[j] = planes.ny[q], nz[j] = planes.nz[q], size[j] = planes.point_size[q];
        kinds |= 2;
      }
    }
    if (kinds == 0) continue;
    const V is_sphere = _mm256_cmp_pd(_mm256_load_pd(sph), zero, _CMP_NEQ_UQ);
    const V t = load(t_in + i);
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    // P = O + t D; a sphere's is re-projected onto it along the radial direction.
    V px = load(rays.ox + i) + t * dx, py = load(rays.oy + i) + t * dy, pz = load(rays.oz + i) + t * dz;
    V gx = _mm256_load_pd(nx), gy = _mm256_load_pd(ny), gz = _mm256_load_pd(nz);
    V offset = splat(margins.coordinate) * _mm256_max_pd(max_abs(px, py, pz), _mm256_load_pd(size)) +
               splat(margins.size) * t;
    if (kinds & 1) {
      const V scx = _mm256_load_pd(cx), scy = _mm256_load_pd(cy), scz = _mm256_load_pd(cz), sr = _mm256_load_pd(r);
      const V rx = px - scx, ry = py - scy, rz = pz - scz;
      const V len = sqrt(dot(rx, ry, rz, rx, ry, rz));
      const V has = gt(len, zero);
      const V ux = pick(has, rx / len, zero), uy = pick(has, ry / len, splat(1)), uz = pick(has, rz / len, zero);
      gx = pick(is_sphere, ux, gx);
      gy = pick(is_sphere, uy, gy);
      gz = pick(is_sphere, uz, gz);
      px = pick(is_sphere, scx + sr * ux, px);
      py = pick(is_sphere, scy + sr * uy, py);
      pz = pick(is_sphere, scz + sr * uz, pz);
      offset = pick(is_sphere, _mm256_load_pd(base) + splat(margins.size) * (sr + t), offset);
    }
    // The ray's side: a sphere's or plane's shading normal is its geometric one.
    const V entering = lt(dot(gx, gy, gz, dx, dy, dz), zero);
    gx = pick(entering, gx, negate(gx));
    gy = pick(entering, gy, negate(gy));
    gz = pick(entering, gz, negate(gz));
    // All four lanes are written: a triangle's lane is overwritten by the caller afterwards,
    // a missed ray's is never read.
    store(out.px + i, px);
    store(out.py + i, py);
    store(out.pz + i, pz);
    store(out.nx + i, gx);
    store(out.ny + i, gy);
    store(out.nz + i, gz);
    store(out.gx + i, gx);
    store(out.gy + i, gy);
    store(out.gz + i, gz);
    store(out.vx + i, negate(dx));
    store(out.vy + i, negate(dy));
    store(out.vz + i, negate(dz));
    store(out.offset + i, offset);
    const int enter_bits = lanes_set(entering);
    for (int j = 0; j < 4; ++j) out.entering[i + j] = (enter_bits >> j) & 1;
  }
}

void triangle_records(const TriangleRecords& tris, const OffsetMargins& margins, const Rays& rays, const double* t_in,
                      const std::int32_t* id, const double* b1_in, const double* b2_in, int lanes, const HitRecords& out) {
  const V zero = _mm256_setzero_pd(), one = splat(1);
  for (int i = 0; i < lanes; i += 4) {
    // Each lane's triangle; lanes of other kinds borrow the first one's (and are not written).
    std::int64_t k[4];
    int mine = 0;
    for (int j = 0; j < 4; ++j) {
      k[j] = id[i + j] - tris.first_id;
      if (k[j] >= 0 && k[j] < tris.count && tris.flat[k[j]]) mine |= 1 << j;
    }
    if (mine == 0) continue;
    const std::int64_t first = k[__builtin_ctz(static_cast<unsigned>(mine))];
    for (int j = 0; j < 4; ++j) {
      if (!((mine >> j) & 1)) k[j] = first;
    }
    const bool shared = k[0] == k[1] && k[1] == k[2] && k[2] == k[3];  // usually: one floor, one triangle
    const __m256i tri_at = _mm256_set_epi64x(k[3] * tris.stride, k[2] * tris.stride, k[1] * tris.stride, k[0] * tris.stride);
    const __m256i normal_at = _mm256_set_epi64x(3 * k[3], 3 * k[2], 3 * k[1], 3 * k[0]);
    const __m256i size_at = _mm256_set_epi64x(k[3], k[2], k[1], k[0]);
    const auto fetch = [&](const double* base, __m256i at, std::int64_t shared_at) {
      return shared ? splat(base[shared_at]) : _mm256_i64gather_pd(base, at, 8);
    };
    V v[9];
    for (int c = 0; c < 9; ++c) v[c] = fetch(tris.vertices + c, tri_at, first * tris.stride);
    V n[3];
    for (int c = 0; c < 3; ++c) n[c] = fetch(tris.normal + c, normal_at, 3 * first);
    const V size = fetch(tris.magnitude, size_at, first);
    const V m = lane_mask(mine);
    const V b1 = load(b1_in + i), b2 = load(b2_in + i);
    const V b0 = (one - b1) - b2;
    const auto keep = [&](double* p, V x) { store(p + i, pick(m, x, load(p + i))); };
    double* const p_out[3] = {out.px, out.py, out.pz};
    for (int c = 0; c < 3; ++c) {  // glm's b0 v0 + b1 v1 + b2 v2, left to right
      keep(p_out[c], (b0 * v[c] + b1 * v[3 + c]) + b2 * v[6 + c]);
    }
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    V gx = n[0], gy = n[1], gz = n[2];
    const V entering = lt(dot(gx, gy, gz, dx, dy, dz), zero);
    gx = pick(entering, gx, negate(gx));
    gy = pick(entering, gy, negate(gy));
    gz = pick(entering, gz, negate(gz));
    keep(out.nx, gx), keep(out.ny, gy), keep(out.nz, gz);
    keep(out.gx, gx), keep(out.gy, gy), keep(out.gz, gz);
    keep(out.vx, negate(dx)), keep(out.vy, negate(dy)), keep(out.vz, negate(dz));
    keep(out.offset, splat(margins.coordinate) * size + splat(margins.size) * load(t_in + i));
    const int enter_bits = lanes_set(entering);
    for (int j = 0; j < 4; ++j) {
      if ((mine >> j) & 1) out.entering[i + j] = (enter_bits >> j) & 1;
    }
  }
}

void camera_dirs(const CameraIn& cam, const double* x_plus_u, const double* y_plus_v, int lanes, double* dx,
                 double* dy, double* dz) {
  const V two = splat(2), one = splat(1);
  for (int i = 0; i < lanes; i += 4) {
    // camera_ray: sx = 2 (x + u) / W - 1, sy = 1 - 2 (y + v) / H, D = normalize(F + sx R + sy U).
    const V sx = two * load(x_plus_u + i) / splat(cam.width) - one;
    const V sy = one - two * load(y_plus_v + i) / splat(cam.height);
    const V x = (splat(cam.fx) + sx * splat(cam.rx)) + sy * splat(cam.ux);
    const V y = (splat(cam.fy) + sx * splat(cam.ry)) + sy * splat(cam.uy);
    const V z = (splat(cam.fz) + sx * splat(cam.rz)) + sy * splat(cam.uz);
    const V inv = one / sqrt(dot(x, y, z, x, y, z));  // glm::normalize: v * inversesqrt(v.v)
    store(dx + i, x * inv);
    store(dy + i, y * inv);
    store(dz + i, z * inv);
  }
}

int light(const LightIn& lt_in, const ShadedPoints& pts, int lanes, const LightOut& out) {
  const V zero = _mm256_setzero_pd();
  const V lpx = splat(lt_in.x), lpy = splat(lt_in.y), lpz = splat(lt_in.z);
  int lit = 0;
  for (int i = 0; i < lanes; i += 4) {
    if (byte_lanes(pts.active + i) == 0) {
      if (out.shadow) {
        store(out.t_max + i, zero);
        put_byte_lanes(out.shadow + i, 0);
      }
      continue;
    }
    const V px = load(pts.px + i), py = load(pts.py + i), pz = load(pts.pz + i);
    const V nx = load(pts.nx + i), ny = load(pts.ny + i), nz = load(pts.nz + i);
    // L: towards a point light (NaN when it sits on P), or minus a directional light's direction.
    V lx = lpx, ly = lpy, lz = lpz;
    if (lt_in.point) {
      const V tx = lpx - px, ty = lpy - py, tz = lpz - pz;
      const V dist = sqrt(dot(tx, ty, tz, tx, ty, tz));
      lx = tx / dist;
      ly = ty / dist;
      lz = tz / dist;
    }
    const V n_dot_l = dot(nx, ny, nz, lx, ly, lz);
    store(out.n_dot_l + i, n_dot_l);
    const V vx = load(pts.vx + i), vy = load(pts.vy + i), vz = load(pts.vz + i);
    if (!lt_in.blinn) {  // R = 2 (N.L) N - L
      const V k = splat(2.0) * n_dot_l;
      const V rx = k * nx - lx, ry = k * ny - ly, rz = k * nz - lz;
      store(out.cos_spec + i, dot(rx, ry, rz, vx, vy, vz));
    } else {  // H = normalize(L + V), N itself when L = -V
      const V hx = lx + vx, hy = ly + vy, hz = lz + vz;
      const V len = sqrt(dot(hx, hy, hz, hx, hy, hz));
      const V has = gt(len, zero);
      const V rx = pick(has, hx / len, nx), ry = pick(has, hy / len, ny), rz = pick(has, hz / len, nz);
      store(out.cos_spec + i, both(has, dot(nx, ny, nz, rx, ry, rz)));
    }
    // offset_origin(P, Ng, L, offset): off the side of the surface the ray leaves by.
    const V gx = load(pts.gx + i), gy = load(pts.gy + i), gz = load(pts.gz + i);
    const V off = load(pts.offset + i);
    const V out_side = ge(dot(lx, ly, lz, gx, gy, gz), zero);
    const V ogx = off * gx, ogy = off * gy, ogz = off * gz;
    const V ox = pick(out_side, px + ogx, px - ogx);
    const V oy = pick(out_side, py + ogy, py - ogy);
    const V oz = pick(out_side, pz + ogz, pz - ogz);
    store(out.ox + i, ox);
    store(out.oy + i, oy);
    store(out.oz + i, oz);
    V t_max = splat(kInf);
    if (lt_in.point) {  // the open segment to the light, pulled in at the light's end
      const V tx = lpx - ox, ty = lpy - oy, tz = lpz - oz;
      const V dist = sqrt(dot(tx, ty, tz, tx, ty, tz));
      t_max = dist - splat(lt_in.shrink);
      store(out.dx + i, tx / dist);
      store(out.dy + i, ty / dist);
      store(out.dz + i, tz / dist);
    } else {
      store(out.dx + i, lx);
      store(out.dy + i, ly);
      store(out.dz + i, lz);
    }
    if (out.shadow) {  // a term where active and N.L > 0; a ray to test where t_max > 0 too
      const int on = byte_lanes(pts.active + i) & lanes_set(gt(n_dot_l, zero));
      const int test = on & lanes_set(gt(t_max, zero));
      lit += __builtin_popcount(static_cast<unsigned>(on));
      put_byte_lanes(out.shadow + i, spread_bits(on) + spread_bits(test));
      t_max = both(lane_mask(test), t_max);
    }
    store(out.t_max + i, t_max);
  }
  return lit;
}

void bounce(const BounceIn& in, int lanes, const BounceOut& out) {
  const V zero = _mm256_setzero_pd(), one = splat(1);
  const auto clamp_unit = [&](V x) {  // x > 1 ? 1 : (x < -1 ? -1 : x)
    return pick(gt(x, one), one, pick(lt(x, negate(one)), negate(one), x));
  };
  for (int i = 0; i < lanes; i += 4) {
    if ((in.active[i] | in.active[i + 1] | in.active[i + 2] | in.active[i + 3]) == 0) continue;
    const V dx = load(in.dx + i), dy = load(in.dy + i), dz = load(in.dz + i);
    const V nx = load(in.nx + i), ny = load(in.ny + i), nz = load(in.nz + i);
    const V ior = load(in.ior + i);
    const V entering = gt(_mm256_set_pd(in.entering[i + 3], in.entering[i + 2], in.entering[i + 1], in.entering[i]), zero);
    const V d_dot_n = dot(dx, dy, dz, nx, ny, nz);
    const V cos_i = clamp_unit(negate(d_dot_n));
    const V eta = pick(entering, one / ior, ior);
    const V sin2_t = (eta * eta) * (one - cos_i * cos_i);
    const V k = one - sin2_t;
    const V tir = lt(k, zero);
    // fresnel_exact(cos_i, eta): its clamp leaves a clamped cos_i as it is.
    const V cos_t = sqrt(one - sin2_t);
    const V eta_cos_i = eta * cos_i, eta_cos_t = eta * cos_t;
    const V rs = (eta_cos_i - cos_t) / (eta_cos_i + cos_t);
    const V rp = (cos_i - eta_cos_t) / (cos_i + eta_cos_t);
    const V f = splat(0.5) * (rs * rs + rp * rp);
    const V f_clamped = pick(gt(f, one), one, pick(lt(f, zero), zero, f));
    const V fresnel = pick(either(tir, ge(sin2_t, one)), one, f_clamped);
    // reflect_dir(D, N) = normalize(D - (2 D.N / N.N) N); a zero N leaves D.
    const V nn = dot(nx, ny, nz, nx, ny, nz);
    const V kr = pick(gt(nn, zero), splat(2.0) * d_dot_n / nn, zero);
    const V rx = dx - kr * nx, ry = dy - kr * ny, rz = dz - kr * nz;
    const V r_inv = one / sqrt(dot(rx, ry, rz, rx, ry, rz));
    const V mx = rx * r_inv, my = ry * r_inv, mz = rz * r_inv;
    // normalize(eta D + (eta cos_i - sqrt(k)) N), or the mirror direction under TIR.
    const V c = eta_cos_i - sqrt(k);
    const V ux = eta * dx + c * nx, uy = eta * dy + c * ny, uz = eta * dz + c * nz;
    const V u_inv = one / sqrt(dot(ux, uy, uz, ux, uy, uz));
    store(out.eta + i, eta);
    store(out.fresnel + i, fresnel);
    store(out.mx + i, mx);
    store(out.my + i, my);
    store(out.mz + i, mz);
    store(out.tx + i, pick(tir, mx, ux * u_inv));
    store(out.ty + i, pick(tir, my, uy * u_inv));
    store(out.tz + i, pick(tir, mz, uz * u_inv));
    const int tir_bits = lanes_set(tir);
    for (int j = 0; j < 4; ++j) out.tir[i + j] = (tir_bits >> j) & 1;
  }
}

namespace {

// Four rays with what the box test (BoxRay) and the watertight triangle test (make_shear) need.
struct Packet {
  V o[3], d[3];
  V inv[3];             // 1 / d
  int sign[3];          // bit j set when lane j's d[a] has its sign bit set
  int octant(int j) const { return ((sign[0] >> j) & 1) | (((sign[1] >> j) & 1) << 1) | (((sign[2] >> j) & 1) << 2); }
  // The shear of each lane: its axis permutation as masks, its origin permuted, sx, sy, sz.
  V kx_is0, kx_is1, ky_is0, ky_is1, kz_is0, kz_is1;
  V okx, oky, okz;
  V sx, sy, sz;
  bool uniform;         // all four lanes share one permutation, namely kx, ky, kz
  int kx, ky, kz;
};

// Four rays of `rays` from lane i with their triangle shear only (inv and sign unset: the loose
// triangles test no boxes); `live`: the lanes that matter (the shear's `uniform` looks at those
// only).
Packet shear_packet(const Rays& rays, int i, int live) {
  Packet p;
  p.o[0] = load(rays.ox + i), p.o[1] = load(rays.oy + i), p.o[2] = load(rays.oz + i);
  p.d[0] = load(rays.dx + i), p.d[1] = load(rays.dy + i), p.d[2] = load(rays.dz + i);
  // make_shear, lane by lane: kz is the axis of the largest |d| (the first of equals), kx and ky
  // follow it cyclically, swapped when d[kz] < 0.
  const V ax = and_not(sign_bit(), p.d[0]), ay = and_not(sign_bit(), p.d[1]), az = and_not(sign_bit(), p.d[2]);
  const V x_ge_y = ge(ax, ay);
  const V kz0 = both(x_ge_y, ge(ax, az));
  const V kz1 = and_not(x_ge_y, ge(ay, az));
  const V kz2 = and_not(either(kz0, kz1), _mm256_castsi256_pd(_mm256_set1_epi64x(-1)));
  const V d_kz = pick(kz0, p.d[0], pick(kz1, p.d[1], p.d[2]));
  const V swap = lt(d_kz, _mm256_setzero_pd());
  p.kz_is0 = kz0, p.kz_is1 = kz1;
  p.kx_is0 = pick(swap, kz1, kz2), p.kx_is1 = pick(swap, kz2, kz0);
  p.ky_is0 = pick(swap, kz2, kz1), p.ky_is1 = pick(swap, kz0, kz2);
  const auto select = [](V is0, V is1, const V* v) { return pick(is0, v[0], pick(is1, v[1], v[2])); };
  p.okx = select(p.kx_is0, p.kx_is1, p.o), p.oky = select(p.ky_is0, p.ky_is1, p.o), p.okz = select(kz0, kz1, p.o);
  p.sz = splat(1.0) / d_kz;
  p.sx = select(p.kx_is0, p.kx_is1, p.d) * p.sz;
  p.sy = select(p.ky_is0, p.ky_is1, p.d) * p.sz;
  // One permutation for all live lanes: kz and the swap agree.
  const int m0 = lanes_set(kz0) & live, m1 = lanes_set(kz1) & live, ms = lanes_set(swap) & live;
  p.uniform = (m0 == 0 || m0 == live) && (m1 == 0 || m1 == live) && (ms == 0 || ms == live);
  const int first = __builtin_ctz(static_cast<unsigned>(live));
  p.kz = (m0 >> first) & 1 ? 0 : (m1 >> first) & 1 ? 1 : 2;
  const bool swapped = (ms >> first) & 1;
  p.kx = swapped ? (p.kz + 2) % 3 : (p.kz + 1) % 3;
  p.ky = swapped ? (p.kz + 1) % 3 : (p.kz + 2) % 3;
  return p;
}

// The same with what the box tests need too (1 / d and the sign octants).
Packet make_packet(const Rays& rays, int i, int live) {
  Packet p = shear_packet(rays, i, live);
  for (int a = 0; a < 3; ++a) p.inv[a] = splat(1.0) / p.d[a];
  for (int a = 0; a < 3; ++a) p.sign[a] = lanes_set(p.d[a]);
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
inline V hits_box(const Node& n, const Packet& p, const Octant& o, V t_max, const Hierarchy& h) {
  V t0 = _mm256_setzero_pd();
  V t1 = t_max * splat(h.t_max_slack);
  for (int a = 0; a < 3; ++a) {
    const V tn = (splat(n.box[o.near[a]]) - p.o[a]) * p.inv[a];
    const V tf = (splat(n.box[o.far[a]]) - p.o[a]) * p.inv[a] * splat(h.far_widen);
    t0 = _mm256_max_pd(tn, t0);  // tn > t0 ? tn : t0
    t1 = _mm256_min_pd(tf, t1);  // tf < t1 ? tf : t1
  }
  return _mm256_cmp_pd(t0, t1, _CMP_LE_OQ);
}

// Component k of vertex v for each lane, k being each lane's kx, ky or kz (masks is0, is1).
inline V component(const Packet& p, const double* v, int uniform_k, V is0, V is1) {
  if (p.uniform) return splat(v[uniform_k]);
  return pick(is0, splat(v[0]), pick(is1, splat(v[1]), splat(v[2])));
}

// The watertight test of intersect_triangle for four rays: the lanes with a hit at t in
// (0, inf), its t and (when asked) the barycentric weights.
struct TriangleHit {
  V valid, t, u, v, w, det;
};
inline TriangleHit triangle_hit(const Packet& p, const double* v0) {
  const double* v1 = v0 + 3;
  const double* v2 = v0 + 6;
  const V zero = _mm256_setzero_pd();
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
  const V negative = either(either(lt(r.u, zero), lt(r.v, zero)), lt(r.w, zero));
  const V positive = either(either(gt(r.u, zero), gt(r.v, zero)), gt(r.w, zero));
  r.det = (r.u + r.v) + r.w;
  const V t_scaled = (r.u * (p.sz * a_z) + r.v * (p.sz * b_z)) + r.w * (p.sz * c_z);
  r.t = t_scaled / r.det;
  r.valid = and_not(both(negative, positive), both(ne(r.det, zero), both(gt(r.t, zero), lt(r.t, splat(kInf)))));
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

// What a walk keeps for four lanes. Nearest-hit: the nearest so far (t, id, prim, b1, b2).
// Any-hit: `best` holds each lane's fixed t_max, and `blocked` grows.
struct Walk {
  V best, id, prim, b1, b2;
  V blocked;
};

// Tests one triangle (id, prim) for the lanes of `m`.
template <bool kAny>
inline void test_triangle(const Packet& p, const double* v0, double id, double prim, V m, Walk& w) {
  const TriangleHit hit = triangle_hit(p, v0);
  if constexpr (kAny) {
    const V blocks = both(both(m, hit.valid), lt(hit.t, w.best));
    if (lanes_set(blocks) == 0 || !has_area(v0)) return;
    w.blocked = either(w.blocked, blocks);
  } else {
    // replaces(): nearer, or as near and first in the scene's order (id, then prim).
    const V cand_id = splat(id), cand_prim = splat(prim);
    const V first = either(lt(cand_id, w.id), both(_mm256_cmp_pd(cand_id, w.id, _CMP_EQ_OQ), lt(cand_prim, w.prim)));
    const V tie = both(both(_mm256_cmp_pd(hit.t, w.best, _CMP_EQ_OQ), ge(w.id, _mm256_setzero_pd())), first);
    const V take = both(both(m, hit.valid), either(lt(hit.t, w.best), tie));
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
inline V walking(V lanes, const Walk& w) {
  if constexpr (kAny) return and_not(w.blocked, lanes);
  return lanes;
}

// traverse() over one BVH for the lanes of `lanes` (all of one octant): `leaf(first, count, m)`
// tests a leaf's primitives for the lanes m whose own box test passed.
template <bool kAny, class Leaf>
inline void walk(const Node* nodes, const Packet& p, const Octant& octant, V lanes, Walk& w, const Hierarchy& h, Leaf&& leaf) {
  std::uint32_t stack[128];
  int top = 0;
  std::uint32_t index = 0;
  for (;;) {
    const Node& node = nodes[index];
    const V live = walking<kAny>(lanes, w);
    if constexpr (kAny) {
      if (lanes_set(live) == 0) return;  // every lane blocked
    }
    const V m = both(live, hits_box(node, p, octant, w.best, h));
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
void walk_scene(const Hierarchy& h, const Packet& p, const Octant& octant, V lanes, Walk& w) {
  const auto top_leaf = [&](std::uint32_t first, std::uint32_t count, V m) {
    for (std::uint32_t slot = first; slot < first + count; ++slot) {
      const std::int32_t k = h.prim_index[slot];
      switch (h.prim_kind[slot]) {
        case 0: {  // sphere
          const V t = sphere_root(p.o[0], p.o[1], p.o[2], p.d[0], p.d[1], p.d[2], h.cx[k], h.cy[k], h.cz[k], h.r[k], w.best);
          const V hit = both(walking<kAny>(m, w), gt(t, _mm256_setzero_pd()));
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
          walk<kAny>(mesh.nodes, p, octant, m, w, h, [&](std::uint32_t f, std::uint32_t n, V mm) {
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
    for (int j = first; j < 4; ++j) {
      if ((lanes >> j) & 1 && p.octant(j) == octant) group |= 1 << j;
    }
    walk_scene<kAny>(h, p, Octant(octant), lane_mask(group), w);
    lanes &= ~group;
  }
}

// The lanes i .. i + 3 of a shadow batch that still need a query: a ray (t_max > 0) that
// nothing has occluded yet.
int shadow_lanes(const double* t_max, const std::uint8_t* occluded, int i) {
  int live = lanes_set(gt(load(t_max + i), _mm256_setzero_pd()));
  for (int j = 0; j < 4; ++j) {
    if (occluded[i + j]) live &= ~(1 << j);
  }
  return live;
}

}  // namespace

void hierarchy_nearest(const Hierarchy& h, const Rays& rays, int live, const NearestHits& out) {
  if (h.top == nullptr) return;
  for (int i = 0; i < live; i += 4) {
    const int lanes = live - i >= 4 ? 0xF : (1 << (live - i)) - 1;
    const Packet p = make_packet(rays, i, lanes);
    Walk w;
    w.best = load(out.t + i);
    w.id = _mm256_set_pd(out.id[i + 3], out.id[i + 2], out.id[i + 1], out.id[i]);
    w.prim = splat(-1);
    w.b1 = w.b2 = _mm256_setzero_pd();
    w.blocked = _mm256_setzero_pd();
    walk_octants<false>(h, p, lanes, w);
    alignas(32) double t[4], id[4], prim[4], b1[4], b2[4];
    _mm256_store_pd(t, w.best);
    _mm256_store_pd(id, w.id);
    _mm256_store_pd(prim, w.prim);
    _mm256_store_pd(b1, w.b1);
    _mm256_store_pd(b2, w.b2);
    // Whatever the hierarchy finds is nearer than the lane's plane hit (a tie goes to the plane,
    // first in the scene's order), so a nearer t is the mark of a new answer.
    const int changed = lanes_set(lt(w.best, load(out.t + i)));
    for (int j = 0; j < 4; ++j) {
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
  for (int i = 0; i < lanes; i += 4) {
    const int live = shadow_lanes(t_max, occluded_out, i);
    if (live == 0) continue;
    const Packet p = make_packet(rays, i, live);
    Walk w;
    w.best = load(t_max + i);
    w.id = w.prim = w.b1 = w.b2 = _mm256_setzero_pd();
    w.blocked = _mm256_setzero_pd();
    walk_octants<true>(h, p, live, w);
    const int bits = lanes_set(w.blocked) & live;
    for (int j = 0; j < 4; ++j) {
      if (bits & (1 << j)) occluded_out[i + j] = 1;
    }
  }
}

void ray_bounds(const Rays& rays, const double* t_max, int live, double* out) {
  const double* in[6] = {rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz};
  const V inf = splat(__builtin_inf());
  V lo[6], hi[6];
  for (int c = 0; c < 6; ++c) lo[c] = inf, hi[c] = negate(inf);
  for (int i = 0; i < live; i += 4) {
    V m = lane_mask(live - i >= 4 ? 0xF : (1 << (live - i)) - 1);
    if (t_max) m = both(m, gt(load(t_max + i), _mm256_setzero_pd()));
    if (lanes_set(m) == 0) continue;
    for (int c = 0; c < 6; ++c) {
      const V v = load(in[c] + i);
      lo[c] = _mm256_min_pd(lo[c], pick(m, v, inf));
      hi[c] = _mm256_max_pd(hi[c], pick(m, v, negate(inf)));
    }
  }
  for (int c = 0; c < 6; ++c) {
    alignas(32) double l[4], h[4];
    _mm256_store_pd(l, lo[c]);
    _mm256_store_pd(h, hi[c]);
    const int at = c < 3 ? c : c + 3;  // origins' lo, hi, then directions' lo, hi
    out[at] = __builtin_fmin(__builtin_fmin(l[0], l[1]), __builtin_fmin(l[2], l[3]));
    out[at + 3] = __builtin_fmax(__builtin_fmax(h[0], h[1]), __builtin_fmax(h[2], h[3]));
  }
}

void triangles_nearest(const LooseTriangles& tris, const Rays& rays, int live, const NearestHits& out) {
  for (int i = 0; i < live; i += 4) {
    const int lanes = live - i >= 4 ? 0xF : (1 << (live - i)) - 1;
    const Packet p = shear_packet(rays, i, lanes);
    const V m = lane_mask(lanes);
    V best = load(out.t + i);
    V id = _mm256_set_pd(out.id[i + 3], out.id[i + 2], out.id[i + 1], out.id[i]);
    V b1 = _mm256_setzero_pd(), b2 = _mm256_setzero_pd();
    int changed = 0;
    for (int j = 0; j < tris.tested_count; ++j) {
      const int k = tris.tested[j];
      const double* v0 = tris.vertices + k * tris.stride;
      const TriangleHit hit = triangle_hit(p, v0);
      const V take = both(both(m, hit.valid), lt(hit.t, best));
      const int bits = lanes_set(take);
      if (bits == 0 || !has_area(v0)) continue;
      best = pick(take, hit.t, best);
      id = pick(take, splat(tris.first_id + k), id);
      b1 = pick(take, hit.v / hit.det, b1);
      b2 = pick(take, hit.w / hit.det, b2);
      changed |= bits;
    }
    if (changed == 0) continue;
    alignas(32) double t_out[4], id_out[4], b1_out[4], b2_out[4];
    _mm256_store_pd(t_out, best);
    _mm256_store_pd(id_out, id);
    _mm256_store_pd(b1_out, b1);
    _mm256_store_pd(b2_out, b2);
    for (int j = 0; j < 4; ++j) {
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
  for (int i = 0; i < lanes; i += 4) {
    const int live = shadow_lanes(t_max, occluded_out, i);
    if (live == 0) continue;
    const Packet p = shear_packet(rays, i, live);
    const V limit = load(t_max + i);
    V open = lane_mask(live);
    for (int j = 0; j < tris.tested_count && lanes_set(open) != 0; ++j) {
      const int k = tris.tested[j];
      const double* v0 = tris.vertices + k * tris.stride;
      const TriangleHit hit = triangle_hit(p, v0);
      const V blocks = both(both(open, hit.valid), lt(hit.t, limit));
      if (lanes_set(blocks) == 0 || !has_area(v0)) continue;
      open = and_not(blocks, open);
    }
    const int bits = live & ~lanes_set(open);
    for (int j = 0; j < 4; ++j) {
      if (bits & (1 << j)) occluded_out[i + j] = 1;
    }
  }
}

}  // namespace phonglab::packet
