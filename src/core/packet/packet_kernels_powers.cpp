// The specular factor for a whole exponent, kLanes lanes at a time, bit for bit std::pow's value
// where it decides (packet_kernels.h, whole_powers). One source for the instances whose
// instruction set has a fused multiply-add (built with -mfma on x86): the double-double products
// need the exact rounding error of a product, which one fused multiply-add gives. An instance
// without it (SIMD128) builds no powers kernel, and every lane goes to std::pow.
//
// Why it is exact: x^n for a whole n is formed by squaring and multiplying in double-double
// arithmetic (a value as hi + lo), whose relative error after the at most 24 steps allowed here is
// below 2^-75, far inside a ulp. glibc's pow (the one std::pow calls: Arm's algorithm, whose
// documented worst case is 0.54 ulp, 0.509 from its exp and 0.028 from its log) returns a double
// within 0.54 ulp of the true power. Where the double-double result lies within 0.44 ulp of its
// rounded double hi, and hi is not a power of two (where the ulp below is half the ulp above),
// every other double is more than 0.55 ulp from the true power, so pow must return hi. Elsewhere
// (about one lane in eight, and results below 2^-968, where lo could be subnormal) the lane is
// left to std::pow. Deciding every lane instead (a margin of 0.5 ulp) gives pow's neighbour on
// about 0.08 % of lanes, which the seeded test of tests/core/test_packet_powers.cpp finds.
#include "core/packet/packet_kernels.h"
#include "core/packet/packet_simd_ops.h"

#if !defined(PHONGLAB_SIMD_FMA)
#error "the powers kernel needs a fused multiply-add: build it with one (-mfma)"
#endif

namespace phonglab::packet::PHONGLAB_SIMD_NS {
namespace {

struct Wide {  // kLanes double-double values
  V hi, lo;
};
inline V product_error(V a, V b, V p) { return fms(a, b, p); }  // a b - p, exactly
inline Wide renormalise(V s, V e) {  // |s| >= |e|: s + e as hi + lo (Dekker's fast two-sum)
  const V hi = s + e;
  return {hi, e - (hi - s)};
}
// The steps leave hi + lo unnormalised (hi is the rounded product, lo the rest): the chain from
// step to step is then one multiplication. Each squaring doubles lo's size relative to hi's ulp,
// so after s steps |lo| < 2^s ulp(hi), and a step's rounding of lo costs under 2^(s - 104) of the
// value: below 2^-75 in all for the 24 steps allowed.
inline Wide square(Wide a) {  // (hi + lo)^2, lo^2 left out (below 2^-80 of it)
  const V p = a.hi * a.hi;
  return {p, fma(a.hi + a.hi, a.lo, product_error(a.hi, a.hi, p))};
}
inline Wide times(Wide a, V x) {
  const V p = a.hi * x;
  return {p, fma(a.lo, x, product_error(a.hi, x, p))};
}

}  // namespace

namespace {

// whole_powers for kLanes lanes sharing the exponent n: writes the decided lanes, returns their bits.
int lane_powers(const double* cos_spec, int n, int bits, double* out) {
  const V zero = zeros(), one = splat(1);
  // specular_factor's base: clamp_positive(clamp_unit(cos)); NaN and cos <= 0 give 0.
  const V c = load(cos_spec);
  const V clamped = pick(gt(c, one), one, c);
  const V x = pick(gt(clamped, zero), clamped, zero);
  Wide p{x, zero};
  const int top = 31 - __builtin_clz(static_cast<unsigned>(n));
  for (int b = top - 1; b >= 0; --b) {
    p = square(p);
    if (n >> b & 1) p = times(p, x);
  }
  p = renormalise(p.hi, p.lo);
  // ulp(hi) = 2^(exponent - 52): hi's exponent field alone, scaled exactly (hi >= 2^-968).
  const V ulp = and_bits(p.hi, 0x7ff0000000000000ULL) * splat(0x1p-52);
  // The mantissa field's bits, read as a double, are +0 exactly where they are all zero.
  const M power_of_two = eq(and_bits(p.hi, 0x000fffffffffffffULL), zero);
  const M near = both(ge(p.hi, splat(0x1p-968)), le(abs(p.lo), splat(0.44) * ulp));
  const M decided_power = and_not(power_of_two, near);
  // x = 0 gives 0 (pow(0, n) for n > 0) and x = 1 gives 1 (pow(1, y) is 1 for every y).
  const M ends = either(eq(x, zero), eq(x, one));
  const int decided = lanes_set(either(ends, decided_power)) & bits;
  // The other lanes keep what they held: std::pow will write them.
  store(out, pick(lane_mask(decided), pick(ends, x, p.hi), load(out)));
  return decided;
}

}  // namespace

void specular_powers(const double* cos_spec, const std::int32_t* material, const int* power,
                     const std::uint8_t* seen, int lanes, double* spec, std::uint8_t* pending) {
  for (int i = 0; i < lanes; i += kLanes) {
    int bits = byte_lanes(seen + i);
    if (bits != 0) {
      const int first = __builtin_ctz(static_cast<unsigned>(bits));
      const bool same = (equal_int32_lanes(material + i, material[i + first]) & bits) == bits;
      const int n = same ? power[material[i + first]] : -1;
      if (n == 0) {  // no ks: the factor is never read, 0 as the scalar loop writes
        store(spec + i, pick(lane_mask(bits), zeros(), load(spec + i)));
        bits = 0;
      } else if (n > 0) {
        bits &= ~lane_powers(cos_spec + i, n, bits, spec + i);
      }
    }
    put_byte_lanes(pending + i, spread_bits(bits));
  }
}

}  // namespace phonglab::packet::PHONGLAB_SIMD_NS
