// The packet kernels' vocabulary for one instance of them (packet_kernels.h says how the one
// kernel source becomes an instance per instruction set): V holds kLanes doubles, M says which
// of kLanes lanes a comparison holds in, and the operations below are the only ones the kernels
// use. Every one is an exact IEEE operation lane by lane (no fused multiply-add but `fma`, which
// only the powers' instances call), so every instance computes the scalar code's bits.
//
// PHONGLAB_SIMD_WIDTH picks the layer, PHONGLAB_SIMD_NS the instance's namespace:
// - 4: SIMDe's 256-bit vectors (simde__m256d). On x86 built with -mavx2 they are AVX2 itself; in
//   WebAssembly built with -msimd128 each is two SIMD128 registers; on aarch64 two NEON ones.
// - 8: AVX-512 (x86 only), through its intrinsics directly: SIMDe 0.7.4 has neither the
//   int32-to-double conversion nor the gathers the kernels use at that width, and Highway 1.0.3
//   (Debian's) has no double lanes in WebAssembly, which rules it out as the one layer
//   (docs/speed.md, "One kernel source").
// Masks are vectors of all-ones lanes at width 4 and a bit per lane (__mmask8) at width 8, so a
// mask used as a value does not compile at width 8: `keep` is how a mask zeroes a value.
//
// Every function here has internal linkage (an anonymous namespace, SIMDe's static inline
// functions): no instruction-set-specific code is shared with the rest of the program.
#pragma once

#include <cstdint>
#include <cstring>

#if PHONGLAB_SIMD_WIDTH == 8
#include <immintrin.h>
#elif PHONGLAB_SIMD_WIDTH == 4
#include <simde/x86/avx2.h>
#include <simde/x86/fma.h>
#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#elif defined(__aarch64__)
#include <arm_neon.h>
#endif
#else
#error "PHONGLAB_SIMD_WIDTH: 4 or 8"
#endif

namespace phonglab::packet::PHONGLAB_SIMD_NS {
namespace {

constexpr int kLanes = PHONGLAB_SIMD_WIDTH;
constexpr int kAll = (1 << kLanes) - 1;  // every lane's bit
constexpr double kInf = __builtin_huge_val();

#if PHONGLAB_SIMD_WIDTH == 8

using V = __m512d;
using M = __mmask8;

inline V load(const double* p) { return _mm512_loadu_pd(p); }
inline void store(double* p, V v) { _mm512_storeu_pd(p, v); }
inline V splat(double x) { return _mm512_set1_pd(x); }
inline V zeros() { return _mm512_setzero_pd(); }
inline M gt(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ); }      // a > b, false with NaN
inline M lt(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ); }      // a < b
inline M ge(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_GE_OQ); }      // a >= b
inline M le(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ); }      // a <= b
inline M eq(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_EQ_OQ); }      // a == b
inline M ne(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_NEQ_UQ); }     // !(a == b)
inline M not_gt(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_NGT_UQ); } // !(a > b)
inline M both(M a, M b) { return static_cast<M>(a & b); }
inline M either(M a, M b) { return static_cast<M>(a | b); }
inline M and_not(M a, M b) { return static_cast<M>(~a & b); }  // b where a is clear
inline M no_lanes() { return 0; }
inline M all_lanes() { return static_cast<M>(kAll); }
inline M choose(M m, M if_set, M if_clear) { return static_cast<M>((m & if_set) | (~m & if_clear)); }
inline V keep(M m, V a) { return _mm512_maskz_mov_pd(m, a); }  // a where m is set, else 0
inline V pick(M m, V if_set, V if_clear) { return _mm512_mask_blend_pd(m, if_clear, if_set); }
inline V negate(V a) { return _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(a), _mm512_castpd_si512(splat(-0.0)))); }
inline V abs(V a) { return _mm512_abs_pd(a); }  // the sign bit cleared
inline V copysign(V magnitude, V sign) {
  return _mm512_castsi512_pd(_mm512_or_si512(_mm512_castpd_si512(abs(magnitude)),
                                             _mm512_and_si512(_mm512_castpd_si512(splat(-0.0)), _mm512_castpd_si512(sign))));
}
inline V sqrt(V a) { return _mm512_sqrt_pd(a); }
inline V min_of(V a, V b) { return _mm512_min_pd(a, b); }  // a < b ? a : b (b where either is NaN)
inline V max_of(V a, V b) { return _mm512_max_pd(a, b); }  // a > b ? a : b
inline int lanes_set(M m) { return m; }
inline int sign_lanes(V a) { return _mm512_movepi64_mask(_mm512_castpd_si512(a)); }  // bit j: lane j's sign bit
inline M lane_mask(int bits) { return static_cast<M>(bits); }
// The doubles of kLanes int32 values from p on (every int32 is a double exactly).
inline V from_int32(const std::int32_t* p) {
  return _mm512_cvtepi32_pd(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
}
inline V gather(const double* base, const std::int64_t* index) {
  return _mm512_i64gather_pd(_mm512_loadu_si512(index), base, 8);
}
// base[index[j]] where m is set (only those entries are read), 0 elsewhere.
inline V gather_where(const double* base, const std::int32_t* index, M m) {
  return _mm512_mask_i32gather_pd(zeros(), m, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(index)), base, 8);
}
// The bits of a AND'ed with a pattern, as a double.
inline V and_bits(V a, std::uint64_t pattern) {
  return _mm512_castsi512_pd(_mm512_and_si512(_mm512_castpd_si512(a), _mm512_set1_epi64(static_cast<long long>(pattern))));
}
// Bit j set where the int32 p[j] equals v, or is negative.
inline int equal_int32_lanes(const std::int32_t* p, std::int32_t v) {
  const __m256i x = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
  return _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(x, _mm256_set1_epi32(v))));
}
inline int negative_int32_lanes(const std::int32_t* p) {
  return _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p))));
}
// Bit j set where byte j from p on is not 0.
inline int byte_lanes(const std::uint8_t* p) {
  const __m128i bytes = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
  return ~_mm_movemask_epi8(_mm_cmpeq_epi8(bytes, _mm_setzero_si128())) & kAll;
}
#if defined(__FMA__)
#define PHONGLAB_SIMD_FMA 1
inline V fma(V a, V b, V c) { return _mm512_fmadd_pd(a, b, c); }  // a b + c, rounded once
inline V fms(V a, V b, V c) { return _mm512_fmsub_pd(a, b, c); }  // a b - c, rounded once
#endif

