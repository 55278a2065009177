// The web page's shared state, as one plain struct: the session (the document, its edits and undo,
// the formulas, the lesson's presenter), what the view shows (a lesson step's StepView, or the
// panel's term and instruments), the image's size, target and threads, snapshot A, the probed
// pixel and a student's image checked. The parts of the page's binding (WebScene, WebInstruments,
// WebFormulas, WebLesson, and WebView, which renders) each read and write it and reach the
// renderer only through PageImage.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "check/check.h"
#include "core/accel/prepared_scene.h"
#include "core/render/progressive.h"
#include "core/teaching/lesson.h"
#include "session/session.h"
#include "session/snapshot_a.h"

namespace phonglab {

struct PageState {
  Session session{""};
  StepView view;                       // what the image shows (the term keys, a lesson's step)
  int width = 640, height = 360;       // the image's size
  int target = 16;                     // the samples it goes to
  int threads = 1;
  bool interacting = false;            // the hand is on
  int generation = 0;                  // restarts so far
  // The view's scene prepared for the generation (null: the next step prepares it), and "move
  // your head"'s eye of it.
  std::shared_ptr<const PreparedScene> prepared;
  std::optional<Vec3> eye;
  ProgressiveFrame shown;              // the image on screen before a compare or the heat map
  SnapshotA a;                         // A of a compare (a lesson's: its first full image)
  std::string step_scene;              // the scene a lesson's step adopted (scene_label), "" for a file or an embedded scene
  std::string view_probe;              // the lesson step's probed pixel's numbers
  std::optional<std::array<int, 2>> tree_pixel;   // the probed pixel of the image, for its ray tree
  std::optional<std::array<int, 2>> probe_pixel;  // the probed pixel (a shift-click, a lesson step's), for its ring
  bool tree_shown = true;
  int formula_view = 0;                     // 0: yours (the formulas traced), 1: the reference
  std::optional<CheckResult> image_check;   // a student's image, checked
  int check_view = 0;                       // 0 the live render, 1 the student's image, 2 the difference
};

// What the parts of the binding ask of the page's renderer (WebView).
class PageImage {
 public:
  virtual ~PageImage() = default;
  virtual void restart() = 0;  // a new generation: the view or the scene changed
  virtual void reshow() = 0;   // the image on screen shown again under the view (a compare, a check's view)
  virtual bool finished() const = 0;  // the image on screen is the view's, at full resolution and its target
  virtual int target_spp() const = 0;  // the samples the image goes to (a lesson's difference: A's)
  virtual bool constant_ambient() const = 0;  // the image shows ka·Ia, not the indirect light
};

}  // namespace phonglab
