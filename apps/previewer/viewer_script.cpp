// Test scripts: commands run from inside the main loop, so GUI tests drive the real program
// (input goes through ImGui exactly as the window system's would). See docs/previewer.md.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <cstdio>

#include "apps/previewer/script_words.h"
#include "apps/previewer/viewer_app.h"
#include "interaction/camera_control.h"
#include "interaction/scene_objects.h"

namespace phonglab {

using script::parse_double;
using script::parse_int;
using script::parse_vec3;

namespace {

constexpr double kDefaultWaitSeconds = 30;  // generous: sanitizer builds render slowly
constexpr int kBenchGapFrames = 10;         // frames between bench edits: the renderer is mid-pass again

// GLFW key code of a key name: one letter or digit, ESCAPE, F1, F11, SLASH, RIGHT, LEFT, SPACE,
// PAGE_UP or PAGE_DOWN.
int key_code(const std::string& name) {
  if (name == "F1") return GLFW_KEY_F1;
  if (name == "SLASH") return GLFW_KEY_SLASH;
  if (name.size() == 1) {
    const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
    if (c >= 'A' && c <= 'Z') return GLFW_KEY_A + (c - 'A');
    if (c >= '0' && c <= '9') return GLFW_KEY_0 + (c - '0');
  }
  if (name == "ESCAPE") return GLFW_KEY_ESCAPE;
  if (name == "RIGHT") return GLFW_KEY_RIGHT;
  if (name == "LEFT") return GLFW_KEY_LEFT;
  if (name == "SPACE") return GLFW_KEY_SPACE;
  if (name == "PAGE_UP") return GLFW_KEY_PAGE_UP;
  if (name == "PAGE_DOWN") return GLFW_KEY_PAGE_DOWN;
  if (name == "F11") return GLFW_KEY_F11;
  return -1;
}

int mouse_button(const std::string& name) {
  if (name == "left") return 0;
  if (name == "right") return 1;
  if (name == "middle") return 2;
  return -1;
}

}  // namespace

std::vector<ScriptCommand> parse_script(const std::string& text) {
  std::vector<ScriptCommand> commands;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    ScriptCommand command;
    command.line = number;
    for (std::string w; words >> w;) command.words.push_back(w);
    if (!command.words.empty()) commands.push_back(std::move(command));
  }
  return commands;
}

void Viewer::fail_script(const ScriptCommand& command, const std::string& message) {
  if (script_.lenient) {
    std::cerr << "phonglab: script line " << command.line << " (" << command.words.front() << "): " << message << " (skipped)\n";
    ++script_.ignored;
    script_.wait = ScriptWait::kNone;
    script_.item_action = ItemAction{};
    return;
  }
  std::cerr << "phonglab: script line " << command.line << " (" << command.words.front() << "): " << message << "\n";
  if (stats_.log) stats_.log << "script_error line " << command.line << ": " << message << "\n";
  script_.failed = true;
  quit_ = true;
}

void Viewer::push_drag(int button, ImVec2 from, ImVec2 to, int steps, bool shift, int held_key) {
  InputStep hover;
  hover.pos = from;
  hover.shift = shift;
  hover.key = held_key;  // held from before the press to the release
  hover.key_down = held_key >= 0;
  script_.input.push_back(hover);  // ImGui learns what is under the mouse before the press
  InputStep press = hover;
  press.buttons[button] = true;
  script_.input.push_back(press);
  for (int i = 1; i <= steps; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(steps);
    InputStep move = press;
    move.pos = ImVec2(from.x + (to.x - from.x) * t, from.y + (to.y - from.y) * t);
    script_.input.push_back(move);
  }
  InputStep release;
  release.pos = to;
  script_.input.push_back(release);
  if (held_key >= 0) {
    InputStep up = release;
    up.key = held_key;
    up.key_down = false;
    script_.input.push_back(up);
  }
}

void Viewer::push_click(ImVec2 at, bool ctrl) {
  InputStep hover;
  hover.pos = at;
  hover.ctrl = ctrl;
  script_.input.push_back(hover);  // ImGui learns what is under the mouse before the press
  InputStep press = hover;
  press.buttons[0] = true;
  script_.input.push_back(press);
  script_.input.push_back(hover);
}

