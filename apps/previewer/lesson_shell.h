// Presenting a lesson in the previewer: what the session's LessonPresenter answers applied to the
// shell (the step's scene adopted, its view set on the instruments, A taken for a compare), the
// presenter's keys, presenter mode, the Lessons panel and the caption over the image. A class of
// its own beside the shell; it reaches the shell's shared state (ShellState, shell_state.h) and the
// components it works with, given by reference.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/teaching/lesson.h"
#include "session/lesson_presenter.h"

namespace phonglab {

struct ShellState;
class FileShell;
class FormulaShell;
class Instruments;

class LessonShell {
 public:
  // The shell's side of a lesson: where it stands is the session's (LessonPresenter).
  struct LessonState {
    bool applied = false;           // this frame's edits are the lesson's own
    bool probe_pending = false;     // probe the view's pixel once the step's snapshot exists
    std::array<int, 2> shown_size{0, 0};  // the render size the step was shown at (0: not yet)
    bool presenting = false;        // presenter mode
    bool sidebar_before = true;     // the panels' visibility before presenter mode
    bool unfold_panel = false;      // open the Lessons panel once (a lesson was opened)
    std::string error;              // why the last open failed
    std::string path_field;         // the panel's lesson file path
  };

  LessonShell(ShellState& shell, FileShell& files, FormulaShell& formulas, Instruments& tools)
      : s_(shell), files_(files), formulas_(formulas), tools_(tools) {}
  LessonShell(const LessonShell&) = delete;
  LessonShell& operator=(const LessonShell&) = delete;
  LessonState& state() { return state_; }
  const LessonState& state() const { return state_; }

  std::string open_lesson(const std::string& lesson_arg);  // "" or why not; unsaved edits are guarded as for Open
  void start_lesson();                           // the waiting lesson becomes the lesson, at its first step
  void close_lesson();
  void show_place(LessonPlace place);            // shows a step (or its answer) as written
  void present(const LessonPresenter::Show& show);  // what the presenter answers: A cleared, scene, view
  void update_lesson();                          // after apply_edits: the step's probe, its A, exploring
  bool lesson_key(int key);                      // next, previous, presenter mode; true when taken
  void set_presenting(bool on);                  // full screen, panels hidden, caption large
  void sidebar_lessons();
  void draw_lesson_caption();                    // the step's caption in the strip below the image
  // The strip below the image that the captions take, for a view `width` wide: the tallest of
  // the lesson's steps with its answer shown, so the image keeps its size through a lesson (no
  // new render when an answer or a step's longer text appears), at most kCaptionShare of
  // `window_height`; 0 with no lesson open.
  // Measured once per lesson, width, window and caption size, not every frame.
  float caption_strip_height(float width, float window_height);
  static constexpr float kCaptionShare = 0.4f;
  std::optional<std::string> script_lesson_command(const std::vector<std::string>& words);  // "" done, else why not
  void write_lesson_state(std::ostream& out) const;
  // An exercise step (docs/lessons.md): the one shown, its hints left, the next one shown.
  const LessonExercise* exercise() const;
  int hints_left() const;
  void show_hint();

 private:
  void adopt_step_scene(int step);               // the step's scene becomes the document
  void apply_step_view(const StepView& view);    // the term, instruments, probe, head and depth cut of a view
  // An exercise step's formula: the starter (or what the student left there) in its slot when
  // the step is entered, the formulas cleared when it is left.
  void sync_exercise();
  struct CaptionLine {
    std::string text;
    float size;
    std::uint32_t colour;  // ImU32
  };
  std::vector<CaptionLine> caption_lines(int step, bool revealed) const;  // the caption of a step
  float caption_lines_height(const std::vector<CaptionLine>& lines, float width) const;
  float caption_pad() const;

  ShellState& s_;  // the shell's shared state (shell_state.h)
  FileShell& files_;
  FormulaShell& formulas_;
  Instruments& tools_;
  LessonState state_;
  struct StripKey {
    std::string lesson;  // its name and title: another lesson may take the same storage
    float width = 0, window_height = 0, ui_scale = 0;
    bool presenting = false, exploring = false;
    bool operator==(const StripKey&) const = default;
  };
  StripKey strip_key_;       // what strip_height_ was measured for
  float strip_height_ = 0;
};

}  // namespace phonglab
