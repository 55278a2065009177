// A 32-bit integer hash with good avalanche (the "lowbias32" constants of Wellons): the one hash
// of the per-pixel sample rotations and the indirect light's scrambles.
#pragma once

#include <cstdint>

namespace phonglab {

inline std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

}  // namespace phonglab
