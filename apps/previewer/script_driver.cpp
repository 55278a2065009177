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

#include "apps/previewer/script_step.h"
#include "apps/previewer/script_words.h"
#include "apps/previewer/viewer_app.h"
#include "interaction/camera_control.h"
#include "interaction/scene_objects.h"

namespace phonglab {

using script::parse_double;
using script::parse_int;
using script::parse_vec3;

namespace {

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

void ScriptDriver::fail_script(const ScriptCommand& command, const std::string& message) {
  if (run_.lenient) {
    std::cerr << "phonglab: script line " << command.line << " (" << command.words.front() << "): " << message << " (skipped)\n";
    ++run_.ignored;
    run_.wait = ScriptWait::kNone;
    run_.item_action = ItemAction{};
    return;
  }
  std::cerr << "phonglab: script line " << command.line << " (" << command.words.front() << "): " << message << "\n";
  if (s_.stats.log) s_.stats.log << "script_error line " << command.line << ": " << message << "\n";
  run_.failed = true;
  s_.quit = true;
}

void ScriptDriver::push_drag(int button, ImVec2 from, ImVec2 to, int steps, bool shift, int held_key) {
  InputStep hover;
  hover.pos = from;
  hover.shift = shift;
  hover.key = held_key;  // held from before the press to the release
  hover.key_down = held_key >= 0;
  run_.input.push_back(hover);  // ImGui learns what is under the mouse before the press
  InputStep press = hover;
  press.buttons[button] = true;
  run_.input.push_back(press);
  for (int i = 1; i <= steps; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(steps);
    InputStep move = press;
    move.pos = ImVec2(from.x + (to.x - from.x) * t, from.y + (to.y - from.y) * t);
    run_.input.push_back(move);
  }
  InputStep release;
  release.pos = to;
  run_.input.push_back(release);
  if (held_key >= 0) {
    InputStep up = release;
    up.key = held_key;
    up.key_down = false;
    run_.input.push_back(up);
  }
}

void ScriptDriver::push_click(ImVec2 at, bool ctrl) {
  InputStep hover;
  hover.pos = at;
  hover.ctrl = ctrl;
  run_.input.push_back(hover);  // ImGui learns what is under the mouse before the press
  InputStep press = hover;
  press.buttons[0] = true;
  run_.input.push_back(press);
  run_.input.push_back(hover);
}

bool ScriptDriver::push_item_input() {
  const auto it = s_.item_locations.rects.find(run_.item_action.name);
  if (it == s_.item_locations.rects.end()) return false;
  const ImVec2 at((it->second.min.x + it->second.max.x) / 2, (it->second.min.y + it->second.max.y) / 2);
  if (run_.item_action.kind == ItemAction::Kind::kDrag) {
    push_drag(0, at, ImVec2(at.x + static_cast<float>(run_.item_action.dx), at.y + static_cast<float>(run_.item_action.dy)),
              run_.item_action.steps, false);
    return true;
  }
  push_click(at, run_.item_action.kind == ItemAction::Kind::kType);
  if (run_.item_action.kind == ItemAction::Kind::kType) {
    // A key pressed and released over the field (with Ctrl or not).
    const auto tap = [&](int key, bool ctrl) {
      InputStep step;
      step.pos = at;
      step.ctrl = ctrl;
      step.key = key;
      step.key_down = true;
      run_.input.push_back(step);
      step.key_down = false;
      run_.input.push_back(step);
    };
    tap(GLFW_KEY_A, true);  // Ctrl+A: a text field's text is selected too, so TEXT replaces it as in a slider's
    InputStep typed;
    typed.pos = at;
    typed.text = run_.item_action.text;
    run_.input.push_back(typed);
    tap(GLFW_KEY_ENTER, false);
  }
  InputStep after;
  after.pos = at;
  run_.input.push_back(after);
  return true;
}

void ScriptDriver::step_script(double now) {
  ImGuiIO& io = ImGui::GetIO();
  if (!run_.input.empty()) {
    const InputStep step = run_.input.front();
    run_.input.pop_front();
    io.MousePos = step.pos;
    for (int b = 0; b < 3; ++b) io.MouseDown[b] = step.buttons[b];
    io.KeyShift = step.shift;
    io.KeyCtrl = step.ctrl;
    io.MouseWheel += step.wheel;
    if (step.key >= 0) io.KeysDown[step.key] = step.key_down;
    for (const char c : step.text) io.AddInputCharacter(static_cast<unsigned char>(c));
    s_.platform.note_event();
  }
  if (run_.stop_at > 0 && now >= run_.stop_at) {
    s_.quit = true;
    return;
  }
  if (!run_.auto_answer.empty() && run_.input.empty()) {
    // `auto_modal`: a dialog that opens is answered with a click on its button, as a user would.
    std::string name;
    if (files_.guard_visible()) name = "guard." + run_.auto_answer;
    else if (files_.conflict_visible()) name = "conflict.cancel";
    else if (files_.recovery().modal_visible) name = "recovery.later";
    if (!name.empty()) {
      const ItemAction saved = run_.item_action;
      run_.item_action = ItemAction{};
      run_.item_action.name = name;
      push_item_input();
      run_.item_action = saved;
    }
  }
  if (run_.failed || (run_.index >= run_.commands.size() && run_.wait == ScriptWait::kNone)) return;
  if (run_.wait != ScriptWait::kNone) {
    if (!script_wait_done(now)) return;
    run_.wait = ScriptWait::kNone;
  }
  while (run_.index < run_.commands.size() && run_.wait == ScriptWait::kNone && !run_.failed) {
    const ScriptCommand& command = run_.commands[run_.index++];
    if (s_.stats.log) {
      s_.stats.log << "script " << now * 1e3;
      for (const std::string& w : command.words) s_.stats.log << " " << w;
      s_.stats.log << "\n";
    }
    if (!run_script_command(command, now)) return;
  }
}

bool ScriptDriver::script_wait_done(double now) {
  bool done = false;
  switch (run_.wait) {
    case ScriptWait::kNone: return true;
    case ScriptWait::kFrames: done = --run_.frames_left <= 0; break;
    case ScriptWait::kIdle:
      // A lesson's compare is done once its A is taken and the step itself is final.
      done = image_is_final(s_) && !s_.lessons.awaiting_a() && !lesson_shell_.state().applied &&
             formulas_.check_settled();
      break;
    case ScriptWait::kImage:
      done = !s_.upload_pending && s_.drawn_serial > 0 && s_.drawn_generation == s_.renderer.status().generation;
      break;
    case ScriptWait::kFile: {
      std::error_code ec;
      done = std::filesystem::exists(run_.file, ec);
      break;
    }
    case ScriptWait::kInput: done = run_.input.empty(); break;
    case ScriptWait::kItem:
      if (--run_.frames_left > 0) break;
      if (!push_item_input()) {
        fail_script(run_.commands[run_.index - 1], "no widget named '" + run_.item_action.name + "' was drawn (is its panel open?)");
        return false;
      }
      run_.wait = ScriptWait::kInput;  // now wait for the injected input to be used
      return false;
    case ScriptWait::kBench:
      if (run_.bench_waiting_image) {
        // The edit's restart, read from the renderer (the edit may wait for the last image).
        const std::uint64_t generation = s_.renderer.status().generation;
        if (run_.bench_expect_restart && generation > run_.bench_before) {
          run_.bench_generation = generation;
          run_.bench_expect_restart = false;
        }
        if (!run_.bench_expect_restart && s_.drawn_generation >= run_.bench_generation && !s_.upload_pending) {
          run_.bench_waiting_image = false;
          run_.bench_gap_frames = kBenchGapFrames;
        }
      } else if (run_.bench_gap_frames > 0) {
        --run_.bench_gap_frames;
      } else if (run_.bench_left > 0) {
        --run_.bench_left;
        run_.bench_sign = -run_.bench_sign;
        run_.bench_before = s_.renderer.status().generation;
        const Scene& scene = s_.session.scene();
        if (run_.bench_kind == "camera") {
          Camera camera = scene.camera;
          ui::orbit(camera, 0.02 * run_.bench_sign, 0);
          move_camera(s_, camera);
        } else if (!scene.materials.empty()) {
          const int k = std::clamp(s_.selected_material, 0, static_cast<int>(scene.materials.size()) - 1);
          Material m = scene.materials[static_cast<std::size_t>(k)];
          m.kd *= run_.bench_sign > 0 ? 1.25 : 0.8;  // exact inverses in turn: the scene stays put
          apply_edit(s_, {edit::SetMaterial{k, m}});
        }
        run_.bench_waiting_image = true;
        run_.bench_expect_restart = true;
      } else {
        done = true;
      }
      break;
  }
  if (done) return true;
  if (now > run_.deadline) {
    fail_script(run_.commands[run_.index - 1], "timed out");
  }
  return false;
}

// One command of a script being run: its words, when it started, and the ways it ends.
// Waits: for frames, the renderer, an image, a file, and the edit benchmark. nullopt: not one of them.
std::optional<bool> ScriptDriver::script_wait_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "wait_frames") {
    int frames = 0;
    if (w.size() != 2 || !parse_int(w[1], frames)) return step.fail("usage: wait_frames N");
    run_.frames_left = frames;
    return step.wait_for(ScriptWait::kFrames, 99);
  }
  if (name == "wait_idle") return step.wait_for(ScriptWait::kIdle, 1);
  if (name == "wait_image") return step.wait_for(ScriptWait::kImage, 1);
  if (name == "wait_file") {
    if (w.size() < 2) return step.fail("usage: wait_file FILE [TIMEOUT]");
    run_.file = w[1];
    return step.wait_for(ScriptWait::kFile, 2);
  }
  if (name == "bench_edits") {
    int count = 0;
    if (w.size() != 3 || !parse_int(w[1], count) || count < 1 || (w[2] != "material" && w[2] != "camera")) {
      return step.fail("usage: bench_edits N material|camera");
    }
    run_.bench_left = count;
    run_.bench_kind = w[2];
    run_.bench_gap_frames = 0;
    run_.bench_waiting_image = false;
    run_.wait = ScriptWait::kBench;
    run_.deadline = step.now + 10.0 * count + kDefaultWaitSeconds;
    return true;
  }
  return std::nullopt;
}

