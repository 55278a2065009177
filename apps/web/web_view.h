// The web page's view of one session (bound to JavaScript in web_main.cpp): the document, its
// edits and undo are the session's (src/session); the image is the core's render_pass, coarse
// to fine (1/8, 1/4, 1/2, full resolution, then more samples), one pass per step(), on the page's
// thread and, in the threaded module, its helpers (the image the same bits for any count). An
// edit that changes no ray is re-shaded from the first sample's ray trees at full resolution, as
// on the desktop (core/render/ray_trees.h): while the hand is on, a linear edit's image is
// recombined from the trees' sums, and the exact re-shade replaces it when the hand stops; a lesson is the session's LessonPresenter, its views applied here as the desktop's
// LessonShell applies them (web_lesson.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <emscripten/val.h>

#include "core/accel/prepared_scene.h"
#include "core/render/progressive.h"
#include "core/render/render.h"
#include "core/teaching/lesson.h"
#include "check/check.h"
#include "session/session.h"
#include "session/snapshot_a.h"

namespace phonglab {

class WebView {
 public:
  WebView() : session_("") {}

  // The document: an embedded scene's name or a file in the page's memory file system (an
  // upload): "" or the positioned errors, the last good scene kept.
  std::string open(const std::string& scene_arg);
  std::string scene_json() const;
  std::string source() const { return session_.document().source(); }
  // What the scene list shows for the document: an embedded scene's name, a file's name, or the
  // scene a lesson's step showed (also after the lesson is left).
  std::string scene_label() const;
  // What the image shows, for the panel's buttons: 0..5 the full image or a term, -2 the small
  // multiples, -3 the heat map, -1 another view (a lesson's indirect term).
  int view_term() const;

