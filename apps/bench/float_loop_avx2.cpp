// The plain float Whitted loop (float_loop.h), built with -O3 -mavx2 -mfma: the compiler's
// best for code written plainly. This unit defines no inline or template function it shares
// with the rest of the program, and uses no standard container, so no AVX2 copy of shared code
// can reach other callers.
#include <cmath>
#include <cstdint>

#include "apps/bench/float_loop.h"

namespace phonglab::float_loop {
namespace {

constexpr float kEpsilon = 1e-3f;
constexpr float kInf = 3.4e38f;

struct V {
  float x, y, z;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator-(V a) { return {-a.x, -a.y, -a.z}; }
V operator*(float s, V a) { return {s * a.x, s * a.y, s * a.z}; }
V mul(V a, V b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
float dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V normalize(V a) { return (1.0f / std::sqrt(dot(a, a))) * a; }
V load(const float* p) { return {p[0], p[1], p[2]}; }
float max3(V a) { return std::fmax(a.x, std::fmax(a.y, a.z)); }
bool zero(V a) { return a.x == 0 && a.y == 0 && a.z == 0; }

struct Hit {
  float t = kInf;
  V n{0, 0, 0};
  int material = -1;
};

// Nearest hit with t in (kEpsilon, t_max); `any`: stop at the first.
bool intersect(const Scene& s, V o, V d, float t_max, bool any, Hit& hit) {
  hit.t = t_max;
  bool found = false;
  for (int i = 0; i < s.sphere_count; ++i) {
    const Sphere& sp = s.spheres[i];
    const V oc = o - load(sp.c);
    const float b = dot(oc, d), c = dot(oc, oc) - sp.r * sp.r, disc = b * b - c;
    if (disc < 0) continue;
    const float q = std::sqrt(disc);
    float t = -b - q;
    if (t <= kEpsilon) t = -b + q;
    if (t > kEpsilon && t < hit.t) {
      hit.t = t;
      hit.n = (1.0f / sp.r) * (o + t * d - load(sp.c));
      hit.material = sp.material;
      found = true;
      if (any) return true;
    }
  }
  for (int i = 0; i < s.plane_count; ++i) {
    const Plane& pl = s.planes[i];
    const float denom = dot(d, load(pl.n));
    if (denom == 0) continue;
    const float t = dot(load(pl.p) - o, load(pl.n)) / denom;
    if (t > kEpsilon && t < hit.t) {
      hit.t = t;
      hit.n = load(pl.n);
      hit.material = pl.material;
      found = true;
      if (any) return true;
    }
  }
  for (int i = 0; i < s.triangle_count; ++i) {  // Moller-Trumbore
    const Triangle& tr = s.triangles[i];
    const V e1 = load(tr.e1), e2 = load(tr.e2);
    const V p = cross(d, e2);
    const float det = dot(e1, p);
    if (std::fabs(det) < 1e-12f) continue;
    const float inv = 1.0f / det;
    const V tv = o - load(tr.v0);
    const float u = dot(tv, p) * inv;
    if (u < 0 || u > 1) continue;
    const V q = cross(tv, e1);
    const float v = dot(d, q) * inv;
    if (v < 0 || u + v > 1) continue;
    const float t = dot(e2, q) * inv;
    if (t > kEpsilon && t < hit.t) {
      hit.t = t;
      hit.n = normalize(cross(e1, e2));
      hit.material = tr.material;
      found = true;
      if (any) return true;
    }
  }
  return found;
}

float fresnel(float cos_i, float eta) {
  const float sin2_t = eta * eta * (1 - cos_i * cos_i);
  if (sin2_t >= 1) return 1;
  const float cos_t = std::sqrt(1 - sin2_t);
  const float rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  return 0.5f * (rs * rs + rp * rp);
}

V trace(const Scene& s, V o, V d, int depth, float weight, std::uint64_t& rays);

// One child ray with weight k along dir from p, pruned as the renderer prunes.
V child(const Scene& s, V k, V p, V n, V dir, int depth, float weight, std::uint64_t& rays) {
  if (zero(k)) return {0, 0, 0};
  const float w = weight * max3(k);
  if (w < s.min_weight) return {0, 0, 0};
  ++rays;
  const V origin = p + (dot(dir, n) >= 0 ? kEpsilon : -kEpsilon) * n;
  return mul(k, trace(s, origin, dir, depth + 1, w, rays));
}

V shade(const Scene& s, V o, V d, const Hit& hit, int depth, float weight, std::uint64_t& rays) {
  const Material& m = s.materials[hit.material];
  const V p = o + hit.t * d;
  const bool entering = dot(hit.n, d) < 0;
  const V n = entering ? hit.n : -hit.n;
  const V v = -d;
  V color = mul(load(m.ka), load(s.ambient));
  const bool lit = !zero(load(m.kd)) || !zero(load(m.ks));
  for (int li = 0; lit && li < s.light_count; ++li) {
    const Light& light = s.lights[li];
    V l = load(light.v);
    float dist = kInf;
    if (light.point) {
      const V to = l - p;
      dist = std::sqrt(dot(to, to));
      l = (1.0f / dist) * to;
    }
    const float nl = dot(n, l);
    if (nl <= 0) continue;
    ++rays;
    Hit blocker;
    if (intersect(s, p + kEpsilon * n, l, dist, true, blocker)) continue;
    float base;
    if (s.blinn) {
      base = dot(n, normalize(l + v));
    } else {
      base = dot(2 * nl * n - l, v);
    }
    const float spec = base > 0 ? std::pow(base, m.n) : 0;
    color = color + mul(load(light.intensity), nl * load(m.kd) + spec * load(m.ks));
  }
  if (depth >= s.max_depth || (zero(load(m.kr)) && zero(load(m.kt)))) return color;
  const float cos_i = -dot(d, n);
  const float eta = entering ? 1.0f / m.ior : m.ior;
  const float k = 1 - eta * eta * (1 - cos_i * cos_i);
  const V mirror = d + 2 * cos_i * n;
  V kr = load(m.kr), kt = load(m.kt);
  if (m.fresnel && !zero(kt)) {
    const float f = k < 0 ? 1.0f : fresnel(cos_i, eta);
    kr = kr + f * kt;
    kt = (1 - f) * kt;
  }
  color = color + child(s, kr, p, n, mirror, depth, weight, rays);
  if (!zero(kt)) {
    const V dir = k < 0 ? mirror : normalize(eta * d + (eta * cos_i - std::sqrt(k)) * n);
    color = color + child(s, kt, p, n, dir, depth, weight, rays);
  }
  return color;
}

V trace(const Scene& s, V o, V d, int depth, float weight, std::uint64_t& rays) {
  Hit hit;
  if (!intersect(s, o, d, kInf, false, hit)) return load(s.background);
  return shade(s, o, d, hit, depth, weight, rays);
}

}  // namespace

void render_rows(const Scene& s, int y0, int step, float* rgb, std::uint64_t* rays) {
  std::uint64_t count = 0;
  const V eye = load(s.eye), fw = load(s.forward), rt = load(s.right), up = load(s.up);
  const auto width = static_cast<float>(s.width), height = static_cast<float>(s.height);
  for (int y = y0; y < s.height; y += step) {
    for (int x = 0; x < s.width; ++x) {
      const float sx = 2 * (static_cast<float>(x) + 0.5f) / width - 1;
      const float sy = 1 - 2 * (static_cast<float>(y) + 0.5f) / height;
      ++count;
      const V c = trace(s, eye, normalize(fw + sx * rt + sy * up), 0, 1.0f, count);
      float* out = rgb + 3 * (static_cast<std::int64_t>(y) * s.width + x);
      out[0] = c.x;
      out[1] = c.y;
      out[2] = c.z;
    }
  }
  *rays += count;
}

}  // namespace phonglab::float_loop
