// AVX2 kernels of the packet tracer: what happens at the hits (hit records, camera rays, the
// light loop's geometry, the bounce) and the bounds of a batch of rays. See packet_kernels.h
// for the rules these files follow.
#include "core/packet/packet_avx2_ops.h"
#include "core/packet/packet_kernels.h"

namespace phonglab::packet {

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
    // Each lane's primitive (zeros stand in where the lane has another kind): four lanes on one
    // sphere or one plane (the usual case) take it once, broadcast.
    V scx = zero, scy = zero, scz = zero, sr = zero, sbase = zero, is_sphere = zero;
    V pnx = zero, pny = zero, pnz = zero, psize = zero;
    int kinds = 0;
    const __m128i ids = _mm_loadu_si128(reinterpret_cast<const __m128i*>(id + i));
    if (_mm_movemask_epi8(_mm_cmpeq_epi32(ids, _mm_set1_epi32(id[i]))) == 0xFFFF) {
      const std::int32_t k = id[i];
      if (k >= 0 && k < s_count) {
        scx = splat(spheres.cx[k]), scy = splat(spheres.cy[k]), scz = splat(spheres.cz[k]), sr = splat(spheres.r[k]);
        sbase = splat(spheres.offset_base[k]);
        is_sphere = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
        kinds = 1;
      } else if (k >= s_count && k < s_count + p_count) {
        const int q = k - s_count;
        pnx = splat(planes.nx[q]), pny = splat(planes.ny[q]), pnz = splat(planes.nz[q]);
        psize = splat(planes.point_size[q]);
        kinds = 2;
      }
    } else {
      alignas(32) double cx[4] = {}, cy[4] = {}, cz[4] = {}, r[4] = {}, base[4] = {}, sph[4] = {};
      alignas(32) double nx[4] = {}, ny[4] = {}, nz[4] = {}, size[4] = {};
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
      scx = _mm256_load_pd(cx), scy = _mm256_load_pd(cy), scz = _mm256_load_pd(cz), sr = _mm256_load_pd(r);
      sbase = _mm256_load_pd(base);
      is_sphere = _mm256_cmp_pd(_mm256_load_pd(sph), zero, _CMP_NEQ_UQ);
      pnx = _mm256_load_pd(nx), pny = _mm256_load_pd(ny), pnz = _mm256_load_pd(nz), psize = _mm256_load_pd(size);
    }
    if (kinds == 0) continue;
    const V t = load(t_in + i);
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    // P = O + t D; a sphere's is re-projected onto it along the radial direction.
    V px = load(rays.ox + i) + t * dx, py = load(rays.oy + i) + t * dy, pz = load(rays.oz + i) + t * dz;
    V gx = pnx, gy = pny, gz = pnz;
    V offset = splat(margins.coordinate) * _mm256_max_pd(max_abs(px, py, pz), psize) +
               splat(margins.size) * t;
    if (kinds & 1) {
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
      offset = pick(is_sphere, sbase + splat(margins.size) * (sr + t), offset);
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

ShadowCounts light(const LightIn& lt_in, const ShadedPoints& pts, int lanes, const LightOut& out) {
  const V zero = _mm256_setzero_pd();
  const V lpx = splat(lt_in.x), lpy = splat(lt_in.y), lpz = splat(lt_in.z);
  ShadowCounts counts;
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
      counts.lit += __builtin_popcount(static_cast<unsigned>(on));
      counts.tested += __builtin_popcount(static_cast<unsigned>(test));
      put_byte_lanes(out.shadow + i, spread_bits(on) + spread_bits(test));
      t_max = both(lane_mask(test), t_max);
    }
    store(out.t_max + i, t_max);
  }
  return counts;
}

namespace {
// The four lanes' materials from `material` on, as gather indices.
inline __m128i material_lanes(const std::int32_t* material) {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(material));
}
// base[index] where mask is set (only those entries are read), zero elsewhere.
inline V gather(const double* base, __m128i index, V mask) {
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, index, mask, 8);
}
// The entries of a colour per material for the lanes in `bits`: one entry broadcast when those
// lanes share a material (the usual case: a packet sees one object), else gathered.
struct MaterialLanes {
  __m128i index;
  V mask;
  int shared;  // the material all the lanes share, or -1

