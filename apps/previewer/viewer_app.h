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

#include "session/document.h"
#include "session/render_schedule.h"
#include "session/session.h"
#include "apps/previewer/file_browser.h"
#include "apps/previewer/file_shell.h"
#include "apps/previewer/scene_builder.h"
#include "apps/previewer/instruments.h"
#include "apps/previewer/formula_shell.h"
#include "apps/previewer/overlays.h"
#include "apps/previewer/sidebar.h"
#include "apps/previewer/lesson_shell.h"
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

struct ViewerOptions {
  std::string scene_arg = "lecture";  // embedded scene name or scene file
  int width = 1280;                   // window size, screen coordinates
  int height = 720;
  std::string lesson_arg;             // a lesson to present from the start (name or file), or empty
  bool scene_given = false;           // SCENE was on the command line (else a recovery of any scene is offered)
  std::string script_path;            // test hook: commands run from the main loop
  std::string stats_log_path;         // test hook: frame times and edit latencies
};

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
  // What a mouse drag in the viewport does.
  enum class DragMode : std::uint8_t { kNone, kOrbit, kPan, kDolly, kLight, kObject, kWipe };
  struct Drag {
    DragMode mode = DragMode::kNone;
    int button = 0;          // ImGui mouse button that started it
    bool moved = false;      // passed the drag threshold (else a release is a click)
    ImVec2 start;            // where the button went down
    int light = -1;          // kLight: index of the light being moved
    double light_depth = 0;  // kLight: its distance along the view direction
    int object = -1;         // kObject: the object being moved (its index in the file)
    double object_depth = 0; // kObject: its anchor's distance along the view direction
    Vec3 object_start{0};    // kObject: its anchor when grabbed
    Vec3 grab_offset{0};     // kObject: anchor minus the grabbed point, in the view plane
  };
  // The viewport: the window area left of the panels, in ImGui (window) coordinates.
  struct ViewportRect {
    float x = 0;
    float y = 0;
    float width = 0;
    float height = 0;
  };
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
  // Encodes and uploads a new image (or the one on screen under new display settings).
  void upload_images(int view_w, int view_h);
  void draw_gl(int fb_width, int fb_height, const std::string& screenshot);  // upload, image, ImGui, the screenshot wanted
  // The exposure the image on screen is encoded with (none for the heat map's final colours).
  float image_exposure_ev() const;
  // Whether the image on screen (or a term image) must be encoded and uploaded again.
  bool images_stale() const;
  // Whether this frame draws other pixels than the last one drawn (or the window asked for
  // them again); keeps this frame's draw data for the next call.
  bool frame_changed(int fb_width, int fb_height);
  void after_swap();                       // edit-to-image latency of a first image just shown

  // The viewport's cells: one, or the small multiples' 3 x 2 (the full image last).
  struct Cells {
    int columns = 1;
    int rows = 1;
    float x = 0, y = 0;          // the viewport's top-left, window coordinates
    float width = 0, height = 0; // of one cell
    int count() const { return columns * rows; }
    ImVec2 origin(int cell) const {  // top-left of a cell, in reading order
      return ImVec2(x + static_cast<float>(cell % columns) * width, y + static_cast<float>(cell / columns) * height);
    }
  };
  Cells cells() const;

  // The camera the image is rendered with: the scene's, its field of view widened for a view
  // narrower than the image the scene was framed for (see ui::fit_to_view).
  Camera view_camera() const;
  double view_aspect() const;                    // width / height of one rendered image (a cell)

  // Actions.
  void pick(ImVec2 mouse);                       // selects the object (and its material) under a click
  std::optional<Hit> hit_at(ImVec2 mouse) const;  // the nearest hit of the ray through a viewport point
  std::optional<int> object_under(ImVec2 mouse) const;  // the file index of the object seen there
  bool grab_object(ImVec2 mouse, const std::optional<int>& hit_object);  // starts kObject on the selected one
  void drag_object_to(ImVec2 mouse, int view_w, int view_h);
  void undo();                                   // Ctrl+Z: the scene before the last edit
  void redo();                                   // Ctrl+Shift+Z
  void restored();                               // after an undo or redo step: selection and restart
  void apply_edit(const Edit& edit);             // a panel's or a script's edit, to the session; restarts
  void move_camera(const Camera& camera);        // navigation (a drag, the wheel), to the session; restarts
  void note_restart(std::uint64_t generation, double edit_time);  // remembers when its edit happened
  void update_title();                           // "phonglab - source *"
  bool image_is_final() const;                   // the renderer idles and its last image is on screen



  void write_stats_summary(const std::string& label);                 // percentiles into the stats log

  Platform& platform_;
  ViewerOptions options_;
  Session session_;                             // the document, its edits and undo (src/session)
  SceneDocument& doc_ = session_.document();    // its file side, as the shell's files still name it
  LessonPresenter& lessons_ = session_.lessons();  // the lesson being presented
  ProgressiveRenderer renderer_;
  RenderSchedule schedule_;                     // what each frame sends it: snapshot, size, settings (src/session)
  ImageView image_view_;
  std::vector<unsigned char> drawn_bytes_;  // the last drawn frame's draw data and layout (frame_changed)
  std::vector<unsigned char> frame_bytes_;  // this frame's, kept to avoid an allocation a frame

  // The image on screen: the newest frame taken from the renderer.
  ProgressiveFrame shown_;
  bool upload_pending_ = false;          // shown_ is newer than the texture
  std::uint64_t drawn_generation_ = 0;   // generation of the image last put on screen
  std::uint64_t drawn_serial_ = 0;       // its FrameStats::serial

  // UI state.
  ui::RenderSettings render_settings_;
  ui::DisplaySettings display_;
  ui::InstrumentSettings instruments_;
  ui::LightSolo solo_;
  ui::ItemLocations item_locations_;  // named widgets' rectangles (io.UserData), for test scripts
  int selected_material_ = 0;
  int selected_object_ = -1;         // index into the file's objects, -1: none
  int selected_light_ = -1;
  int hovered_light_ = -1;
  std::vector<ui::LightMarker> markers_;  // the light markers as drawn last frame (for grabbing)
  std::map<std::string, ui::ScreenRect> overlay_rects_;  // the overlay boxes drawn last frame (their layout)
  double dolly_limit_ = 1e300;       // farthest the wheel takes the eye from look_at (ui::dolly_limit)
  bool help_visible_ = false;        // the keys overlay (F1 or ?)
  int sidebar_toggles_ = 0;          // H presses handled (the tests count lost taps)
  std::string picked_text_;          // what the last viewport click hit
  bool open_materials_ = false;      // a click picked a material: unfold its panel
  bool sidebar_visible_ = true;
  ViewportRect viewport_;
  Drag drag_;
  bool interacting_ = false;
  bool quit_ = false;
  double next_file_poll_ = 0;        // glfwGetTime() of the next mtime check
  std::string title_;

  // Instruments.
  std::string camera_notice_;          // why the last typed camera value was refused
  std::string figure_path_ = "phonglab-figure.png";
  std::string figure_status_;
  ui::RayTreeSettings rays_;           // ray tree overlay, depth cut, heat map
  std::vector<ScreenSegment> tree_segments_;  // the overlay as drawn this frame (image coordinates)
  double heat_max_ = 0;                // top of the heat map's scale in the image on screen
  static constexpr int kTermCells = 5;  // the small multiples besides the full image
  // Keys 1..6: the full image, then the terms in the order of the equation.
  static constexpr std::array<Term, 6> kShortcutTerms = {Term::kFull, Term::kAmbient, Term::kDiffuse, Term::kSpecular,
                                                         Term::kReflection, Term::kRefraction};
  static constexpr int kMultiplesColumns = 3;  // small multiples: 3 x 2 cells, the full image last
  static constexpr int kMultiplesRows = 2;
  // The small multiples' cells in reading order (the full image is the main renderer's).
  static constexpr const std::array<Term, kTermCells>& kCellTerms = kFiveTerms;

  // Timing.
  // Edits whose first image is not yet on screen: (generation, glfwGetTime() of the edit).
  std::deque<std::pair<std::uint64_t, double>> restart_times_;
  std::uint64_t first_image_generation_ = 0;  // its first image went up this frame; 0: none

  // What this frame's panels and input changed (apply_edits turns them into one restart).
  struct EditFlags {
    bool scene = false;            // materials, lights, shading: restart and mark unsaved
    bool camera = false;           // navigation: restart, not an unsaved change
    bool replaced = false;         // opened or reloaded
    bool settings = false;         // render settings panel
    bool view = false;             // the depth cut: a new snapshot of the same scene, not an edit
    bool frame_requested = false;  // F / "Frame"
    bool reset_requested = false;  // R / "Reset"
    bool while_active = false;     // a slider drag is editing: render coarse while it lasts
  };
  EditFlags edits_;
  // The small multiples: a texture per term, from the main renderer's term images
  // (ProgressiveFrame::terms, in kCellTerms' order).
  struct TermCells {
    std::array<ImageView, kTermCells> views;
  };
  TermCells terms_;
  // Frame pacing and the stats log's measurements.
  struct FrameStats {
    double last_frame_start = 0;
    std::deque<std::pair<double, double>> frame_times;  // (start, duration) over the last second
    bool was_rendering = false;                         // the renderer was busy when this frame started
    bool slept_idle = false;                            // this frame followed an idle sleep, not the 60 Hz pacing
    double last_latency_ms = -1;                        // edit to first image on screen, last measured
    std::string last_first_image;                       // how that image was made: "reshaded 1/1", "traced 1/8", "live 1/1"
    std::vector<double> latencies_ms;                   // for the stats log's summary (kept only with a log)
    std::vector<double> busy_frame_ms;                  // UI frame times while the renderer was working (same)
    std::map<int, std::vector<double>> pass_mrays;      // Mrays/s of the passes taken, by level divisor, 0: the quad-shaded rung (same)
    std::uint64_t last_pass_serial = 0;                 // the last of them
    std::map<int, int> frames_at_level;                 // UI frames by the level divisor of the image on screen, 0: the quad-shaded rung (same)
    std::deque<std::pair<std::uint64_t, double>> full_pending;  // edits (generation, time) not yet seen at full resolution
    std::vector<double> edit_to_full_ms;                // edit to the first full-resolution image of it or a later one (same)
    CpuClock cpu_mark;                                  // the clocks at the last reset: the cores the UI and all took since
    int frames_drawn = 0;                               // frames drawn and swapped since then (the others changed nothing)
    std::ofstream log;
  };
  FrameStats stats_;
  // The lesson being presented: the session's LessonPresenter, and its shell (lesson_shell.h).
  friend class LessonShell;
  LessonShell lesson_shell_{*this};
  // The scene file, the screenshots, the guarding dialogs, the file browser and the recovery
  // offer (file_shell.h).
  friend class FileShell;
  FileShell files_{*this};
  // Building the scene: objects and materials added, edited, deleted (scene_builder.h).
  friend class SceneBuilder;
  SceneBuilder builder_{*this};
  // The panels down the right (sidebar.h).
  friend class Sidebar;
  Sidebar panels_{*this};
  // What is drawn over the image (overlays.h).
  friend class Overlays;
  Overlays overlays_{*this};
  // The teaching instruments' state and rules: the probe, A and the compare, the heat map, the
  // head, the ambient views (instruments.h).
  friend class Instruments;
  Instruments tools_{*this};
  // The student's formulas: the panel, the snapshot's rules, the check beside the renderer
  // (formula_shell.h).
  friend class FormulaShell;
  FormulaShell formulas_{*this};
  int exit_code_ = 0;          // set by handle_signal
  // The test script being run (script_driver.h): a friend, for now, that reads and sets the
  // shell's state directly.
  friend class ScriptDriver;
  ScriptDriver script_{*this};
  // What drives the loop from inside, through the one seam of frame_client.h (the script when
  // --script is given; null otherwise).
  FrameClient* client_ = nullptr;
};

}  // namespace phonglab