bool Viewer::push_item_input() {
  const auto it = item_locations_.rects.find(script_.item_action.name);
  if (it == item_locations_.rects.end()) return false;
  const ImVec2 at((it->second.min.x + it->second.max.x) / 2, (it->second.min.y + it->second.max.y) / 2);
  if (script_.item_action.kind == ItemAction::Kind::kDrag) {
    push_drag(0, at, ImVec2(at.x + static_cast<float>(script_.item_action.dx), at.y + static_cast<float>(script_.item_action.dy)),
              script_.item_action.steps, false);
    return true;
  }
  push_click(at, script_.item_action.kind == ItemAction::Kind::kType);
  if (script_.item_action.kind == ItemAction::Kind::kType) {
    // A key pressed and released over the field (with Ctrl or not).
    const auto tap = [&](int key, bool ctrl) {
      InputStep step;
      step.pos = at;
      step.ctrl = ctrl;
      step.key = key;
      step.key_down = true;
      script_.input.push_back(step);
      step.key_down = false;
      script_.input.push_back(step);
    };
    tap(GLFW_KEY_A, true);  // Ctrl+A: a text field's text is selected too, so TEXT replaces it as in a slider's
    InputStep typed;
    typed.pos = at;
    typed.text = script_.item_action.text;
    script_.input.push_back(typed);
    tap(GLFW_KEY_ENTER, false);
  }
  InputStep after;
  after.pos = at;
  script_.input.push_back(after);
  return true;
}

void Viewer::step_script(double now) {
  ImGuiIO& io = ImGui::GetIO();
  if (!script_.input.empty()) {
    const InputStep step = script_.input.front();
    script_.input.pop_front();
    io.MousePos = step.pos;
    for (int b = 0; b < 3; ++b) io.MouseDown[b] = step.buttons[b];
    io.KeyShift = step.shift;
    io.KeyCtrl = step.ctrl;
    io.MouseWheel += step.wheel;
    if (step.key >= 0) io.KeysDown[step.key] = step.key_down;
    for (const char c : step.text) io.AddInputCharacter(static_cast<unsigned char>(c));
    platform_.note_event();
  }
  if (script_.stop_at > 0 && now >= script_.stop_at) {
    quit_ = true;
    return;
  }
  if (script_.auto_answer != ui::GuardChoice::kNone) {
    if (dialogs_.guard_visible) dialogs_.scripted_choice = script_.auto_answer;
    if (dialogs_.conflict_visible) dialogs_.scripted_choice = ui::GuardChoice::kCancel;
    if (recovery_.modal_visible) recovery_.scripted = static_cast<int>(ui::RecoveryChoice::kLater);
  }
  if (script_.failed || (script_.index >= script_.commands.size() && script_.wait == ScriptWait::kNone)) return;
  if (script_.wait != ScriptWait::kNone) {
    if (!script_wait_done(now)) return;
    script_.wait = ScriptWait::kNone;
  }
  while (script_.index < script_.commands.size() && script_.wait == ScriptWait::kNone && !script_.failed) {
    const ScriptCommand& command = script_.commands[script_.index++];
    if (stats_.log) {
      stats_.log << "script " << now * 1e3;
      for (const std::string& w : command.words) stats_.log << " " << w;
      stats_.log << "\n";
    }
    if (!run_script_command(command, now)) return;
  }
}

