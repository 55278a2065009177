// A lesson: the lecture as an ordered list of steps, each a scene (with the step's changes
// already applied) and what is shown of it, with an optional question whose answer a key press
// reveals. Plain data, read from lesson files by src/io/lesson_io.h; the rules here turn a
// step's view into the renderer's inputs, the same for the previewer and the handouts.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/render/render.h"
#include "core/scene/scene.h"
#include "core/teaching/compare.h"

namespace phonglab {

// What a step shows of its scene.
// What a view under the indirect light shows: the image itself, the indirect term beside ka·Iₐ
// (a wipe, A = ka·Iₐ), or their signed gap on a diverging heat map (ambient_gap_pixels).
enum class AmbientShown : std::uint8_t { kImage, kBeside, kDifference };

struct StepView {
  Term term = Term::kFull;                  // the full image or one term of the equation
  bool small_multiples = false;             // the five terms and their sum side by side
  std::optional<std::array<int, 2>> probe;  // a probed pixel of the scene's image (width x height)
  bool ray_tree = false;                    // the probed pixel's ray tree over the image
  std::optional<int> depth_cut;             // the image with recursion cut at this depth
  std::optional<double> head_angle_deg;     // "move your head": the eye turned by this angle
  bool light_markers = true;                // false: where the lights are is not shown
  CompareView compare = CompareView::kNone; // against snapshot A, taken of `compare_against`
  int compare_against = -1;                 // A: that step (0-based); -1: this step, the head not moved
  double wipe = 0.5;                        // kWipe: the fraction of the width showing A
  double difference_gain = 4;               // kDifference: |live - A| is scaled by this
  Ambient ambient = Ambient::kConstant;     // ka·Ia, or the indirect light it stands in for
  AmbientShown ambient_shown = AmbientShown::kImage;  // with kIndirect: the image, beside ka·Ia, or the gap
  bool operator==(const StepView&) const = default;
};

// A step of kind "exercise": the student writes one term of the equation as a formula
// (docs/formulas.md) and the step says when it matches the reference. The slot's name is
// checked by the lesson reader ("ambient", "diffuse" or "specular").
struct LessonExercise {
  std::string slot;
  std::string task;                // what to write, for the student
  std::string starter;             // the slot's text when the step is first shown ("" : empty)
  std::vector<std::string> hints;  // offered one by one
};

struct LessonStep {
  std::string title;
  std::string caption;   // a few sentences, with the equation or its part
  std::string scene;     // as the lesson names it: an embedded scene or a file
  Scene prepared_scene;  // that scene with the step's changes, muted and soloed lights applied
  StepView view;
  std::string question;  // empty: none; else posed first, and the next key press reveals...
  std::string answer;    // ... this caption
  StepView answer_view;  // ... and this view (the step's view with the answer's changes)
  std::optional<LessonExercise> exercise;  // a step of kind "exercise" (never with a question)
  bool has_question() const { return !question.empty(); }
};

struct Lesson {
  std::string name;         // the embedded lesson's name, or the file's stem
  std::string title;
  std::string description;  // one line: what the lesson teaches
  std::vector<LessonStep> steps;
};

// Where a step stands while it is presented: its index and whether its answer is shown.
struct LessonPlace {
  int step = 0;
  bool revealed = false;
  bool operator==(const LessonPlace&) const = default;
};
// The next place: a posed question's answer first, then the next step (the last stays).
LessonPlace lesson_next(const Lesson& lesson, LessonPlace place);
// The previous place: back from an answer to its question, else to the previous step (posed).
LessonPlace lesson_prev(const Lesson& lesson, LessonPlace place);
// What is shown at a place: the answer's view once revealed.
const StepView& view_at(const LessonStep& step, bool revealed);
const std::string& caption_at(const LessonStep& step, bool revealed);

// The scene rendered for a view: the step's scene with its depth cut applied.
Scene view_scene(const Scene& scene, const StepView& view);
// The probed pixel of `view` in an image of width x height seen through `shown` (the scene's
// camera, or the previewer's fitted to a view of another shape, from the same eye): the pixel
// that sees what the step's pixel sees in the scene's own image (scene.width x scene.height
// through scene.camera). nullopt without a probe, or when it is not in front of `shown`.
std::optional<std::array<int, 2>> probe_in(const Scene& scene, const Camera& shown, const StepView& view, int width,
                                           int height);
// "Move your head": the eye that shades a view, turned about the probed hit (the look-at point
// when nothing is probed or the probe meets nothing); nullopt when the head is not moved.
std::optional<Vec3> view_shading_eye(const PreparedScene& prepared, const StepView& view, int width, int height);
// The view snapshot A is taken of: step `compare_against`'s, or this one with the head not moved.
struct CompareSource {
  int step = 0;
  StepView view;
};
CompareSource compare_source(const Lesson& lesson, int step, const StepView& view);

}  // namespace phonglab