// Real input: drags, clicks, scrolls, keys, probes, the window size. nullopt: not one of them.
std::optional<bool> ScriptDriver::script_input_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
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
      run_.input.push_back(hover);
      InputStep act = hover;
      act.wheel = static_cast<float>(amount);
      run_.input.push_back(act);
      run_.input.push_back(hover);
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
    run_.input.push_back(press);
    run_.input.push_back(release);
    // The press also arrives as a key event, as GLFW's callback delivers it (the viewer's
    // shortcuts read events; ImGui's widgets read the key state above).
    s_.platform.push_key_press(KeyPress{key, (press.ctrl ? GLFW_MOD_CONTROL : 0) | (press.shift ? GLFW_MOD_SHIFT : 0)});
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "probe" || name == "ctrl_click") {
    double x = 0, y = 0;
    if (w.size() != 3 || !parse_double(w[1], x) || !parse_double(w[2], y)) return step.fail("usage: probe|ctrl_click X Y");
    const ImVec2 at(static_cast<float>(x), static_cast<float>(y));
    if (name == "probe") {
      tools_.probe_at(at);
      if (!tools_.probe().tree) return step.fail("nothing to probe (no scene yet)");
      return true;
    }
    push_click(at, true);
    InputStep after;  // Ctrl released again
    after.pos = at;
    run_.input.push_back(after);
    return step.wait_for(ScriptWait::kInput, 99);
  }
  if (name == "resize") {
    int width = 0, height = 0;
    if (w.size() != 3 || !parse_int(w[1], width) || !parse_int(w[2], height) || width < 1 || height < 1) {
      return step.fail("usage: resize W H");
    }
    s_.platform.set_window_size(width, height);
    return true;
  }
  return std::nullopt;
}

