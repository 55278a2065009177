#include "core/accel/bvh.h"
#include "core/base/threads.h"

#include <algorithm>
#include <array>
#include <exception>
#include <functional>
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
// levels (2 cores here: 4 subtrees keep both busy while the larger half finishes). Above the
// first split only one subtree exists, so the root's passes (its references, their bounds and
// its binning) are split in two halves over two threads instead.
constexpr std::uint32_t kParallelMinPrims = 1u << 16;
constexpr int kParallelLevels = 2;

// A primitive during the build: its box beside its index, so binning and partitioning stream
// through one array instead of chasing indices. The centroid is recomputed where it is needed
// (centroid_of: the same expression, so the same bits, as Aabb::centroid): 56 bytes instead of
// 80 is a third less memory traffic in passes that are bound by it at the top levels.
struct PrimRef {
  Aabb box;
  std::uint32_t index;
};

double centroid_of(const PrimRef& r, int axis) { return 0.5 * (r.box.lo[axis] + r.box.hi[axis]); }
Vec3 centroid_of(const PrimRef& r) { return 0.5 * (r.box.lo + r.box.hi); }

// A box without Aabb's initialization to empty (Vec3's default constructor leaves it undefined).
struct BinBox {
  Vec3 lo, hi;
};

// The bins of a node along all three axes. A bin's box is set by the first reference that falls in
// it and read only where its count is not 0: the 48 boxes need no initialization, which matters
// because most of a large mesh's 400k inner nodes are small and leave most bins empty.
struct Bins {
  std::array<std::array<std::uint32_t, kBins>, 3> count{};
  std::array<std::array<BinBox, kBins>, 3> box;

  void add(int axis, int bin, const Aabb& b) {
    if (count[axis][bin]++ == 0) {
      box[axis][bin] = {b.lo, b.hi};
    } else {
      box[axis][bin].lo = glm::min(box[axis][bin].lo, b.lo);
      box[axis][bin].hi = glm::max(box[axis][bin].hi, b.hi);
    }
  }
};

// The bounds of a range of references: of their boxes and of their centroids.
struct RangeBounds {
  Aabb box;
  Aabb centroids;
  void grow(const RangeBounds& b) {
    box.grow(b.box);
    centroids.grow(b.centroids);
  }
};

int bin_of(double c, double lo, double scale) {
  const int b = static_cast<int>((c - lo) * scale);
  return std::clamp(b, 0, kBins - 1);
}

// Min and max do not depend on the order they are taken in, and counts add exactly: bins filled
// in parts and merged equal bins filled in one pass, so the parallel root split is the serial one.
// (Only a zero bound's sign may differ, -0 against +0, which no box test or SAH cost tells apart.)
void merge_bins(Bins& into, const Bins& from) {
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < kBins; ++b) {
      if (from.count[a][b] == 0) continue;
      into.add(a, b, Aabb{from.box[a][b].lo, from.box[a][b].hi});
      into.count[a][b] += from.count[a][b] - 1;
    }
  }
}

class Builder {
 public:
  Builder(std::vector<PrimRef>& refs, int max_leaf) : refs_(refs), max_leaf_(static_cast<std::uint32_t>(max_leaf)) {}

