#include "session/render_schedule.h"

#include "core/teaching/ray_tree_view.h"

#include <utility>

namespace phonglab {

bool RenderSchedule::offer_eye(const std::optional<Vec3>& eye, bool holding) {
  if (eye == eye_ || (holding && image_pending())) return false;
  eye_ = eye;
  return true;
}

std::uint64_t RenderSchedule::send_settings(ProgressiveSettings settings, bool small_multiples) {
  settings.shading_eye = eye_;
  multiples_sent_ = small_multiples;
  target_spp_sent_ = settings.target_spp;
  const std::uint64_t before = renderer_.status().generation;
  const std::uint64_t generation = renderer_.set_settings(settings);
  if (generation == before) return 0;
  sent_generation_ = generation;
  return generation;
}

RenderSchedule::Sent RenderSchedule::send_scene(const Frame& frame, const Scene& scene, std::uint64_t version) {
  const bool edited = frame.edited || !snapshot_ || version != sent_version_;
  if (edited && !deferred_) deferred_since_ = frame.now;
  const bool scene_changed = edited || deferred_;
  const bool resized = frame.width != width_ || frame.height != height_;
  Sent sent;
  sent.deferred = scene_changed && frame.dragging && !resized && !frame.replaced && image_pending() &&
                  frame.now - deferred_since_ < kMaxDeferral;
  deferred_ = sent.deferred;
  if (!((scene_changed && !sent.deferred) || resized)) return sent;
  if (scene_changed) {
    Scene shown = scene;
    if (frame.camera) shown.camera = *frame.camera;
    apply_depth_cut(shown, frame.depth_cut);
    snapshot_ = rules_.any() ? std::make_shared<const PreparedScene>(std::move(shown), PreparedScene::AccelFactory{},
                                                                     make_rules_experiment(rules_))
                             : std::make_shared<const PreparedScene>(std::move(shown));
    sent_version_ = version;
    sent.scene = true;
    sent.edit_time = deferred_since_;
  }
  width_ = frame.width;
  height_ = frame.height;
  // One restart per UI frame, however many edits it gathered.
  sent.generation = sent_generation_ = renderer_.set_scene(snapshot_, width_, height_);
  sent.restarted = true;
  return sent;
}

}  // namespace phonglab
