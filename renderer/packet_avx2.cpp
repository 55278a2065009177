// AVX2 kernels of the packet tracer; see packet_kernels.h for the rules this file follows
// (only plain data, intrinsics and functions with internal linkage: no header with inline code).
#include "renderer/packet_kernels.h"

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

void light(const LightIn& lt_in, const ShadedPoints& pts, int lanes, const LightOut& out) {
  const V zero = _mm256_setzero_pd();
  const V lpx = splat(lt_in.x), lpy = splat(lt_in.y), lpz = splat(lt_in.z);
  for (int i = 0; i < lanes; i += 4) {
    if ((pts.active[i] | pts.active[i + 1] | pts.active[i + 2] | pts.active[i + 3]) == 0) continue;
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
    if (lt_in.point) {  // the open segment to the light, pulled in at the light's end
      const V tx = lpx - ox, ty = lpy - oy, tz = lpz - oz;
      const V dist = sqrt(dot(tx, ty, tz, tx, ty, tz));
      store(out.t_max + i, dist - splat(lt_in.shrink));
      store(out.dx + i, tx / dist);
      store(out.dy + i, ty / dist);
      store(out.dz + i, tz / dist);
    } else {
      store(out.t_max + i, splat(kInf));
      store(out.dx + i, lx);
      store(out.dy + i, ly);
      store(out.dz + i, lz);
    }
  }
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

}  // namespace phonglab::packet