#else  // PHONGLAB_SIMD_WIDTH == 4

using V = simde__m256d;
using M = simde__m256d;  // lanes of all ones or all zeros
// A V as two 128-bit halves of the target's own type and back (register moves once compiled),
// for what the target's instructions do as x86 does and SIMDe's do not (WebAssembly, aarch64).
template <class Half>
struct Halves {
  Half lo, hi;
};
template <class Half>
inline Halves<Half> split(V a) {
  static_assert(sizeof(Halves<Half>) == sizeof(V));
  Halves<Half> h;
  std::memcpy(&h, &a, sizeof h);
  return h;
}
template <class Half>
inline V join(Half lo, Half hi) {
  const Halves<Half> h{lo, hi};
  V r;
  std::memcpy(&r, &h, sizeof r);
  return r;
}

inline V load(const double* p) { return simde_mm256_loadu_pd(p); }
inline void store(double* p, V v) { simde_mm256_storeu_pd(p, v); }
inline V splat(double x) { return simde_mm256_set1_pd(x); }
inline V zeros() { return simde_mm256_setzero_pd(); }
inline M gt(V a, V b) { return simde_mm256_cmp_pd(a, b, SIMDE_CMP_GT_OQ); }
inline M lt(V a, V b) { return simde_mm256_cmp_pd(a, b, SIMDE_CMP_LT_OQ); }
inline M ge(V a, V b) { return simde_mm256_cmp_pd(a, b, SIMDE_CMP_GE_OQ); }
inline M le(V a, V b) { return simde_mm256_cmp_pd(a, b, SIMDE_CMP_LE_OQ); }
inline M eq(V a, V b) { return simde_mm256_cmp_pd(a, b, SIMDE_CMP_EQ_OQ); }
inline M ne(V a, V b) { return simde_mm256_cmp_pd(a, b, SIMDE_CMP_NEQ_UQ); }
inline M not_gt(V a, V b) { return simde_mm256_cmp_pd(a, b, SIMDE_CMP_NGT_UQ); }
inline M both(M a, M b) { return simde_mm256_and_pd(a, b); }
inline M either(M a, M b) { return simde_mm256_or_pd(a, b); }
inline M and_not(M a, M b) { return simde_mm256_andnot_pd(a, b); }
inline M no_lanes() { return zeros(); }
inline M all_lanes() { return simde_mm256_castsi256_pd(simde_mm256_set1_epi64x(-1)); }
inline M choose(M m, M if_set, M if_clear) { return simde_mm256_blendv_pd(if_clear, if_set, m); }
inline V keep(M m, V a) { return simde_mm256_and_pd(m, a); }
inline V pick(M m, V if_set, V if_clear) { return simde_mm256_blendv_pd(if_clear, if_set, m); }
inline V negate(V a) { return simde_mm256_xor_pd(a, splat(-0.0)); }
inline V abs(V a) { return simde_mm256_andnot_pd(splat(-0.0), a); }
inline V copysign(V magnitude, V sign) {
  return simde_mm256_or_pd(simde_mm256_andnot_pd(splat(-0.0), magnitude), simde_mm256_and_pd(splat(-0.0), sign));
}
inline V sqrt(V a) { return simde_mm256_sqrt_pd(a); }
#if defined(SIMDE_X86_AVX_NATIVE)
inline V min_of(V a, V b) { return simde_mm256_min_pd(a, b); }  // minpd: a < b ? a : b
inline V max_of(V a, V b) { return simde_mm256_max_pd(a, b); }  // maxpd: a > b ? a : b
#elif defined(__wasm_simd128__)
// SIMDe's min and max are the target's own elsewhere, which return NaN where either operand is
// one (WebAssembly's f64x2.min, NEON's fmin), not minpd's second operand. SIMD128's pseudo-min
// is minpd's rule exactly: pmin(b, a) = a < b ? a : b, one instruction per half.
template <class Op>
inline V per_half(V a, V b, Op op) {
  const Halves<v128_t> x = split<v128_t>(a), y = split<v128_t>(b);
  return join(op(x.lo, y.lo), op(x.hi, y.hi));
}
inline V min_of(V a, V b) { return per_half(a, b, [](v128_t x, v128_t y) { return wasm_f64x2_pmin(y, x); }); }
inline V max_of(V a, V b) { return per_half(a, b, [](v128_t x, v128_t y) { return wasm_f64x2_pmax(y, x); }); }
#else
// As above (NEON's fmin and fmax return NaN): minpd's rule written out.
inline V min_of(V a, V b) { return pick(lt(a, b), a, b); }
inline V max_of(V a, V b) { return pick(gt(a, b), a, b); }
#endif
#if defined(__wasm_simd128__)
// SIMDe's movemask is a loop over the lanes in WebAssembly; SIMD128 has the instruction itself,
// one per half of the four lanes (which are two v128 registers).
inline int sign_lanes(V a) {
  const Halves<v128_t> h = split<v128_t>(a);
  return wasm_i64x2_bitmask(h.lo) | wasm_i64x2_bitmask(h.hi) << 2;
}
#else
inline int sign_lanes(V a) { return simde_mm256_movemask_pd(a); }
#endif
inline int lanes_set(M m) { return sign_lanes(m); }
#if defined(__wasm_simd128__)
// SIMDe 0.7.4 writes these as loops over the lanes in WebAssembly; SIMD128 has them.
inline M lane_mask(int bits) {
  const v128_t b = wasm_i64x2_splat(bits);
  const v128_t lo = wasm_i64x2_make(1, 2), hi = wasm_i64x2_make(4, 8);
  return join(wasm_i64x2_eq(wasm_v128_and(b, lo), lo), wasm_i64x2_eq(wasm_v128_and(b, hi), hi));
}
inline V from_int32(const std::int32_t* p) {
  const v128_t x = wasm_v128_load(p);
  return join(wasm_f64x2_convert_low_i32x4(x), wasm_f64x2_convert_low_i32x4(wasm_i32x4_shuffle(x, x, 2, 3, 0, 1)));
}
#else
inline M lane_mask(int bits) {
  const simde__m256i select = simde_mm256_set_epi64x(8, 4, 2, 1);
  const simde__m256i set = simde_mm256_and_si256(simde_mm256_set1_epi64x(bits), select);
  return simde_mm256_castsi256_pd(simde_mm256_cmpeq_epi64(set, select));
}
inline V from_int32(const std::int32_t* p) { return simde_mm256_cvtepi32_pd(simde_mm_loadu_si128(p)); }
#endif
inline V gather(const double* base, const std::int64_t* index) {
  return simde_mm256_i64gather_pd(base, simde_mm256_loadu_si256(index), 8);
}
inline V gather_where(const double* base, const std::int32_t* index, M m) {
  return simde_mm256_mask_i32gather_pd(zeros(), base, simde_mm_loadu_si128(index), m, 8);
}
inline V and_bits(V a, std::uint64_t pattern) {
  return simde_mm256_castsi256_pd(
      simde_mm256_and_si256(simde_mm256_castpd_si256(a), simde_mm256_set1_epi64x(static_cast<std::int64_t>(pattern))));
}
#if defined(__wasm_simd128__)
inline int equal_int32_lanes(const std::int32_t* p, std::int32_t v) {
  return wasm_i32x4_bitmask(wasm_i32x4_eq(wasm_v128_load(p), wasm_i32x4_splat(v)));
}
inline int negative_int32_lanes(const std::int32_t* p) { return wasm_i32x4_bitmask(wasm_v128_load(p)); }
inline int byte_lanes(const std::uint8_t* p) {
  return ~wasm_i8x16_bitmask(wasm_i8x16_eq(wasm_v128_load32_zero(p), wasm_i8x16_splat(0))) & kAll;
}
#else
inline int equal_int32_lanes(const std::int32_t* p, std::int32_t v) {
  const simde__m128i x = simde_mm_loadu_si128(p);
  return simde_mm_movemask_ps(simde_mm_castsi128_ps(simde_mm_cmpeq_epi32(x, simde_mm_set1_epi32(v))));
}
inline int negative_int32_lanes(const std::int32_t* p) {
  return simde_mm_movemask_ps(simde_mm_castsi128_ps(simde_mm_loadu_si128(p)));
}
inline int byte_lanes(const std::uint8_t* p) {
  std::int32_t word;
  std::memcpy(&word, p, 4);
  const simde__m128i bytes = simde_mm_cvtsi32_si128(word);
  return ~simde_mm_movemask_epi8(simde_mm_cmpeq_epi8(bytes, simde_mm_setzero_si128())) & kAll;
}
#endif
#if defined(__FMA__)
#define PHONGLAB_SIMD_FMA 1
inline V fma(V a, V b, V c) { return simde_mm256_fmadd_pd(a, b, c); }
inline V fms(V a, V b, V c) { return simde_mm256_fmsub_pd(a, b, c); }
#elif defined(__aarch64__)
// SIMDe's fmadd is a product and a sum, rounded twice, where x86's FMA is not native: NEON's
// own fused instructions instead, half by half.
inline V fma(V a, V b, V c) {  // c + a b, rounded once
  const Halves<float64x2_t> x = split<float64x2_t>(a), y = split<float64x2_t>(b), z = split<float64x2_t>(c);
  return join(vfmaq_f64(z.lo, x.lo, y.lo), vfmaq_f64(z.hi, x.hi, y.hi));
}
inline V fms(V a, V b, V c) {  // a b - c = -(c - a b), rounded once
  const Halves<float64x2_t> x = split<float64x2_t>(a), y = split<float64x2_t>(b), z = split<float64x2_t>(c);
  return join(vnegq_f64(vfmsq_f64(z.lo, x.lo, y.lo)), vnegq_f64(vfmsq_f64(z.hi, x.hi, y.hi)));
}
#define PHONGLAB_SIMD_FMA 1
#endif

#endif

inline V dot(V ax, V ay, V az, V bx, V by, V bz) { return (ax * bx + ay * by) + az * bz; }  // glm's order

// Byte flags and lane bits (kLanes <= 8 bytes a group, as one word).
// Bit j of `bits` as byte j (0 or 1) of a word, and kLanes such bytes stored from p on. Four
// bits at a time: bit j of the product moves to 8 j and no two products overlap.
inline std::uint64_t spread_bits(int bits) {
  const auto four = [](unsigned b) { return static_cast<std::uint64_t>((b * 0x204081u) & 0x01010101u); };
  const unsigned u = static_cast<unsigned>(bits);
  return kLanes > 4 ? four(u & 0xF) | four((u >> 4) & 0xF) << 32 : four(u & 0xF);
}
inline void put_byte_lanes(std::uint8_t* p, std::uint64_t word) { std::memcpy(p, &word, kLanes); }
// The bits of lanes [0, live) of a group: all of them from kLanes live lanes on.
inline int live_lanes(int live) { return live >= kLanes ? kAll : (1 << live) - 1; }

}  // namespace
}  // namespace phonglab::packet::PHONGLAB_SIMD_NS
