// The ray tree overlay's geometry, without any drawing: a probed pixel's ray tree (ProbeNode)
// flattened into world-space segments of known kinds, and their projection into the image
// through the renderer's own camera formula (the inverse of camera_ray), clipped to the near
// plane and to the image rectangle. Also the depth cut: the scene the image "with recursion
// cut at depth d" is rendered from. Pure: the previewer draws the result, the tests check it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/scene/camera.h"
#include "core/scene/scene.h"
#include "core/shading/shading.h"

namespace phonglab {

// What a segment of the overlay stands for.
enum class TreeSegmentKind : std::uint8_t {
  kPrimary,        // camera to the primary hit (or out of the scene)
  kShadowVisible,  // hit point towards a light it sees: to a point light, a fixed length for a directional one
  kShadowBlocked,  // hit point to where the shadow ray meets the occluder
  kReflection,     // a reflected ray (its depth says which bounce)
  kRefraction,     // a refracted ray, or one sent along the mirror direction under total internal reflection
  kArrowN,         // shading normal N at the primary hit
  kArrowL,         // unit vector towards a light, at the primary hit
  kArrowR,         // Phong: R, the mirror of L about N; Blinn-Phong: the half vector H
  kArrowV,         // towards the eye that shades the primary hit (moves with "move your head")
};

// The N, L, R (H) and V arrows at the primary hit, and the letter each is labelled with.
inline bool is_arrow(TreeSegmentKind kind) { return kind >= TreeSegmentKind::kArrowN; }
inline const char* arrow_letter(TreeSegmentKind kind, bool blinn) {
  switch (kind) {
    case TreeSegmentKind::kArrowN: return "N";
    case TreeSegmentKind::kArrowL: return "L";
    case TreeSegmentKind::kArrowR: return blinn ? "H" : "R";
    case TreeSegmentKind::kArrowV: return "V";
    default: return "";
  }
}

// One straight piece of the overlay in world space.
struct TreeSegment {
  TreeSegmentKind kind = TreeSegmentKind::kPrimary;
  int depth = 0;         // the ray's depth (0 primary); shadow rays and arrows: the depth of their hit
  Vec3 from{0}, to{0};   // world units
  bool escapes = false;  // the ray missed everything: `to` is a far point along it
  int light = -1;        // shadow rays and L, R arrows: index into Scene::lights
  bool blocked = false;  // L and R arrows: that light's shadow ray met something (vis = 0)
};

// The one palette of a ray tree, sRGB 8-bit, for the previewer, the page and the handouts: the
// primary ray white, shadow rays yellow (light seen) or red (blocked), reflections cyan to violet
// and refractions green by bounce (depth 1..4+), N white, L yellow, R (H) magenta, V orange; an L
// or R arrow towards a light its shadow ray found blocked is grey (yellow would read "lit"; the
// blocked red is the shadow ray's, which stops at the occluder while the arrow goes on).
std::array<std::uint8_t, 3> segment_srgb8(TreeSegmentKind kind, int depth, bool blocked = false);
inline std::array<std::uint8_t, 3> segment_srgb8(const TreeSegment& s) { return segment_srgb8(s.kind, s.depth, s.blocked); }

// Which parts to build and how long the open-ended ones are.
struct RayTreeViewOptions {
  bool shadow_rays = true;     // one per light on the lit side of each hit
  bool secondary_rays = true;  // reflected and refracted rays, all depths
  bool arrows = true;          // N, V and per lit light L and R at the primary hit
  // Lengths of the open-ended parts, as fractions of the primary hit's distance from the camera
  // (the look-at distance when it misses), so they look the same at any scene scale.
  double arrow_length = 0.15;        // 0.15 of the hit distance: about a fifth of the image height at fov 40
  double directional_length = 0.6;   // shadow rays to directional lights (no end point of their own)
  double escape_length = 1e4;        // rays that miss: far enough to reach the image edge or their vanishing point
};

// The overlay's segments for the ray tree `root` (a PixelProbe's root) of `scene` (the
// snapshot that was probed): the primary ray, then for every hit its shadow rays and its
// reflected and refracted children, depth first; the arrows last.
std::vector<TreeSegment> ray_tree_segments(const Scene& scene, const ProbeNode& root,
                                           const RayTreeViewOptions& options = {});

// A point of the image plane in pixel units: x across from the left edge, y down from the top
// edge. Pixel (x, y) covers [x, x+1) x [y, y+1); its centre is (x + 0.5, y + 0.5).
struct ImagePoint {
  double x = 0;
  double y = 0;
};

// Where the world point `p` appears in the image of `frame`: the inverse of camera_ray, so the
// point at any distance along camera_ray(frame, x, y, u, v) lands on (x + u, y + v). nullopt
// for points on or behind the camera plane.
std::optional<ImagePoint> project_point(const CameraFrame& frame, const Vec3& p);

// The visible part of the world segment a-b: clipped to the half-space at least `near` in
// front of the camera, projected, then clipped to the image rectangle [0, W] x [0, H].
// nullopt when nothing is left.
std::optional<std::array<ImagePoint, 2>> project_segment(const CameraFrame& frame, const Vec3& a, const Vec3& b,
                                                         double near);

// A segment of the overlay in image coordinates.
struct ScreenSegment {
  TreeSegmentKind kind = TreeSegmentKind::kPrimary;
  int depth = 0;
  int light = -1;
  bool escapes = false;
  bool blocked = false;  // as TreeSegment's
  ImagePoint from, to;   // clipped to the image
  bool to_visible = true;  // `to` is the segment's real end (not cut by the near plane or the image edge)
};

// Projects every segment with project_segment; parts wholly hidden are left out. `near` is
// the near-plane distance in world units (a small fraction of the scene's scale).
std::vector<ScreenSegment> project_ray_tree(const CameraFrame& frame, const std::vector<TreeSegment>& segments,
                                            double near);

// The near-plane distance the overlay uses for a tree: a thousandth of its reference length
// (the primary hit distance, else the look-at distance).
double ray_tree_near(const Scene& scene, const ProbeNode& root);

// The recursion limit of the image "cut at depth `cut`": min(scene max_depth, cut); the
// scene's own limit when there is no cut.
int cut_max_depth(int scene_max_depth, std::optional<int> cut);

// Applies the depth cut to a copy of the scene made for display (never to the edited scene:
// the cut is a way of looking at it, not an edit).
void apply_depth_cut(Scene& scene, std::optional<int> cut);

}  // namespace phonglab