  MaterialLanes(const std::int32_t* material, int bits) : index(material_lanes(material)), mask(lane_mask(bits)) {
    const int first = __builtin_ctz(static_cast<unsigned>(bits));
    const int same = _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(index, _mm_set1_epi32(material[first]))));
    shared = (same & bits) == bits ? material[first] : -1;
  }
  V of(const double* base) const { return shared >= 0 ? splat(base[shared]) : gather(base, index, mask); }
};
// Bit j set where lane j of the four from id on is a hit (id >= 0) and j < live.
inline int hit_lanes(const std::int32_t* id, int live) {
  const __m128i ids = _mm_loadu_si128(reinterpret_cast<const __m128i*>(id));
  const int bits = ~_mm_movemask_ps(_mm_castsi128_ps(ids)) & 0xF;  // the sign bit clear
  return live < 4 ? bits & ((1 << live) - 1) : bits;
}
// *p += x where mask is set.
inline void add_where(double* p, V mask, V x) {
  const V old = load(p);
  store(p, pick(mask, old + x, old));
}
}  // namespace

void add_light(const ByMaterial& kd, const ByMaterial& ks, const std::int32_t* material, const std::uint8_t* seen,
               const double* n_dot_l, const double* spec, int lanes, const ColorLanes& diffuse,
               const ColorLanes& specular) {
  for (int i = 0; i < lanes; i += 4) {
    const int bits = byte_lanes(seen + i);
    if (bits == 0) continue;
    const MaterialLanes m(material + i, bits);
    const V mask = m.mask;
    const V ndl = load(n_dot_l + i), sp = load(spec + i);
    add_where(diffuse.r + i, mask, m.of(kd.r) * ndl);
    add_where(diffuse.g + i, mask, m.of(kd.g) * ndl);
    add_where(diffuse.b + i, mask, m.of(kd.b) * ndl);
    add_where(specular.r + i, mask, m.of(ks.r) * sp);
    add_where(specular.g + i, mask, m.of(ks.g) * sp);
    add_where(specular.b + i, mask, m.of(ks.b) * sp);
  }
}

void hit_bounds(const double* px, const double* py, const double* pz, const double* offset, const std::int32_t* id,
                int live, double* out) {
  V lx = splat(kInf), ly = lx, lz = lx, hx = splat(-kInf), hy = hx, hz = hx, off = _mm256_setzero_pd();
  for (int i = 0; i < live; i += 4) {
    const int bits = hit_lanes(id + i, live - i);
    if (bits == 0) continue;
    const V mask = lane_mask(bits);
    // minpd and maxpd give their second operand where the first is NaN.
    const V x = load(px + i), y = load(py + i), z = load(pz + i);
    lx = pick(mask, _mm256_min_pd(x, lx), lx), ly = pick(mask, _mm256_min_pd(y, ly), ly);
    lz = pick(mask, _mm256_min_pd(z, lz), lz);
    hx = pick(mask, _mm256_max_pd(x, hx), hx), hy = pick(mask, _mm256_max_pd(y, hy), hy);
    hz = pick(mask, _mm256_max_pd(z, hz), hz);
    off = pick(mask, _mm256_max_pd(load(offset + i), off), off);
  }
  alignas(32) double v[7][4];
  const V all[7] = {lx, ly, lz, hx, hy, hz, off};
  for (int k = 0; k < 7; ++k) {
    _mm256_store_pd(v[k], all[k]);
    double r = v[k][0];
    for (int j = 1; j < 4; ++j) r = k < 3 ? (v[k][j] < r ? v[k][j] : r) : (r < v[k][j] ? v[k][j] : r);
    out[k] = r;
  }
}

void sum_terms(const ByMaterial& ambient, const std::int32_t* material, const std::int32_t* id,
               const TermLanes& terms, int live, double* out) {
  const V zero = _mm256_setzero_pd();
  const auto lanes_of = [](const ColorLanes* c, int i, V& r, V& g, V& b) {
    if (c) r = load(c->r + i), g = load(c->g + i), b = load(c->b + i);
  };
  for (int i = 0; i < live; i += 4) {
    const int bits = hit_lanes(id + i, live - i);
    if (bits == 0) continue;
    const MaterialLanes m(material + i, bits);
    V rr = zero, rg = zero, rb = zero, tr = zero, tg = zero, tb = zero;
    lanes_of(terms.reflection, i, rr, rg, rb);
    lanes_of(terms.refraction, i, tr, tg, tb);
    const ColorLanes& d = terms.diffuse;
    const ColorLanes& s = terms.specular;
    alignas(32) double r[4], g[4], b[4];
    _mm256_store_pd(r, (((m.of(ambient.r) + load(d.r + i)) + load(s.r + i)) + rr) + tr);
    _mm256_store_pd(g, (((m.of(ambient.g) + load(d.g + i)) + load(s.g + i)) + rg) + tg);
    _mm256_store_pd(b, (((m.of(ambient.b) + load(d.b + i)) + load(s.b + i)) + rb) + tb);
    for (int j = 0; j < 4; ++j) {
      if (!(bits >> j & 1)) continue;
      double* o = out + 3 * (i + j);
      o[0] = r[j], o[1] = g[j], o[2] = b[j];
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

}  // namespace phonglab::packet
