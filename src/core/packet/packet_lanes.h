// How many lanes the packet tracer's batches come in: the widest instance's (AVX-512: 8 doubles),
// so every instance's loop over whole groups of its own lanes (8, 4 or 2) covers a batch. Arrays
// that packet kernels read in place (the driver's batches, RayTrees' geometry, shadow rays) are
// padded to it.
#pragma once

namespace phonglab::packet {

constexpr int kBatchLanes = 8;
constexpr int padded_lanes(int n) { return (n + kBatchLanes - 1) / kBatchLanes * kBatchLanes; }

}  // namespace phonglab::packet