  // Builds the subtree over refs[begin, end) at the end of `out`, depth-first; node indices are
  // relative to `out`. `bounds` are those of the range (its parent's partition computed them).
  // Returns the subtree's depth.
  int build(std::vector<BvhNode>& out, std::uint32_t begin, std::uint32_t end, const RangeBounds& bounds, int level) {
    const std::uint32_t index = static_cast<std::uint32_t>(out.size());
    out.emplace_back();
    const Aabb& box = bounds.box;
    const Aabb& centroid_box = bounds.centroids;
    out[index].box = box;
    const std::uint32_t n = end - begin;
    if (n <= max_leaf_ || level + 1 >= kMaxDepth) return leaf(out[index], begin, n);
    const bool parallel = n >= kParallelMinPrims && level < kParallelLevels;

    // Bin the centroids along all three axes in one pass (in two halves at once at the root).
    Bins bins;
    const Vec3 extent = centroid_box.hi - centroid_box.lo;
    Vec3 scale;
    for (int a = 0; a < 3; ++a) scale[a] = extent[a] > 0 ? kBins / extent[a] : 0;
    if (parallel && level == 0) {
      const std::uint32_t half = begin + n / 2;
      Bins upper;
      in_parallel([&] { fill_bins(upper, half, end, centroid_box.lo, scale); },
                  [&] { fill_bins(bins, begin, half, centroid_box.lo, scale); });
      merge_bins(bins, upper);
    } else {
      fill_bins(bins, begin, end, centroid_box.lo, scale);
    }
    // Price each of the kBins - 1 boundaries per axis: a sweep from the right, then the left.
    // An empty bin changes neither side's box nor count, so the boundary after it costs exactly
    // what the one before it did and can never win (only a strictly lower cost replaces the
    // best): empty bins are skipped, and their right-hand cost is copied.
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int a = 0; a < 3; ++a) {
      if (!(extent[a] > 0)) continue;
      std::array<double, kBins> right_cost{};
      Aabb acc;
      std::uint32_t acc_n = 0;
      for (int b = kBins - 1; b > 0; --b) {
        if (bins.count[a][b] == 0) {
          right_cost[b] = b + 1 < kBins ? right_cost[b + 1] : 0;
          continue;
        }
        acc.grow(Aabb{bins.box[a][b].lo, bins.box[a][b].hi});
        acc_n += bins.count[a][b];
        right_cost[b] = acc.half_area() * acc_n;
      }
      acc = Aabb{};
      acc_n = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        if (bins.count[a][b] == 0) continue;
        acc.grow(Aabb{bins.box[a][b].lo, bins.box[a][b].hi});
        acc_n += bins.count[a][b];
        const double cost = acc.half_area() * acc_n + right_cost[b + 1];
        if (acc_n < n && cost < best_cost) {
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
    RangeBounds left, right;
    if (best_axis < 0) {
      // All centroids coincide: split by count so no leaf grows without bound.
      if (small) return leaf(out[index], begin, n);
      axis = 0;
      mid = begin + n / 2;
      left = range_bounds(begin, mid);
      right = range_bounds(mid, end);
    } else {
      if (leaf_cost <= split_cost && small) return leaf(out[index], begin, n);
      axis = best_axis;
      mid = partition(begin, end, axis, centroid_box.lo[axis], scale[axis], best_bin, left.centroids, right.centroids);
      // The children's boxes are the unions of the bins on either side of the split.
      for (int b = 0; b < kBins; ++b) {
        if (bins.count[axis][b] > 0) (b <= best_bin ? left : right).box.grow(Aabb{bins.box[axis][b].lo, bins.box[axis][b].hi});
      }
    }
    out[index].axis = static_cast<std::uint32_t>(axis);
    out[index].count = 0;
    int left_depth = 0, right_depth = 0;
    if (parallel) {
      // Both halves at once: the left one on a thread of its own, straight into `out` (which
      // this thread leaves alone until that is done), the right one into an array of its own,
      // appended after it with its indices shifted. An array over m primitives gets at most
      // 2m - 1 nodes and is reserved for them, so none grows by copying.
      std::vector<BvhNode> right_nodes;
      right_nodes.reserve(2 * std::size_t{end - mid} - 1);
      in_parallel([&] { left_depth = build(out, begin, mid, left, level + 1); },
                  [&] { right_depth = build(right_nodes, mid, end, right, level + 1); });
      out[index].first = static_cast<std::uint32_t>(out.size());
      append(out, right_nodes);
    } else {
      left_depth = build(out, begin, mid, left, level + 1);
      out[index].first = static_cast<std::uint32_t>(out.size());
      right_depth = build(out, mid, end, right, level + 1);
    }
    return 1 + std::max(left_depth, right_depth);
  }

 private:
  static int leaf(BvhNode& node, std::uint32_t begin, std::uint32_t n) {
    node.first = begin;
    node.count = n;
    return 1;
  }

  void fill_bins(Bins& bins, std::uint32_t begin, std::uint32_t end, const Vec3& lo, const Vec3& scale) const {
    for (std::uint32_t i = begin; i < end; ++i) {
      const PrimRef& r = refs_[i];
      for (int a = 0; a < 3; ++a) bins.add(a, bin_of(centroid_of(r, a), lo[a], scale[a]), r.box);
    }
  }

  RangeBounds range_bounds(std::uint32_t begin, std::uint32_t end) const {
    RangeBounds b;
    for (std::uint32_t i = begin; i < end; ++i) {
      b.box.grow(refs_[i].box);
      b.centroids.grow(centroid_of(refs_[i]));
    }
    return b;
  }

  // Moves the references whose centroid falls in a bin up to `best_bin` along `axis` before the
  // others and returns where the others start; grows `left` and `right` by the centroids of
  // either side on the way, which saves the children a pass over their range for them.
  // The moves are those of libstdc++'s std::partition (from both ends, swapping the first
  // misplaced pair), which this replaced: the same leaves in the same order as before.
  std::uint32_t partition(std::uint32_t begin, std::uint32_t end, int axis, double lo, double scale, int best_bin,
                          Aabb& left, Aabb& right) {
    PrimRef* first = refs_.data() + begin;
    PrimRef* last = refs_.data() + end;
    const auto goes_left = [&](const PrimRef& r) { return bin_of(centroid_of(r, axis), lo, scale) <= best_bin; };
    for (;;) {
      for (;;) {
        if (first == last) return static_cast<std::uint32_t>(first - refs_.data());
        if (!goes_left(*first)) break;
        left.grow(centroid_of(*first));
        ++first;
      }
      right.grow(centroid_of(*first));  // it ends on the right, swapped or where the scans meet
      --last;
      for (;;) {
        if (first == last) return static_cast<std::uint32_t>(first - refs_.data());
        if (goes_left(*last)) break;
        right.grow(centroid_of(*last));
        --last;
      }
      left.grow(centroid_of(*last));
      std::swap(*first, *last);
      ++first;
    }
  }

  // Appends a subtree built in its own array; its inner nodes' child indices move with it.
  static void append(std::vector<BvhNode>& out, const std::vector<BvhNode>& sub) {
    const auto shift = static_cast<std::uint32_t>(out.size());
    out.insert(out.end(), sub.begin(), sub.end());
    for (std::size_t i = shift; i < out.size(); ++i) {
      if (out[i].count == 0) out[i].first += shift;
    }
  }

  std::vector<PrimRef>& refs_;
  std::uint32_t max_leaf_;
};

// Fills refs[begin, end) from the boxes and returns their bounds.
RangeBounds make_refs(std::vector<PrimRef>& refs, std::size_t begin, std::size_t end,
                      const std::function<Aabb(std::size_t)>& box_of) {
  RangeBounds b;
  for (std::size_t i = begin; i < end; ++i) {
    refs[i] = PrimRef{box_of(i), static_cast<std::uint32_t>(i)};
    b.box.grow(refs[i].box);
    b.centroids.grow(centroid_of(refs[i]));
  }
  return b;
}

}  // namespace