// Widgets found by name, edits (set, undo, redo, solo). nullopt: not one of them.
std::optional<bool> ScriptDriver::script_item_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "undo" || name == "redo" || name == "snapshot_a") {
    if (name == "undo") builder_.undo();
    else if (name == "redo") builder_.redo();
    else tools_.snapshot_a();
    return true;
  }
  if (name == "check_image" || name == "close_image") {
    // check_image PATH: a student's image of the view checked (a refusal is in dump_state's
    // image_check_error, not a broken script); close_image: back to the live image.
    if (name == "close_image") {
      formulas_.close_image();
      return true;
    }
    if (w.size() != 2) return step.fail("usage: check_image PATH");
    formulas_.open_image(w[1]);
    return true;
  }
  if (name == "save_formulas" || name == "open_formulas") {
    // save_formulas|open_formulas [PATH]: the Formula panel's file buttons (a refusal is in
    // dump_state's formula_file_status, not a broken script).
    if (w.size() > 2) return step.fail("usage: " + name + " [PATH]");
    const std::string path = w.size() == 2 ? w[1] : "";
    if (name == "save_formulas") formulas_.save_formulas(path);
    else formulas_.open_formulas(path);
    return true;
  }
  if (name == "formula" || name == "formula_view") {
    // formula SLOT TEXT...: the slot's text as typed (the words joined by spaces; "" clears it);
    // formula_view yours|reference|difference.
    if (name == "formula_view") {
      if (w.size() != 2 || !formulas_.set_view(w[1])) return step.fail("usage: formula_view yours|reference|difference");
      return true;
    }
    const std::optional<FormulaSlot> slot = w.size() >= 2 ? formula_slot_from_name(w[1]) : std::nullopt;
    if (!slot) return step.fail("usage: formula ambient|diffuse|specular TEXT...");
    std::string text;
    for (std::size_t i = 2; i < w.size(); ++i) text += (i > 2 ? " " : "") + w[i];
    if (text == "\"\"") text.clear();
    formulas_.set_text(*slot, text);
    return true;
  }
  if (name == "solo") {
    int index = 0;
    if (w.size() != 2 || !parse_int(w[1], index) || index < 0 ||
        index >= static_cast<int>(s_.doc.scene().lights.size())) {
      return step.fail("usage: solo I");
    }
    Scene soloed = s_.session.scene();
    ui::toggle_solo(soloed.lights, s_.solo, index);
    apply_edit(s_, {edit::SetScene{std::move(soloed)}});
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
    s_.item_locations.scroll_to = w[1];
    run_.frames_left = 3;
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
    run_.item_action = action;
    s_.item_locations.scroll_to = action.name;
    run_.frames_left = 3;  // the scroll lands, the widget is drawn where it will be clicked
    return step.wait_for(ScriptWait::kItem, 99);
  }
  return std::nullopt;
}

