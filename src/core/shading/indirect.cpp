#include "core/shading/indirect.h"

#include <cmath>
#include <numbers>

#include "core/scene/hash.h"

namespace phonglab {

namespace {

std::uint32_t reverse_bits(std::uint32_t x) {
  x = ((x >> 1) & 0x55555555U) | ((x & 0x55555555U) << 1);
  x = ((x >> 2) & 0x33333333U) | ((x & 0x33333333U) << 2);
  x = ((x >> 4) & 0x0F0F0F0FU) | ((x & 0x0F0F0F0FU) << 4);
  x = ((x >> 8) & 0x00FF00FFU) | ((x & 0x00FF00FFU) << 8);
  return (x >> 16) | (x << 16);
}

// Owen scrambling of a 32-bit fraction: every bit is flipped by a hash of the bits above it
// (more significant in the fraction). Reversed, "above" becomes "below", which is what adding a
// number and xoring with the product by an even number change: a carry or a product never
// reaches down. A bijection of [0, 2^32), and a random one of the nested kind for each seed.
std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  x = reverse_bits(x);
  x += seed;
  x ^= x * 0x6c50b47cU;
  x ^= x * 0xb82f1e52U;
  x ^= x * 0xc7afe638U;
  x ^= x * 0x8d22f6e6U;
  return reverse_bits(x);
}

// The first two dimensions of the Sobol sequence, a (0,2)-sequence in base 2: dimension 0 is the
// van der Corput sequence, dimension 1 uses the direction numbers v_k = v_{k-1} ^ (v_{k-1} >> 1).
std::uint32_t sobol0(std::uint32_t i) { return reverse_bits(i); }
std::uint32_t sobol1(std::uint32_t i) {
  std::uint32_t v = 1U << 31, r = 0;
  for (; i != 0; i >>= 1, v ^= v >> 1) {
    if (i & 1U) r ^= v;
  }
  return r;
}

double unit(std::uint32_t x) { return static_cast<double>(x) * 0x1p-32; }

}  // namespace

std::uint32_t indirect_pixel_key(int x, int y, std::uint32_t seed) {
  return hash32(static_cast<std::uint32_t>(x) * 0x9E3779B1U ^ hash32(static_cast<std::uint32_t>(y) ^ hash32(seed ^ 0x5bd1e995U)));
}

void IndirectSampler::next_point(double& u1, double& u2) {
  const std::uint32_t d = hash32(key_ ^ hash32(dimension_++));
  // The index shuffled (Owen-scrambled: the first 2^k indices stay the first 2^k), so that the
  // gathers of one tree are not correlated with each other, then each coordinate scrambled.
  const std::uint32_t i = owen_scramble(sample_, hash32(d ^ 0x68bc21ebU));
  u1 = unit(owen_scramble(sobol0(i), hash32(d ^ 0x02e5be93U)));
  u2 = unit(owen_scramble(sobol1(i), hash32(d ^ 0x967a889bU)));
}

double IndirectSampler::next_choice() {
  const std::uint32_t d = hash32(key_ ^ hash32(~choice_++));
  const std::uint32_t i = owen_scramble(sample_, hash32(d ^ 0x3c6ef372U));
  return unit(owen_scramble(sobol0(i), hash32(d ^ 0xa54ff53aU)));
}

Vec3 cosine_direction(const Vec3& n, double u1, double u2) {
  // An orthonormal basis about n without a branch on a chosen axis (Duff et al., JCGT 2017).
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const Vec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const Vec3 s(b, sign + n.y * n.y * a, -n.y);
  const double r = std::sqrt(u1);
  const double phi = 2 * std::numbers::pi * u2;
  const double z = std::sqrt(1 - u1);  // u1 < 1: z > 0
  return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * s + z * n);
}

}  // namespace phonglab
