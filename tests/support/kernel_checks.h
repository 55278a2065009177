// Checks of the packet kernels' own rules that no scene reaches reliably, for whichever instance
// runs (tests/core/test_packet.cpp natively, tests/web/simd_check.cpp in the page's engine).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/packet/packet_kernels.h"
#include "core/shading/shading.h"

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

// The whole powers' kernel (packet::specular_powers) against specular_factor (std::pow, this
// build's libm): seeded bases in [0, 1) for each exponent of kPowerExponents, `rounds` batches of
// 4096 lanes. Every lane the kernel decides must hold std::pow's double bit for bit: `failures`
// names the first few that do not; `decided` is the share of lanes decided, per exponent. Only
// where packet_fma_supported().
inline constexpr std::array<int, 11> kPowerExponents = {1, 2, 3, 10, 20, 64, 200, 255, 300, 1000, 4095};
struct PowerCheck {
  std::string failures;
  std::array<double, kPowerExponents.size()> decided{};
};
inline PowerCheck check_powers(int rounds) {
  constexpr int kLanes = 4096;
  PowerCheck check;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<double> cos_spec(kLanes), spec(kLanes);
  const std::vector<std::int32_t> material(kLanes, 0);
  const std::vector<std::uint8_t> seen(kLanes, 1);
  std::vector<std::uint8_t> pending(kLanes);
  int wrong = 0;
  for (std::size_t e = 0; e < kPowerExponents.size(); ++e) {
    const int n = kPowerExponents[e];
    long decided = 0;
    for (int round = 0; round < rounds; ++round) {
      for (double& c : cos_spec) c = unit(rng);
      packet::specular_powers(cos_spec.data(), material.data(), &n, seen.data(), kLanes, spec.data(), pending.data());
      for (std::size_t i = 0; i < cos_spec.size(); ++i) {
        if (pending[i]) continue;
        ++decided;
        const double want = specular_factor(cos_spec[i], n);
        if (std::memcmp(&spec[i], &want, sizeof want) != 0 && ++wrong <= 5) {
          check.failures += "n " + std::to_string(n) + " cos " + std::to_string(cos_spec[i]) + ": not std::pow's double\n";
        }
      }
    }
    check.decided[e] = static_cast<double>(decided) / (static_cast<double>(rounds) * kLanes);
  }
  if (wrong > 5) check.failures += std::to_string(wrong) + " lanes in all\n";
  return check;
}

}  // namespace phonglab::test