bool Viewer::script_wait_done(double now) {
  bool done = false;
  switch (script_.wait) {
    case ScriptWait::kNone: return true;
    case ScriptWait::kFrames: done = --script_.frames_left <= 0; break;
    case ScriptWait::kIdle:
      // A lesson's compare is done once its A is taken and the step itself is final.
      done = image_is_final() && !lessons_.awaiting_a() && !lesson_.applied;
      break;
    case ScriptWait::kImage:
      done = !upload_pending_ && drawn_serial_ > 0 && drawn_generation_ == renderer_.status().generation;
      break;
    case ScriptWait::kFile: {
      std::error_code ec;
      done = std::filesystem::exists(script_.file, ec);
      break;
    }
    case ScriptWait::kInput: done = script_.input.empty(); break;
    case ScriptWait::kItem:
      if (--script_.frames_left > 0) break;
      if (!push_item_input()) {
        fail_script(script_.commands[script_.index - 1], "no widget named '" + script_.item_action.name + "' was drawn (is its panel open?)");
        return false;
      }
      script_.wait = ScriptWait::kInput;  // now wait for the injected input to be used
      return false;
    case ScriptWait::kBench:
      if (script_.bench_waiting_image) {
        if (!script_.bench_expect_restart && drawn_generation_ >= script_.bench_generation && !upload_pending_) {
          script_.bench_waiting_image = false;
          script_.bench_gap_frames = kBenchGapFrames;
        }
      } else if (script_.bench_gap_frames > 0) {
        --script_.bench_gap_frames;
      } else if (script_.bench_left > 0) {
        --script_.bench_left;
        script_.bench_sign = -script_.bench_sign;
        const Scene& scene = session_.scene();
        if (script_.bench_kind == "camera") {
          Camera camera = scene.camera;
          ui::orbit(camera, 0.02 * script_.bench_sign, 0);
          move_camera(camera);
        } else if (!scene.materials.empty()) {
          const int k = std::clamp(selected_material_, 0, static_cast<int>(scene.materials.size()) - 1);
          Material m = scene.materials[static_cast<std::size_t>(k)];
          m.kd *= script_.bench_sign > 0 ? 1.25 : 0.8;  // exact inverses in turn: the scene stays put
          apply_edit({edit::SetMaterial{k, m}});
        }
        script_.bench_waiting_image = true;
        script_.bench_expect_restart = true;
      } else {
        done = true;
      }
      break;
  }
  if (done) return true;
  if (now > script_.deadline) {
    fail_script(script_.commands[script_.index - 1], "timed out");
  }
  return false;
}

// One command of a script being run: its words, when it started, and the ways it ends.
struct Viewer::ScriptStep {
  Viewer& viewer;
  const ScriptCommand& command;
  const std::vector<std::string>& w;
  double now;
  bool fail(const std::string& message) {
    viewer.fail_script(command, message);
    return false;
  }
  // Waits for `kind`, with the timeout in word `timeout_word` when there is one.
  bool wait_for(ScriptWait kind, std::size_t timeout_word) {
    double timeout = kDefaultWaitSeconds;
    if (w.size() > timeout_word && !parse_double(w[timeout_word], timeout)) return fail("bad timeout");
    viewer.script_.wait = kind;
    viewer.script_.deadline = now + timeout;
    return true;
  }
};

// Waits: for frames, the renderer, an image, a file, and the edit benchmark. nullopt: not one of them.
std::optional<bool> Viewer::script_wait_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "wait_frames") {
    int frames = 0;
    if (w.size() != 2 || !parse_int(w[1], frames)) return step.fail("usage: wait_frames N");
    script_.frames_left = frames;
    return step.wait_for(ScriptWait::kFrames, 99);
  }
  if (name == "wait_idle") return step.wait_for(ScriptWait::kIdle, 1);
  if (name == "wait_image") return step.wait_for(ScriptWait::kImage, 1);
  if (name == "wait_file") {
    if (w.size() < 2) return step.fail("usage: wait_file FILE [TIMEOUT]");
    script_.file = w[1];
    return step.wait_for(ScriptWait::kFile, 2);
  }
  if (name == "bench_edits") {
    int count = 0;
    if (w.size() != 3 || !parse_int(w[1], count) || count < 1 || (w[2] != "material" && w[2] != "camera")) {
      return step.fail("usage: bench_edits N material|camera");
    }
    script_.bench_left = count;
    script_.bench_kind = w[2];
    script_.bench_gap_frames = 0;
    script_.bench_waiting_image = false;
    script_.wait = ScriptWait::kBench;
    script_.deadline = step.now + 10.0 * count + kDefaultWaitSeconds;
    return true;
  }
  return std::nullopt;
}