  void set_size(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  // The samples the image goes to; fewer than it has already: the image starts again (the 1 spp
  // switch shows the pixel centres, what a student's own tracer computes first).
  void set_target(int spp);
  int target() const { return target_; }
  void set_term(int term);            // 0..5: the full image, then the five terms
  // The heat map: rays per pixel on the core's perceptual ramp, 0 to the image's maximum
  // (heat_max(): the scale's top), what `phonglab-cli render --term rays` writes; off: the full image.
  void set_heat_map(bool on);
  double heat_max() const { return heat_max_; }
  void set_head_angle(double degrees);  // "move your head" (0: off)
  // While the hand is on, each edit's image is one pass at the desktop's live level (the finest
  // whose measured pass fits a 24th of a second); when it lets go, finer levels follow.
  void set_interacting(bool on);
  // Threads a pass runs on: 1 in the page's one-thread module; in the threaded one, at most the
  // workers started with it (the page passes navigator.hardwareConcurrency).
  void set_threads(int threads) { threads_ = std::clamp(threads, 1, 64); }
  int threads() const { return threads_; }

  // The student's formulas (docs/formulas.md), the session's with its undo: slot 0 ambient, 1
  // diffuse, 2 specular. Returns the text's positioned error ("" when it compiles; with an
  // error the last good formula keeps rendering).
  std::string set_formula(int slot, const std::string& text);
  std::string formula_text(int slot) const;
  std::string formula_error(int slot) const;
  // The formulas' own file (docs/formulas.md): the session's texts as the file's text, and a
  // file's text opened as one undo step ("" , or its first error, positioned: nothing changes).
  std::string formulas_file_text() const;
  std::string open_formulas(const std::string& text, const std::string& name);
  // What the image shows: 0 yours (with the formulas), 1 the reference (the equation's terms).
  void set_formula_view(int view);
  // The formulas checked against the reference at a reduced size (at most 320 wide, the view's
  // aspect; a second or less on one core): the verdict as JSON (check's --json keys and a
  // `summary` in words), or "" with no formula.
  std::string check_formulas_json();
  // A student's own image of the view (a file in the page's memory file system, from the
  // chooser): refused unless it has the image's size (both sizes named); checked against the
  // reference at the view's camera and size, A of the compare. The verdict as JSON (keys of
  // check --json, `summary`, or `error`).
  std::string check_image_json(const std::string& path);
  void close_image();
  // What the image shows with a student's image checked: 0 the live render, 1 the student's
  // image, 2 the check's difference (orange brighter, blue darker, magenta NaN).
  void set_check_view(int view);

  // One pass: true when it made a new image (false: the target is reached).
  bool step();
  int image_width() const { return shown_width_; }
  int image_height() const { return shown_height_; }
  int spp() const { return static_cast<int>(shown_spp_); }
  int divisor() const { return shown_divisor_; }
  bool quads() const { return shown_quads_; }        // the image is the quad-shaded live rung (divisor 1)
  bool live() const { return passes_.live_shown(); }        // the image is a linear edit's recombination
  bool reshaded() const { return passes_.reshaded(); }      // this generation's first sample was re-shaded
  int generation() const { return generation_; }             // restarts so far
  int shown_generation() const { return shown_generation_; }  // the one the image belongs to
  emscripten::val pixels() const;  // RGBA, image_width() x image_height()
  int images() const { return images_; }  // images encoded so far: a new one to draw when it moves

  // Navigation, as on the desktop: a drag orbits about look_at, the wheel dollies, a shift-drag
  // (or the middle button) pans.
  void orbit(double dx_px, double dy_px);  // never under the scene's floor (ui::orbit_in)
  void reset_camera();                      // the camera the document was read with (the key R)
  void dolly(double steps);
  void pan(double dx_px, double dy_px);
  // The point lights' markers: JSON [[x, y] or null (behind the camera or not a point light), ...]
  // in the image's pixels. A marker dragged moves its light in the view plane at the depth it
  // had when grabbed (light_depth), one undo step for the drag (held until set_interacting(false)).
  std::string light_markers() const;
  double light_depth(int l) const;
  void drag_light(int l, double x_px, double y_px, double depth);
  // The five terms and the full image side by side (the desktop's key M).
  void set_small_multiples(bool on);
  // The A/B compare outside lessons, by the session's rules (SnapshotA, as on the desktop): A is
  // the finished image on screen (asked before it is finished, taken when it is; an edit first
  // drops the request); the view then shows A left of `wipe` (mode 1) or |live - A| x 4 (mode 2,
  // once the live image has A's samples); mode 0 the live image. A stays across edits (that is
  // the point) until another scene or lesson; compare_caption() says what is shown.
  void take_a();
  void set_compare(int mode, double wipe);
  bool has_a() const { return a_.has_image(); }
  std::string compare_caption() const;
  // The image with recursion cut at depth `cut` (0: the scene's own max depth).
  void set_depth_cut(int cut);
  int max_depth() const { return session_.scene().max_depth; }
  int depth_cut() const { return view_.depth_cut.value_or(0); }
  // The ray tree of the probed pixel (a shift-click, or a lesson step's probe with its tree) over
  // the image, as the desktop draws it (core/teaching/ray_tree_view.h): JSON [{kind, depth,
  // light, escapes, blocked, colour, from: [x, y], to: [x, y], end}, ...] in the image's pixels,
  // kind one of primary, seen, blocked, reflection, refraction, N, L, R (H for Blinn-Phong), V;
  // colour the one palette's (segment_srgb8: an L or R towards a blocked light is grey); "[]": none.
  std::string ray_tree() const;
  void set_ray_tree(bool on) { tree_shown_ = on; }
  // The probed pixel (a shift-click's, or a lesson step's while its question is asked too), for the
  // ring that marks it: JSON [x, y] in the image's pixels, or null.
  std::string probed_pixel() const;

  // The material under a point of the image (u, v in [0, 1) from the top-left), -1: none; the
  // equation's numbers there, as `phonglab-cli probe` prints them.
  int material_at(double u, double v) const;
  std::string probe(double u, double v);  // and its ray tree shown (ray_tree())

  int material_count() const { return static_cast<int>(session_.scene().materials.size()); }
  std::string material_name(int m) const;
  double coefficient(int m, const std::string& name) const;  // a colour's largest channel, or n, ior
  void set_coefficient(int m, const std::string& name, double value, bool held);
  int light_count() const { return static_cast<int>(session_.scene().lights.size()); }
  double light_intensity(int l) const;  // the largest channel
  void set_light_intensity(int l, double value, bool held);
  bool undo();
  bool redo();

  // Lessons (web_lesson.cpp): an embedded lesson's name, "" or its errors; the presenter's keys;
  // where it stands as JSON (title, step, steps, caption, question, revealed, exploring).
  std::string open_lesson(const std::string& name);
  bool lesson_next();
  bool lesson_prev();
  bool lesson_show(int step);
  void close_lesson();
  std::string lesson_state() const;
  bool lesson_hint();  // the exercise's next hint (lesson_state's "hints"); false when none is left
  std::string view_probe() const { return view_probe_; }  // the step's probed pixel's numbers

  // The speed: `frames` passes of the document at the page's size, 1 spp each on threads(),
  // the full image as the desktop's scalar renderer traces it; JSON: the passes' times (ms) and
  // the rays of one.
  std::string bench(int frames) const;

 private:
  void apply(const Edit& e);
  void edited_by_hand();
  void restart();
  ProgressiveSettings settings() const;  // the generation's, from the view
  int trace_width() const;   // the traced image's size at full resolution: one cell in the small multiples
  int trace_height() const;
  void begin_generation();  // the view's scene prepared, and how its first sample is made
  // The indirect light beside ka·Ia, or their gap: the indirect term traced with the term images.
  bool ambient_pair() const {
    return !view_.small_multiples && view_.ambient == Ambient::kIndirect && view_.ambient_shown != AmbientShown::kImage;
  }
  Term pass_term() const { return view_.small_multiples ? Term::kFull : ambient_pair() ? Term::kIndirect : view_.term; }
  PixelProbe probe_at(double u, double v) const;
  void encode();
  std::vector<glm::vec3> live_pixels() const;
  void present(const LessonPresenter::Show& show);
  void adopt_step(int index);  // the document takes a lesson step's scene
  void apply_view(const StepView& view);
  void update_lesson();
  bool finished() const;  // the image on screen is the view's, at full resolution and its target
  int target_spp() const;  // the samples the image goes to (a lesson's difference: A's)
  bool constant_ambient() const { return ambient_for(pass_term(), view_.ambient) != Ambient::kIndirect; }

  Session session_;
  std::shared_ptr<const PreparedScene> prepared_;
  std::vector<unsigned char> rgba_;
  int width_ = 640, height_ = 360, target_ = 16, threads_ = 1;
  int formula_view_ = 0;  // 0: yours (the formulas traced), 1: the reference
  std::optional<CheckResult> image_check_;  // a student's image, checked
  int check_view_ = 0;
  std::optional<std::vector<glm::vec3>> check_view_pixels() const;
  int shown_width_ = 0, shown_height_ = 0, shown_divisor_ = 8;
  bool shown_quads_ = false;
  std::uint32_t shown_spp_ = 0;
  int generation_ = 0, shown_generation_ = -1, images_ = 0;
  bool interacting_ = false;
  PassScheduler passes_;  // the generation's passes, as the desktop's render thread has them
  StepView view_;                      // what the image shows (the term keys, a lesson's step)
  std::string step_scene_;             // the scene a lesson's step adopted (scene_label), "" for a file or an embedded scene
  std::optional<Vec3> eye_;            // "move your head"'s eye, from view_ at each restart
  ProgressiveFrame shown_;              // the image on screen before a compare or the heat map
  SnapshotA a_;                         // A of a compare (a lesson's: its first full image)
  std::string view_probe_;
  std::optional<std::array<int, 2>> tree_pixel_;  // the probed pixel of the image, for its ray tree
  std::optional<std::array<int, 2>> probe_pixel_;  // the probed pixel (a shift-click, a lesson step's), for its ring
  bool tree_shown_ = true;
  double heat_max_ = 0;
};

}  // namespace phonglab
