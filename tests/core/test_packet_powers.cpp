// The packet tracer's whole specular powers (packet::specular_powers, src/core/packet/packet_kernels_powers.cpp, every instance)
// against specular_factor, the one definition (std::pow): every lane the kernel decides holds
// std::pow's double bit for bit, every other seen lane is left to the caller, and most lanes are
// decided. Seeded, so a failure repeats. Deciding every lane (a margin of 0.5 ulp instead of
// 0.44) gives pow's neighbour on about 0.08 % of lanes: the first test then fails on ~100 of them.
#include <gtest/gtest.h>

#include <cstdint>
#include <algorithm>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/packet/packet.h"
#include "tests/support/kernel_checks.h"
#include "tests/support/simd_targets.h"
#include "core/packet/packet_kernels.h"
#include "core/shading/shading.h"

using namespace phonglab;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct Lanes {
  std::vector<double> cos_spec, spec;
  std::vector<std::int32_t> material;
  std::vector<std::uint8_t> seen, pending;
  explicit Lanes(int n) : cos_spec(n), spec(n, -7.0), material(n, 0), seen(n, 1), pending(n, 9) {}
  void run(const std::vector<int>& power) {
    packet::specular_powers(cos_spec.data(), material.data(), power.data(), seen.data(),
                            static_cast<int>(cos_spec.size()), spec.data(), pending.data());
  }
};

}  // namespace

TEST(PacketPowers, DecidedLanesHoldStdPowsDoubleBitForBit) {
  if (!packet_fma_supported()) GTEST_SKIP() << "no fused multiply-add in this CPU's packet kernels";
  test::for_each_simd_target([&] {
    const test::PowerCheck check = test::check_powers(40);
    EXPECT_EQ(check.failures, "");
    for (std::size_t e = 0; e < test::kPowerExponents.size(); ++e) {
      // About one lane in eight is too near a rounding boundary; results below 2^-968 go to
      // std::pow too (x < 0.107 for n = 300, most lanes of the largest n).
      const int n = test::kPowerExponents[e];
      if (n <= 20) {
        EXPECT_GT(check.decided[e], 0.85) << "n " << n;
      } else if (n <= 300) {
        EXPECT_GT(check.decided[e], 0.75) << "n " << n;
      }
    }
  });
}

TEST(PacketPowers, EdgeBasesFollowSpecularFactor) {
  if (!packet_fma_supported()) GTEST_SKIP() << "no fused multiply-add in this CPU's packet kernels";
  test::for_each_simd_target([&] {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> bases = {0.0,   -0.0,  -0.25, -1.0,   -3.0,   1.0,      1.0 + 1e-15, 2.0,  nan,
                                       0.5,   0.25,  1e-300, 1e-20, 0.9999999999999999, 0x1p-60, 0.03, 0.7,  0.999};
    Lanes lanes(packet::padded_lanes(static_cast<int>(bases.size())));
    std::copy(bases.begin(), bases.end(), lanes.cos_spec.begin());
    for (int n : {1, 2, 10, 200}) {
      lanes.run({n});
      for (std::size_t i = 0; i < bases.size(); ++i) {
        if (lanes.pending[i]) continue;
        EXPECT_TRUE(same_bits(lanes.spec[i], specular_factor(bases[i], n))) << "n " << n << " base " << bases[i];
      }
      // 0 and 1 (and what clamps to them) are exact; a power of two is left to std::pow.
      for (std::size_t i : {0u, 1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u}) EXPECT_EQ(lanes.pending[i], 0) << "base " << bases[i];
      EXPECT_EQ(lanes.pending[9], 1);   // 0.5^n
      EXPECT_EQ(lanes.pending[10], 1);  // 0.25^n
    }
  });
}

// Groups of the instance's lanes: one of mixed materials, one without ks, one left to std::pow.
TEST(PacketPowers, OtherLanesAreLeftToTheCaller) {
  if (!packet_fma_supported()) GTEST_SKIP() << "no fused multiply-add in this CPU's packet kernels";
  test::for_each_simd_target([&] {
    if (!packet_fma_supported()) return;
    const int w = packet_simd_lanes();
    const auto at = [](int i) { return static_cast<std::size_t>(i); };
    Lanes lanes(packet::padded_lanes(3 * w));
    for (double& c : lanes.cos_spec) c = 0.8;
    std::fill(lanes.seen.begin(), lanes.seen.end(), 0);
    std::vector<std::uint8_t> pending(lanes.seen.size(), 0);
    for (int j = 0; j < w; ++j) {
      lanes.material[at(j)] = j == 2 ? 1 : 0;  // mixed
      lanes.material[at(w + j)] = 2;           // no ks
      lanes.material[at(2 * w + j)] = 1;       // std::pow
      lanes.seen[at(j)] = j != 3;
      lanes.seen[at(w + j)] = j != 2;
      lanes.seen[at(2 * w + j)] = 1;
      pending[at(j)] = j != 3;
      pending[at(2 * w + j)] = 1;
    }
    lanes.run({10, -1, 0});
    EXPECT_EQ(lanes.pending, pending);
    EXPECT_EQ(lanes.spec[at(w)], 0.0);       // a seen lane without ks: factor 0
    EXPECT_EQ(lanes.spec[at(w + 2)], -7.0);  // not seen: untouched
    EXPECT_EQ(lanes.spec[3], -7.0);
  });
}

TEST(PacketPowers, WholeExponentsWithinTheStepLimit) {
  EXPECT_EQ(whole_power_exponent(10), 10);
  EXPECT_EQ(whole_power_exponent(1), 1);
  EXPECT_EQ(whole_power_exponent(4095), 4095);  // 11 squarings and 11 products
  EXPECT_EQ(whole_power_exponent(4096), 4096);
  EXPECT_EQ(whole_power_exponent(4097), -1);
  EXPECT_EQ(whole_power_exponent(10.5), -1);
  EXPECT_EQ(whole_power_exponent(0.5), -1);
  EXPECT_EQ(whole_power_exponent(0), -1);
  EXPECT_EQ(whole_power_exponent(std::numeric_limits<double>::quiet_NaN()), -1);
}