// Real input: drags, clicks, scrolls, keys, probes, the window size. nullopt: not one of them.
std::optional<bool> Viewer::script_input_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "drag") {
    // drag BUTTON X0 Y0 X1 Y1 [STEPS] [shift]
    int button = w.size() >= 6 ? mouse_button(w[1]) : -1;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int steps = 10;
    if (button < 0 || !parse_double(w[2], x0) || !parse_double(w[3], y0) || !parse_double(w[4], x1) ||
        !parse_double(w[5], y1) || (w.size() > 6 && !parse_int(w[6], steps)) || steps < 1) {
      return step.fail("usage: drag left|right|middle X0 Y0 X1 Y1 [STEPS] [shift]");
    }
    const bool shift = w.size() > 7 && w[7] == "shift";
    push_drag(button, ImVec2(static_cast<float>(x0), static_cast<float>(y0)),
              ImVec2(static_cast<float>(x1), static_cast<float>(y1)), steps, shift);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "drag_light") {
    // drag_light I DX DY [STEPS]: grabs light I's marker where it is drawn and drags it by
    // (DX, DY), in STEPS frames (10).
    int index = -1;
    double dx = 0, dy = 0;
    int steps = 10;
    const std::vector<Light>& lights = doc_.scene().lights;
    if ((w.size() != 4 && w.size() != 5) || !parse_int(w[1], index) || !parse_double(w[2], dx) ||
        !parse_double(w[3], dy) || index < 0 || index >= static_cast<int>(lights.size()) ||
        (w.size() == 5 && (!parse_int(w[4], steps) || steps < 1))) {
      return step.fail("usage: drag_light I DX DY [STEPS]");
    }
    // Where its marker (or its arrow at the edge) was drawn last frame: what a user would grab.
    const auto marker = std::find_if(markers_.begin(), markers_.end(),
                                     [&](const ui::LightMarker& m) { return m.index == index; });
    if (marker == markers_.end()) return step.fail("light " + w[1] + " has no marker (behind the camera, or not a point light)");
    const ImVec2 from = marker->pos;
    push_drag(0, from, ImVec2(from.x + static_cast<float>(dx), from.y + static_cast<float>(dy)), steps, false);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "drag_object") {
    // drag_object I DX DY [x|y|z|v]: selects object I, grabs it by its marker (where it is drawn)
    // and drags by DX, DY pixels, the axis key (or V, up and down) held for a constrained move.
    int index = -1, axis_key = -1;
    double dx = 0, dy = 0;
    if ((w.size() != 4 && w.size() != 5) || !parse_int(w[1], index) || !parse_double(w[2], dx) || !parse_double(w[3], dy)) {
      return step.fail("usage: drag_object I DX DY [x|y|z|v]");
    }
    if (w.size() == 5) {
      if (w[4] != "x" && w[4] != "y" && w[4] != "z" && w[4] != "v") return step.fail("usage: drag_object I DX DY [x|y|z|v]");
      axis_key = w[4] == "v" ? GLFW_KEY_V : GLFW_KEY_X + (w[4][0] - 'x');
    }
    // No such object, or none to grab on screen: the program says so, as for a refused edit.
    if (index < 0 || index >= ui::object_count(doc_.scene())) {
      refuse("no objects[" + w[1] + "]");
      return true;
    }
    select_object(index);
    const std::optional<ImVec2> from = object_screen_point(index);
    if (!from) {
      refuse("objects[" + w[1] + "] is behind the camera: nothing to grab");
      return true;
    }
    push_drag(0, *from, ImVec2(from->x + static_cast<float>(dx), from->y + static_cast<float>(dy)), 12, false, axis_key);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "click" || name == "scroll") {
    double x = 0, y = 0, amount = 0;
    if (w.size() < 3 || !parse_double(w[1], x) || !parse_double(w[2], y) ||
        (name == "scroll" && (w.size() != 4 || !parse_double(w[3], amount)))) {
      return step.fail("usage: click X Y | scroll X Y CLICKS");
    }
    const ImVec2 at(static_cast<float>(x), static_cast<float>(y));
    if (name == "click") {
      push_click(at, false);
    } else {
      InputStep hover;
      hover.pos = at;
      script_.input.push_back(hover);
      InputStep act = hover;
      act.wheel = static_cast<float>(amount);
      script_.input.push_back(act);
      script_.input.push_back(hover);
    }
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "key") {
    const int key = w.size() >= 2 ? key_code(w[1]) : -1;
    if (key < 0) return step.fail("usage: key F|R|H|ESCAPE|<letter> [ctrl] [shift]");
    InputStep press;
    press.pos = ImGui::GetIO().MousePos;
    for (std::size_t i = 2; i < w.size(); ++i) {
      if (w[i] == "ctrl") press.ctrl = true;
      else if (w[i] == "shift") press.shift = true;
      else return step.fail("usage: key F|R|H|ESCAPE|<letter> [ctrl] [shift]");
    }
    press.key = key;
    press.key_down = true;
    InputStep release = press;
    release.key_down = false;
    script_.input.push_back(press);
    script_.input.push_back(release);
    // The press also arrives as a key event, as GLFW's callback delivers it (the viewer's
    // shortcuts read events; ImGui's widgets read the key state above).
    platform_.push_key_press(KeyPress{key, (press.ctrl ? GLFW_MOD_CONTROL : 0) | (press.shift ? GLFW_MOD_SHIFT : 0)});
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "probe" || name == "ctrl_click") {
    double x = 0, y = 0;
    if (w.size() != 3 || !parse_double(w[1], x) || !parse_double(w[2], y)) return step.fail("usage: probe|ctrl_click X Y");
    const ImVec2 at(static_cast<float>(x), static_cast<float>(y));
    if (name == "probe") {
      probe_at(at);
      if (!probed_.tree) return step.fail("nothing to probe (no scene yet)");
      return true;
    }
    push_click(at, true);
    InputStep after;  // Ctrl released again
    after.pos = at;
    script_.input.push_back(after);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "resize") {
    int width = 0, height = 0;
    if (w.size() != 3 || !parse_int(w[1], width) || !parse_int(w[2], height) || width < 1 || height < 1) {
      return step.fail("usage: resize W H");
    }
    glfwSetWindowSize(platform_.window(), width, height);
    return true;
  }
  return std::nullopt;
}

