#include "app/viewer_app.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <backends/imgui_impl_opengl3.h>

#include "renderer/camera.h"
#include "renderer/figure.h"
#include "renderer/geometry.h"
#include "renderer/heat_map.h"
#include "renderer/image_io.h"
#include "renderer/probe_report.h"
#include "renderer/ray_tree_view.h"
#include "renderer/shading.h"
#include "ui/camera_control.h"

namespace phonglab {

namespace {

constexpr double kFramePeriod = 1.0 / 60;   // UI pacing where vsync does not block (Xvfb, some drivers)
constexpr double kEarlyFrameGap = 0.004;    // a new edit's first image may go up this soon after a frame
constexpr double kActivityWindow = 1.0;     // keep drawing this long after an input event, seconds
constexpr double kIdleWait = 0.5;           // idle wake-up period, seconds: also the file poll rate
constexpr double kFilePollPeriod = 0.5;     // "poll mtime about twice a second"
constexpr float kSidebarWidth = 400;        // panel width at UI scale 1, ImGui units
constexpr float kDragThreshold = 3;         // pixels a press may move and still be a click
constexpr double kOrbitRadPerPixel = 0.008; // about 1.4 turns across a 1280-pixel drag
constexpr double kDollyPerPixel = 0.01;     // distance factor e^0.01 per pixel dragged
constexpr double kDollyPerWheelClick = 0.85;
constexpr float kMarkerGrabFactor = 1.8f;   // a marker can be grabbed a little outside its disc
constexpr int kInteractiveDivisor = 4;      // while dragging, refine no further than 1/4 resolution
constexpr double kMaxDeferral = 1.0;        // a drag's edit waits at most this long for the renderer, s
constexpr int kMultiplesColumns = 3;        // small multiples: 3 x 2 cells, the full image last
constexpr int kMultiplesRows = 2;
constexpr int kFigureCellHeight = 270;      // slide figure cells: a quarter of 1080p per row
// The small multiples' cells in reading order (the full image is the main renderer's).
constexpr std::array<Term, 5> kCellTerms = {Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection,
                                            Term::kRefraction};

// Inverse of the sRGB transfer curve, so that writing through image_io's sRGB encoder gives
// back the 8-bit value shown on screen.
double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

ProgressiveSettings progressive_settings(const ui::RenderSettings& s, const std::optional<Vec3>& shading_eye) {
  ProgressiveSettings p;
  p.shading_eye = shading_eye;
  p.target_spp = s.target_spp;
  p.threads = s.threads;
  p.term = s.term;
  p.interactive_divisor = kInteractiveDivisor;
  p.lower_thread_priority = true;  // the UI thread stays ahead of the workers on few cores
  return p;
}

const char* object_kind_name(ObjectRef::Kind kind) {
  switch (kind) {
    case ObjectRef::Kind::kSphere: return "sphere";
    case ObjectRef::Kind::kPlane: return "plane";
    case ObjectRef::Kind::kTriangle: return "triangle";
    case ObjectRef::Kind::kMesh: return "mesh";
    case ObjectRef::Kind::kNone: break;
  }
  return "object";
}

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (const double x : v) sum += x;
  return v.empty() ? 0 : sum / static_cast<double>(v.size());
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<std::size_t>(std::lround(p * static_cast<double>(v.size() - 1)));
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
  std::string error;
  PlatformOptions platform_options;
  platform_options.width = options.width;
  platform_options.height = options.height;
  std::unique_ptr<Platform> platform = Platform::create(platform_options, error);
  if (!platform) {
    std::cerr << "phonglab: " << error << "\n"
              << "phonglab needs a display with OpenGL 3.3. Without one, render with phonglab-cli, e.g.\n"
              << "  phonglab-cli render " << options.scene_arg << " -o image.png\n";
    return 1;
  }
  Viewer viewer(*platform, options);
  error = viewer.init();
  if (!error.empty()) {
    std::cerr << "phonglab: " << error << "\n";
    return 1;
  }
  return viewer.run();
}

Viewer::Viewer(Platform& platform, const ViewerOptions& options)
    : platform_(platform),
      options_(options),
      // The render thread only wakes the event loop; the UI takes the image itself.
      renderer_(progressive_settings(ui::RenderSettings{}, std::nullopt), [] { glfwPostEmptyEvent(); }) {}

Viewer::~Viewer() = default;

std::string Viewer::init() {
  std::string error = image_view_.init();
  if (!error.empty()) return error;
  for (ImageView& view : term_views_) {
    error = view.init();
    if (!error.empty()) return error;
  }
  if (!doc_.open(options_.scene_arg)) {
    // The UI starts anyway, on the default scene, with the file's diagnostics on show.
    const std::string load_error = doc_.error_text();
    std::cerr << "phonglab: " << load_error << "\n";
    doc_.open("lecture");
    file_state_.error_text = load_error;
    file_state_.path_field = options_.scene_arg;
  } else {
    file_state_.status = doc_.status();
    file_state_.path_field = doc_.file_path();
  }
  scene_replaced_ = true;
  selected_light_ = doc_.scene().lights.empty() ? -1 : 0;
  if (!options_.script_path.empty()) {
    std::ifstream in(options_.script_path);
    if (!in) return "cannot read script " + options_.script_path;
    std::ostringstream text;
    text << in.rdbuf();
    script_ = parse_script(text.str());
  }
  if (!options_.stats_log_path.empty()) {
    stats_log_.open(options_.stats_log_path);
    if (!stats_log_) return "cannot write " + options_.stats_log_path;
  }
  update_title();
  return {};
}

int Viewer::run() {
  GLFWwindow* window = platform_.window();
  last_frame_start_ = glfwGetTime();
  while (!quit_) {
    wait_for_next_frame();
    const double frame_start = glfwGetTime();
    const double frame_seconds = frame_start - last_frame_start_;
    last_frame_start_ = frame_start;
    // Frames after an idle sleep say nothing about drawing speed.
    if (!slept_idle_) frame_times_.emplace_back(frame_start, frame_seconds);
    while (!frame_times_.empty() && frame_times_.front().first < frame_start - 1.0) frame_times_.pop_front();
    // Frames paced while the renderer works are the ones the 60 Hz target is about.
    if (was_rendering_ && stats_log_) {
      busy_frame_ms_.push_back(frame_seconds * 1e3);
      stats_log_ << "frame " << frame_start * 1e3 << " " << frame_seconds * 1e3 << "\n";
    }
    was_rendering_ = !renderer_.status().idle;

    platform_.update_scale();
    if (glfwWindowShouldClose(window)) {
      // Closing goes through the unsaved-changes guard like any other way of quitting.
      glfwSetWindowShouldClose(window, GLFW_FALSE);
      request(PendingAction{PendingAction::Kind::kQuit, {}});
    }
    poll_scene_file(frame_start);

    int fb_width = 0, fb_height = 0;
    glfwGetFramebufferSize(window, &fb_width, &fb_height);
    if (fb_width <= 0 || fb_height <= 0) continue;  // minimised: nothing to draw, keep running

    platform_.begin_backend_frame();
    step_script(frame_start);
    ImGui::NewFrame();
    layout();
    handle_viewport_input();
    draw_sidebar();
    draw_overlays();
    handle_guard_modal();
    apply_edits(frame_start);
    ImGui::Render();
    draw_gl(fb_width, fb_height);
    glfwSwapBuffers(window);
    after_swap();
  }
  write_stats_summary("session");
  return script_failed_ ? 3 : 0;
}

bool Viewer::poll_render_frame() {
  for (std::size_t i = 0; i < term_renderers_.size(); ++i) {
    if (term_renderers_[i] && term_renderers_[i]->take_frame(term_frames_[i])) term_upload_pending_[i] = true;
  }
  if (!renderer_.take_frame(shown_)) return false;
  upload_pending_ = true;
  return true;
}

void Viewer::wait_for_next_frame() {
  const ProgressiveStatus status = renderer_.status();
  const double now = glfwGetTime();
  const bool script_running = script_index_ < script_.size() || !input_steps_.empty();
  const bool busy = !status.idle || upload_pending_ || now - platform_.last_event_time() < kActivityWindow ||
                    script_running || guard_visible_ || drag_.mode != DragMode::kNone || !terms_idle();
  slept_idle_ = !busy;
  if (!busy) {
    // Nothing moves: sleep until an event, a new image (the render thread posts an empty
    // event) or the next file poll.
    glfwWaitEventsTimeout(kIdleWait);
    poll_render_frame();
    return;
  }
  const double deadline = last_frame_start_ + kFramePeriod;
  for (;;) {
    poll_render_frame();
    // The first image after an edit goes up at once: that is the latency users feel.
    const bool first_image = upload_pending_ && shown_.generation != drawn_generation_;
    const double t = glfwGetTime();
    const double early = last_frame_start_ + kEarlyFrameGap;
    if (first_image && t >= early) break;
    if (t >= deadline) break;
    glfwWaitEventsTimeout(first_image ? early - t : deadline - t);
  }
  glfwPollEvents();
}

void Viewer::poll_scene_file(double now) {
  if (now < next_file_poll_) return;
  next_file_poll_ = now + kFilePollPeriod;
  if (doc_.file_path().empty() || !file_state_.auto_reload || !doc_.changed_on_disk()) {
    file_state_.changed_on_disk = false;
    return;
  }
  if (doc_.dirty()) {
    file_state_.changed_on_disk = true;  // never throw away edits silently
    return;
  }
  reload_scene(true);
}

void Viewer::layout() {
  const ImGuiIO& io = ImGui::GetIO();
  const float sidebar = sidebar_visible_ ? std::min(kSidebarWidth * platform_.ui_scale(), io.DisplaySize.x * 0.5f) : 0;
  viewport_ = ViewportRect{0, 0, std::max(io.DisplaySize.x - sidebar, 0.0f), io.DisplaySize.y};
}

void Viewer::handle_viewport_input() {
  ImGuiIO& io = ImGui::GetIO();
  Scene& scene = doc_.scene();
  Camera& camera = scene.camera;
  const ImVec2 mouse = io.MousePos;
  const bool over_viewport = ImGui::IsMousePosValid(&mouse) && mouse.x >= viewport_.x &&
                             mouse.x < viewport_.x + viewport_.width && mouse.y >= viewport_.y &&
                             mouse.y < viewport_.y + viewport_.height;
  const bool mouse_is_ours = over_viewport && !io.WantCaptureMouse;
  const int view_w = std::max(1, static_cast<int>(std::lround(viewport_.width)));
  const int view_h = std::max(1, static_cast<int>(std::lround(viewport_.height)));

  // The point light under the mouse, if any.
  hovered_light_ = -1;
  if (drag_.mode == DragMode::kNone && mouse_is_ours) {
    const float grab = ui::light_marker_radius(platform_.ui_scale()) * kMarkerGrabFactor;
    float best = grab * grab;
    for (int i = 0; i < static_cast<int>(scene.lights.size()); ++i) {
      const Light& light = scene.lights[static_cast<std::size_t>(i)];
      if (light.type != LightType::kPoint) continue;
      const auto p = ui::project(camera, light.position, view_w, view_h);
      if (!p) continue;
      const float dx = static_cast<float>(p->x) + viewport_.x - mouse.x;
      const float dy = static_cast<float>(p->y) + viewport_.y - mouse.y;
      if (dx * dx + dy * dy <= best) {
        best = dx * dx + dy * dy;
        hovered_light_ = i;
      }
    }
  }

  if (drag_.mode == DragMode::kNone) {
    if (mouse_is_ours) {
      for (int button = 0; button < 3; ++button) {
        if (!ImGui::IsMouseClicked(button)) continue;
        drag_ = Drag{};
        drag_.button = button;
        drag_.start = mouse;
        if (button == ImGuiMouseButton_Left && hovered_light_ >= 0) {
          drag_.mode = DragMode::kLight;
          drag_.light = hovered_light_;
          drag_.light_depth = ui::view_depth(camera, scene.lights[static_cast<std::size_t>(hovered_light_)].position);
          selected_light_ = hovered_light_;
        } else if (button == ImGuiMouseButton_Left) {
          drag_.mode = io.KeyShift ? DragMode::kPan : DragMode::kOrbit;
        } else {
          drag_.mode = button == ImGuiMouseButton_Right ? DragMode::kDolly : DragMode::kPan;
        }
        break;
      }
      if (io.MouseWheel != 0) {
        ui::dolly(camera, std::pow(kDollyPerWheelClick, static_cast<double>(io.MouseWheel)));
        camera_changed_ = true;
      }
    }
  } else if (ImGui::IsMouseDown(drag_.button)) {
    if (!drag_.moved && ImGui::IsMouseDragging(drag_.button, kDragThreshold)) drag_.moved = true;
    const ImVec2 d = io.MouseDelta;
    if (drag_.moved && (d.x != 0 || d.y != 0)) {
      const double per_px = kOrbitRadPerPixel / platform_.ui_scale();
      switch (drag_.mode) {
        case DragMode::kOrbit:
          // Drag right: the scene turns right; drag down: look more from above.
          ui::orbit(camera, -d.x * per_px, d.y * per_px);
          camera_changed_ = true;
          break;
        case DragMode::kPan:
          ui::pan(camera, d.x, d.y, viewport_.height);
          camera_changed_ = true;
          break;
        case DragMode::kDolly:
          ui::dolly(camera, std::exp(d.y * kDollyPerPixel / platform_.ui_scale()));
          camera_changed_ = true;
          break;
        case DragMode::kLight:
          if (drag_.light >= 0 && drag_.light < static_cast<int>(scene.lights.size())) {
            const ui::ViewportPoint at{mouse.x - viewport_.x, mouse.y - viewport_.y};
            scene.lights[static_cast<std::size_t>(drag_.light)].position =
                ui::unproject(camera, at, drag_.light_depth, view_w, view_h);
            scene_edited_ = true;
          }
          break;
        case DragMode::kNone:
          break;
      }
    }
  } else {
    if (drag_.mode == DragMode::kOrbit && !drag_.moved) {
      // Plain click selects a material (as before); Ctrl+click, or any click in probe mode, probes.
      if (instruments_.probe_mode || io.KeyCtrl) probe_at(drag_.start);
      else pick(drag_.start);
    }
    drag_ = Drag{};
  }
  interacting_ = drag_.mode != DragMode::kNone && drag_.moved;

  if (!io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_F, false)) frame_requested_ = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) reset_requested_ = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_H, false)) sidebar_visible_ = !sidebar_visible_;
  }
  // Ctrl+Z is also a text field's own undo: only take it when no field has the keyboard.
  if (!io.WantTextInput && io.KeyCtrl) {
    if (ImGui::IsKeyPressed(GLFW_KEY_Z, false)) {
      if (io.KeyShift) redo();
      else undo();
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_Y, false)) redo();
  }
}

