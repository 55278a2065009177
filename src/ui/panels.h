// The previewer's ImGui panels. Each draws into the current ImGui window, edits plain data
// passed by reference and returns whether it edited it ("edited"); button presses come back as
// requests in small action structs that the app carries out. No GL here, no file access.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <imgui.h>

#include "core/render/indirect_probe.h"
#include "core/render/progressive.h"
#include "core/render/render.h"
#include "check/formula.h"
#include "core/scene/scene.h"
#include "core/shading/shading.h"
#include "core/teaching/lesson.h"
#include "interaction/file_browser.h"
#include "interaction/history.h"
#include "ui/overlay.h"

namespace phonglab::ui {

// The Formula panel (docs/formulas.md): what a student types for the ambient, diffuse and
// specular terms, which image the view shows, and the check's verdict.
enum class FormulaView : std::uint8_t { kYours, kReference, kDifference };
std::string_view formula_view_name(FormulaView view);  // "yours", "reference", "difference"
std::optional<FormulaView> formula_view_from_name(std::string_view name);
struct FormulaPanelState {
  std::array<std::string, kFormulaSlots> texts;   // the boxes (edited in place)
  std::array<std::string, kFormulaSlots> errors;  // each text's error, "" when it compiles
  std::string names;                              // the names a formula may use
  FormulaView view = FormulaView::kYours;
  std::string verdict;                            // the check's summary ("" before one)
  bool matches = false;
  int hints_left = -1;                            // a lesson's exercise: its hints not yet shown (-1: none)
  std::string probe;                              // yours against the reference at the probed pixel ("" : none)
  // A student's own image (docs/checking.md): the path typed, the image checked, its verdict.
  std::string image_path;
  std::string image_name;     // "" : none loaded
  std::string image_verdict;  // the check's summary, or "checking..."
  bool image_matches = false;
  std::string image_error;    // why the last one was refused
  std::string image_probe;    // yours against the reference at the probed pixel
  // The formulas' own file (docs/formulas.md): its path, what the last save or open did.
  std::string formulas_path;
  std::string formulas_status;
  bool formulas_failed = false;
};
struct FormulaPanelEdits {
  int slot = -1;        // this slot's text changed
  bool held = false;    // ...and its box is still being typed in
  int starter = -1;     // "starter" asked for this slot (the reference's names, to be completed)
  bool view = false;    // the view changed
  bool hint = false;    // "hint" asked for (a lesson's exercise)
  bool open_image = false;   // "check this image" (image_path)
  bool close_image = false;
  bool save_formulas = false;  // to formulas_path
  bool open_formulas = false;  // from formulas_path
};
FormulaPanelEdits formula_panel(FormulaPanelState& state);

// Buttons of the camera panel.
struct CameraActions {
  bool frame_scene = false;  // "Frame (F)": fit the scene into the view
  bool reset = false;        // "Reset (R)": back to the camera of the scene file
};

// Position, look-at, up and vertical field of view. Returns true when the camera changed. A
// value the renderer cannot use is refused and `notice` says why (shown until the next edit).
bool camera_panel(Camera& camera, CameraActions& actions, std::string& notice);

// "What ambient stands in for" (the key I): the lecture's ka·Ia, the image with the indirect
// light in its place, the indirect term beside the ambient term (ka·Ia left of the middle,
// indirect right), or |indirect − ka·Ia| as a heat map.
enum class AmbientView : std::uint8_t { kConstant, kIndirect, kBeside, kDifference };
std::string_view ambient_view_name(AmbientView view);  // "constant", "indirect", "beside", "difference"
std::optional<AmbientView> ambient_view_from_name(std::string_view name);
std::string ambient_view_caption(AmbientView view);     // what the image shows, for the overlay

// The term buttons (the full image, then each term of the equation), the side-by-side switch,
// what ambient stands in for and the debug views. Edits them directly.
void show_panel(Term& term, bool& small_multiples, AmbientView& ambient_view, bool blinn);

// A list of the materials to pick from and the lecture's coefficients of the selected one,
// each beside the term of the equation it scales. `selected` may change without an edit.
bool materials_panel(std::vector<Material>& materials, int& selected, SpecularModel model);

// The last object or material edit's outcome, as the panels show it: what was done, or why
// nothing was (`refused`).
struct EditNotice {
  std::string text;
  bool refused = false;
  bool material = false;  // a material's edit's: shown in the Materials panel too
};

// What the Objects panel asks for; the app carries it out, one undo step each.
struct ObjectActions {
  ObjectRef::Kind add = ObjectRef::Kind::kNone;  // "+ sphere" ...; kMesh: from the OBJ path field
  int duplicate = -1;                            // object to duplicate, -1: none
  int remove = -1;                               // object to delete, -1: none
  std::string field;                             // a field of the selected object was edited: its name
  std::vector<double> values;                    // its numbers
  std::string text;                              // field "material": the chosen material's name; "name": the new name
};
// The scene's objects by index, kind and material; add, duplicate, delete; the selected one's
// numbers and material. `selected` may change without an edit; `notice` is the last edit's
// result or refusal.
void objects_panel(const Scene& scene, int& selected, std::string& mesh_path, const EditNotice& notice,
                   ObjectActions& actions);

// New, duplicate, rename (to `name_field`), delete and the preset library for the selected material.
struct MaterialActions {
  bool add = false, duplicate = false, remove = false;
  std::string rename;  // the new name, when "Rename to" was pressed
  std::string preset;  // a preset chosen from the library
};
void material_library(const Scene& scene, int selected, std::string& name_field, MaterialActions& actions);

// Light list with add/remove, per-light mute (the enabled box) and solo ("S": this light
// alone, again to restore), and the selected light's type, intensity, position or direction.
// `selected` may change without an edit.
bool lights_panel(std::vector<Light>& lights, int& selected, LightSolo& solo);

// Scene-wide shading: ambient Ia, background, recursion depth, pruning weight, specular model.
bool shading_settings_panel(Scene& scene);

// How the previewer renders (not part of the scene file).
struct RenderSettings {
  int target_spp = 64;          // samples per pixel, then the renderer idles
  float resolution_scale = 1;   // rendered pixels per framebuffer pixel along each axis
  int threads = 0;              // 0 = all hardware threads
  Term term = Term::kFull;      // full image, one term of the equation, or a debug view
  int live_images_per_s = 24;   // while dragging: images a second the start level must allow (0: 1/8 always)
  int tree_budget_mib = 512;    // memory for the first sample's ray trees (re-shading); 0: none
  AmbientView ambient_view = AmbientView::kConstant;
};
bool render_settings_panel(RenderSettings& settings, int hardware_threads);

// The teaching instruments' switches (previewer state, not part of the scene file).
struct InstrumentSettings {
  bool probe_mode = false;       // a plain click probes the pixel instead of selecting a material
  bool small_multiples = false;  // the five terms and their sum side by side
  int compare = 0;               // 0 live image, 1 wipe against snapshot A, 2 |live - A| difference
  float wipe = 0.5f;             // wipe position: fraction of the viewport showing A (left)
  float difference_gain = 4;     // the difference image is scaled by this
  bool move_head = false;        // shade with the eye turned about the probed point (view rays stay)
  float head_angle_deg = 0;      // that turn, degrees about the camera's up axis
};
// Buttons of the instruments panel.
struct InstrumentActions {
  bool snapshot_a = false;   // keep the image shown now as A
  bool undo = false;
  bool redo = false;
  bool save_figure = false;  // write the slide figure to `figure_path`
  bool head_reference = false;  // keep the image now as A and show |live - A| (move-your-head difference)
};
// Probe mode, small multiples, compare against A, undo/redo and the slide figure.
// `have_a` enables the compare views; the counts label the undo buttons. Returns "edited".
bool instruments_panel(InstrumentSettings& settings, InstrumentActions& actions, bool have_a,
                       std::size_t undo_count, std::size_t redo_count, std::string& figure_path,
                       const std::string& figure_status);

// The "move your head" plot: the probed hit's specular factor against the head angle.
struct HeadPlotView {
  const ProbeNode* hit = nullptr;  // the probe's primary hit (P, N, lights)
  Vec3 eye_at_zero{0};             // the camera position (angle 0)
  Vec3 axis{0, 1, 0};              // unit axis the eye turns about (the camera's up)
  double shininess = 1;            // n of the hit's material
  bool blinn = false;              // N.H instead of R.V
  float angle_deg = 0;             // the current angle (marked)
  float width = 300;               // of the plot, screen pixels
};
// max(0, R.V)^n (or N.H^n) of the first light on the lit side, for angles -90..90 degrees,
// with the current angle marked. Nothing to edit.
void head_plot(const HeadPlotView& view);

// What the probe panel shows: the renderer's ray tree of one pixel and the report around it.
struct ProbeView {
  const Scene* scene = nullptr;     // the snapshot probed
  const PixelProbe* probe = nullptr;
  int image_width = 0;              // of the image the pixel belongs to
  int image_height = 0;
  std::string report;               // probe_to_text: the equation with the numbers filled in
  std::vector<std::string> occluders;  // per primary-hit light: object_name of its occluder
  unsigned char srgb[3] = {};       // the displayed 8-bit value (exposure and curve applied)
  float exposure_ev = 0;
  const IndirectProbe* indirect = nullptr;  // what ambient stands in for at the pixel
  std::string cli_command;          // the same pixel in phonglab-cli probe ("" when the scene has no name to give)
};
// The probed pixel: P, N, V, per light L, R (or H), N.L, R.V (or N.H), the powered factor,
// visibility, each term's RGB, the children and the totals, to four significant digits (every
// digit with `all_digits`, which the panel's box switches).
void probe_panel(const ProbeView& view, bool& all_digits);

// Display-time transform of the linear image (a shader uniform: never restarts rendering).
struct DisplaySettings {
  float exposure_ev = 0;  // stops: pixels are scaled by 2^exposure_ev
  bool srgb = true;       // sRGB transfer curve (true) or raw linear values (false)
  bool light_markers = true;  // the lights' markers and labels over the view ("where is the light?")
  bool show_stats = true; // the stats overlay over the viewport (one summary line)
  bool stats_details = false;  // the overlay's full table (frame times, rays, tracer)
  float ui_size_dragged = -1;  // the UI size slider's value while it is held (applied on release); <0: not held
  float ui_size = 1;      // panel and text size on top of the monitor's scale (projectors)
};
bool display_panel(DisplaySettings& display);

// What is open and what happened to it.
struct SceneFileState {
  std::string source;        // shown name: the file path, or "embedded scene 'lecture'"
  std::string file_path;     // where Save writes; empty for embedded scenes (use Save as)
  std::string path_field;    // the Open / Save-as text field
  bool dirty = false;        // edits not saved
  bool opened_mesh = false;  // the document is an OBJ opened alone: Save would overwrite a mesh
  bool auto_reload = true;   // reload by itself when the file changes on disk
  bool changed_on_disk = false;  // the file changed while there were unsaved edits
  std::string error_text;    // diagnostics of the last failed open, reload or save
  std::string status;        // last success message
};

// Buttons of the scene panel.
struct SceneFileActions {
  bool open = false;             // open path_field (a file or an embedded scene's name)
  bool save = false;             // write to file_path
  bool save_as = false;          // write to path_field
  bool reload = false;           // read file_path again
  std::string open_embedded;     // name of an embedded scene to open, or empty
  bool browse_open = false;      // "Open..." (Ctrl+O): the file browser
  bool browse_save = false;      // "Save as..." (Ctrl+Shift+S): the file browser
};
void scene_file_panel(SceneFileState& state, SceneFileActions& actions);

// The Open and Save-as dialog: the folder's subfolders (double-click or Enter to go in) and the
// files of the filter, the recent files, and for Open the embedded scenes; a name field that
// takes a file name or a path (Enter takes it, Esc cancels). Requests come back in `actions`.
struct FileBrowserView {
  bool save = false;                           // Save as (else Open)
  const FolderListing* listing = nullptr;
  const std::vector<std::string>* recent = nullptr;
  std::string* name_field = nullptr;           // edited in place
  std::string error;                           // why the last choice failed
};
struct FileBrowserActions {
  std::string go_to;     // a folder to list instead
  std::string chosen;    // the file to open or save to
  std::string embedded;  // an embedded scene to open
  bool cancel = false;
};
// Whether the dialog is showing; `open_now` opens it.
bool file_browser_dialog(bool open_now, const FileBrowserView& view, FileBrowserActions& actions);

// Where screenshots go.
struct ScreenshotState {
  std::string png_path = "phonglab.png";  // what is shown (exposure and sRGB applied)
  std::string pfm_path = "phonglab.pfm";  // the linear image, unclamped
  std::string status;                     // last result
};
struct ScreenshotActions {
  bool save_png = false;
  bool save_pfm = false;
};
void screenshot_panel(ScreenshotState& state, ScreenshotActions& actions);

// Figures for the stats overlay.
struct StatsView {
  double ui_frame_ms = 0;         // mean UI frame time over the last second
  double ui_frame_max_ms = 0;     // slowest UI frame in the last second
  double edit_to_image_ms = -1;   // last edit to the first image of it on screen; <0: none yet
  bool have_frame = false;        // an image is shown at all
  int level_divisor = 1;          // of the image shown
  bool level_quads = false;       // the image shown is the quad-shaded live rung
  int image_width = 0;            // pixels of the image shown
  int image_height = 0;
  std::uint32_t spp = 0;          // samples per pixel of the image shown
  int target_spp = 0;
  FrameStats frame;               // the renderer's figures for the image shown
  bool idle = false;              // renderer reached its target (or is capped while dragging)
  bool interacting = false;       // a drag is in progress
  std::string scene_error;        // non-empty: the last load failed (the old scene stays)
  bool details = false;           // the full table, not only the summary line
};
// The stats overlay's contents, drawn into the current window: one summary line, and with
// `details` the frame times, latency, pass figures, tracer and rays.
void stats_overlay(const StatsView& stats);

// Answer of the unsaved-changes and the changed-on-disk dialogs.
enum class GuardChoice : std::uint8_t { kNone, kSave, kSaveAs, kDiscard, kCancel, kOverwrite, kReload };

// What the unsaved-changes dialog knows.
struct GuardView {
  std::string action;             // what would lose the edits: "quit", "open other.json"
  bool can_save = false;          // Save writes the document's own file (not embedded, not an OBJ)
  bool changed_on_disk = false;   // the file changed outside since it was read: Save would overwrite that
};
// Call every frame. `open_now` opens it (on the frame the guarded action is asked for). Save is
// offered when the document has a file; Save as (to `save_as_path`, edited in the dialog) always.
// kNone while undecided or closed. Its buttons are located as guard.save, guard.save_as,
// guard.discard and guard.cancel (a test script clicks them as a user does).
GuardChoice unsaved_changes_modal(bool open_now, const GuardView& view, std::string& save_as_path);

// The offer of a recovery file at start: Restore, Discard, or Not now (kept for the next start).
enum class RecoveryChoice : std::uint8_t { kNone, kRestore, kDiscard, kLater };
// Call every frame while an offer waits. `source` names the scene, `saved` says when (text).
// Buttons: recovery.restore, recovery.discard, recovery.later.
RecoveryChoice recovery_modal(bool open_now, const std::string& source, const std::string& saved);

// Call every frame. Opens (with `open_now`) when Save finds that `file` changed on disk since it
// was read or written: Overwrite, Reload from disk (losing the edits) or Cancel (conflict.overwrite,
// conflict.reload, conflict.cancel).
GuardChoice changed_on_disk_modal(bool open_now, const std::string& file);

// What the Lessons panel shows.
struct LessonPanelView {
  const Lesson* lesson = nullptr;  // nullptr: none open
  LessonPlace place;
  bool exploring = false;          // something was changed since the step was shown
  bool presenting = false;         // presenter mode (full screen, panels hidden)
  std::string error;               // why the last open failed
};
// What it asks for; the app carries it out.
struct LessonActions {
  std::string open;  // an embedded lesson's name or the path field's file
  int go_to = -1;    // a step to show as written (0-based), -1: none
  bool next = false, prev = false;
  bool back = false;     // the current step again, as written
  bool present = false;  // presenter mode on or off
  bool close = false;
};
// The embedded lessons and a path field, the open lesson's steps, next and previous, presenter
// mode, and the way back from exploring. Nothing to edit.
void lessons_panel(const LessonPanelView& view, std::string& path_field, LessonActions& actions);

}  // namespace phonglab::ui