// Widgets found by name, edits (set, undo, redo, solo). nullopt: not one of them.
std::optional<bool> Viewer::script_item_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "undo" || name == "redo" || name == "snapshot_a") {
    if (name == "undo") undo();
    else if (name == "redo") redo();
    else snapshot_a();
    return true;
  }
  if (name == "solo") {
    int index = 0;
    if (w.size() != 2 || !parse_int(w[1], index) || index < 0 ||
        index >= static_cast<int>(doc_.scene().lights.size())) {
      return step.fail("usage: solo I");
    }
    Scene soloed = session_.scene();
    ui::toggle_solo(soloed.lights, solo_, index);
    apply_edit({edit::SetScene{std::move(soloed)}});
    return true;
  }
  if (name == "set") {
    if (!script_set(w)) return step.fail("usage: set material NAME ka|kd|ks|kr|kt|n|ior|fresnel V.. | set light I "
                                    "position|direction|intensity|enabled V.. | set camera position|look_at|up|fov V.. | "
                                    "set render target_spp|resolution_scale|threads|live_images_per_s|tree_budget_mib|term V | set display exposure|srgb|stats V | "
                                    "set instruments probe_mode|multiples|compare|wipe|gain|head|head_angle|ray_tree|tree_shadows|"
                                    "tree_secondary|tree_arrows|tree_legend|depth_cut|heat V");
    return true;
  }
  if (name == "show_item") {
    // show_item NAME: scrolls the sidebar until the widget is in view (nothing is clicked).
    if (w.size() != 2) return step.fail("usage: show_item NAME");
    item_locations_.scroll_to = w[1];
    script_.frames_left = 3;
    return step.wait_for(ScriptWait::kFrames, 99);
  }
  if (name == "click_item" || name == "drag_item" || name == "type_item") {
    // Real (injected) mouse input on a widget found by name (docs/previewer.md lists the names):
    // click_item NAME | drag_item NAME DX DY [STEPS] | type_item NAME TEXT (Ctrl+click, which turns
    // a slider or drag field into a text field with its text selected, then TEXT and Enter).
    // The sidebar first scrolls the widget into view, as a user would.
    ItemAction action;
    action.name = w.size() > 1 ? w[1] : "";
    bool ok = w.size() == 2 && name == "click_item";
    if (name == "drag_item") {
      action.kind = ItemAction::Kind::kDrag;
      ok = (w.size() == 4 || w.size() == 5) && parse_double(w[2], action.dx) && parse_double(w[3], action.dy) &&
           (w.size() == 4 || parse_int(w[4], action.steps)) && action.steps >= 1;
    } else if (name == "type_item") {
      action.kind = ItemAction::Kind::kType;
      ok = w.size() == 3;
      if (ok) action.text = w[2];
    }
    if (!ok) return step.fail("usage: click_item NAME | drag_item NAME DX DY [STEPS] | type_item NAME TEXT");
    script_.item_action = action;
    item_locations_.scroll_to = action.name;
    script_.frames_left = 3;  // the scroll lands, the widget is drawn where it will be clicked
    return step.wait_for(ScriptWait::kItem, 99);
  }
  return std::nullopt;
}