void Viewer::pick(ImVec2 mouse) {
  if (!snapshot_) return;
  const int w = std::max(1, static_cast<int>(std::lround(viewport_.width)));
  const int h = std::max(1, static_cast<int>(std::lround(viewport_.height)));
  const double x = mouse.x - viewport_.x;
  const double y = mouse.y - viewport_.y;
  const int px = std::clamp(static_cast<int>(std::floor(x)), 0, w - 1);
  const int py = std::clamp(static_cast<int>(std::floor(y)), 0, h - 1);
  // The same camera formula as the renderer, through the clicked point of the pixel.
  const CameraFrame frame = make_camera_frame(doc_.scene().camera, w, h);
  const Ray ray = camera_ray(frame, px, py, std::clamp(x - px, 0.0, 1.0), std::clamp(y - py, 0.0, 1.0));
  const std::optional<Hit> hit = intersect(*snapshot_, ray);
  if (!hit) {
    picked_text_ = "the background";
    return;
  }
  const Scene& scene = *snapshot_;
  selected_material_ = hit->material;
  open_materials_ = true;
  std::ostringstream text;
  // The probe's naming: "objects[i]", and a mesh's OBJ face.
  text << object_kind_name(hit->object.kind) << " " << object_name(scene, hit->object);
  if (hit->material >= 0 && hit->material < static_cast<int>(scene.materials.size())) {
    text << ", material '" << scene.materials[static_cast<std::size_t>(hit->material)].name << "'";
  }
  picked_text_ = text.str();
}

