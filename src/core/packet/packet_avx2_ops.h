// The AVX2 kernels' shared operations (four doubles as V, comparisons as masks, glm's dot order,
// lane masks and byte flags), for the AVX2 translation units of src/core/packet only: every
// function here has internal linkage, so no AVX2 code can be shared with the rest of the program
// (packet_kernels.h says why).
#pragma once

#include <immintrin.h>

#include <cstdint>

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
inline std::uint32_t spread_bits(int bits) {  // bit j moves to 8 j: no two products overlap
  return (static_cast<std::uint32_t>(bits) * 0x204081u) & 0x01010101u;
}
inline void put_byte_lanes(std::uint8_t* p, std::uint32_t word) { __builtin_memcpy(p, &word, 4); }

inline V lane_mask(int bits) {  // lane j all ones where bit j is set
  const __m256i select = _mm256_set_epi64x(8, 4, 2, 1);
  const __m256i set = _mm256_and_si256(_mm256_set1_epi64x(bits), select);
  return _mm256_castsi256_pd(_mm256_cmpeq_epi64(set, select));
}

}  // namespace
}  // namespace phonglab::packet
