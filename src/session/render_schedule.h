// The renderer's scheduling, without a window: what one UI frame's edits send to the progressive
// renderer. A frame gives at most one restart: a new snapshot of the scene when something in it or
// its view changed, the render size when the window changed, the settings when they differ from
// the last ones sent. During a drag, a new snapshot waits until the renderer has shown the previous
// one (kMaxDeferral at most): restarting every UI frame would cancel each pass before it ends
// whenever a pass takes longer than a frame, and the view would freeze until the hand stops.
// "Move your head"'s eye waits the same way while a slider is held. Unit-tested in
// tests/session/test_render_schedule.cpp.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "core/accel/prepared_scene.h"
#include "check/rules.h"
#include "core/render/progressive.h"
#include "core/scene/scene.h"

namespace phonglab {

class RenderSchedule {
 public:
  static constexpr double kMaxDeferral = 1.0;  // a drag's edit waits at most this long for the renderer, s

  explicit RenderSchedule(ProgressiveRenderer& renderer) : renderer_(renderer) {}

  // The head-moved eye the renderer and the probe shade with. A new one is taken at once, except
  // while the hand holds an edit and the last snapshot's first image is not in: each restart would
  // cancel the re-shade under way, and a cancelled re-shade of a new eye leaves the trees half
  // updated, so every later eye of the drag would be traced, coarse. Returns whether it changed.
  bool offer_eye(const std::optional<Vec3>& eye, bool holding);
  const std::optional<Vec3>& eye() const { return eye_; }

  // Whether the small multiples (term images) or the target spp wanted differ from those last
  // sent: they then go out with the next send_settings.
  bool wants_changed(bool small_multiples, int target_spp) const {
    return small_multiples != multiples_sent_ || target_spp != target_spp_sent_;
  }
  // The settings, made for `small_multiples`, with the eye (settings.shading_eye is set from
  // eye()). Returns the renderer's new generation, or 0 when they were the ones it had.
  std::uint64_t send_settings(ProgressiveSettings settings, bool small_multiples);

  // One UI frame's scene side.
  struct Frame {
    bool edited = false;    // the view changed (the window's camera, the depth cut, the formulas traced)
    bool replaced = false;  // another document: never deferred
    bool dragging = false;  // the hand is on (a drag, a slider held)
    int width = 0;          // the render size, 0 x 0: nothing visible
    int height = 0;
    double now = 0;         // the frame's start, s
    // The view the snapshot is rendered with: its camera (the window's fitting of the scene's;
    // none: the scene's own) and the depth cut, which changes what is rendered, never the scene.
    std::optional<Camera> camera;
    std::optional<int> depth_cut;
  };
  struct Sent {
    bool scene = false;      // a new snapshot went out
    bool restarted = false;  // the renderer restarted (a snapshot or a size)
    bool deferred = false;   // an edit waits for the renderer's current first image
    std::uint64_t generation = 0;
    double edit_time = 0;    // the oldest edit the snapshot carries (latency counts from it)
  };
  // Sends the frame's scene side: a snapshot when none was sent, the view changed or the scene
  // did (its `version`, SceneDocument::version, differs from the last snapshot's): `scene` (the
  // session's) with the frame's view, prepared with the rules.
  Sent send_scene(const Frame& frame, const Scene& scene, std::uint64_t version);
  // The rules the snapshots are traced with (a student's formulas: src/check/rules.h); none:
  // the production renderer. A change counts as an edit of the next frame (frame.edited).
  void set_rules(const LocalRules& rules) { rules_ = rules; }
  const LocalRules& rules() const { return rules_; }

  // The snapshot the renderer has (picking, the probe, figures), its size and generation.
  const std::shared_ptr<const PreparedScene>& snapshot() const { return snapshot_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::uint64_t sent_generation() const { return sent_generation_; }
  // The last generation sent has no image yet.
  bool image_pending() const { return renderer_.status().published_generation < sent_generation_; }

 private:
  ProgressiveRenderer& renderer_;
  std::shared_ptr<const PreparedScene> snapshot_;
  LocalRules rules_;
  int width_ = 0;
  int height_ = 0;
  std::uint64_t sent_generation_ = 0;
  std::uint64_t sent_version_ = 0;  // the scene's version in the last snapshot
  std::optional<Vec3> eye_;
  bool multiples_sent_ = false;
  int target_spp_sent_ = 0;
  bool deferred_ = false;      // an edit waits for the renderer's current first image
  double deferred_since_ = 0;  // the oldest such edit, s
};

}  // namespace phonglab
