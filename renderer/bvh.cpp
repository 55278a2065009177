#include "renderer/bvh.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace phonglab {

Aabb sphere_bounds(const Sphere& s) {
  // c +- r rounds to within half an ulp of |c| + r; widen by two ulps of that magnitude.
  const double pad = (max_abs(s.center) + s.radius) * 0x1p-51;
  const Vec3 r(s.radius + pad);
  return Aabb{s.center - r, s.center + r};
}

Aabb triangle_bounds(const Triangle& t) {
  Aabb b;
  b.grow(t.v0);
  b.grow(t.v1);
  b.grow(t.v2);
  return b;
}

namespace {

constexpr int kBins = 16;
// The traversal stack holds one entry per level; beyond this depth a node becomes a leaf.
constexpr int kMaxDepth = 96;
// SAH costs of a box test and of a primitive test, in the same (arbitrary) unit.
constexpr double kTraversalCost = 1.0;
constexpr double kPrimitiveCost = 1.5;

struct Builder {
  const std::vector<Aabb>& boxes;
  std::vector<Vec3> centroids;
  std::vector<std::uint32_t>& order;
  std::vector<BvhNode>& nodes;
  int max_leaf;
  int depth = 0;

  struct Bin {
    Aabb box;
    std::uint32_t count = 0;
  };

  // Builds the subtree over order[begin, end) into nodes[index]; children follow depth-first.
  void build(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int level) {
    depth = std::max(depth, level + 1);
    BvhNode& node = nodes[index];
    Aabb centroid_box;
    for (std::uint32_t i = begin; i < end; ++i) {
      node.box.grow(boxes[order[i]]);
      centroid_box.grow(centroids[order[i]]);
    }
    const std::uint32_t n = end - begin;
    if (n <= static_cast<std::uint32_t>(max_leaf) || level + 1 >= kMaxDepth) {
      make_leaf(index, begin, n);
      return;
    }
    // Best split over the three axes' bin boundaries.
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    const Vec3 extent = centroid_box.hi - centroid_box.lo;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0)) continue;
      std::array<Bin, kBins> bins{};
      const double scale = kBins / extent[axis];
      for (std::uint32_t i = begin; i < end; ++i) {
        const int b = bin_of(centroids[order[i]][axis], centroid_box.lo[axis], scale);
        bins[b].box.grow(boxes[order[i]]);
        ++bins[b].count;
      }
      // Sweep from the right, then from the left, pricing each of the kBins - 1 boundaries.
      std::array<double, kBins> right_cost{};
      Aabb acc;
      std::uint32_t acc_n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.grow(bins[b].box);
        acc_n += bins[b].count;
        right_cost[b] = acc_n == 0 ? 0 : acc.half_area() * acc_n;
      }
      acc = Aabb{};
      acc_n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.grow(bins[b].box);
        acc_n += bins[b].count;
        const double cost = acc.half_area() * acc_n + right_cost[b + 1];
        if (acc_n > 0 && acc_n < n && cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    const double parent_area = node.box.half_area();
    const double split_cost = kTraversalCost + kPrimitiveCost * best_cost / (parent_area > 0 ? parent_area : 1);
    const double leaf_cost = kPrimitiveCost * n;
    std::uint32_t mid;
    int axis;
    if (best_axis < 0) {
      // All centroids coincide: split by count so no leaf grows without bound.
      if (n <= 4u * static_cast<std::uint32_t>(max_leaf)) {
        make_leaf(index, begin, n);
        return;
      }
      axis = 0;
      mid = begin + n / 2;
    } else {
      if (leaf_cost <= split_cost && n <= 4u * static_cast<std::uint32_t>(max_leaf)) {
        make_leaf(index, begin, n);
        return;
      }
      axis = best_axis;
      const double lo = centroid_box.lo[axis];
      const double scale = kBins / extent[axis];
      const auto split =
          std::partition(order.begin() + begin, order.begin() + end, [&](std::uint32_t p) {
            return bin_of(centroids[p][axis], lo, scale) <= best_bin;
          });
      mid = static_cast<std::uint32_t>(split - order.begin());
    }
    node.axis = static_cast<std::uint32_t>(axis);
    node.count = 0;
    const std::uint32_t left = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    build(left, begin, mid, level + 1);
    const std::uint32_t right = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    nodes[index].first = right;  // `node` may dangle: the vector grew
    build(right, mid, end, level + 1);
  }

  static int bin_of(double c, double lo, double scale) {
    const int b = static_cast<int>((c - lo) * scale);
    return std::clamp(b, 0, kBins - 1);
  }

  void make_leaf(std::uint32_t index, std::uint32_t begin, std::uint32_t n) {
    nodes[index].first = begin;
    nodes[index].count = n;
  }
};

}  // namespace

Bvh build_bvh(const std::vector<Aabb>& boxes, int max_leaf) {
  Bvh bvh;
  if (boxes.empty()) return bvh;
  bvh.order.resize(boxes.size());
  std::iota(bvh.order.begin(), bvh.order.end(), 0u);
  std::vector<Vec3> centroids(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) centroids[i] = boxes[i].centroid();
  bvh.nodes.reserve(2 * boxes.size() / std::max(1, max_leaf) + 1);
  bvh.nodes.emplace_back();
  Builder builder{boxes, std::move(centroids), bvh.order, bvh.nodes, std::max(1, max_leaf)};
  builder.build(0, 0, static_cast<std::uint32_t>(boxes.size()), 0);
  bvh.depth = builder.depth;
  bvh.nodes.shrink_to_fit();
  return bvh;
}

}  // namespace phonglab
