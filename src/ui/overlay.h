// Drawing over the image: text on dark plates, light markers, the probe ring, captions that name
// what is shown, the keys overlay, and the small layout rules that keep them apart. ImGui draw
// lists only; no GL.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <imgui.h>

#include "core/render/render.h"
#include "ui/widgets.h"

namespace phonglab::ui {


// A light drawn in the viewport.
struct LightMarker {
  ImVec2 pos;            // screen position of the marker (the light, or the edge point towards it)
  ImVec2 label_pos;      // top-left of its "L<i>" label, placed clear of everything else
  ImVec4 color;          // its intensity as a display colour
  bool enabled = true;   // a disabled light is drawn hollow and dim
  bool selected = false; // drawn with a highlight ring
  bool hovered = false;  // under the mouse: grab cursor hint
  bool offscreen = false;  // outside the view: drawn as an arrow at the edge, pointing at it
  ImVec2 toward;         // offscreen: unit screen direction from `pos` towards the light
  int index = 0;         // into Scene::lights (the label)
};

// Whether two screen rectangles share any area.
bool overlaps(const ScreenRect& a, const ScreenRect& b);
// The rectangle of `size` placed with its point `pivot` ((0, 0) top-left .. (1, 1) bottom-right,
// as ImGui's SetNextWindowPos takes it) at `anchor`.
ScreenRect rect_at(ImVec2 anchor, ImVec2 pivot, ImVec2 size);
// The width and height of a rectangle.
inline ImVec2 size_of(const ScreenRect& r) { return ImVec2(r.max.x - r.min.x, r.max.y - r.min.y); }

// Radius of a light marker in screen pixels for a UI scale.
inline float light_marker_radius(float ui_scale) { return 7.0f * ui_scale; }

// Markers on the background draw list: over the rendered image, under the panels.
void draw_light_markers(std::span<const LightMarker> markers, float radius, float ui_scale);

// `text` at `at` (top-left) in white on a dark rounded plate, readable on any image; wrapped at
// `wrap_width` pixels when that is positive.
void text_on_plate(ImDrawList* draw, ImVec2 at, const char* text, float ui_scale, float alpha = 0.75f,
                   float wrap_width = 0);

// The probed pixel's mark: a yellow ring with a gap, on a black outline.
void draw_probe_ring(ImDrawList* draw, ImVec2 centre, float ui_scale);

// An edge point of a marker `half` wide, moved along the edge of [lo, hi] until it overlaps none of
// `taken` (or left where it was if no place is free).
ImVec2 slide_clear(ImVec2 pos, float half, const std::vector<ScreenRect>& taken, ImVec2 lo, ImVec2 hi);

// Where a marker's label goes: right, left, below or above it, the first place inside [lo, hi]
// that overlaps none of `taken`.
ImVec2 place_label(const LightMarker& marker, float radius, const std::vector<ScreenRect>& taken, ImVec2 lo, ImVec2 hi);

// The caption of a view: "specular only: I_l ks max(0,R.V)^n", "the full image: I", a debug view.
std::string term_caption(Term term, bool blinn);

// The keys and mouse controls, as a table (the F1 overlay).
void keys_help();

}  // namespace phonglab::ui
