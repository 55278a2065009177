// The packet tracer's kernels, what happens at the hits: hit records, camera rays, the light
// loop's geometry and sums, the bounce, and the bounds of a batch of rays. One source for every
// instance (packet_kernels.h), over the vocabulary of packet_simd_ops.h.
#include "core/packet/packet_kernels.h"
#include "core/packet/packet_simd_ops.h"

namespace phonglab::packet::PHONGLAB_SIMD_NS {

void hit_records(const Spheres& spheres, const Planes& planes, const OffsetMargins& margins, const Rays& rays,
                 const double* t_in, const std::int32_t* id, int lanes, const HitRecords& out) {
  const V zero = zeros();
  const auto max_abs = [&](V x, V y, V z) {  // std::max of non-negative values: the same as max_of
    return max_of(max_of(abs(x), abs(y)), abs(z));
  };
  const int s_count = spheres.count, p_count = planes.count;
  for (int i = 0; i < lanes; i += kLanes) {
    // Each lane's primitive (zeros stand in where the lane has another kind): lanes all on one
    // sphere or one plane (the usual case) take it once, broadcast.
    V scx = zero, scy = zero, scz = zero, sr = zero, sbase = zero;
    M is_sphere = no_lanes();
    V pnx = zero, pny = zero, pnz = zero, psize = zero;
    int kinds = 0;
    if (equal_int32_lanes(id + i, id[i]) == kAll) {
      const std::int32_t k = id[i];
      if (k >= 0 && k < s_count) {
        scx = splat(spheres.cx[k]), scy = splat(spheres.cy[k]), scz = splat(spheres.cz[k]), sr = splat(spheres.r[k]);
        sbase = splat(spheres.offset_base[k]);
        is_sphere = all_lanes();
        kinds = 1;
      } else if (k >= s_count && k < s_count + p_count) {
        const int q = k - s_count;
        pnx = splat(planes.nx[q]), pny = splat(planes.ny[q]), pnz = splat(planes.nz[q]);
        psize = splat(planes.point_size[q]);
        kinds = 2;
      }
    } else {
      double cx[kLanes] = {}, cy[kLanes] = {}, cz[kLanes] = {}, r[kLanes] = {}, base[kLanes] = {};
      double nx[kLanes] = {}, ny[kLanes] = {}, nz[kLanes] = {}, size[kLanes] = {};
      int sphere_bits = 0;
      for (int j = 0; j < kLanes; ++j) {
        const std::int32_t k = id[i + j];
        if (k >= 0 && k < s_count) {
          cx[j] = spheres.cx[k], cy[j] = spheres.cy[k], cz[j] = spheres.cz[k], r[j] = spheres.r[k];
          base[j] = spheres.offset_base[k];
          sphere_bits |= 1 << j;
          kinds |= 1;
        } else if (k >= s_count && k < s_count + p_count) {
          const int q = k - s_count;
          nx[j] = planes.nx[q], ny[j] = planes.ny[q], nz[j] = planes.nz[q], size[j] = planes.point_size[q];
          kinds |= 2;
        }
      }
      scx = load(cx), scy = load(cy), scz = load(cz), sr = load(r);
      sbase = load(base);
      is_sphere = lane_mask(sphere_bits);
      pnx = load(nx), pny = load(ny), pnz = load(nz), psize = load(size);
    }
    if (kinds == 0) continue;
    const V t = load(t_in + i);
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    // P = O + t D; a sphere's is re-projected onto it along the radial direction.
    V px = load(rays.ox + i) + t * dx, py = load(rays.oy + i) + t * dy, pz = load(rays.oz + i) + t * dz;
    V gx = pnx, gy = pny, gz = pnz;
    V offset = splat(margins.coordinate) * max_of(max_abs(px, py, pz), psize) + splat(margins.size) * t;
    if (kinds & 1) {
      const V rx = px - scx, ry = py - scy, rz = pz - scz;
      const V len = sqrt(dot(rx, ry, rz, rx, ry, rz));
      const M has = gt(len, zero);
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
    const M entering = lt(dot(gx, gy, gz, dx, dy, dz), zero);
    gx = pick(entering, gx, negate(gx));
    gy = pick(entering, gy, negate(gy));
    gz = pick(entering, gz, negate(gz));
    // Every lane is written: a triangle's lane is overwritten by the caller afterwards, a
    // missed ray's is never read.
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
    put_byte_lanes(out.entering + i, spread_bits(lanes_set(entering)));
  }
}

void triangle_records(const TriangleRecords& tris, const OffsetMargins& margins, const Rays& rays, const double* t_in,
                      const std::int32_t* id, const double* b1_in, const double* b2_in, int lanes, const HitRecords& out) {
  const V zero = zeros(), one = splat(1);
  for (int i = 0; i < lanes; i += kLanes) {
    // Each lane's triangle; lanes of other kinds borrow the first one's (and are not written).
    std::int64_t k[kLanes];
    int mine = 0;
    for (int j = 0; j < kLanes; ++j) {
      k[j] = id[i + j] - tris.first_id;
      if (k[j] >= 0 && k[j] < tris.count && tris.flat[k[j]]) mine |= 1 << j;
    }
    if (mine == 0) continue;
    const std::int64_t first = k[__builtin_ctz(static_cast<unsigned>(mine))];
    bool shared = true;  // usually: one floor, one triangle
    std::int64_t tri_at[kLanes], normal_at[kLanes];
    for (int j = 0; j < kLanes; ++j) {
      if (!((mine >> j) & 1)) k[j] = first;
      shared = shared && k[j] == first;
      tri_at[j] = k[j] * tris.stride;
      normal_at[j] = 3 * k[j];
    }
    const auto fetch = [&](const double* base, const std::int64_t* at, std::int64_t shared_at) {
      return shared ? splat(base[shared_at]) : gather(base, at);
    };
    V v[9];
    for (int c = 0; c < 9; ++c) v[c] = fetch(tris.vertices + c, tri_at, first * tris.stride);
    V n[3];
    for (int c = 0; c < 3; ++c) n[c] = fetch(tris.normal + c, normal_at, 3 * first);
    const V size = fetch(tris.magnitude, k, first);
    const M m = lane_mask(mine);
    const V b1 = load(b1_in + i), b2 = load(b2_in + i);
    const V b0 = (one - b1) - b2;
    const auto write = [&](double* p, V x) { store(p + i, pick(m, x, load(p + i))); };
    double* const p_out[3] = {out.px, out.py, out.pz};
    for (int c = 0; c < 3; ++c) {  // glm's b0 v0 + b1 v1 + b2 v2, left to right
      write(p_out[c], (b0 * v[c] + b1 * v[3 + c]) + b2 * v[6 + c]);
    }
    const V dx = load(rays.dx + i), dy = load(rays.dy + i), dz = load(rays.dz + i);
    V gx = n[0], gy = n[1], gz = n[2];
    const M entering = lt(dot(gx, gy, gz, dx, dy, dz), zero);
    gx = pick(entering, gx, negate(gx));
    gy = pick(entering, gy, negate(gy));
    gz = pick(entering, gz, negate(gz));
    write(out.nx, gx), write(out.ny, gy), write(out.nz, gz);
    write(out.gx, gx), write(out.gy, gy), write(out.gz, gz);
    write(out.vx, negate(dx)), write(out.vy, negate(dy)), write(out.vz, negate(dz));
    write(out.offset, splat(margins.coordinate) * size + splat(margins.size) * load(t_in + i));
    const int enter_bits = lanes_set(entering);
    for (int j = 0; j < kLanes; ++j) {
      if ((mine >> j) & 1) out.entering[i + j] = (enter_bits >> j) & 1;
    }
  }
}

void camera_dirs(const CameraIn& cam, const double* x_plus_u, const double* y_plus_v, int lanes, double* dx,
                 double* dy, double* dz) {
  const V two = splat(2), one = splat(1);
  for (int i = 0; i < lanes; i += kLanes) {
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
  const V zero = zeros();
  const V lpx = splat(lt_in.x), lpy = splat(lt_in.y), lpz = splat(lt_in.z);
  ShadowCounts counts;
  for (int i = 0; i < lanes; i += kLanes) {
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
      const M has = gt(len, zero);
      const V rx = pick(has, hx / len, nx), ry = pick(has, hy / len, ny), rz = pick(has, hz / len, nz);
      store(out.cos_spec + i, keep(has, dot(nx, ny, nz, rx, ry, rz)));
    }
    // offset_origin(P, Ng, L, offset): off the side of the surface the ray leaves by.
    const V gx = load(pts.gx + i), gy = load(pts.gy + i), gz = load(pts.gz + i);
    const V off = load(pts.offset + i);
    const M out_side = ge(dot(lx, ly, lz, gx, gy, gz), zero);
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
      t_max = keep(lane_mask(test), t_max);
    }
    store(out.t_max + i, t_max);
  }
  return counts;
}

namespace {
// The entries of a colour per material for the lanes in `bits`: one entry broadcast when those
// lanes share a material (the usual case: a packet sees one object), else gathered.
struct MaterialLanes {
  const std::int32_t* index;
  M mask;
  int shared = -1;  // the material all the lanes share, or -1

