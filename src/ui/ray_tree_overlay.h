// The ray tree overlay, the depth cut and the heat map in the previewer: the panel that
// switches them, the drawing of a probed pixel's ray tree over the view (geometry from
// src/core/teaching/ray_tree_view.h) and the legends. ImGui only: no GL.
#pragma once

#include <optional>
#include <span>
#include <string>

#include <imgui.h>

#include "core/teaching/ray_tree_view.h"
#include "core/render/render.h"

namespace phonglab::ui {

// Previewer state, not part of the scene file.
struct RayTreeSettings {
  bool overlay = true;         // draw the probed pixel's ray tree over the view
  bool shadow_rays = true;     // ... its shadow rays
  bool secondary_rays = true;  // ... its reflected and refracted rays
  bool arrows = true;          // ... N, L, R (H), V at the primary hit
  bool legend = true;          // the colour key beside it
  bool depth_cut = false;      // show the image with recursion cut at `cut_depth`
  int cut_depth = 1;           // 0: local shading only, 1: one bounce, ...
  bool heat_map = false;       // rays per pixel as a heat map (the "rays" view)
};

// The depth cut as RenderOptions-style input: the cut depth, or nullopt when off.
inline std::optional<int> depth_cut_of(const RayTreeSettings& s) {
  return s.depth_cut ? std::optional<int>(s.cut_depth) : std::nullopt;
}

// What the panel reports about the probed tree.
struct RayTreeSummary {
  const PixelProbe* probe = nullptr;  // nullptr: nothing probed yet
  int scene_max_depth = 5;            // the scene's own limit (the cut slider's top)
  double heat_max = 0;                // top of the heat map's scale (rays per pixel)
};

// The depth-cut slider's printf format for a scene's max depth: "%d of 5", or for a scene of depth 0
// "%d: the scene's max depth is 0" (never "1 of 0").
std::string depth_cut_format(int scene_max_depth);

// The overlay's switches, the depth cut and the heat map switch, with what the probed tree
// holds (rays by kind, blocked shadow rays, the deepest ray). Returns "edited".
bool rays_panel(RayTreeSettings& settings, const RayTreeSummary& summary);

// Display colour of a segment kind (reflection and refraction by depth).
ImU32 segment_color(TreeSegmentKind kind, int depth, bool blocked = false);

// Where the image lies on screen: pixel (x, y) of the render covers
// [origin + (x, y) * scale, origin + (x + 1, y + 1) * scale).
struct ImageRect {
  ImVec2 origin;
  ImVec2 scale{1, 1};
};

// Draws the projected tree on `draw`: rays as lines with their end points, blocked shadow
// rays ending in a cross at the occluder, the primary hit as a disc, depth numbers at the
// secondary hits, N, L, R (H when `blinn`), V as labelled arrows (L and R numbered by light
// when `light_count` > 1).
void draw_ray_tree(ImDrawList* draw, std::span<const ScreenSegment> segments, const ImageRect& rect, float ui_scale,
                   bool blinn, int light_count);

// The colour key for the kinds present in `segments` (into the current window).
void ray_tree_legend(std::span<const ScreenSegment> segments, bool blinn);

// The heat map's scale: the ramp from 0 to `max` rays per pixel, `width` pixels wide (into the
// current window).
void heat_legend(double max, float width);
// The signed gap's ramp (AmbientView::kDifference): -scale blue, 0 black, +scale orange, and what
// the colours say.
void ambient_gap_legend(double scale, float width);

}  // namespace phonglab::ui
