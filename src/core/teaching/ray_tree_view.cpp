#include "core/teaching/ray_tree_view.h"

#include <algorithm>
#include <cmath>

namespace phonglab {

namespace {

// The length the open-ended parts scale with: the primary hit's distance from the camera,
// else (a miss) the distance to the look-at point.
double reference_length(const Scene& scene, const ProbeNode& root) {
  if (root.hit && root.t > 0) return root.t;
  const double d = glm::length(scene.camera.look_at - scene.camera.position);
  return d > 0 ? d : 1;
}

struct Builder {
  const RayTreeViewOptions& options;
  double reference;
  std::vector<TreeSegment> out;

  void add(TreeSegmentKind kind, int depth, const Vec3& from, const Vec3& to, bool escapes = false, int light = -1) {
    TreeSegment s;
    s.kind = kind;
    s.depth = depth;
    s.from = from;
    s.to = to;
    s.escapes = escapes;
    s.light = light;
    out.push_back(s);
  }

  // The ray of `node` (kind given by how it was spawned), then what it spawned.
  void ray(const ProbeNode& node, TreeSegmentKind kind) {
    if (node.hit) add(kind, node.depth, node.origin, node.p);
    else add(kind, node.depth, node.origin, node.origin + node.dir * (options.escape_length * reference), true);
    if (!node.hit) return;
    if (options.shadow_rays) {
      for (const ProbeLight& pl : node.lights) {
        if (!pl.lit_side) continue;  // N.L <= 0: no shadow ray was cast
        if (!pl.visible) {
          add(TreeSegmentKind::kShadowBlocked, node.depth, node.p, node.p + pl.l * pl.occluder_distance, false, pl.index);
        } else if (std::isfinite(pl.distance)) {
          add(TreeSegmentKind::kShadowVisible, node.depth, node.p, node.p + pl.l * pl.distance, false, pl.index);
        } else {
          add(TreeSegmentKind::kShadowVisible, node.depth, node.p, node.p + pl.l * (options.directional_length * reference),
              true, pl.index);
        }
      }
    }
    if (!options.secondary_rays) return;
    if (node.reflection) ray(*node.reflection, TreeSegmentKind::kReflection);
    if (node.refraction) ray(*node.refraction, TreeSegmentKind::kRefraction);
  }

