// The test scripts' driver: commands run from inside the previewer's main loop, real input injected
// into ImGui as the window system's would be, waits on frames, the renderer, images and files, and
// `dump_state` (docs/previewer.md lists the commands). The main loop calls it only through
// `FrameClient`; the commands reach the shell's shared state (ShellState, shell_state.h) and the
// components it works with, given by reference.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <imgui.h>

#include "apps/previewer/frame_client.h"
#include "ui/panels.h"

namespace phonglab {

struct ShellState;
class FileShell;
class FormulaShell;
class Instruments;
class LessonShell;
class Overlays;
class SceneBuilder;

// One scripted frame of input, injected into ImGui as if it came from the window system.
struct InputStep {
  ImVec2 pos;                  // mouse position, window coordinates
  bool buttons[3] = {};        // left, right, middle held
  bool shift = false;          // shift held
  bool ctrl = false;           // control held
  int key = -1;                // GLFW key code to press or release in this frame, -1 for none
  bool key_down = false;       // press (true) or release (false) `key`
  float wheel = 0;             // wheel clicks, positive away from the user
  std::string text;            // characters typed in this frame (into the active text field)
};

// One line of a test script: the words, and where it came from.
struct ScriptCommand {
  int line = 0;
  std::vector<std::string> words;
};

// Splits a script into commands (one per line, '#' starts a comment). Commands are
// checked when they run; see docs/previewer.md for the list.
std::vector<ScriptCommand> parse_script(const std::string& text);

class ScriptDriver : public FrameClient {
 public:
  ScriptDriver(ShellState& shell, SceneBuilder& builder, FileShell& files, FormulaShell& formulas, LessonShell& lesson_shell, Instruments& tools, Overlays& overlays)
      : s_(shell), builder_(builder), files_(files), formulas_(formulas), lesson_shell_(lesson_shell), tools_(tools), overlays_(overlays) {}
  ScriptDriver(const ScriptDriver&) = delete;
  ScriptDriver& operator=(const ScriptDriver&) = delete;

  void load(std::vector<ScriptCommand> commands) { run_.commands = std::move(commands); }
  // The shell's frame (FrameClient): this frame's input injected and commands run until one
  // waits; the window screenshot asked
  // for after this frame's drawing (a screenshot that cannot be written fails the script); commands or input still to come; the hand on (injected
  // input under way, or the edit benchmark); exit status 3 when the script failed.
  void before_frame(double now) override { step_script(now); }
  std::string screenshot_wanted() override { return std::exchange(run_.screenshot, std::string()); }
  void screenshot_failed() override { run_.failed = true; }
  bool busy() const override { return run_.index < run_.commands.size() || !run_.input.empty(); }
  bool hand_on() const override { return !run_.input.empty() || run_.wait == ScriptWait::kBench; }
  int exit_status() const override { return run_.failed ? 3 : 0; }

 private:
  // What the script is waiting for before its next command.
  enum class ScriptWait : std::uint8_t { kNone, kFrames, kIdle, kImage, kFile, kInput, kBench, kItem };
  // A scripted click, drag or typed value on a widget found by name (click_item and friends).
  struct ItemAction {
    enum class Kind : std::uint8_t { kClick, kDrag, kType };
    Kind kind = Kind::kClick;
    std::string name;     // as ui::locate recorded it
    double dx = 0;        // kDrag: how far, window pixels
    double dy = 0;
    int steps = 10;       // kDrag: mouse moves on the way
    std::string text;     // kType: what is typed
  };

  void step_script(double now);                  // injects this frame's input, runs commands until one waits
  bool script_wait_done(double now);             // whether the current wait is over (fails on timeout)
  bool run_script_command(const ScriptCommand& command, double now);  // false: the script failed
  struct ScriptStep;  // one command being run (script_driver.cpp)
  std::optional<bool> script_wait_command(ScriptStep& step);
  std::optional<bool> script_input_command(ScriptStep& step);
  std::optional<bool> script_drag_command(ScriptStep& step);  // script_driver_drag.cpp
  std::optional<bool> script_item_command(ScriptStep& step);
  std::optional<bool> script_file_command(ScriptStep& step);
  std::optional<bool> script_other_command(ScriptStep& step);
  bool script_set(const std::vector<std::string>& words);             // the `set` command
  bool set_material_field(const std::vector<std::string>& words);     // its parts (script_driver_set.cpp)
  bool set_light_field(const std::vector<std::string>& words);
  bool set_camera_field(const std::vector<std::string>& words);
  bool set_render_field(const std::vector<std::string>& words);
  bool set_instrument(const std::vector<std::string>& words);
  bool set_display_field(const std::vector<std::string>& words);
  void fail_script(const ScriptCommand& command, const std::string& message);  // report, exit status 3
  void push_drag(int button, ImVec2 from, ImVec2 to, int steps, bool shift, int held_key = -1);  // queues a drag's input (a key held throughout)
  void push_click(ImVec2 at, bool ctrl);          // queues a left click (hover, press, release)
  bool push_item_input();                        // queues run_.item_action's input; false: no such widget
  void write_state(const std::string& path) const;                    // `dump_state`
  void write_document_state(std::ostream& out) const;  // write_state's parts (script_state.cpp)
  void write_layout_state(std::ostream& out) const;
  void write_rays_state(std::ostream& out) const;
  void write_probe_state(std::ostream& out) const;
  std::string depth_cut_label() const;                                // the depth-cut slider's text
  struct ScriptRun {
    std::vector<ScriptCommand> commands;
    std::size_t index = 0;
    ScriptWait wait = ScriptWait::kNone;
    int frames_left = 0;
    double deadline = 0;
    std::string file;
    std::deque<InputStep> input;
    ItemAction item_action;  // the widget action waiting for its widget to scroll into view
    bool failed = false;
    // The soak test's random walk (tests/gui/soak.sh): a command that fails is reported and
    // skipped (`lenient 1`), dialogs are answered as they open (`auto_modal discard`), and the
    // script ends at a time (`stop_after S`).
    bool lenient = false;
    int ignored = 0;                    // commands that failed and were skipped
    std::string auto_answer;            // `auto_modal discard`: the guard's button clicked ("" off)
    double stop_at = 0;                 // glfwGetTime() to quit at; 0: none
    std::string screenshot;             // window screenshot to take after drawing this frame
    int bench_left = 0;                 // bench_edits: edits still to make
    int bench_gap_frames = 0;           // frames to wait after an image before the next edit
    std::string bench_kind;             // "material" or "camera"
    bool bench_waiting_image = false;   // an edit was made; its first image is not up yet
    bool bench_expect_restart = false;  // the bench's edit waits for its restart: a generation after bench_before
    std::uint64_t bench_before = 0;     // the renderer's generation when the edit was made
    std::uint64_t bench_generation = 0; // the restart's generation, whose image the bench waits for
    int bench_sign = 1;  // edits alternate direction so the scene stays put
  };

  ShellState& s_;  // the shell's shared state (shell_state.h)
  SceneBuilder& builder_;
  FileShell& files_;
  FormulaShell& formulas_;
  LessonShell& lesson_shell_;
  Instruments& tools_;
  Overlays& overlays_;
  ScriptRun run_;
};

}  // namespace phonglab
