// Every instance of the packet kernels (packet_kernels.h) this CPU runs, one after another.
#pragma once

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/packet/packet.h"

namespace phonglab::test {

// Runs body once per instance this CPU runs (AVX-512 and AVX2 on such a CPU; "off", the scalar
// renderer, left out), each under a SCOPED_TRACE naming it, then puts back the one that ran before.
template <class Body>
void for_each_simd_target(Body&& body) {
  const std::string before = packet_simd_key();
  for (const std::string& key : packet_simd_targets()) {
    if (key == "off") continue;
    ASSERT_TRUE(set_packet_simd_target(key));
    SCOPED_TRACE("packet kernels " + key);
    body();
  }
  set_packet_simd_target(before);
}

}  // namespace phonglab::test
