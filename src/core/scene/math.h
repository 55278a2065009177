// Vector types and small numeric helpers. Geometry and shading run in double precision:
// measured at about the same cost as float here, and free of acne at every scene scale
// the project supports (docs/accuracy.md).
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace phonglab {

using Vec3 = glm::dvec3;
using Color = glm::dvec3;  // linear RGB

// Largest absolute component: the magnitude that sets a position's rounding error.
inline double max_abs(const Vec3& v) {
  return std::max(std::max(std::abs(v.x), std::abs(v.y)), std::abs(v.z));
}

// Largest channel of a colour (path weights use it).
inline double max_channel(const Color& c) { return std::max(std::max(c.x, c.y), c.z); }

inline bool is_zero(const Color& c) { return c.x == 0 && c.y == 0 && c.z == 0; }

struct Ray {
  Vec3 origin;
  Vec3 dir;  // unit length
};

// Makes a ray; `dir` must be unit length and finite.
inline Ray make_ray(const Vec3& origin, const Vec3& dir) { return Ray{origin, dir}; }

// The inverse of the sRGB transfer curve (IEC 61966-2-1): an encoded value in [0, 1] to linear.
inline double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

inline bool all_finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// max(0, x) that maps NaN to 0 whatever the argument order (docs/accuracy.md N5).
inline double clamp_positive(double x) { return x > 0 ? x : 0; }

// Clamp to [-1, 1]: dot products of unit vectors can leave it by rounding (docs/accuracy.md N4).
inline double clamp_unit(double x) { return x > 1 ? 1 : (x < -1 ? -1 : x); }

// Mirror direction of d about the plane with normal n: d - 2(d.n)n / (n.n), exact for a normal
// of any length (docs/accuracy.md R5: a normal of length 1.01 would otherwise tilt it by up to 1.1
// degrees), and renormalised so a slightly non-unit d never yields a non-unit direction.
// A zero normal leaves d unchanged.
inline Vec3 reflect_dir(const Vec3& d, const Vec3& n) {
  const double nn = glm::dot(n, n);
  const double k = nn > 0 ? 2.0 * glm::dot(d, n) / nn : 0.0;
  return glm::normalize(d - k * n);
}

}  // namespace phonglab