  void arrows(const ProbeNode& root) {
    if (!root.hit) return;
    const double length = options.arrow_length * reference;
    add(TreeSegmentKind::kArrowN, 0, root.p, root.p + root.n * length);
    add(TreeSegmentKind::kArrowV, 0, root.p, root.p + root.v * length);
    for (const ProbeLight& pl : root.lights) {
      if (!pl.lit_side) continue;  // R (and the light's part of the equation) only where N.L > 0
      add(TreeSegmentKind::kArrowL, 0, root.p, root.p + pl.l * length, false, pl.index);
      out.back().blocked = !pl.visible;
      const double r_length = glm::length(pl.r);
      if (r_length > 0) {
        add(TreeSegmentKind::kArrowR, 0, root.p, root.p + pl.r / r_length * length, false, pl.index);
        out.back().blocked = !pl.visible;
      }
    }
  }
};

// Liang-Barsky: clips the parameter range [t0, t1] of p + t d to the slab lo <= x <= hi.
bool clip_slab(double p, double d, double lo, double hi, double& t0, double& t1) {
  if (d == 0) return p >= lo && p <= hi;
  double ta = (lo - p) / d;
  double tb = (hi - p) / d;
  if (ta > tb) std::swap(ta, tb);
  t0 = std::max(t0, ta);
  t1 = std::min(t1, tb);
  return t0 <= t1;
}

}  // namespace

std::vector<TreeSegment> ray_tree_segments(const Scene& scene, const ProbeNode& root, const RayTreeViewOptions& options) {
  Builder builder{options, reference_length(scene, root), {}};
  builder.ray(root, TreeSegmentKind::kPrimary);
  if (options.arrows) builder.arrows(root);
  return std::move(builder.out);
}

std::optional<ImagePoint> project_point(const CameraFrame& frame, const Vec3& p) {
  const Vec3 v = p - frame.origin;
  const double z = glm::dot(v, frame.forward);
  if (!(z > 0)) return std::nullopt;
  // camera_ray's direction is F + sx R + sy U (R and U scaled, all three orthogonal), so a
  // point seen along it has v = z (F + sx R + sy U): sx = v.R / (z R.R), likewise sy.
  const double sx = glm::dot(v, frame.right) / (z * glm::dot(frame.right, frame.right));
  const double sy = glm::dot(v, frame.up) / (z * glm::dot(frame.up, frame.up));
  return ImagePoint{(sx + 1) * frame.width / 2, (1 - sy) * frame.height / 2};
}

std::optional<std::array<ImagePoint, 2>> project_segment(const CameraFrame& frame, const Vec3& a, const Vec3& b,
                                                         double near) {
  // Near plane first: a ray may pass behind the camera, where projection flips it.
  Vec3 pa = a, pb = b;
  const double za = glm::dot(a - frame.origin, frame.forward);
  const double zb = glm::dot(b - frame.origin, frame.forward);
  if (za < near && zb < near) return std::nullopt;
  if (za < near) pa = a + (b - a) * ((near - za) / (zb - za));
  if (zb < near) pb = a + (b - a) * ((near - za) / (zb - za));
  const std::optional<ImagePoint> qa = project_point(frame, pa);
  const std::optional<ImagePoint> qb = project_point(frame, pb);
  if (!qa || !qb) return std::nullopt;
  // Then the image rectangle.
  const double dx = qb->x - qa->x;
  const double dy = qb->y - qa->y;
  double t0 = 0, t1 = 1;
  if (!clip_slab(qa->x, dx, 0, frame.width, t0, t1) || !clip_slab(qa->y, dy, 0, frame.height, t0, t1)) {
    return std::nullopt;
  }
  // Rounding in the clip may leave a point a few ulps outside: clamp it in.
  const auto inside = [&](double x, double y) {
    return ImagePoint{std::clamp(x, 0.0, static_cast<double>(frame.width)), std::clamp(y, 0.0, static_cast<double>(frame.height))};
  };
  return std::array<ImagePoint, 2>{inside(qa->x + t0 * dx, qa->y + t0 * dy), inside(qa->x + t1 * dx, qa->y + t1 * dy)};
}

std::vector<ScreenSegment> project_ray_tree(const CameraFrame& frame, const std::vector<TreeSegment>& segments,
                                            double near) {
  std::vector<ScreenSegment> out;
  out.reserve(segments.size());
  for (const TreeSegment& s : segments) {
    const auto ends = project_segment(frame, s.from, s.to, near);
    if (!ends) continue;
    ScreenSegment screen;
    screen.kind = s.kind;
    screen.depth = s.depth;
    screen.light = s.light;
    screen.escapes = s.escapes;
    screen.blocked = s.blocked;
    screen.from = (*ends)[0];
    screen.to = (*ends)[1];
    // The real end is on screen when it lies in front of the near plane and inside the image
    // (the clip then kept it); take its projection exactly rather than the clip's re-computation.
    const double z_end = glm::dot(s.to - frame.origin, frame.forward);
    const auto end = z_end >= near ? project_point(frame, s.to) : std::nullopt;
    screen.to_visible = !s.escapes && end && end->x >= 0 && end->x <= frame.width && end->y >= 0 && end->y <= frame.height;
    if (screen.to_visible) screen.to = *end;
    out.push_back(screen);
  }
  return out;
}

double ray_tree_near(const Scene& scene, const ProbeNode& root) { return 1e-3 * reference_length(scene, root); }

int cut_max_depth(int scene_max_depth, std::optional<int> cut) {
  return cut ? std::min(scene_max_depth, std::max(*cut, 0)) : scene_max_depth;
}

void apply_depth_cut(Scene& scene, std::optional<int> cut) { scene.max_depth = cut_max_depth(scene.max_depth, cut); }

std::array<std::uint8_t, 3> segment_srgb8(TreeSegmentKind kind, int depth, bool blocked) {
  using Rgb = std::array<std::uint8_t, 3>;
  static constexpr std::array<Rgb, 4> kReflection = {Rgb{0, 230, 255}, Rgb{60, 140, 255}, Rgb{140, 100, 255}, Rgb{210, 90, 255}};
  static constexpr std::array<Rgb, 4> kRefraction = {Rgb{70, 255, 110}, Rgb{190, 255, 50}, Rgb{0, 185, 110}, Rgb{150, 210, 140}};
  static constexpr Rgb kBlocked{255, 55, 45};
  static constexpr Rgb kUnlit{150, 150, 150};  // L, R towards a light that does not reach the point
  const auto bounce = static_cast<std::size_t>(std::clamp(depth, 1, 4) - 1);
  switch (kind) {
    case TreeSegmentKind::kPrimary: return {245, 245, 245};
    case TreeSegmentKind::kShadowVisible: return {255, 220, 40};
    case TreeSegmentKind::kShadowBlocked: return kBlocked;
    case TreeSegmentKind::kReflection: return kReflection[bounce];
    case TreeSegmentKind::kRefraction: return kRefraction[bounce];
    case TreeSegmentKind::kArrowN: return {255, 255, 255};
    case TreeSegmentKind::kArrowL: return blocked ? kUnlit : Rgb{255, 220, 40};
    case TreeSegmentKind::kArrowR: return blocked ? kUnlit : Rgb{255, 80, 220};
    case TreeSegmentKind::kArrowV: return {255, 150, 40};
  }
  return {255, 255, 255};
}

}  // namespace phonglab
