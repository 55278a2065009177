// The previewer shell's shared state, as one plain struct: the session (the scene, its file, its
// edits and undo), the renderer and what the frames send it, the image on screen, the panels'
// settings, the selection, the viewport and the frame's edits. Every component of the shell
// (Sidebar, Overlays, Instruments, FileShell, SceneBuilder, LessonShell, FormulaShell, the test
// scripts' ScriptDriver) is given this struct and the components it works with, by reference;
// none reaches another's private state. The queries and edits every component shares are the free
// functions at the end: one definition each.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <imgui.h>

#include "apps/previewer/viewer_gl.h"
#include "apps/previewer/viewer_platform.h"
#include "core/render/progressive.h"
#include "session/document.h"
#include "session/render_schedule.h"
#include "session/session.h"
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

constexpr int kTermCells = 5;  // the small multiples besides the full image
constexpr int kMultiplesColumns = 3;  // small multiples: 3 x 2 cells, the full image last
constexpr int kMultiplesRows = 2;
// The small multiples' cells in reading order (the full image is the main renderer's).
inline constexpr const std::array<Term, kTermCells>& kCellTerms = kFiveTerms;

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

// What this frame's panels and input changed (the main loop's apply_edits turns them into one restart).
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

// Frame pacing and the stats log's measurements.
struct ShellStats {
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

struct ShellState {
  // The renderer starts with `settings`; it calls `wake` when it has an image.
  ShellState(Platform& platform_in, const ViewerOptions& options_in, const ProgressiveSettings& settings,
             std::function<void()> wake)
      : platform(platform_in), options(options_in), renderer(settings, std::move(wake)), schedule(renderer) {}
  ShellState(const ShellState&) = delete;
  ShellState& operator=(const ShellState&) = delete;

  Platform& platform;
  ViewerOptions options;
  Session session;                           // the document, its edits and undo (src/session)
  SceneDocument& doc = session.document();   // its file side
  LessonPresenter& lessons = session.lessons();  // the lesson being presented
  ProgressiveRenderer renderer;
  RenderSchedule schedule;                   // what each frame sends it: snapshot, size, settings (src/session)
  ImageView image_view;                      // the image's texture

  // The image on screen: the newest frame taken from the renderer.
  ProgressiveFrame shown;
  bool upload_pending = false;          // shown is newer than the texture
  std::uint64_t drawn_generation = 0;   // generation of the image last put on screen
  std::uint64_t drawn_serial = 0;       // its FrameStats::serial

  // The panels' settings.
  ui::RenderSettings render_settings;
  ui::DisplaySettings display;
  ui::InstrumentSettings instruments;
  ui::LightSolo solo;
  ui::RayTreeSettings rays;             // ray tree overlay, depth cut, heat map
  ui::ItemLocations item_locations;     // named widgets' rectangles (io.UserData), for test scripts
  std::string camera_notice;            // why the last typed camera value was refused
  std::string figure_path = "phonglab-figure.png";
  std::string figure_status;

  // The selection and what the last frame drew over the image.
  int selected_material = 0;
  int selected_object = -1;             // index into the file's objects, -1: none
  int selected_light = -1;
  int hovered_light = -1;
  bool open_materials = false;          // a click picked a material: unfold its panel
  std::string picked_text;              // what the last viewport click hit
  std::vector<ui::LightMarker> markers; // the light markers as drawn last frame (for grabbing)
  std::map<std::string, ui::ScreenRect> overlay_rects;  // the overlay boxes drawn last frame (their layout)
  std::vector<ScreenSegment> tree_segments;  // the ray tree overlay as drawn this frame (image coordinates)
  double heat_max = 0;                  // top of the heat map's scale in the image on screen

  // The window.
  bool help_visible = false;            // the keys overlay (F1 or ?)
  int sidebar_toggles = 0;              // H presses handled (the tests count lost taps)
  bool sidebar_visible = true;
  ViewportRect viewport;
  Drag drag;
  bool interacting = false;             // a drag over the view is under way
  bool quit = false;
  int exit_code = 0;                    // set by a signal

  EditFlags edits;                      // what this frame changed
  ShellStats stats;
};

// The viewport's cells (one, or the small multiples' 3 x 2).
Cells cells(const ShellState& s);
// Width / height of one rendered image (a cell); 0 with no viewport.
double view_aspect(const ShellState& s);
// The camera the image is rendered with: the scene's, its field of view widened for a view
// narrower than the image the scene was framed for (see ui::fit_to_view).
Camera view_camera(const ShellState& s);
// The renderer idles and its last image is on screen.
bool image_is_final(const ShellState& s);
// A panel's or a script's edit, to the session; the frame restarts the renderer.
void apply_edit(ShellState& s, const Edit& edit);
// Navigation (a drag, the wheel, a typed camera), to the session; the frame restarts the renderer.
void move_camera(ShellState& s, const Camera& camera);
// The stats log's percentiles and level counts, under `label`.
void write_stats_summary(ShellStats& stats, const std::string& label);

}  // namespace phonglab
