#include "core/teaching/lesson.h"

#include <algorithm>
#include <cmath>

#include "core/scene/camera.h"
#include "core/teaching/ray_tree_view.h"

namespace phonglab {

LessonPlace lesson_next(const Lesson& lesson, LessonPlace place) {
  const int last = static_cast<int>(lesson.steps.size()) - 1;
  if (last < 0) return {};
  place.step = std::clamp(place.step, 0, last);
  if (!place.revealed && lesson.steps[static_cast<std::size_t>(place.step)].has_question()) return {place.step, true};
  if (place.step == last) return place;
  return {place.step + 1, false};
}

LessonPlace lesson_prev(const Lesson& lesson, LessonPlace place) {
  const int last = static_cast<int>(lesson.steps.size()) - 1;
  if (last < 0) return {};
  place.step = std::clamp(place.step, 0, last);
  if (place.revealed) return {place.step, false};
  return {std::max(0, place.step - 1), false};
}

const StepView& view_at(const LessonStep& step, bool revealed) {
  return revealed && step.has_question() ? step.answer_view : step.view;
}

const std::string& caption_at(const LessonStep& step, bool revealed) {
  return revealed && step.has_question() ? step.answer : step.caption;
}

Scene view_scene(const Scene& scene, const StepView& view) {
  Scene s = scene;
  apply_depth_cut(s, view.depth_cut);
  return s;
}

std::optional<std::array<int, 2>> probe_in(const Scene& scene, const Camera& shown, const StepView& view, int width,
                                           int height) {
  if (!view.probe || width < 1 || height < 1) return std::nullopt;
  // The step's pixel centre seen from the step's camera in the scene's own image, then found in
  // the shown image: the same eye, so the point along that ray projects where the hit does.
  const CameraFrame step = make_camera_frame(scene.camera, std::max(scene.width, 1), std::max(scene.height, 1));
  const Ray ray = camera_ray(step, (*view.probe)[0], (*view.probe)[1], 0.5, 0.5);
  const std::optional<ImagePoint> at = project_point(make_camera_frame(shown, width, height), ray.origin + ray.dir);
  if (!at || !std::isfinite(at->x) || !std::isfinite(at->y)) return std::nullopt;
  const auto pixel = [](double p, int size) { return static_cast<int>(std::clamp(std::floor(p), 0.0, size - 1.0)); };
  return std::array<int, 2>{pixel(at->x, width), pixel(at->y, height)};
}

std::optional<Vec3> view_shading_eye(const PreparedScene& prepared, const StepView& view, int width, int height) {
  if (!view.head_angle_deg) return std::nullopt;
  const Scene& scene = prepared.scene();
  Vec3 pivot = scene.camera.look_at;
  if (const auto pixel = probe_in(scene, scene.camera, view, width, height)) {
    const PixelProbe probe = probe_pixel(prepared, width, height, (*pixel)[0], (*pixel)[1]);
    if (probe.root.hit) pivot = probe.root.p;
  }
  return head_eye(scene.camera, pivot, *view.head_angle_deg);
}

CompareSource compare_source(const Lesson& lesson, int step, const StepView& view) {
  const int n = static_cast<int>(lesson.steps.size());
  if (view.compare_against >= 0 && view.compare_against < n) {
    StepView v = lesson.steps[static_cast<std::size_t>(view.compare_against)].view;
    v.compare = CompareView::kNone;
    return {view.compare_against, v};
  }
  StepView v = view;
  v.compare = CompareView::kNone;
  v.head_angle_deg.reset();
  return {step, v};
}

}  // namespace phonglab
