// The previewer's main loop: holds the session (src/session: the scene, its file, edits and undo), hands the
// progressive renderer a snapshot at most once per UI frame, shows its latest image, draws the
// panels, turns mouse drags into camera and light moves, and runs test scripts.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <fstream>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "apps/previewer/shell_state.h"
#include "apps/previewer/file_browser.h"
#include "apps/previewer/file_shell.h"
#include "apps/previewer/scene_builder.h"
#include "apps/previewer/instruments.h"
#include "apps/previewer/formula_shell.h"
#include "apps/previewer/overlays.h"
#include "apps/previewer/sidebar.h"
#include "apps/previewer/lesson_shell.h"
#include "apps/previewer/screen_plan.h"
#include "apps/previewer/script_driver.h"
#include "apps/previewer/viewer_gl.h"
#include "apps/previewer/viewer_platform.h"
#include "io/image_io.h"
#include "core/render/progressive.h"
#include "core/teaching/lesson.h"
#include "interaction/history.h"
#include "interaction/recovery.h"
#include "ui/panels.h"
#include "ui/ray_tree_overlay.h"

namespace phonglab {

// Opens the window and runs until the user quits. Returns the process exit code: 0, 1 when
// there is no display (the message points at phonglab-cli), 3 when a test script failed,
// 128 + the signal for SIGINT, SIGTERM and SIGHUP (130, 143, 129; unsaved edits are kept in a
// recovery file first).
int run_viewer(const ViewerOptions& options);

// SIGINT, SIGTERM and SIGHUP go to one thread that notes them and wakes the main loop (call
// before any other thread starts, so they all block them); a second one ends at once.
void start_signal_watcher();
// The signal that arrived, 0 while none did.
int pending_signal();

class Viewer {
 public:
  Viewer(Platform& platform, const ViewerOptions& options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Initialises GL resources; an empty string or the error.
  std::string init();
  // The main loop. Returns the exit code.
  int run();

 private:
  // Frame phases, in order.
  void wait_for_next_frame();              // 60 Hz pacing, early for a new edit's first image, sleep when idle
  bool poll_render_frame();                // takes the renderer's newest image into shown_, if any
  void poll_scene_file(double now);        // twice a second: reload a changed file (or flag it)
  void layout();                           // the viewport rectangle beside the panels
  void handle_viewport_input();            // drags, wheel, clicks and keys over the image
  void drag_viewport(ImVec2 mouse, ImVec2 delta, const Camera& view, int view_w, int view_h);  // one drag step
  void handle_keys();                      // this frame's key presses (GLFW events, none lost)
  void shortcut(int key, bool shift);      // what a plain (or shifted) key does over the view
  void apply_edits(double frame_start);    // at most one restart for everything this frame changed
  // A new image from the renderer taken as the one on screen (its generation, the heat map's top).
  void take_images();
  // Encodes and uploads a new image (or the one on screen under new display settings).
  void upload_images(const DisplayBlocks& blocks);  // the view's image widened into `blocks`, the small multiples'
  void draw_gl(const ScreenPlan& plan, int fb_width, int fb_height, const std::string& screenshot);  // upload, image, ImGui, the screenshot wanted
  void draw_software(const ScreenPlan& plan, int fb_width, int fb_height, const std::string& screenshot);  // headless: the screenshot drawn on the CPU
  // The exposure the image on screen is encoded with (none for the heat map's final colours).
  float image_exposure_ev() const;
  // Whether the image on screen (or a term image) must be encoded and uploaded again.
  bool images_stale() const;
  // Whether this frame draws other pixels than the last one drawn (or the window asked for
  // them again); keeps this frame's draw data for the next call.
  bool frame_changed(int fb_width, int fb_height);
  void after_swap();                       // edit-to-image latency of a first image just shown

  // Actions.
  void pick(ImVec2 mouse);                       // selects the object (and its material) under a click
  std::optional<Hit> hit_at(ImVec2 mouse) const;  // the nearest hit of the ray through a viewport point
  std::optional<int> object_under(ImVec2 mouse) const;  // the file index of the object seen there
  bool grab_object(ImVec2 mouse, const std::optional<int>& hit_object);  // starts kObject on the selected one
  void drag_object_to(ImVec2 mouse, int view_w, int view_h);
  void note_restart(std::uint64_t generation, double edit_time);  // remembers when its edit happened
  void update_title();                           // "phonglab - source *"




  ShellState s_;                              // the state every component reads (shell_state.h)
  std::vector<unsigned char> drawn_bytes_;  // the last drawn frame's draw data and layout (frame_changed)
  std::vector<unsigned char> frame_bytes_;  // this frame's, kept to avoid an allocation a frame
  double dolly_limit_ = 1e300;       // farthest the wheel takes the eye from look_at (ui::dolly_limit)
  double next_file_poll_ = 0;        // glfwGetTime() of the next mtime check
  std::string title_;
  // Keys 1..6: the full image, then the terms in the order of the equation.
  static constexpr std::array<Term, 6> kShortcutTerms = {Term::kFull, Term::kAmbient, Term::kDiffuse, Term::kSpecular,
                                                         Term::kReflection, Term::kRefraction};
  // Edits whose first image is not yet on screen: (generation, glfwGetTime() of the edit).
  std::deque<std::pair<std::uint64_t, double>> restart_times_;
  std::uint64_t first_image_generation_ = 0;  // its first image went up this frame; 0: none
  // The small multiples: a texture per term, from the main renderer's term images
  // (ProgressiveFrame::terms, in kCellTerms' order).
  std::array<ImageView, kTermCells> term_views_;

  // The shell's components, each given the shared state and the components it works with (their
  // references are bound before the components they name are built; none uses another while
  // being built).
  LessonShell lesson_shell_{s_, files_, formulas_, tools_};  // the lesson being presented (lesson_shell.h)
  // The scene file, the screenshots, the guarding dialogs, the file browser and the recovery
  // offer (file_shell.h).
  FileShell files_{s_, lesson_shell_, tools_};
  // Building the scene: objects and materials added, edited, deleted, undo and redo (scene_builder.h).
  SceneBuilder builder_{s_, files_, formulas_, lesson_shell_};
  // The teaching instruments' state and rules: the probe, A and the compare, the heat map, the
  // head, the ambient views (instruments.h).
  Instruments tools_{s_, formulas_};
  // The student's formulas: the panel, the snapshot's rules, the check beside the renderer
  // (formula_shell.h).
  FormulaShell formulas_{s_, lesson_shell_, tools_};
  Sidebar panels_{s_, builder_, files_, formulas_, lesson_shell_, tools_};  // the panels down the right (sidebar.h)
  Overlays overlays_{s_, builder_, files_, lesson_shell_, tools_};           // what is drawn over the image (overlays.h)
  // The test script being run (script_driver.h), and what drives the loop from inside through
  // the one seam of frame_client.h (the script when --script is given; null otherwise).
  ScriptDriver script_{s_, builder_, files_, formulas_, lesson_shell_, tools_, overlays_};
  FrameClient* client_ = nullptr;
};

}  // namespace phonglab
