// The hard cases' long-double reference (tests/core/test_hardcases.cpp, docs/accuracy.md):
// ray-sphere and ray-plane hits, the local Phong term, the pinhole camera of docs/model.md and
// the exact Fresnel equations, computed from a scene's input numbers in long double (64-bit
// mantissa on x86-64: 11 bits more than the renderer) and sharing no code with it.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "core/scene/math.h"
#include "core/scene/scene.h"

namespace phonglab::reference {

// ---------------------------------------------------------------------------------------------
// Long double reference arithmetic (64-bit mantissa on x86-64: 11 bits more than the renderer).

using LD = long double;
inline constexpr LD kPiL = 3.141592653589793238462643383279502884L;
inline constexpr double kPi = std::numbers::pi;
inline constexpr LD kInfL = std::numeric_limits<LD>::infinity();

struct LV {
  LD x = 0, y = 0, z = 0;
  LD at(int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};
inline LV operator+(const LV& a, const LV& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline LV operator-(const LV& a, const LV& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline LV operator-(const LV& a) { return {-a.x, -a.y, -a.z}; }
inline LV operator*(LD s, const LV& a) { return {s * a.x, s * a.y, s * a.z}; }
inline LV mul(const LV& a, const LV& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline LD dot(const LV& a, const LV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline LV cross(const LV& a, const LV& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline LD length(const LV& a) { return std::sqrt(dot(a, a)); }
inline LV normalized(const LV& a) { return (1 / length(a)) * a; }
inline LV to_ld(const Vec3& v) { return {v.x, v.y, v.z}; }
inline Vec3 to_d(const LV& v) {
  return {static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z)};
}
// Angle between two vectors, accurate at every angle (acos is not near 0 and pi).
inline LD angle_between(const LV& a, const LV& b) { return std::atan2(length(cross(a, b)), dot(a, b)); }

inline std::string str(const Vec3& v) {
  std::ostringstream os;
  os.precision(17);
  os << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return os.str();
}
inline std::string str(const LV& v) { return str(to_d(v)); }

// ---------------------------------------------------------------------------------------------
// Reference geometry.

// Distance along the unit direction d from o to the first point of the sphere (c, r) ahead
// (t > t_min). Both roots come from the perpendicular-distance form, without cancellation.
struct RefRoots {
  bool hit = false;
  LD t0 = 0, t1 = 0;  // t0 <= t1
};
inline RefRoots ref_sphere_roots(const LV& c, LD r, const LV& o, const LV& d) {
  const LV f = o - c;
  const LD b = dot(f, d);
  const LV perp = f - b * d;
  const LD disc = r * r - dot(perp, perp);
  if (disc < 0) return {};
  const LD root = std::sqrt(disc);
  RefRoots out;
  out.hit = true;
  const LD q = -(b + std::copysign(root, b));
  const LD cc = dot(f, f) - r * r;
  out.t0 = q != 0 ? cc / q : 0;
  out.t1 = q;
  if (out.t0 > out.t1) std::swap(out.t0, out.t1);
  return out;
}
inline std::optional<LD> ref_sphere_t(const LV& c, LD r, const LV& o, const LV& d, LD t_min = 0) {
  const RefRoots roots = ref_sphere_roots(c, r, o, d);
  if (!roots.hit) return std::nullopt;
  if (roots.t0 > t_min) return roots.t0;
  if (roots.t1 > t_min) return roots.t1;
  return std::nullopt;
}
// Perpendicular distance from c to the line o + s d (d unit).
inline LD ref_line_distance(const LV& c, const LV& o, const LV& d) {
  const LV f = o - c;
  return length(f - dot(f, d) * d);
}

inline std::optional<LD> ref_plane_t(const LV& p0, const LV& n, const LV& o, const LV& d) {
  const LD denom = dot(d, n);
  if (denom == 0) return std::nullopt;
  const LD t = dot(p0 - o, n) / denom;
  if (t > 0) return t;
  return std::nullopt;
}

// Nearest hit among a scene's spheres and planes (triangles are not modelled by this reference).
struct RefHit {
  bool hit = false;
  LD t = kInfL;
  LV p, ng;  // hit point and outward unit normal
  int material = 0;
};
inline RefHit ref_intersect(const Scene& scene, const LV& o, const LV& d) {
  RefHit best;
  for (const Sphere& s : scene.spheres) {
    const LV c = to_ld(s.center);
    if (auto t = ref_sphere_t(c, s.radius, o, d); t && *t < best.t) {
      best.hit = true;
      best.t = *t;
      best.p = o + *t * d;
      best.ng = normalized(best.p - c);
      best.material = s.material;
    }
  }
  for (const Plane& pl : scene.planes) {
    const LV n = normalized(to_ld(pl.normal));
    if (auto t = ref_plane_t(to_ld(pl.point), n, o, d); t && *t < best.t) {
      best.hit = true;
      best.t = *t;
      best.p = o + *t * d;
      best.ng = n;
      best.material = pl.material;
    }
  }
  return best;
}

// The local term of docs/model.md at a hit, with every light on the lit side taken as visible: test
// scenes that use it are built so that nothing lies between a lit point and its lights.
// `lit_lights` receives the number of lights with N.L > 0 (the shadow rays docs/model.md requires).
struct RefLocal {
  LV ambient, diffuse, specular;
  int lit_lights = 0;
  LD min_abs_n_dot_l = kInfL;  // closeness of any light to the N.L = 0 boundary
  LV sum() const { return ambient + diffuse + specular; }
};
inline RefLocal ref_local(const Scene& scene, const RefHit& h, const LV& d) {
  const Material& m = scene.materials[h.material];
  const LV n = dot(h.ng, d) < 0 ? h.ng : -h.ng;
  const LV v = -d;
  RefLocal out;
  out.ambient = mul(to_ld(m.ka), to_ld(scene.ambient));
  for (const Light& light : scene.lights) {
    if (!light.enabled) continue;
    LV l;
    if (light.type == LightType::kPoint) {
      const LV to_light = to_ld(light.position) - h.p;
      if (length(to_light) == 0) continue;
      l = normalized(to_light);
    } else {
      l = -normalized(to_ld(light.direction));
    }
    const LD n_dot_l = dot(n, l);
    out.min_abs_n_dot_l = std::min(out.min_abs_n_dot_l, std::abs(n_dot_l));
    if (!(n_dot_l > 0)) continue;
    ++out.lit_lights;
    LD base;
    if (scene.specular_model == SpecularModel::kPhong) {
      base = dot(2 * n_dot_l * n - l, v);
    } else {
      base = dot(n, normalized(l + v));
    }
    const LD spec = std::pow(std::max<LD>(base, 0), static_cast<LD>(m.n));  // pow(0, 0) = 1
    const LV intensity = to_ld(light.intensity);
    out.diffuse = out.diffuse + n_dot_l * mul(intensity, to_ld(m.kd));
    out.specular = out.specular + spec * mul(intensity, to_ld(m.ks));
  }
  return out;
}

// The pinhole camera of docs/model.md, camera and samples, in long double.
struct RefCamera {
  LV origin, forward, right, up;  // right scaled by h * W / H, up by h
  int width = 1, height = 1;
};
inline RefCamera ref_camera(const Camera& cam, int width, int height) {
  RefCamera c;
  c.width = width;
  c.height = height;
  c.origin = to_ld(cam.position);
  c.forward = normalized(to_ld(cam.look_at) - c.origin);
  const LV right = normalized(cross(c.forward, to_ld(cam.up)));
  const LV up = cross(right, c.forward);
  const LD h = std::tan(static_cast<LD>(cam.fov_y_deg) * kPiL / 360);
  c.right = (h * width / height) * right;
  c.up = h * up;
  return c;
}
// Direction of the ray through the centre of pixel (x, y).
inline LV ref_pixel_dir(const RefCamera& c, int x, int y) {
  const LD sx = 2 * (x + 0.5L) / c.width - 1;
  const LD sy = 1 - 2 * (y + 0.5L) / c.height;
  return normalized(c.forward + sx * c.right + sy * c.up);
}

// Exact unpolarised Fresnel reflectance from n1 (incident side) into n2, cos_i in [0, 1].
inline LD ref_fresnel(LD cos_i, LD n1, LD n2, LD* sin_t2_out = nullptr) {
  const LD sin_i2 = 1 - cos_i * cos_i;
  const LD sin_t2 = (n1 / n2) * (n1 / n2) * sin_i2;
  if (sin_t2_out) *sin_t2_out = sin_t2;
  if (sin_t2 >= 1) return 1;
  const LD cos_t = std::sqrt(1 - sin_t2);
  const LD rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const LD rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  return (rs * rs + rp * rp) / 2;
}


}  // namespace phonglab::reference