Bvh build_bvh(const std::vector<Aabb>& boxes, int max_leaf) {
  return build_bvh(boxes.size(), [&](std::size_t i) { return boxes[i]; }, max_leaf);
}

Bvh build_bvh(std::size_t count, const std::function<Aabb(std::size_t)>& box_of, int max_leaf) {
  Bvh bvh;
  if (count == 0) return bvh;
  std::vector<PrimRef> refs(count);
  RangeBounds bounds;
  if (count >= kParallelMinPrims) {
    RangeBounds upper;
    in_parallel([&] { upper = make_refs(refs, count / 2, count, box_of); },
                [&] { bounds = make_refs(refs, 0, count / 2, box_of); });
    bounds.grow(upper);
  } else {
    bounds = make_refs(refs, 0, count, box_of);
  }
  bvh.nodes.reserve(2 * count - 1);  // the most a binary tree over `count` leaves can have
  Builder builder(refs, std::max(1, max_leaf));
  bvh.depth = builder.build(bvh.nodes, 0, static_cast<std::uint32_t>(count), bounds, 0);
  bvh.nodes.shrink_to_fit();
  bvh.order.resize(count);
  for (std::size_t i = 0; i < count; ++i) bvh.order[i] = refs[i].index;
  return bvh;
}

}  // namespace phonglab
