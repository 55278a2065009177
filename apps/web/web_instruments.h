// What the page's image shows and the instruments over it: the term, the heat map, "move your
// head", the small multiples, the depth cut, the A/B compare, the probe and its ray tree. A change
// made by hand leaves a lesson's step as written (exploring) and restarts the image.
#pragma once

#include <string>

#include "apps/web/page_state.h"

namespace phonglab {

class WebLesson;

class WebInstruments {
 public:
  WebInstruments(PageState& state, PageImage& image, WebLesson& lesson) : s_(state), image_(image), lesson_(lesson) {}
  WebInstruments(const WebInstruments&) = delete;
  WebInstruments& operator=(const WebInstruments&) = delete;

  // What the image shows, for the panel's buttons: 0..5 the full image or a term, -2 the small
  // multiples, -3 the heat map, -1 another view (a lesson's indirect term).
  int view_term() const;
  void set_term(int term);  // 0..5: the full image, then the five terms
  // The heat map: rays per pixel on the core's perceptual ramp, 0 to the image's maximum (the
  // scale's top), what `phonglab-cli render --term rays` writes; off: the full image.
  void set_heat_map(bool on);
  void set_head_angle(double degrees);  // "move your head" (0: off)
  // The five terms and the full image side by side (the desktop's key M).
  void set_small_multiples(bool on);
  // The image with recursion cut at depth `cut` (0: the scene's own max depth).
  void set_depth_cut(int cut);
  int max_depth() const { return s_.session.scene().max_depth; }
  int depth_cut() const { return s_.view.depth_cut.value_or(0); }

  // The A/B compare outside lessons, by the session's rules (SnapshotA, as on the desktop): A is
  // the finished image on screen (asked before it is finished, taken when it is; an edit first
  // drops the request); the view then shows A left of `wipe` (mode 1) or |live - A| x 4 (mode 2,
  // once the live image has A's samples); mode 0 the live image. A stays across edits (that is
  // the point) until another scene or lesson; compare_caption() says what is shown.
  void take_a();
  void set_compare(int mode, double wipe);
  bool has_a() const { return s_.a.has_image(); }
  std::string compare_caption() const;

  // The ray tree of the probed pixel (a shift-click, or a lesson step's probe with its tree) over
  // the image, as the desktop draws it (core/teaching/ray_tree_view.h): JSON [{kind, depth,
  // light, escapes, blocked, colour, from: [x, y], to: [x, y], end}, ...] in the image's pixels,
  // kind one of primary, seen, blocked, reflection, refraction, N, L, R (H for Blinn-Phong), V;
  // colour the one palette's (segment_srgb8: an L or R towards a blocked light is grey); "[]": none.
  std::string ray_tree() const;
  void set_ray_tree(bool on) { s_.tree_shown = on; }
  // The probed pixel (a shift-click's, or a lesson step's while its question is asked too), for the
  // ring that marks it: JSON [x, y] in the image's pixels, or null.
  std::string probed_pixel() const;
  // The material under a point of the image (u, v in [0, 1) from the top-left), -1: none; the
  // equation's numbers there, as `phonglab-cli probe` prints them.
  int material_at(double u, double v) const;
  std::string probe(double u, double v);  // and its ray tree shown (ray_tree())

 private:
  PixelProbe probe_at(double u, double v) const;

  PageState& s_;
  PageImage& image_;
  WebLesson& lesson_;
};

}  // namespace phonglab