// Files: figures, screenshots, images, scenes, dialogs, dump_state. nullopt: not one of them.
std::optional<bool> Viewer::script_file_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "figure") {
    if (w.size() != 2) return step.fail("usage: figure FILE.png");
    save_figure(w[1]);
    if (figure_status_.rfind("saved ", 0) != 0) return step.fail(figure_status_);
    return true;
  }
  if (name == "screenshot") {
    if (w.size() != 2) return step.fail("usage: screenshot FILE.png");
    script_.screenshot = w[1];
    // Taken when this frame is drawn: later commands wait for the next frame so they
    // cannot change what it shows (or resize the window under it).
    script_.frames_left = 1;
    return step.wait_for(ScriptWait::kFrames, 99);
  }
  if (name == "save_png" || name == "save_pfm") {
    if (w.size() != 2) return step.fail("usage: save_png|save_pfm FILE");
    if (name == "save_png") save_png(w[1]);
    else save_pfm(w[1]);
    if (screenshot_state_.status.rfind("saved ", 0) != 0) return step.fail(screenshot_state_.status);
    return true;
  }
  if (name == "open") {
    if (w.size() != 2) return step.fail("usage: open SCENE");
    request(PendingAction{PendingAction::Kind::kOpen, w[1]});
    return true;
  }
  if (name == "save_as") {
    if (w.size() != 2) return step.fail("usage: save_as FILE");
    file_state_.path_field = w[1];
    save_scene(true);
    if (doc_.dirty()) return step.fail(file_state_.error_text);
    return true;
  }
  if (name == "close") {
    glfwSetWindowShouldClose(platform_.window(), GLFW_TRUE);  // as the window manager's close button
    return true;
  }
  if (name == "modal") {
    constexpr const char* kUsage = "usage: modal save|save_as|discard|cancel|overwrite|reload (the recovery offer: restore|discard|later)";
    if (w.size() != 2) return step.fail(kUsage);
    if (recovery_.modal_visible && !dialogs_.guard_visible && !dialogs_.conflict_visible) {
      if (w[1] == "restore") recovery_.scripted = static_cast<int>(ui::RecoveryChoice::kRestore);
      else if (w[1] == "discard") recovery_.scripted = static_cast<int>(ui::RecoveryChoice::kDiscard);
      else if (w[1] == "later") recovery_.scripted = static_cast<int>(ui::RecoveryChoice::kLater);
      else return step.fail(kUsage);
      return true;
    }
    if (!dialogs_.guard_visible && !dialogs_.conflict_visible) return step.fail("no unsaved-changes, changed-on-disk or recovery dialog is open");
    if (w[1] == "save") dialogs_.scripted_choice = ui::GuardChoice::kSave;
    else if (w[1] == "save_as") dialogs_.scripted_choice = ui::GuardChoice::kSaveAs;
    else if (w[1] == "discard") dialogs_.scripted_choice = ui::GuardChoice::kDiscard;
    else if (w[1] == "cancel") dialogs_.scripted_choice = ui::GuardChoice::kCancel;
    else if (w[1] == "overwrite") dialogs_.scripted_choice = ui::GuardChoice::kOverwrite;
    else if (w[1] == "reload") dialogs_.scripted_choice = ui::GuardChoice::kReload;
    else return step.fail(kUsage);
    return true;
  }
  if (name == "save") {
    // The Save button, through the same checks: a file changed on disk opens its dialog, a
    // refusal (an embedded scene, an OBJ) shows in the Scene panel and in dump_state's error.
    if (w.size() != 1) return step.fail("usage: save");
    save_scene(false);
    return true;
  }
  if (name == "dump_state") {
    if (w.size() != 2) return step.fail("usage: dump_state FILE");
    write_state(w[1]);
    return true;
  }
  if (name == "touch") {
    if (w.size() != 2) return step.fail("usage: touch FILE");
    std::ofstream(w[1]) << "\n";
    return true;
  }
  return std::nullopt;
}