void Viewer::draw_sidebar() {
  if (!sidebar_visible_) return;
  const ImGuiIO& io = ImGui::GetIO();
  const float width = io.DisplaySize.x - viewport_.width;
  if (width < 1 || io.DisplaySize.y < 1) return;
  ImGui::SetNextWindowPos(ImVec2(viewport_.width, 0));
  ImGui::SetNextWindowSize(ImVec2(width, io.DisplaySize.y));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoFocusOnAppearing;
  if (ImGui::Begin("##sidebar", nullptr, flags)) {
    ImGui::Text("phonglab %s", PHONGLAB_VERSION);
    ImGui::SameLine();
    ImGui::TextDisabled(" H hides the panels");
    // Labels sit right of the widgets; leave them room.
    ImGui::PushItemWidth(-ImGui::GetFontSize() * 6.5f);
    Scene& scene = doc_.scene();

    if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) {
      file_state_.source = doc_.source();
      file_state_.file_path = doc_.file_path();
      file_state_.dirty = doc_.dirty();
      ui::SceneFileActions actions;
      ui::scene_file_panel(file_state_, actions);
      if (actions.open) request(PendingAction{PendingAction::Kind::kOpen, file_state_.path_field});
      if (!actions.open_embedded.empty()) request(PendingAction{PendingAction::Kind::kOpen, actions.open_embedded});
      if (actions.save) save_scene(false);
      if (actions.save_as) save_scene(true);
      if (actions.reload) request(PendingAction{PendingAction::Kind::kReload, {}});
    }
    if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) {
      ui::CameraActions actions;
      if (ui::camera_panel(scene.camera, actions)) camera_changed_ = true;
      frame_requested_ |= actions.frame_scene;
      reset_requested_ |= actions.reset;
    }
    if (open_materials_) {
      ImGui::SetNextItemOpen(true);
      open_materials_ = false;
    }
    if (ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (picked_text_.empty()) ImGui::TextDisabled("Click an object in the view to select its material.");
      else ImGui::TextDisabled("Clicked: %s", picked_text_.c_str());
      if (ui::materials_panel(scene.materials, selected_material_, scene.specular_model)) scene_edited_ = true;
    }
    if (ImGui::CollapsingHeader("Lights")) {
      if (ui::lights_panel(scene.lights, selected_light_, solo_)) scene_edited_ = true;
    }
    if (ImGui::CollapsingHeader("Instruments", ImGuiTreeNodeFlags_DefaultOpen)) {
      ui::InstrumentActions actions;
      const ui::InstrumentSettings before = instruments_;
      if (ui::instruments_panel(instruments_, actions, !image_a_.pixels.empty(), history_.undo_count(),
                                history_.redo_count(), figure_path_, figure_status_)) {
        if (before.small_multiples != instruments_.small_multiples) settings_changed_ = true;
        upload_pending_ = upload_pending_ || !shown_.pixels.empty();  // a compare view changed
      }
      if (actions.snapshot_a) snapshot_a();
      if (actions.undo) undo();
      if (actions.redo) redo();
      if (actions.save_figure) save_figure(figure_path_);
      if (actions.head_reference) {
        snapshot_a();
        instruments_.compare = 2;
        upload_pending_ = upload_pending_ || !shown_.pixels.empty();
      }
    }
    if (ImGui::CollapsingHeader("Rays: tree, depth cut, heat map", ImGuiTreeNodeFlags_DefaultOpen)) {
      rays_.heat_map = render_settings_.term == Term::kRays;
      const ui::RayTreeSettings before = rays_;
      ui::RayTreeSummary summary;
      summary.probe = probe_ ? &*probe_ : nullptr;
      summary.scene_max_depth = scene.max_depth;
      summary.heat_max = heat_max_;
      if (ui::rays_panel(rays_, summary)) {
        if (before.depth_cut != rays_.depth_cut || (rays_.depth_cut && before.cut_depth != rays_.cut_depth)) {
          view_changed_ = true;
        }
        if (before.heat_map != rays_.heat_map) set_heat_map(rays_.heat_map);
      }
    }
    if (probe_ && ImGui::CollapsingHeader("Probe", ImGuiTreeNodeFlags_DefaultOpen)) {
      ui::ProbeView view;
      view.scene = snapshot_.get();
      view.probe = &*probe_;
      view.image_width = render_width_;
      view.image_height = render_height_;
      view.report = probe_report_;
      view.occluders = probe_occluders_;
      view.exposure_ev = display_.exposure_ev;
      const double gain = std::exp2(static_cast<double>(display_.exposure_ev));
      for (int c = 0; c < 3; ++c) {
        const double v = std::clamp(probe_->root.total[c] * gain, 0.0, 1.0);
        view.srgb[c] = display_.srgb ? linear_to_srgb8(v) : static_cast<unsigned char>(std::lround(v * 255));
      }
      ui::probe_panel(view);
    }
    if (ImGui::CollapsingHeader("Render")) {
      if (ui::shading_settings_panel(scene)) scene_edited_ = true;
      ImGui::Separator();
      const int hardware = resolve_thread_count(0);
      if (ui::render_settings_panel(render_settings_, hardware)) settings_changed_ = true;
    }
    if (ImGui::CollapsingHeader("Display") && ui::display_panel(display_)) platform_.set_user_scale(display_.ui_size);
    if (ImGui::CollapsingHeader("Screenshot")) {
      ui::ScreenshotActions actions;
      ui::screenshot_panel(screenshot_state_, actions);
      if (actions.save_png) save_png(screenshot_state_.png_path);
      if (actions.save_pfm) save_pfm(screenshot_state_.pfm_path);
    }
    ImGui::PopItemWidth();
  }
  ImGui::End();
  // While a slider is held, each tick is an edit: keep the renderer at coarse levels.
  if (!ImGui::IsAnyItemActive()) edited_while_active_ = false;
  else if (scene_edited_ || camera_changed_) edited_while_active_ = true;
}

