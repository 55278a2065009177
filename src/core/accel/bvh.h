// A bounding volume hierarchy over axis-aligned boxes: a binned surface-area-heuristic build
// and a conservative (never missing) double-precision traversal. It knows nothing of what the
// boxes hold: callers test the primitives of each leaf themselves.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/scene/math.h"

namespace phonglab {

// Axis-aligned box; empty (lo > hi) when default-constructed.
struct Aabb {
  Vec3 lo{std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity()};
  void grow(const Vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Aabb& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  Vec3 centroid() const { return 0.5 * (lo + hi); }
  // Half the surface area (the SAH only compares areas); 0 for an empty box.
  double half_area() const {
    if (empty()) return 0;
    const Vec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

// Box of a sphere, widened by a few ulps so rounding of c +- r never cuts the sphere off.
Aabb sphere_bounds(const Sphere& s);
// Box of a triangle (exact: its corners are its vertices).
Aabb triangle_bounds(const Triangle& t);

struct BvhNode {
  Aabb box;
  std::uint32_t first = 0;  // leaf: first slot in Bvh::order; inner: index of the second child
  std::uint32_t count = 0;  // leaf: number of primitives; inner: 0 (first child is the next node)
  std::uint32_t axis = 0;   // inner: split axis; the child below the split comes first
};

struct Bvh {
  std::vector<BvhNode> nodes;        // depth-first; nodes[0] is the root (absent when empty)
  std::vector<std::uint32_t> order;  // primitive index held by each leaf slot
  int depth = 0;                     // longest root-to-leaf path, in nodes
};

// Binned SAH build (16 bins per axis over the centroids' extent). Leaves hold at most
// `max_leaf` primitives, fewer when the SAH finds a split cheaper than testing them all.
Bvh build_bvh(const std::vector<Aabb>& boxes, int max_leaf = 4);
// The same over `count` boxes given one at a time, so no array of them sits beside the build's
// own. `box_of` is called from two threads at once (for 2^16 boxes and more).
Bvh build_bvh(std::size_t count, const std::function<Aabb(std::size_t)>& box_of, int max_leaf = 4);

// A ray prepared for box tests: reciprocal direction (+-inf for a zero component). A component
// is negative by its sign bit, so that -0 (whose reciprocal is -inf) crosses slabs from above.
struct BoxRay {
  Vec3 origin;
  Vec3 inv_dir;
  bool negative[3];
  explicit BoxRay(const Ray& ray)
      : origin(ray.origin), inv_dir(1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z),
        negative{std::signbit(ray.dir.x), std::signbit(ray.dir.y), std::signbit(ray.dir.z)} {}
};

// Whether the ray meets the box within (0, t_max]. Conservative: the far distance is widened
// by 2 gamma(3) (pbrt-v4 section 6.8) so rounding never rejects a box the ray touches, and a
// NaN slab (0 * inf, origin on a slab plane with a zero direction component) constrains nothing.
// t_max is widened too: a primitive's computed t (rounded in its own test) may lie a few ulps
// before the computed entry of a box that holds it, and such a box must still be visited for the
// answer to equal brute force's (2^-32 covers tens of ulps and changes no visit in practice).
inline constexpr double kBoxFarWiden = 1 + 2 * (3 * 0x1p-53) / (1 - 3 * 0x1p-53);
inline constexpr double kBoxTmaxSlack = 1 + 0x1p-32;
inline bool hits_box(const Aabb& box, const BoxRay& r, double t_max) {
  double t0 = 0;
  double t1 = t_max * kBoxTmaxSlack;
  for (int a = 0; a < 3; ++a) {
    const double near_plane = r.negative[a] ? box.hi[a] : box.lo[a];
    const double far_plane = r.negative[a] ? box.lo[a] : box.hi[a];
    const double tn = (near_plane - r.origin[a]) * r.inv_dir[a];
    const double tf = (far_plane - r.origin[a]) * r.inv_dir[a] * kBoxFarWiden;
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
  }
  return t0 <= t1;
}

// Visits the leaves whose boxes the ray meets within (0, t_max], nearer side first.
// `leaf(first, count)` tests the primitives of order[first .. first+count) and returns true to
// stop (any-hit queries); it may lower t_max (nearest-hit queries), which prunes what follows.
template <class LeafFn>
void traverse(const Bvh& bvh, const BoxRay& ray, const double& t_max, LeafFn&& leaf) {
  if (bvh.nodes.empty()) return;
  std::uint32_t stack[128];
  int top = 0;
  std::uint32_t index = 0;
  for (;;) {
    const BvhNode& node = bvh.nodes[index];
    if (hits_box(node.box, ray, t_max)) {
      if (node.count > 0) {
        if (leaf(node.first, node.count)) return;
      } else {
        // Near child first: the one below the split when the ray travels up the axis.
        const bool flip = ray.negative[node.axis];
        stack[top++] = flip ? index + 1 : node.first;
        index = flip ? node.first : index + 1;
        continue;
      }
    }
    if (top == 0) return;
    index = stack[--top];
  }
}

}  // namespace phonglab
