#include "renderer/bvh.h"

#include <algorithm>
#include <array>
#include <exception>
#include <thread>

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
// Subtrees of more primitives than this are built on their own thread, down to kParallelLevels
// levels (2 cores here: 4 subtrees keep both busy while the larger half finishes).
constexpr std::uint32_t kParallelMinPrims = 1u << 16;
constexpr int kParallelLevels = 2;

// A primitive during the build: its box and centroid kept beside its index, so binning and
// partitioning stream through one array instead of chasing indices.
struct PrimRef {
  Aabb box;
  Vec3 centroid;
  std::uint32_t index;
};

struct Bin {
  Aabb box;
  std::uint32_t count = 0;
};

int bin_of(double c, double lo, double scale) {
  const int b = static_cast<int>((c - lo) * scale);
  return std::clamp(b, 0, kBins - 1);
}

class Builder {
 public:
  Builder(std::vector<PrimRef>& refs, int max_leaf) : refs_(refs), max_leaf_(static_cast<std::uint32_t>(max_leaf)) {}

  // Builds the subtree over refs[begin, end) at the end of `out`, depth-first; node indices are
  // relative to `out`. Returns the subtree's depth.
  int build(std::vector<BvhNode>& out, std::uint32_t begin, std::uint32_t end, int level) {
    const std::uint32_t index = static_cast<std::uint32_t>(out.size());
    out.emplace_back();
    Aabb box, centroid_box;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.grow(refs_[i].box);
      centroid_box.grow(refs_[i].centroid);
    }
    out[index].box = box;
    const std::uint32_t n = end - begin;
    if (n <= max_leaf_ || level + 1 >= kMaxDepth) return leaf(out[index], begin, n);

    // Bin the centroids along all three axes in one pass.
    std::array<std::array<Bin, kBins>, 3> bins{};
    const Vec3 extent = centroid_box.hi - centroid_box.lo;
    Vec3 scale;
    for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0 ? kBins / extent[a] : 0;
    for (std::uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      for (int a = 0; a < 3; ++a) {
        Bin& b = bins[a][bin_of(r.centroid[a], centroid_box.lo[a], scale[a])];
        b.box.grow(r.box);
        ++b.count;
      }
    }
    // Price each of the kBins - 1 boundaries per axis: a sweep from the right, then the left.
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int a = 0; a < 3; ++a) {
      if (!(extent[a] > 0)) continue;
      std::array<double, kBins> right_cost{};
      Aabb acc;
      std::uint32_t acc_n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.grow(bins[a][b].box);
        acc_n += bins[a][b].count;
        right_cost[b] = acc_n == 0 ? 0 : acc.half_area() * acc_n;
      }
      acc = Aabb{};
      acc_n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.grow(bins[a][b].box);
        acc_n += bins[a][b].count;
        const double cost = acc.half_area() * acc_n + right_cost[b + 1];
        if (acc_n > 0 && acc_n < n && cost < best_cost) {
          best_cost = cost;
          best_axis = a;
          best_bin = b;
        }
      }
    }
    const double parent_area = box.half_area();
    const double split_cost = kTraversalCost + kPrimitiveCost * best_cost / (parent_area > 0 ? parent_area : 1);
    const double leaf_cost = kPrimitiveCost * n;
    const bool small = n <= 4 * max_leaf_;
    std::uint32_t mid;
    int axis;
    if (best_axis < 0) {
      // All centroids coincide: split by count so no leaf grows without bound.
      if (small) return leaf(out[index], begin, n);
      axis = 0;
      mid = begin + n / 2;
    } else {
      if (leaf_cost <= split_cost && small) return leaf(out[index], begin, n);
      axis = best_axis;
      const double lo = centroid_box.lo[axis];
      const double sc = scale[axis];
      const auto split = std::partition(refs_.begin() + begin, refs_.begin() + end, [&](const PrimRef& r) {
        return bin_of(r.centroid[axis], lo, sc) <= best_bin;
      });
      mid = static_cast<std::uint32_t>(split - refs_.begin());
    }
    out[index].axis = static_cast<std::uint32_t>(axis);
    out[index].count = 0;
    int left_depth = 0, right_depth = 0;
    if (n >= kParallelMinPrims && level < kParallelLevels) {
      // The two halves into their own arrays at once, then appended with indices shifted.
      std::vector<BvhNode> left_nodes, right_nodes;
      std::exception_ptr left_error;
      std::thread left_thread([&] {
        try {
          left_depth = build(left_nodes, begin, mid, level + 1);
        } catch (...) {
          left_error = std::current_exception();  // rethrown below: out of memory, say
        }
      });
      try {
        right_depth = build(right_nodes, mid, end, level + 1);
      } catch (...) {
        left_thread.join();
        throw;
      }
      left_thread.join();
      if (left_error) std::rethrow_exception(left_error);
      append(out, left_nodes);
      out[index].first = static_cast<std::uint32_t>(out.size());
      append(out, right_nodes);
    } else {
      left_depth = build(out, begin, mid, level + 1);
      out[index].first = static_cast<std::uint32_t>(out.size());
      right_depth = build(out, mid, end, level + 1);
    }
    return 1 + std::max(left_depth, right_depth);
  }

 private:
  static int leaf(BvhNode& node, std::uint32_t begin, std::uint32_t n) {
    node.first = begin;
    node.count = n;
    return 1;
  }

  // Appends a subtree built in its own array; its inner nodes' child indices move with it.
  static void append(std::vector<BvhNode>& out, const std::vector<BvhNode>& sub) {
    const auto shift = static_cast<std::uint32_t>(out.size());
    for (BvhNode node : sub) {
      if (node.count == 0) node.first += shift;
      out.push_back(node);
    }
  }

  std::vector<PrimRef>& refs_;
  std::uint32_t max_leaf_;
};

}  // namespace

Bvh build_bvh(const std::vector<Aabb>& boxes, int max_leaf) {
  Bvh bvh;
  if (boxes.empty()) return bvh;
  std::vector<PrimRef> refs(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    refs[i] = PrimRef{boxes[i], boxes[i].centroid(), static_cast<std::uint32_t>(i)};
  }
  bvh.nodes.reserve(2 * boxes.size() / static_cast<std::size_t>(std::max(1, max_leaf)) + 1);
  Builder builder(refs, std::max(1, max_leaf));
  bvh.depth = builder.build(bvh.nodes, 0, static_cast<std::uint32_t>(refs.size()), 0);
  bvh.nodes.shrink_to_fit();
  bvh.order.resize(refs.size());
  for (std::size_t i = 0; i < refs.size(); ++i) bvh.order[i] = refs[i].index;
  return bvh;
}

}  // namespace phonglab