void Viewer::draw_overlays() {
  if (viewport_.width < 1 || viewport_.height < 1) return;
  const Scene& scene = doc_.scene();
  const float scale = platform_.ui_scale();
  const int view_w = static_cast<int>(std::lround(viewport_.width));
  const int view_h = static_cast<int>(std::lround(viewport_.height));

  std::vector<ui::LightMarker> markers;
  for (int i = 0; i < static_cast<int>(scene.lights.size()); ++i) {
    const Light& light = scene.lights[static_cast<std::size_t>(i)];
    if (light.type != LightType::kPoint) continue;
    const auto p = ui::project(scene.camera, light.position, view_w, view_h);
    if (!p) continue;  // behind the camera
    ui::LightMarker marker;
    const ImVec2 at(static_cast<float>(p->x), static_cast<float>(p->y));
    const float inset = 2.5f * ui::light_marker_radius(scale);
    const ImVec2 clamped(std::clamp(at.x, inset, std::max(inset, viewport_.width - inset)),
                         std::clamp(at.y, inset, std::max(inset, viewport_.height - inset)));
    if (clamped.x != at.x || clamped.y != at.y) {
      const float dx = at.x - clamped.x, dy = at.y - clamped.y;
      const float length = std::sqrt(dx * dx + dy * dy);
      marker.offscreen = true;
      marker.toward = ImVec2(dx / length, dy / length);
    }
    marker.pos = ImVec2(viewport_.x + clamped.x, viewport_.y + clamped.y);
    const double m = std::max(max_channel(light.intensity), 1e-9);
    marker.color = ImVec4(static_cast<float>(light.intensity.x / m), static_cast<float>(light.intensity.y / m),
                          static_cast<float>(light.intensity.z / m), 1.0f);
    marker.enabled = light.enabled;
    marker.selected = i == selected_light_;
    marker.hovered = i == hovered_light_ || (drag_.mode == DragMode::kLight && drag_.light == i);
    marker.index = i;
    markers.push_back(marker);
  }
  ui::draw_light_markers(markers, ui::light_marker_radius(scale));
  if (hovered_light_ >= 0) ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);

  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const bool multiples = instruments_.small_multiples;
  const int columns = multiples ? kMultiplesColumns : 1;
  const int rows = multiples ? kMultiplesRows : 1;
  const float cell_w = viewport_.width / static_cast<float>(columns);
  const float cell_h = viewport_.height / static_cast<float>(rows);
  if (multiples) {
    for (int cell = 0; cell < columns * rows; ++cell) {
      const ImVec2 at(viewport_.x + static_cast<float>(cell % columns) * cell_w + 4 * scale,
                      viewport_.y + static_cast<float>(cell / columns) * cell_h + cell_h - ImGui::GetFontSize() - 4 * scale);
      const std::string_view label = figure_label(cell < kTermCells ? kCellTerms[static_cast<std::size_t>(cell)] : Term::kFull);
      draw->AddText(at, IM_COL32(255, 255, 255, 230), label.data(), label.data() + label.size());
    }
  }
  // The probed pixel: a ring with a gap in every cell, so the term images can be compared there.
  if (probe_ && render_width_ > 0 && render_height_ > 0) {
    for (int cell = 0; cell < columns * rows; ++cell) {
      const float x = viewport_.x + static_cast<float>(cell % columns) * cell_w +
                      (static_cast<float>(probe_x_) + 0.5f) / static_cast<float>(render_width_) * cell_w;
      const float y = viewport_.y + static_cast<float>(cell / columns) * cell_h +
                      (static_cast<float>(probe_y_) + 0.5f) / static_cast<float>(render_height_) * cell_h;
      const float r = 6 * scale;
      draw->AddCircle(ImVec2(x, y), r, IM_COL32(0, 0, 0, 255), 20, 3 * scale);
      draw->AddCircle(ImVec2(x, y), r, IM_COL32(255, 230, 0, 255), 20, 1.5f * scale);
      draw->AddLine(ImVec2(x - 2.2f * r, y), ImVec2(x - r, y), IM_COL32(255, 230, 0, 255), 1.5f * scale);
      draw->AddLine(ImVec2(x + r, y), ImVec2(x + 2.2f * r, y), IM_COL32(255, 230, 0, 255), 1.5f * scale);
      draw->AddLine(ImVec2(x, y - 2.2f * r), ImVec2(x, y - r), IM_COL32(255, 230, 0, 255), 1.5f * scale);
      draw->AddLine(ImVec2(x, y + r), ImVec2(x, y + 2.2f * r), IM_COL32(255, 230, 0, 255), 1.5f * scale);
    }
  }
  // The depth cut is a way of looking: say so on the image, at the top centre.
  if (snapshot_ && rays_.depth_cut) {
    char caption[96];
    std::snprintf(caption, sizeof caption, "recursion cut at depth %d (scene max depth %d)", snapshot_->max_depth,
                  doc_.scene().max_depth);
    const ImVec2 size = ImGui::CalcTextSize(caption);
    const ImVec2 at(viewport_.x + (viewport_.width - size.x) / 2, viewport_.y + 8 * scale);
    draw->AddRectFilled(ImVec2(at.x - 6 * scale, at.y - 3 * scale), ImVec2(at.x + size.x + 6 * scale, at.y + size.y + 3 * scale),
                        IM_COL32(0, 0, 0, 170), 4 * scale);
    draw->AddText(at, IM_COL32(255, 255, 255, 240), caption);
  }
  // The ray tree over the full image: the only cell, or the last of the small multiples.
  tree_segments_.clear();
  const int full_cell = columns * rows - 1;
  draw_ray_tree_overlay(viewport_.x + static_cast<float>(full_cell % columns) * cell_w,
                        viewport_.y + static_cast<float>(full_cell / columns) * cell_h, cell_w, cell_h);
  if (heat_shown() && heat_max_ > 0) {
    ImGui::SetNextWindowPos(ImVec2(viewport_.x + viewport_.width - 8 * scale, viewport_.y + viewport_.height - 8 * scale),
                            ImGuiCond_Always, ImVec2(1, 1));
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("##heat_legend", nullptr, flags)) ui::heat_legend(heat_max_, 220 * scale);
    ImGui::End();
  }
  if (instruments_.compare == 1 && !image_a_.pixels.empty()) {
    const float x = viewport_.x + instruments_.wipe * cell_w + static_cast<float>(columns - 1) * cell_w;
    const float y0 = viewport_.y + static_cast<float>(rows - 1) * cell_h;
    draw->AddLine(ImVec2(x, y0), ImVec2(x, y0 + cell_h), IM_COL32(255, 255, 255, 200), 2 * scale);
    draw->AddText(ImVec2(x - ImGui::CalcTextSize("A ").x, y0 + cell_h / 2), IM_COL32(255, 255, 255, 230), "A");
  }

  // "Move your head": the highlight against the head angle, in a small window at the
  // viewport's bottom-left (visible however the panels are scrolled).
  if (instruments_.move_head && snapshot_) {
    ui::HeadPlotView plot;
    plot.hit = probe_ ? &probe_->root : nullptr;
    plot.eye_at_zero = snapshot_->camera.position;
    plot.axis = glm::normalize(make_camera_frame(snapshot_->camera, 1, 1).up);
    if (probe_ && probe_->root.hit && probe_->root.material >= 0 &&
        probe_->root.material < static_cast<int>(snapshot_->materials.size())) {
      plot.shininess = snapshot_->materials[static_cast<std::size_t>(probe_->root.material)].n;
    }
    plot.blinn = snapshot_->specular_model == SpecularModel::kBlinn;
    plot.angle_deg = instruments_.head_angle_deg;
    plot.width = 340 * scale;
    ImGui::SetNextWindowPos(ImVec2(viewport_.x + 8 * scale, viewport_.y + viewport_.height - 8 * scale), ImGuiCond_Always,
                            ImVec2(0, 1));
    ImGui::SetNextWindowBgAlpha(0.75f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    if (ImGui::Begin("##head_plot", nullptr, flags)) ui::head_plot(plot);
    ImGui::End();
  }

  if (display_.show_stats) {
    const ProgressiveStatus status = renderer_.status();
    ui::StatsView stats;
    double sum = 0, slowest = 0;
    for (const auto& [start, seconds] : frame_times_) {
      sum += seconds;
      slowest = std::max(slowest, seconds);
    }
    stats.ui_frame_ms = frame_times_.empty() ? 0 : sum / static_cast<double>(frame_times_.size()) * 1e3;
    stats.ui_frame_max_ms = slowest * 1e3;
    stats.edit_to_image_ms = last_latency_ms_;
    stats.have_frame = !shown_.pixels.empty();
    stats.level_divisor = shown_.divisor;
    stats.image_width = shown_.width;
    stats.image_height = shown_.height;
    stats.spp = shown_.spp;
    stats.target_spp = render_settings_.target_spp;
    stats.frame = shown_.stats;
    stats.idle = status.idle;
    stats.interacting = interacting_ || edited_while_active_;
    stats.scene_error = file_state_.error_text;
    ui::stats_overlay(stats, ImVec2(viewport_.x + 8 * scale, viewport_.y + 8 * scale));
  }
  if (shown_.pixels.empty()) {
    const char* text = "rendering...";
    const ImVec2 size = ImGui::CalcTextSize(text);
    ImGui::GetBackgroundDrawList()->AddText(
        ImVec2(viewport_.x + (viewport_.width - size.x) / 2, viewport_.y + (viewport_.height - size.y) / 2),
        IM_COL32(200, 200, 200, 255), text);
  }
}