// The script itself: log lines, statistics, fail and quit. nullopt: not one of them.
std::optional<bool> Viewer::script_other_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "log") {
    std::string text;
    for (std::size_t i = 1; i < w.size(); ++i) text += (i > 1 ? " " : "") + w[i];
    std::cerr << "phonglab script: " << text << "\n";
    return true;
  }
  if (name == "stats_reset") {
    stats_.busy_frame_ms.clear();
    stats_.latencies_ms.clear();
    stats_.pass_mrays.clear();
    stats_.frames_at_level.clear();
    stats_.full_pending.clear();
    stats_.edit_to_full_ms.clear();
    return true;
  }
  if (name == "stats_summary") {
    write_stats_summary(w.size() > 1 ? w[1] : "script");
    return true;
  }
  if (name == "fail") {
    std::string text;
    for (std::size_t i = 1; i < w.size(); ++i) text += (i > 1 ? " " : "") + w[i];
    return step.fail(text.empty() ? "fail command reached" : text);
  }
  if (name == "quit") {
    quit_ = true;
    return true;
  }
  if (name == "lenient") {
    if (w.size() != 2 || (w[1] != "0" && w[1] != "1")) return step.fail("usage: lenient 0|1");
    script_.lenient = w[1] == "1";
    return true;
  }
  if (name == "auto_modal") {
    if (w.size() != 2 || (w[1] != "discard" && w[1] != "off")) return step.fail("usage: auto_modal discard|off");
    script_.auto_answer = w[1] == "discard" ? ui::GuardChoice::kDiscard : ui::GuardChoice::kNone;
    return true;
  }
  if (name == "stop_after") {
    double s = 0;
    if (w.size() != 2 || !parse_double(w[1], s) || s <= 0) return step.fail("usage: stop_after SECONDS");
    script_.stop_at = step.now + s;
    return true;
  }
  return std::nullopt;
}

bool Viewer::run_script_command(const ScriptCommand& command, double now) {
  ScriptStep step{*this, command, command.words, now};
  if (const std::optional<std::string> error = script_scene_command(command.words)) {
    return error->empty() ? true : step.fail(*error);
  }
  if (const std::optional<std::string> error = script_lesson_command(command.words)) {
    return error->empty() ? true : step.fail(*error);
  }
  for (const auto group : {&Viewer::script_wait_command, &Viewer::script_input_command, &Viewer::script_item_command,
                           &Viewer::script_file_command, &Viewer::script_other_command}) {
    if (const std::optional<bool> done = (this->*group)(step)) return *done;
  }
  return step.fail("unknown command");
}

}  // namespace phonglab