// Files: figures, screenshots, images, scenes, dialogs, dump_state. nullopt: not one of them.
std::optional<bool> ScriptDriver::script_file_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "figure") {
    if (w.size() != 2) return step.fail("usage: figure FILE.png");
    tools_.save_figure(w[1]);
    if (s_.figure_status.rfind("saved ", 0) != 0) return step.fail(s_.figure_status);
    return true;
  }
  if (name == "screenshot") {
    if (w.size() != 2) return step.fail("usage: screenshot FILE.png");
    run_.screenshot = w[1];
    // Taken when this frame is drawn: later commands wait for the next frame so they
    // cannot change what it shows (or resize the window under it).
    run_.frames_left = 1;
    return step.wait_for(ScriptWait::kFrames, 99);
  }
  if (name == "save_png" || name == "save_pfm") {
    if (w.size() != 2) return step.fail("usage: save_png|save_pfm FILE");
    if (name == "save_png") files_.save_png(w[1]);
    else files_.save_pfm(w[1]);
    if (files_.screenshot_state().status.rfind("saved ", 0) != 0) return step.fail(files_.screenshot_state().status);
    return true;
  }
  if (name == "open") {
    if (w.size() != 2) return step.fail("usage: open SCENE");
    files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kOpen, w[1]});
    return true;
  }
  if (name == "save_as") {
    if (w.size() != 2) return step.fail("usage: save_as FILE");
    files_.file_state().path_field = w[1];
    files_.save_scene(true);
    if (s_.doc.dirty()) return step.fail(files_.file_state().error_text);
    return true;
  }
  if (name == "close") {
    s_.platform.request_close();  // as the window manager's close button
    return true;
  }
  if (name == "modal") {
    // The open dialog's button, clicked as a user would (its name as the dialog locates it).
    constexpr const char* kUsage = "usage: modal save|save_as|discard|cancel|overwrite|reload (the recovery offer: restore|discard|later)";
    if (w.size() != 2) return step.fail(kUsage);
    const bool recovery = files_.recovery().modal_visible && !files_.guard_visible() && !files_.conflict_visible();
    if (!recovery && !files_.guard_visible() && !files_.conflict_visible()) {
      return step.fail("no unsaved-changes, changed-on-disk or recovery dialog is open");
    }
    const std::string& a = w[1];
    const bool known = recovery ? (a == "restore" || a == "discard" || a == "later")
                       : files_.conflict_visible() ? (a == "overwrite" || a == "reload" || a == "cancel")
                                                   : (a == "save" || a == "save_as" || a == "discard" || a == "cancel");
    if (!known) return step.fail(kUsage);
    run_.item_action = ItemAction{};
    run_.item_action.name = (recovery ? "recovery." : files_.conflict_visible() ? "conflict." : "guard.") + a;
    run_.frames_left = 1;
    return step.wait_for(ScriptWait::kItem, 99);
  }
  if (name == "save") {
    // The Save button, through the same checks: a file changed on disk opens its dialog, a
    // refusal (an embedded scene, an OBJ) shows in the Scene panel and in dump_state's error.
    if (w.size() != 1) return step.fail("usage: save");
    files_.save_scene(false);
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
std::optional<bool> ScriptDriver::script_other_command(ScriptStep& step) {
  const std::vector<std::string>& w = step.w;
  const std::string& name = w[0];
  if (name == "log") {
    std::string text;
    for (std::size_t i = 1; i < w.size(); ++i) text += (i > 1 ? " " : "") + w[i];
    std::cerr << "phonglab script: " << text << "\n";
    return true;
  }
  if (name == "stats_reset") {
    s_.stats.busy_frame_ms.clear();
    s_.stats.latencies_ms.clear();
    s_.stats.pass_mrays.clear();
    s_.stats.frames_at_level.clear();
    s_.stats.full_pending.clear();
    s_.stats.edit_to_full_ms.clear();
    s_.stats.cpu_mark = CpuClock::now();
    s_.stats.frames_drawn = 0;
    return true;
  }
  if (name == "stats_summary") {
    write_stats_summary(s_.stats, w.size() > 1 ? w[1] : "script");
    return true;
  }
  if (name == "fail") {
    std::string text;
    for (std::size_t i = 1; i < w.size(); ++i) text += (i > 1 ? " " : "") + w[i];
    return step.fail(text.empty() ? "fail command reached" : text);
  }
  if (name == "quit") {
    s_.quit = true;
    return true;
  }
  if (name == "lenient") {
    if (w.size() != 2 || (w[1] != "0" && w[1] != "1")) return step.fail("usage: lenient 0|1");
    run_.lenient = w[1] == "1";
    return true;
  }
  if (name == "auto_modal") {
    if (w.size() != 2 || (w[1] != "discard" && w[1] != "off")) return step.fail("usage: auto_modal discard|off");
    run_.auto_answer = w[1] == "discard" ? "discard" : "";
    return true;
  }
  if (name == "stop_after") {
    double s = 0;
    if (w.size() != 2 || !parse_double(w[1], s) || s <= 0) return step.fail("usage: stop_after SECONDS");
    run_.stop_at = step.now + s;
    return true;
  }
  return std::nullopt;
}

bool ScriptDriver::run_script_command(const ScriptCommand& command, double now) {
  ScriptStep step{*this, command, command.words, now};
  if (const std::optional<std::string> error = builder_.script_scene_command(command.words)) {
    return error->empty() ? true : step.fail(*error);
  }
  if (const std::optional<std::string> error = lesson_shell_.script_lesson_command(command.words)) {
    return error->empty() ? true : step.fail(*error);
  }
  for (const auto group : {&ScriptDriver::script_wait_command, &ScriptDriver::script_input_command,
                           &ScriptDriver::script_drag_command, &ScriptDriver::script_item_command,
                           &ScriptDriver::script_file_command, &ScriptDriver::script_other_command}) {
    if (const std::optional<bool> done = (this->*group)(step)) return *done;
  }
  return step.fail("unknown command");
}

}  // namespace phonglab