void Viewer::draw_ray_tree_overlay(float cell_x, float cell_y, float cell_w, float cell_h) {
  if (!probe_ || !rays_.overlay || !snapshot_ || render_width_ <= 0 || render_height_ <= 0) return;
  RayTreeViewOptions options;
  options.shadow_rays = rays_.shadow_rays;
  options.secondary_rays = rays_.secondary_rays;
  options.arrows = rays_.arrows;
  // The probe was taken in snapshot_ at the render size: project with that camera and size.
  const CameraFrame frame = make_camera_frame(snapshot_->camera, render_width_, render_height_);
  tree_segments_ = project_ray_tree(frame, ray_tree_segments(*snapshot_, probe_->root, options),
                                    ray_tree_near(*snapshot_, probe_->root));
  int lit_lights = 0;
  for (const ProbeLight& light : probe_->root.lights) lit_lights += light.lit_side ? 1 : 0;
  const float scale = platform_.ui_scale();
  const ui::ImageRect rect{ImVec2(cell_x, cell_y), ImVec2(cell_w / static_cast<float>(render_width_),
                                                          cell_h / static_cast<float>(render_height_))};
  const bool blinn = snapshot_->specular_model == SpecularModel::kBlinn;
  ui::draw_ray_tree(ImGui::GetBackgroundDrawList(), tree_segments_, rect, scale, blinn, lit_lights);
  if (!rays_.legend) return;
  ImGui::SetNextWindowPos(ImVec2(viewport_.x + viewport_.width - 8 * scale, viewport_.y + 8 * scale), ImGuiCond_Always,
                          ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.75f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin("##ray_tree_legend", nullptr, flags)) ui::ray_tree_legend(tree_segments_, blinn);
  ImGui::End();
}

void Viewer::request(PendingAction action) {
  if (!doc_.dirty()) {
    perform(action);
    return;
  }
  pending_ = std::move(action);
  open_guard_ = true;
}

void Viewer::perform(const PendingAction& action) {
  switch (action.kind) {
    case PendingAction::Kind::kQuit: quit_ = true; break;
    case PendingAction::Kind::kOpen: open_scene(action.arg); break;
    case PendingAction::Kind::kReload: reload_scene(false); break;
    case PendingAction::Kind::kNone: break;
  }
}

void Viewer::handle_guard_modal() {
  std::string action = "quit";
  if (pending_.kind == PendingAction::Kind::kOpen) action = "open " + pending_.arg;
  if (pending_.kind == PendingAction::Kind::kReload) action = "reload the file";
  const ui::GuardChoice choice =
      ui::unsaved_changes_modal(open_guard_, action, !doc_.file_path().empty(), scripted_choice_);
  if (open_guard_) guard_visible_ = true;
  open_guard_ = false;
  scripted_choice_ = ui::GuardChoice::kNone;
  if (choice == ui::GuardChoice::kNone) return;
  guard_visible_ = false;
  const PendingAction pending = std::move(pending_);
  pending_ = PendingAction{};
  if (choice == ui::GuardChoice::kSave) {
    save_scene(false);
    if (!doc_.dirty()) perform(pending);
  } else if (choice == ui::GuardChoice::kDiscard) {
    perform(pending);
  }
}

