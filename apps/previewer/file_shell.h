// The previewer's files: opening, reloading and saving the scene through the unsaved-changes and
// changed-on-disk dialogs, the file browser, screenshots, and the offer of kept edits at start and
// the exit on a signal. The document itself is the session's (SceneDocument, RecoveryKeeper); this
// class holds the dialogs' and panels' state and reaches the shell's shared state (ShellState,
// shell_state.h) and the components it works with, given by reference.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "apps/previewer/file_browser.h"
#include "interaction/recovery.h"
#include "io/image_io.h"
#include "session/document.h"
#include "session/file_flow.h"
#include "ui/panels.h"

namespace phonglab {

struct ShellState;
class Instruments;
class LessonShell;

class FileShell {
 public:
  // An action that would lose unsaved edits (the flow's: session/file_flow.h).
  using PendingAction = FileFlow::Action;
  // The offer of kept edits and the exit on a signal (the files are the session's RecoveryKeeper).
  struct Recovery {
    std::optional<ui::RecoveryEntry> offer;  // found at start, waiting for an answer
    bool open_modal = false;   // open the offer's dialog this frame
    bool modal_visible = false;
    bool keep = false;         // exiting on a signal: the file stays for the next start
    bool after_lesson = false; // started with a lesson: the offer waits until it closes (never over a slide)
  };

  FileShell(ShellState& shell, LessonShell& lesson_shell, Instruments& tools);
  FileShell(const FileShell&) = delete;
  FileShell& operator=(const FileShell&) = delete;

  ui::SceneFileState& file_state() { return file_state_; }
  const ui::SceneFileState& file_state() const { return file_state_; }
  ui::ScreenshotState& screenshot_state() { return screenshot_state_; }
  const ui::ScreenshotState& screenshot_state() const { return screenshot_state_; }
  // The dialogs' decisions (what waits for which question); the modals draw its question.
  const FileFlow& flow() const { return flow_; }
  // Whether the unsaved-changes or the changed-on-disk dialog is up (drawn, not yet answered).
  bool guard_visible() const { return shown_ == FileFlow::Question::kUnsavedChanges; }
  bool conflict_visible() const { return shown_ == FileFlow::Question::kChangedOnDisk; }
  FileBrowser& browser() { return browser_; }
  const FileBrowser& browser() const { return browser_; }
  Recovery& recovery() { return recovery_; }
  const Recovery& recovery() const { return recovery_; }

  void handle_guard_modal();               // the unsaved-changes dialog and its answer
  void handle_conflict_modal();            // the changed-on-disk dialog (from Save) and its answer
  void handle_file_browser();              // draws the file browser and carries out its choice
  void request(PendingAction action);      // runs it, or asks first when there are unsaved edits
  void perform(const PendingAction& action);  // runs it
  void poll_file();                        // a change on disk: reloaded, or flagged over unsaved edits
  void open_scene(const std::string& scene_arg);
  void document_replaced();                // a new document: its selection, status and recovery anew
  void reload_scene(bool keep_view);
  void save_scene(bool as);                // Save (false) or Save as the path field (true), then what waited behind it
  bool begin_screenshot(Image& image);     // the shown image's size, or false (and why) before the first
  void save_png(const std::string& path);  // what is shown, exposure and curve applied
  void save_pfm(const std::string& path);  // the linear image
  // The whole window's pixels (RGB, 8 bits a channel, rows from the top) as a PNG; false (said
  // on stderr, and the shell quits) when it cannot be written.
  bool save_window_screenshot(const std::string& path, const std::vector<unsigned char>& rgb, int fb_width, int fb_height);
  void find_recovery();                    // at start: a recovery to offer
  void handle_recovery_modal();            // the offer and its answer
  bool handle_signal();                    // a signal arrived: the recovery written, the exit code set

 private:
  void carry_out(FileFlow::Outcome outcome);  // what the flow left to the shell: reload, report the save, run
  void report_save(bool wrote);               // the status or the document's error
  // Writes a screenshot and reports it in the Screenshot panel; `kind` prefixes the size.
  void write_screenshot(const std::string& path, const Image& image, const char* kind);
  void restore_recovery(const ui::RecoveryEntry& entry);

  ShellState& s_;  // the shell's shared state (shell_state.h)
  LessonShell& lesson_shell_;
  Instruments& tools_;
  ui::SceneFileState file_state_;
  ui::ScreenshotState screenshot_state_;
  FileFlow flow_;
  FileFlow::Question shown_ = FileFlow::Question::kNone;  // the question whose dialog is up
  FileBrowser browser_;  // the Open / Save-as file browser and the recent files
  Recovery recovery_;
};

}  // namespace phonglab