  MaterialLanes(const std::int32_t* material, int bits) : index(material), mask(lane_mask(bits)) {
    const int first = __builtin_ctz(static_cast<unsigned>(bits));
    if ((equal_int32_lanes(material, material[first]) & bits) == bits) shared = material[first];
  }
  V of(const double* base) const { return shared >= 0 ? splat(base[shared]) : gather_where(base, index, mask); }
};
// Bit j set where lane j of the group from id on is a hit (id >= 0) and j < live.
inline int hit_lanes(const std::int32_t* id, int live) {
  return ~negative_int32_lanes(id) & live_lanes(live);
}
// *p += x where mask is set.
inline void add_where(double* p, M mask, V x) {
  const V old = load(p);
  store(p, pick(mask, old + x, old));
}
}  // namespace

void add_light(const ByMaterial& kd, const ByMaterial& ks, const std::int32_t* material, const std::uint8_t* seen,
               const double* n_dot_l, const double* spec, int lanes, const ColorLanes& diffuse,
               const ColorLanes& specular) {
  for (int i = 0; i < lanes; i += kLanes) {
    const int bits = byte_lanes(seen + i);
    if (bits == 0) continue;
    const MaterialLanes m(material + i, bits);
    const M mask = m.mask;
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
  V lx = splat(kInf), ly = lx, lz = lx, hx = splat(-kInf), hy = hx, hz = hx, off = zeros();
  for (int i = 0; i < live; i += kLanes) {
    const int bits = hit_lanes(id + i, live - i);
    if (bits == 0) continue;
    const M mask = lane_mask(bits);
    // min_of and max_of give their second operand where the first is NaN.
    const V x = load(px + i), y = load(py + i), z = load(pz + i);
    lx = pick(mask, min_of(x, lx), lx), ly = pick(mask, min_of(y, ly), ly);
    lz = pick(mask, min_of(z, lz), lz);
    hx = pick(mask, max_of(x, hx), hx), hy = pick(mask, max_of(y, hy), hy);
    hz = pick(mask, max_of(z, hz), hz);
    off = pick(mask, max_of(load(offset + i), off), off);
  }
  double v[7][kLanes];
  const V all[7] = {lx, ly, lz, hx, hy, hz, off};
  for (int k = 0; k < 7; ++k) {
    store(v[k], all[k]);
    double r = v[k][0];
    for (int j = 1; j < kLanes; ++j) r = k < 3 ? (v[k][j] < r ? v[k][j] : r) : (r < v[k][j] ? v[k][j] : r);
    out[k] = r;
  }
}

void sum_terms(const ByMaterial& ambient, const std::int32_t* material, const std::int32_t* id,
               const TermLanes& terms, int live, double* out) {
  const V zero = zeros();
  const auto lanes_of = [](const ColorLanes* c, int i, V& r, V& g, V& b) {
    if (c) r = load(c->r + i), g = load(c->g + i), b = load(c->b + i);
  };
  for (int i = 0; i < live; i += kLanes) {
    const int bits = hit_lanes(id + i, live - i);
    if (bits == 0) continue;
    const MaterialLanes m(material + i, bits);
    V rr = zero, rg = zero, rb = zero, tr = zero, tg = zero, tb = zero;
    lanes_of(terms.reflection, i, rr, rg, rb);
    lanes_of(terms.refraction, i, tr, tg, tb);
    const ColorLanes& d = terms.diffuse;
    const ColorLanes& s = terms.specular;
    double r[kLanes], g[kLanes], b[kLanes];
    store(r, (((m.of(ambient.r) + load(d.r + i)) + load(s.r + i)) + rr) + tr);
    store(g, (((m.of(ambient.g) + load(d.g + i)) + load(s.g + i)) + rg) + tg);
    store(b, (((m.of(ambient.b) + load(d.b + i)) + load(s.b + i)) + rb) + tb);
    for (int j = 0; j < kLanes; ++j) {
      if (!(bits >> j & 1)) continue;
      double* o = out + 3 * (i + j);
      o[0] = r[j], o[1] = g[j], o[2] = b[j];
    }
  }
}

void bounce(const BounceIn& in, int lanes, const BounceOut& out) {
  const V zero = zeros(), one = splat(1);
  const auto clamp_unit = [&](V x) {  // x > 1 ? 1 : (x < -1 ? -1 : x)
    return pick(gt(x, one), one, pick(lt(x, negate(one)), negate(one), x));
  };
  for (int i = 0; i < lanes; i += kLanes) {
    if (byte_lanes(in.active + i) == 0) continue;
    const V dx = load(in.dx + i), dy = load(in.dy + i), dz = load(in.dz + i);
    const V nx = load(in.nx + i), ny = load(in.ny + i), nz = load(in.nz + i);
    const V ior = load(in.ior + i);
    const M entering = lane_mask(byte_lanes(in.entering + i));
    const V d_dot_n = dot(dx, dy, dz, nx, ny, nz);
    const V cos_i = clamp_unit(negate(d_dot_n));
    const V eta = pick(entering, one / ior, ior);
    const V sin2_t = (eta * eta) * (one - cos_i * cos_i);
    const V k = one - sin2_t;
    const M tir = lt(k, zero);
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
    put_byte_lanes(out.tir + i, spread_bits(lanes_set(tir)));
  }
}

void ray_bounds(const Rays& rays, const double* t_max, int live, double* out) {
  const double* in[6] = {rays.ox, rays.oy, rays.oz, rays.dx, rays.dy, rays.dz};
  const V inf = splat(__builtin_inf());
  V lo[6], hi[6];
  for (int c = 0; c < 6; ++c) lo[c] = inf, hi[c] = negate(inf);
  for (int i = 0; i < live; i += kLanes) {
    M m = lane_mask(live_lanes(live - i));
    if (t_max) m = both(m, gt(load(t_max + i), zeros()));
    if (lanes_set(m) == 0) continue;
    for (int c = 0; c < 6; ++c) {
      const V v = load(in[c] + i);
      lo[c] = min_of(lo[c], pick(m, v, inf));
      hi[c] = max_of(hi[c], pick(m, v, negate(inf)));
    }
  }
  for (int c = 0; c < 6; ++c) {
    double l[kLanes], h[kLanes];
    store(l, lo[c]);
    store(h, hi[c]);
    const int at = c < 3 ? c : c + 3;  // origins' lo, hi, then directions' lo, hi
    double l_min = l[0], h_max = h[0];
    for (int j = 1; j < kLanes; ++j) l_min = __builtin_fmin(l_min, l[j]), h_max = __builtin_fmax(h_max, h[j]);
    out[at] = l_min;
    out[at + 3] = h_max;
  }
}

}  // namespace phonglab::packet::PHONGLAB_SIMD_NS
