// The Formula panel's shell (docs/formulas.md): the student's texts turned into the session's
// formula edits, the snapshot traced with the formulas that render, which view is shown (yours, the
// reference, the difference), and the check of yours against the reference, run beside the renderer
// at a reduced size whenever the formulas or the view change. It reaches the shell's shared state
// (ShellState, shell_state.h) and the components it works with, given by reference.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "check/check.h"
#include "ui/panels.h"

namespace phonglab {

struct ShellState;
class Instruments;
class LessonShell;

class FormulaShell {
 public:
  FormulaShell(ShellState& shell, LessonShell& lesson_shell, Instruments& tools)
      : s_(shell), lesson_shell_(lesson_shell), tools_(tools) {}
  ~FormulaShell();
  FormulaShell(const FormulaShell&) = delete;
  FormulaShell& operator=(const FormulaShell&) = delete;

  void sidebar_formulas();  // the panel; its edits go to the session
  // A student's own image of the view (docs/checking.md): read, refused unless it has the view's
  // size (both sizes named), made A of the compare and checked beside the renderer. "" or why not.
  std::string open_image(const std::string& path);
  void close_image();
  const std::optional<CheckResult>& image_check() const { return image_result_; }
  const std::string& image_name() const { return image_name_; }
  const std::string& image_error() const { return image_error_; }
  // A slot's text as if typed and the box left (script commands, a lesson's exercise).
  void set_text(FormulaSlot slot, const std::string& text);
  bool set_view(std::string_view name);
  // The formulas' own file (docs/formulas.md): saved atomically, or opened as one undo step (a
  // bad file changes nothing and its first error is shown). "" : the panel's path, by default
  // beside the scene file as NAME.formulas.json. False when it failed (formulas_status says why).
  bool save_formulas(const std::string& path);
  bool open_formulas(const std::string& path);
  const std::string& formulas_status() const { return panel_.formulas_status; }
  void unfold() { unfold_ = true; }  // open the panel (a lesson's exercise)
  bool take_unfold() { return std::exchange(unfold_, false); }
  ui::FormulaView view() const { return panel_.view; }
  // Once a UI frame before the snapshot goes out: the rules the renderer traces with (the
  // formulas, or none for the reference view); true when they changed (a new snapshot).
  bool sync_rules();
  // Starts a check when the formulas or the view's snapshot changed and none is running; takes
  // a finished one's result.
  void poll_check();
  // The difference view's pixels at the render size, when it is on and a check is in.
  std::optional<std::vector<glm::vec3>> difference_pixels(int width, int height) const;
  // The last check's verdict ("" when none: no formula, or not yet in), its result.
  const std::optional<CheckResult>& last_check() const { return result_; }
  bool checking() const { return running_.load(); }
  // No check to wait for: no formula, or the last one is in for what renders now.
  bool check_settled() const;
  const ui::FormulaPanelState& panel() const { return panel_; }

 private:
  void refresh_panel();  // the texts and errors from the session
  std::string formulas_path() const;

  ShellState& s_;  // the shell's shared state (shell_state.h)
  LessonShell& lesson_shell_;
  Instruments& tools_;
  ui::FormulaPanelState panel_;
  bool unfold_ = false;
  std::uint64_t rules_version_ = 0;
  bool rules_sent_any_ = false;
  ui::FormulaView rules_view_ = ui::FormulaView::kYours;
  // The check beside the renderer.
  std::thread worker_;
  std::atomic<bool> running_{false};
  std::mutex mutex_;
  std::optional<CheckResult> finished_;  // the worker's, under mutex_
  bool finished_image_ = false;          // ... an image's check (else the formulas')
  std::optional<CheckResult> result_;    // the formulas' check shown
  // A student's image: what was read, its check, why the last one was refused.
  std::optional<StudentImage> image_;
  std::string image_name_, image_error_;
  std::optional<CheckResult> image_result_;
  bool image_check_pending_ = false;
  const void* checked_snapshot_ = nullptr;
  std::uint64_t checked_version_ = ~std::uint64_t{0};
};

}  // namespace phonglab