void Viewer::open_scene(const std::string& scene_arg) {
  if (scene_arg.empty()) {
    file_state_.error_text = "Open: type a scene file path or an embedded scene name into the path field";
    return;
  }
  if (!doc_.open(scene_arg)) {
    file_state_.error_text = doc_.error_text();  // the old scene stays
    return;
  }
  file_state_.error_text.clear();
  file_state_.status = doc_.status();
  file_state_.changed_on_disk = false;
  file_state_.path_field = doc_.file_path().empty() ? scene_arg : doc_.file_path();
  selected_material_ = 0;
  selected_light_ = doc_.scene().lights.empty() ? -1 : 0;
  picked_text_.clear();
  probe_.reset();
  drag_ = Drag{};
  scene_replaced_ = true;
}

void Viewer::reload_scene(bool keep_view) {
  if (!doc_.reload(keep_view)) {
    file_state_.error_text = doc_.error_text();
    return;
  }
  file_state_.error_text.clear();
  file_state_.status = doc_.status();
  file_state_.changed_on_disk = false;
  const int materials = static_cast<int>(doc_.scene().materials.size());
  selected_material_ = std::clamp(selected_material_, 0, std::max(materials - 1, 0));
  if (selected_light_ >= static_cast<int>(doc_.scene().lights.size())) selected_light_ = -1;
  drag_ = Drag{};
  scene_replaced_ = true;
}

void Viewer::save_scene(bool as) {
  const bool ok = as ? doc_.save_as(file_state_.path_field) : doc_.save();
  if (ok) {
    file_state_.error_text.clear();
    file_state_.status = doc_.status();
    file_state_.changed_on_disk = false;
  } else {
    file_state_.error_text = doc_.error_text();
  }
}

void Viewer::save_png(const std::string& path) {
  if (shown_.pixels.empty()) {
    screenshot_state_.status = "no image yet";
    return;
  }
  Image image;
  image.width = shown_.width;
  image.height = shown_.height;
  image.pixels.reserve(shown_.pixels.size());
  // The heat map is written as shown: its colours, without exposure.
  const bool heat = heat_shown();
  const std::vector<glm::vec3> source = heat ? display_pixels() : shown_.pixels;
  const float exposure = heat ? 1.0f : std::exp2(display_.exposure_ev);
  for (const glm::vec3& p : source) {
    glm::vec3 v = glm::clamp(p * exposure, 0.0f, 1.0f);
    // Linear display shows the values themselves as 8-bit codes: pre-decode them so the
    // sRGB encoder of write_image gives those codes back.
    if (!display_.srgb) {
      for (int c = 0; c < 3; ++c) v[c] = static_cast<float>(srgb_to_linear(v[c]));
    }
    image.pixels.push_back(v);
  }
  write_screenshot(path, image, "");
}

void Viewer::save_pfm(const std::string& path) {
  if (shown_.pixels.empty()) {
    screenshot_state_.status = "no image yet";
    return;
  }
  Image image;
  image.width = shown_.width;
  image.height = shown_.height;
  image.pixels = shown_.pixels;
  write_screenshot(path, image, "linear, ");
}

void Viewer::write_screenshot(const std::string& path, const Image& image, const char* kind) {
  const std::string error = write_image(path, image);
  std::ostringstream status;
  if (error.empty()) {
    status << "saved " << path << " (" << kind << image.width << "x" << image.height << ", " << shown_.spp << " spp)";
  } else {
    status << error;
  }
  screenshot_state_.status = status.str();
}

void Viewer::save_window_screenshot(const std::string& path, int fb_width, int fb_height) {
  const std::vector<unsigned char> rgb = read_framebuffer_rgb8(fb_width, fb_height);
  Image image;
  image.width = fb_width;
  image.height = fb_height;
  image.pixels.resize(static_cast<std::size_t>(fb_width) * static_cast<std::size_t>(fb_height));
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      image.pixels[i][c] = static_cast<float>(srgb_to_linear(rgb[i * 3 + static_cast<std::size_t>(c)] / 255.0));
    }
  }
  const std::string error = write_image(path, image);
  if (!error.empty()) {
    std::cerr << "phonglab: screenshot: " << error << "\n";
    script_failed_ = true;
    quit_ = true;
  }
}

void Viewer::note_restart(std::uint64_t generation, double edit_time) {
  restart_times_.emplace_back(generation, edit_time);
  constexpr std::size_t kKeep = 256;  // a few seconds of drag frames; older ones never show
  while (restart_times_.size() > kKeep) restart_times_.pop_front();
  if (bench_expect_restart_) {
    bench_generation_ = generation;
    bench_expect_restart_ = false;
  }
}

void Viewer::apply_edits(double frame_start) {
  Scene& scene = doc_.scene();
  const ImGuiIO& io = ImGui::GetIO();
  if (frame_requested_ && viewport_.height > 0) {
    if (ui::frame_scene(scene.camera, scene, viewport_.width / viewport_.height)) camera_changed_ = true;
  }
  if (reset_requested_) {
    scene.camera = doc_.loaded_camera();
    camera_changed_ = true;
  }
  frame_requested_ = reset_requested_ = false;
  if (scene_edited_) doc_.mark_dirty();
  if (scene_replaced_) {
    history_.reset(scene);
    commit_pending_ = false;
    solo_ = ui::LightSolo{};
  } else if (scene_edited_ && !restored_) {
    commit_pending_ = true;
  }
  restored_ = false;
  // One undo step per gesture: a slider drag or a light drag commits when it ends.
  if (commit_pending_ && !ImGui::IsAnyItemActive() && drag_.mode != DragMode::kLight) {
    history_.commit(scene);
    commit_pending_ = false;
  }

  // "Move your head": a new shading eye (angle, probe or camera changed) restarts the renderers.
  const std::optional<Vec3> eye = head_eye();
  if (eye != shading_eye_) {
    shading_eye_ = eye;
    settings_changed_ = true;
    if (probe_) refresh_probe();
  }
  if (settings_changed_) {
    const std::uint64_t before = renderer_.status().generation;
    const std::uint64_t generation = renderer_.set_settings(progressive_settings(render_settings_, shading_eye_));
    if (generation != before) {
      sent_generation_ = generation;
      note_restart(generation, frame_start);
    }
  }

  const float resolution = render_settings_.resolution_scale;
  int width = static_cast<int>(std::lround(viewport_.width * io.DisplayFramebufferScale.x * resolution));
  int height = static_cast<int>(std::lround(viewport_.height * io.DisplayFramebufferScale.y * resolution));
  if (instruments_.small_multiples) {
    width /= kMultiplesColumns;
    height /= kMultiplesRows;
  }
  if (viewport_.width >= 1 && viewport_.height >= 1) {
    width = std::max(width, 1);
    height = std::max(height, 1);
  } else {
    width = height = 0;  // nothing visible: the renderer idles
  }
  const bool resized = width != render_width_ || height != render_height_;
  const bool edited = scene_edited_ || camera_changed_ || scene_replaced_ || view_changed_ || !snapshot_;
  if (edited && !change_deferred_) deferred_since_ = frame_start;
  const bool scene_changed = edited || change_deferred_;
  // During a drag, a new snapshot waits until the renderer has shown the previous one:
  // restarting every UI frame would cancel each coarse pass before it finishes whenever a
  // pass takes longer than a frame, and the view would freeze until the drag ends.
  const bool dragging = interacting_ || edited_while_active_;
  const bool first_image_pending = renderer_.status().published_generation < sent_generation_;
  const bool defer = scene_changed && dragging && !resized && !scene_replaced_ && first_image_pending &&
                     frame_start - deferred_since_ < kMaxDeferral;
  change_deferred_ = defer;
  if ((scene_changed && !defer) || resized) {
    if (scene_changed) {
      auto snapshot = std::make_shared<Scene>(scene);
      // The depth cut changes what is rendered, never the scene: history and file keep max_depth.
      apply_depth_cut(*snapshot, ui::depth_cut_of(rays_));
      prepare_scene(*snapshot);
      snapshot_ = std::move(snapshot);
    }
    render_width_ = width;
    render_height_ = height;
    // One restart per UI frame, however many edits it gathered.
    const std::uint64_t generation = renderer_.set_scene(snapshot_, width, height);
    sent_generation_ = generation;
    // Latency counts from the oldest edit this snapshot carries.
    if (scene_changed) note_restart(generation, deferred_since_);
    if (probe_) refresh_probe();
  }
  update_term_renderers((scene_changed && !defer) || resized);
  renderer_.set_interacting(interacting_ || edited_while_active_);
  for (const auto& term_renderer : term_renderers_) {
    if (term_renderer) term_renderer->set_interacting(interacting_ || edited_while_active_);
  }
  scene_edited_ = camera_changed_ = scene_replaced_ = settings_changed_ = view_changed_ = false;
  update_title();
}

