// Checks of the packet kernels' own rules that no scene reaches reliably, for whichever instance
// runs (tests/core/test_packet.cpp natively, tests/web/simd_check.cpp in the page's engine).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/packet/packet_kernels.h"

namespace phonglab::test {

// hit_bounds passes over a NaN coordinate (as minpd and maxpd do: the other operand where one is
// NaN), whatever lane it is in; an instruction that returns NaN instead (WebAssembly's f64x2.min,
// NEON's fmin) poisons the box. Returns what went wrong, or "".
inline std::string nan_bounds_failures() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::string failures;
  for (int at = 0; at < packet::kBatchLanes; ++at) {
    std::vector<double> x(packet::kBatchLanes), y(x.size(), 0.0), z(x.size(), 0.0), offset(x.size(), 0.5);
    for (int i = 0; i < packet::kBatchLanes; ++i) x[static_cast<std::size_t>(i)] = 1.0 + i;
    x[static_cast<std::size_t>(at)] = nan;
    const std::vector<std::int32_t> id(x.size(), 0);
    double out[7];
    packet::hit_bounds(x.data(), y.data(), z.data(), offset.data(), id.data(), packet::kBatchLanes, out);
    const double lo = at == 0 ? 2.0 : 1.0, hi = at == packet::kBatchLanes - 1 ? packet::kBatchLanes - 1.0 : packet::kBatchLanes;
    if (!(out[0] == lo && out[3] == hi)) {
      failures += "hit_bounds with NaN in lane " + std::to_string(at) + ": x from " + std::to_string(out[0]) + " to " +
                  std::to_string(out[3]) + ", not " + std::to_string(lo) + " to " + std::to_string(hi) + "\n";
    }
  }
  return failures;
}

}  // namespace phonglab::test