void Viewer::draw_gl(int fb_width, int fb_height) {
  glViewport(0, 0, fb_width, fb_height);
  glClearColor(0.10f, 0.10f, 0.11f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (upload_pending_) {
    heat_max_ = heat_shown() ? heat_max(shown_.pixels) : 0;
    image_view_.upload(shown_.width, shown_.height, display_pixels());
    upload_pending_ = false;
    if (shown_.generation != drawn_generation_) first_image_generation_ = shown_.generation;
    drawn_generation_ = shown_.generation;
    drawn_serial_ = shown_.stats.serial;
  }
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  // The heat map's colours are final: exposure does not apply to them.
  const float exposure_ev = heat_shown() ? 0.0f : display_.exposure_ev;
  const int view_w = static_cast<int>(std::lround(viewport_.width * scale.x));
  const int view_h = static_cast<int>(std::lround(viewport_.height * scale.y));
  const int view_x = static_cast<int>(std::lround(viewport_.x * scale.x));
  const int view_y = fb_height - view_h - static_cast<int>(std::lround(viewport_.y * scale.y));  // GL counts from the bottom
  if (instruments_.small_multiples) {
    // 3 x 2 cells, top row first; GL rows count from the bottom.
    const int cell_w = view_w / kMultiplesColumns;
    const int cell_h = view_h / kMultiplesRows;
    for (int cell = 0; cell < kMultiplesColumns * kMultiplesRows; ++cell) {
      const int x = view_x + (cell % kMultiplesColumns) * cell_w;
      const int y = view_y + (kMultiplesRows - 1 - cell / kMultiplesColumns) * cell_h;
      if (cell == kTermCells) {
        image_view_.draw(x, y, cell_w, cell_h, exposure_ev, display_.srgb, shown_.divisor > 1);
        continue;
      }
      const auto i = static_cast<std::size_t>(cell);
      if (term_upload_pending_[i]) {
        term_views_[i].upload(term_frames_[i].width, term_frames_[i].height, term_frames_[i].pixels);
        term_upload_pending_[i] = false;
        term_drawn_serial_[i] = term_frames_[i].stats.serial;
      }
      if (term_views_[i].has_image()) {
        term_views_[i].draw(x, y, cell_w, cell_h, display_.exposure_ev, display_.srgb, term_frames_[i].divisor > 1);
      }
    }
  } else {
    // Coarse levels as crisp blocks; a reduced-resolution final image is smoothed.
    const bool nearest = shown_.divisor > 1 || shown_.width == view_w;
    image_view_.draw(view_x, view_y, view_w, view_h, exposure_ev, display_.srgb, nearest);
  }
  glViewport(0, 0, fb_width, fb_height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!screenshot_request_.empty()) {
    save_window_screenshot(screenshot_request_, fb_width, fb_height);
    screenshot_request_.clear();
  }
}

void Viewer::after_swap() {
  if (first_image_generation_ == 0) return;
  const double now = glfwGetTime();
  for (const auto& [generation, edit_time] : restart_times_) {
    if (generation != first_image_generation_) continue;
    last_latency_ms_ = (now - edit_time) * 1e3;
    // The renderer's share: restart to publication of this image.
    if (stats_log_) {
      latencies_ms_.push_back(last_latency_ms_);
      stats_log_ << "latency " << generation << " " << last_latency_ms_ << " 1/" << shown_.divisor << " render_ms "
                 << shown_.stats.ms_since_restart << " pass_ms " << shown_.stats.pass_ms << "\n";
    }
    break;
  }
  // Edits up to this one are on screen or were overtaken by it.
  while (!restart_times_.empty() && restart_times_.front().first <= first_image_generation_) restart_times_.pop_front();
  first_image_generation_ = 0;
}

void Viewer::update_title() {
  std::string title = "phonglab - " + doc_.source() + (doc_.dirty() ? " *" : "");
  if (title == title_) return;
  title_ = std::move(title);
  glfwSetWindowTitle(platform_.window(), title_.c_str());
}

bool Viewer::image_is_final() const {
  const ProgressiveStatus status = renderer_.status();
  return status.idle && status.serial > 0 && drawn_serial_ == status.serial &&
         drawn_generation_ == status.generation && !upload_pending_ && terms_idle();
}

bool Viewer::terms_idle() const {
  for (std::size_t i = 0; i < term_renderers_.size(); ++i) {
    if (!term_renderers_[i]) continue;
    const ProgressiveStatus status = term_renderers_[i]->status();
    if (!status.idle || term_upload_pending_[i] || (status.serial > 0 && term_drawn_serial_[i] != status.serial)) {
      return false;
    }
  }
  return true;
}

void Viewer::update_term_renderers(bool scene_changed) {
  if (!instruments_.small_multiples) {
    for (auto& term_renderer : term_renderers_) term_renderer.reset();  // joins its thread
    return;
  }
  const bool started = !term_renderers_[0];
  ProgressiveSettings settings = progressive_settings(render_settings_, shading_eye_);
  // Five more renderers share the machine with the main one.
  settings.threads = std::max(1, resolve_thread_count(render_settings_.threads) / 3);
  for (std::size_t i = 0; i < term_renderers_.size(); ++i) {
    settings.term = kCellTerms[i];
    if (!term_renderers_[i]) {
      term_renderers_[i] = std::make_unique<ProgressiveRenderer>(settings, [] { glfwPostEmptyEvent(); });
      term_frames_[i] = ProgressiveFrame{};
      term_drawn_serial_[i] = 0;
      term_upload_pending_[i] = false;
    } else {
      term_renderers_[i]->set_settings(settings);
    }
    if ((started || scene_changed) && snapshot_) term_renderers_[i]->set_scene(snapshot_, render_width_, render_height_);
  }
}

std::optional<std::array<int, 2>> Viewer::render_pixel_at(ImVec2 mouse) const {
  if (render_width_ <= 0 || render_height_ <= 0 || viewport_.width < 1 || viewport_.height < 1) return std::nullopt;
  const int columns = instruments_.small_multiples ? kMultiplesColumns : 1;
  const int rows = instruments_.small_multiples ? kMultiplesRows : 1;
  const double cell_w = static_cast<double>(viewport_.width) / columns;
  const double cell_h = static_cast<double>(viewport_.height) / rows;
  const double x = mouse.x - viewport_.x;
  const double y = mouse.y - viewport_.y;
  // Within its cell, the point maps to the render pixel the cell shows there.
  const double u = (x - std::floor(x / cell_w) * cell_w) / cell_w;
  const double v = (y - std::floor(y / cell_h) * cell_h) / cell_h;
  return std::array<int, 2>{std::clamp(static_cast<int>(std::floor(u * render_width_)), 0, render_width_ - 1),
                            std::clamp(static_cast<int>(std::floor(v * render_height_)), 0, render_height_ - 1)};
}

void Viewer::probe_at(ImVec2 mouse) {
  const auto pixel = render_pixel_at(mouse);
  if (!pixel || !snapshot_) return;
  probe_x_ = (*pixel)[0];
  probe_y_ = (*pixel)[1];
  refresh_probe();
}

void Viewer::refresh_probe() {
  if (!snapshot_ || render_width_ <= 0 || render_height_ <= 0) {
    probe_.reset();
    return;
  }
  probe_x_ = std::clamp(probe_x_, 0, render_width_ - 1);
  probe_y_ = std::clamp(probe_y_, 0, render_height_ - 1);
  // The renderer's own replay of the pixel's centre ray: the numbers are the image's.
  probe_ = probe_pixel(*snapshot_, render_width_, render_height_, probe_x_, probe_y_, shading_eye_);
  probe_report_ = probe_to_text(*snapshot_, *probe_);
  probe_occluders_.clear();
  for (const ProbeLight& light : probe_->root.lights) probe_occluders_.push_back(object_name(*snapshot_, light.occluder));
}

void Viewer::undo() {
  if (commit_pending_) {
    history_.commit(doc_.scene());  // a gesture still in progress becomes the step undone
    commit_pending_ = false;
  }
  restore(history_.undo(doc_.scene()));
}

void Viewer::redo() { restore(history_.redo(doc_.scene())); }

void Viewer::restore(std::optional<Scene> step) {
  if (!step) return;
  Scene& scene = doc_.scene();
  scene = std::move(*step);
  selected_light_ = std::min(selected_light_, static_cast<int>(scene.lights.size()) - 1);
  scene_edited_ = true;
  restored_ = true;
}

void Viewer::snapshot_a() {
  if (shown_.pixels.empty()) return;
  image_a_ = shown_;
  if (instruments_.compare == 0) instruments_.compare = 1;
  upload_pending_ = true;
}

bool Viewer::heat_shown() const { return render_settings_.term == Term::kRays && instruments_.compare == 0; }

void Viewer::set_heat_map(bool on) {
  if (on == (render_settings_.term == Term::kRays)) return;
  if (on) term_before_heat_ = render_settings_.term;
  render_settings_.term = on ? Term::kRays : (term_before_heat_ == Term::kRays ? Term::kFull : term_before_heat_);
  rays_.heat_map = on;
  settings_changed_ = true;
}

std::vector<glm::vec3> Viewer::display_pixels() const {
  if (heat_shown()) {
    // Rays per pixel on the ramp, 0 to the image's maximum. With the sRGB curve the shader
    // encodes heat_color back to the ramp; raw display shows the ramp's codes themselves.
    const double max = heat_max(shown_.pixels);
    if (display_.srgb) return heat_map_pixels(shown_.pixels, max);
    std::vector<glm::vec3> out(shown_.pixels.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(heat_ramp_srgb(max > 0 ? shown_.pixels[i].x / max : 0));
    return out;
  }
  const bool comparable = instruments_.compare != 0 && image_a_.width == shown_.width &&
                          image_a_.height == shown_.height && image_a_.pixels.size() == shown_.pixels.size();
  if (!comparable) return shown_.pixels;
  std::vector<glm::vec3> out(shown_.pixels.size());
  const int wipe_x = static_cast<int>(std::lround(instruments_.wipe * static_cast<float>(shown_.width)));
  for (int y = 0; y < shown_.height; ++y) {
    for (int x = 0; x < shown_.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(shown_.width) + static_cast<std::size_t>(x);
      if (instruments_.compare == 1) out[i] = x < wipe_x ? image_a_.pixels[i] : shown_.pixels[i];
      else out[i] = glm::abs(shown_.pixels[i] - image_a_.pixels[i]) * instruments_.difference_gain;
    }
  }
  return out;
}

Vec3 Viewer::head_pivot() const {
  if (probe_ && probe_->root.hit) return probe_->root.p;
  return doc_.scene().camera.look_at;
}

std::optional<Vec3> Viewer::head_eye() const {
  if (!instruments_.move_head) return std::nullopt;
  return ui::head_eye(doc_.scene().camera, head_pivot(), static_cast<double>(instruments_.head_angle_deg));
}

void Viewer::save_figure(const std::string& path) {
  if (!snapshot_ || viewport_.height < 1) {
    figure_status_ = "no scene yet";
    return;
  }
  FigureOptions options;
  options.cell_height = kFigureCellHeight;
  options.cell_width = std::max(1, static_cast<int>(std::lround(kFigureCellHeight * viewport_.width / viewport_.height)));
  options.threads = render_settings_.threads;
  const std::string error = write_figure(path, *snapshot_, options);
  figure_status_ = error.empty() ? "saved " + path : error;
}

void Viewer::write_stats_summary(const std::string& label) {
  if (!stats_log_) return;
  stats_log_ << "summary " << label << " ui_frames " << busy_frame_ms_.size() << " mean_ms " << mean(busy_frame_ms_)
             << " p50_ms " << percentile(busy_frame_ms_, 0.5) << " p95_ms " << percentile(busy_frame_ms_, 0.95)
             << " p99_ms " << percentile(busy_frame_ms_, 0.99) << " max_ms " << percentile(busy_frame_ms_, 1.0) << "\n";
  stats_log_ << "summary " << label << " edit_to_image n " << latencies_ms_.size() << " mean_ms " << mean(latencies_ms_)
             << " p50_ms " << percentile(latencies_ms_, 0.5) << " p95_ms " << percentile(latencies_ms_, 0.95)
             << " max_ms " << percentile(latencies_ms_, 1.0) << "\n";
  stats_log_.flush();
}

}  // namespace phonglab
