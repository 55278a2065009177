#include "apps/previewer/viewer_app.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include <backends/imgui_impl_opengl3.h>

#include "core/scene/camera.h"
#include "io/figure.h"
#include "core/geometry/geometry.h"
#include "core/teaching/heat_map.h"
#include "io/image_io.h"
#include "io/probe_report.h"
#include "core/teaching/ray_tree_view.h"
#include "core/shading/shading.h"
#include "interaction/camera_control.h"
#include "interaction/scene_objects.h"
#include "ui/widgets.h"

namespace phonglab {

namespace {

// The stats log's key for the level of an image: its divisor, 0 for the quad-shaded live rung.
int level_key(const ProgressiveFrame& frame) { return frame.quads ? 0 : frame.divisor; }

constexpr float kClear[3] = {0.10f, 0.10f, 0.11f};  // the window where neither the image nor a panel is

constexpr double kFramePeriod = 1.0 / 60;   // UI pacing where vsync does not block (Xvfb, some drivers)
constexpr double kEarlyFrameGap = 0.004;    // a new edit's first image may go up this soon after a frame
// A live image is waited for in its edit's own frame up to this long (when the last one was as quick):
constexpr std::chrono::milliseconds kLiveImageWait{12};
constexpr double kDrawTime = 0.005;         // what a frame keeps for drawing after that wait, seconds
constexpr double kActivityWindow = 1.0;     // keep drawing this long after an input event, seconds
constexpr double kIdleWait = 0.5;           // idle wake-up period, seconds: also the file poll rate
constexpr double kFilePollPeriod = 0.5;     // "poll mtime about twice a second"
constexpr float kSidebarWidth = 400;        // panel width at UI scale 1, ImGui units
constexpr int kInteractiveDivisor = 4;      // while dragging, refine no further than 1/4 resolution
constexpr float kPresenterScale = 1.9f;     // presenter mode's UI size at 1080 lines (in proportion to the height)

// The renderer's settings for the panel's; the eye is the schedule's (RenderSchedule::send_settings).
ProgressiveSettings progressive_settings(const ui::RenderSettings& s, bool small_multiples) {
  ProgressiveSettings p;
  p.term_images = small_multiples;  // one trace, five sums
  p.target_spp = s.target_spp;
  p.threads = s.threads;
  // The small multiples' last cell is the full image, the sum of the five term images: the
  // main image is then the full one, whichever term the panel has selected.
  p.term = small_multiples ? Term::kFull : s.term;
  // What ambient stands in for: the image with indirect light, or the indirect term with the
  // lecture's terms beside it (display_pixels puts its ambient term and the indirect one side by side).
  if (s.ambient_view == ui::AmbientView::kIndirect) p.ambient = Ambient::kIndirect;
  if (s.ambient_view == ui::AmbientView::kBeside || s.ambient_view == ui::AmbientView::kDifference) {
    p.term = Term::kIndirect;
    p.term_images = true;
  }
  p.interactive_divisor = kInteractiveDivisor;
  p.live_images_per_s = s.live_images_per_s;
  p.tree_budget_bytes = static_cast<std::size_t>(std::max(s.tree_budget_mib, 0)) << 20;
  p.lower_thread_priority = true;  // the UI thread stays ahead of the workers on few cores
  return p;
}


bool same_camera(const Camera& a, const Camera& b) {
  return a.position == b.position && a.look_at == b.look_at && a.up == b.up && a.fov_y_deg == b.fov_y_deg;
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
  start_signal_watcher();  // before GLFW and Mesa start their threads
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
      renderer_(progressive_settings(ui::RenderSettings{}, false), [] { glfwPostEmptyEvent(); }),
      schedule_(renderer_) {}

Viewer::~Viewer() = default;

std::string Viewer::init() {
  ImGui::GetIO().UserData = &item_locations_;
  std::string error = image_view_.init(glfwGetProcAddress);
  if (!error.empty()) return error;
  for (ImageView& view : terms_.views) {
    error = view.init(glfwGetProcAddress);
    if (!error.empty()) return error;
  }
  if (!doc_.open(options_.scene_arg)) {
    // The UI starts anyway, on the default scene, with the file's diagnostics on show.
    const std::string load_error = doc_.error_text();
    std::cerr << "phonglab: " << load_error << "\n";
    doc_.open("lecture");
    files_.file_state().error_text = load_error;
    files_.file_state().path_field = options_.scene_arg;
  } else {
    files_.file_state().status = doc_.status();
    files_.file_state().path_field = doc_.file_path();
  }
  edits_.replaced = true;
  selected_light_ = doc_.scene().lights.empty() ? -1 : 0;
  if (!options_.lesson_arg.empty()) lesson_shell_.open_lesson(options_.lesson_arg);  // a lesson that fails to load is shown in its panel
  // A lesson's steps are nobody's file: what an earlier session kept is offered once it closes.
  files_.recovery().after_lesson = lessons_.lesson() != nullptr || lessons_.waiting() != nullptr;
  if (!files_.recovery().after_lesson) files_.find_recovery();
  if (!options_.script_path.empty()) {
    std::ifstream in(options_.script_path);
    if (!in) return "cannot read script " + options_.script_path;
    std::ostringstream text;
    text << in.rdbuf();
    script_.load(parse_script(text.str()));
    client_ = &script_;
  }
  if (!options_.stats_log_path.empty()) {
    stats_.log.open(options_.stats_log_path);
    if (!stats_.log) return "cannot write " + options_.stats_log_path;
  }
  update_title();
  return {};
}

int Viewer::run() {
  GLFWwindow* window = platform_.window();
  stats_.last_frame_start = glfwGetTime();
  while (!quit_) {
    wait_for_next_frame();
    if (files_.handle_signal()) break;
    const double frame_start = glfwGetTime();
    const double frame_seconds = frame_start - stats_.last_frame_start;
    stats_.last_frame_start = frame_start;
    // Frames after an idle sleep say nothing about drawing speed.
    if (!stats_.slept_idle) stats_.frame_times.emplace_back(frame_start, frame_seconds);
    while (!stats_.frame_times.empty() && stats_.frame_times.front().first < frame_start - 1.0) stats_.frame_times.pop_front();
    // Frames paced while the renderer works are the ones the 60 Hz target is about.
    if (stats_.was_rendering && stats_.log) {
      stats_.busy_frame_ms.push_back(frame_seconds * 1e3);
      stats_.log << "frame " << frame_start * 1e3 << " " << frame_seconds * 1e3 << "\n";
    }
    stats_.was_rendering = !renderer_.status().idle;

    // Presenter mode reads from the back of a hall: every text and marker grows with the window's
    // height (the UI font about 28 px at 1080 lines, the caption's title about 60 px).
    float presenter = 1;
    if (lesson_shell_.state().presenting) {
      int window_w = 0, window_h = 0;
      glfwGetWindowSize(window, &window_w, &window_h);
      presenter = std::max(1.0f, static_cast<float>(window_h) / 1080.0f * kPresenterScale);
    }
    platform_.set_user_scale(display_.ui_size * presenter);
    platform_.update_scale();
    if (glfwWindowShouldClose(window)) {
      // Closing goes through the unsaved-changes guard like any other way of quitting.
      glfwSetWindowShouldClose(window, GLFW_FALSE);
      files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kQuit, {}});
    }
    poll_scene_file(frame_start);

    int fb_width = 0, fb_height = 0;
    glfwGetFramebufferSize(window, &fb_width, &fb_height);
    if (fb_width <= 0 || fb_height <= 0) continue;  // minimised: nothing to draw, keep running

    platform_.begin_backend_frame();
    if (client_) client_->before_frame(frame_start);
    ImGui::NewFrame();
    layout();
    handle_viewport_input();
    panels_.draw_sidebar();
    overlays_.draw_overlays();
    files_.handle_guard_modal();
    files_.handle_recovery_modal();
    apply_edits(frame_start);
    lesson_shell_.update_lesson();
    session_.recovery().autosave(doc_, frame_start);
    ImGui::Render();
    // A frame that would draw the same pixels as the one on screen is not drawn: software GL
    // spends the UI thread's time (and the machine's memory traffic) on every copy and swap.
    const std::string shot = client_ ? client_->screenshot_wanted() : "";
    if (frame_changed(fb_width, fb_height) || !shot.empty()) {
      draw_gl(fb_width, fb_height, shot);
      glfwSwapBuffers(window);
      ++stats_.frames_drawn;
    }
    after_swap();
  }
  write_stats_summary("session");
  if (!files_.recovery().keep) session_.recovery().remove();  // a clean quit (saved, or the edits discarded)
  if (exit_code_ != 0) return exit_code_;
  return client_ ? client_->exit_status() : 0;
}

bool Viewer::poll_render_frame() {
  if (!renderer_.take_frame(shown_)) return false;
  upload_pending_ = true;
  if (stats_.log && shown_.stats.serial != stats_.last_pass_serial && shown_.stats.pass_ms > 0) {
    stats_.last_pass_serial = shown_.stats.serial;
    stats_.pass_mrays[level_key(shown_)].push_back(shown_.stats.mrays_per_s);
  }
  return true;
}

void Viewer::wait_for_next_frame() {
  const ProgressiveStatus status = renderer_.status();
  const double now = glfwGetTime();
  const bool script_running = client_ && client_->busy();
  const bool busy = !status.idle || upload_pending_ || now - platform_.last_event_time() < kActivityWindow ||
                    script_running || files_.dialogs().guard_visible || files_.browser().visible() || drag_.mode != DragMode::kNone;
  stats_.slept_idle = !busy;
  if (!busy) {
    // Nothing moves: sleep until an event, a new image (the render thread posts an empty
    // event) or the next file poll.
    glfwWaitEventsTimeout(kIdleWait);
    poll_render_frame();
    return;
  }
  const double deadline = stats_.last_frame_start + kFramePeriod;
  for (;;) {
    poll_render_frame();
    // The first image after an edit goes up at once: that is the latency users feel.
    const bool first_image = upload_pending_ && shown_.generation != drawn_generation_;
    const double t = glfwGetTime();
    const double early = stats_.last_frame_start + kEarlyFrameGap;
    if (first_image && t >= early) break;
    if (t >= deadline) break;
    glfwWaitEventsTimeout(first_image ? early - t : deadline - t);
  }
  glfwPollEvents();
}

void Viewer::poll_scene_file(double now) {
  if (now < next_file_poll_) return;
  next_file_poll_ = now + kFilePollPeriod;
  if (doc_.file_path().empty() || !files_.file_state().auto_reload || !doc_.changed_on_disk()) {
    files_.file_state().changed_on_disk = false;
    return;
  }
  if (doc_.dirty()) {
    files_.file_state().changed_on_disk = true;  // never throw away edits silently
    return;
  }
  files_.reload_scene(true);
}

void Viewer::layout() {
  const ImGuiIO& io = ImGui::GetIO();
  const float sidebar = sidebar_visible_ ? std::min(kSidebarWidth * platform_.ui_scale(), io.DisplaySize.x * 0.5f) : 0;
  viewport_ = ViewportRect{0, 0, std::max(io.DisplaySize.x - sidebar, 0.0f), io.DisplaySize.y};
  // A lesson's caption lies below the image, never over it: the image leaves it its strip.
  viewport_.height = std::max(viewport_.height - lesson_shell_.caption_strip_height(viewport_.width, io.DisplaySize.y), 0.0f);
}

Viewer::Cells Viewer::cells() const {
  Cells c;
  c.columns = instruments_.small_multiples ? kMultiplesColumns : 1;
  c.rows = instruments_.small_multiples ? kMultiplesRows : 1;
  c.x = viewport_.x;
  c.y = viewport_.y;
  c.width = viewport_.width / static_cast<float>(c.columns);
  c.height = viewport_.height / static_cast<float>(c.rows);
  return c;
}

double Viewer::view_aspect() const {
  if (!(viewport_.width >= 1 && viewport_.height >= 1)) return 0;
  const Cells c = cells();
  return static_cast<double>(c.width) / static_cast<double>(c.height);
}

Camera Viewer::view_camera() const {
  const Scene& scene = doc_.scene();
  const double framed = scene.height > 0 ? static_cast<double>(scene.width) / scene.height : 0;
  return ui::fit_to_view(scene.camera, framed, view_aspect());
}

void Viewer::note_restart(std::uint64_t generation, double edit_time) {
  restart_times_.emplace_back(generation, edit_time);
  if (stats_.log) stats_.full_pending.emplace_back(generation, edit_time);
  constexpr std::size_t kKeep = 256;  // a few seconds of drag frames; older ones never show
  while (restart_times_.size() > kKeep) restart_times_.pop_front();
  if (client_) client_->restarted(generation);
}

void Viewer::apply_edits(double frame_start) {
  const ImGuiIO& io = ImGui::GetIO();
  if (edits_.frame_requested && viewport_.height > 0) {
    // Framed for the scene's own image: the view's fitting keeps that in any window.
    const Scene& scene = session_.scene();
    const double framed = scene.height > 0 ? static_cast<double>(scene.width) / scene.height : 1;
    Camera camera = scene.camera;
    if (ui::frame_scene(camera, scene, framed)) move_camera(camera);
  }
  if (edits_.reset_requested) move_camera(doc_.loaded_camera());
  const Scene& scene = session_.scene();
  edits_.frame_requested = edits_.reset_requested = false;
  // Any change the lesson did not make itself leaves its step as written: exploring.
  if (lessons_.lesson() && !lesson_shell_.state().applied && (edits_.scene || edits_.camera || edits_.settings || edits_.view)) {
    lessons_.explored();
  }
  lesson_shell_.state().applied = false;
  if (edits_.scene) session_.recovery().edited(frame_start);
  if (edits_.replaced) {
    dolly_limit_ = ui::dolly_limit(scene, doc_.loaded_camera());
    session_.reset_history();
    solo_ = ui::LightSolo{};
  }
  // One undo step per gesture: a slider drag, a light drag or an object drag commits when it ends.
  session_.settle(ImGui::IsAnyItemActive() || drag_.mode != DragMode::kNone);

  // "Move your head": a new shading eye (angle, probe or camera changed) re-shades; while a
  // slider is held, the next eye waits for the last one's image (RenderSchedule::offer_eye).
  if (schedule_.offer_eye(tools_.head_eye(), interacting_ || edits_.while_active || ImGui::IsAnyItemActive())) {
    edits_.settings = true;
    if (tools_.probe().tree) tools_.refresh_probe();
  }
  // The small multiples, turned on or off from anywhere (panel, M, script): term images or none;
  // a lesson's difference keeps the live image at A's samples: the target follows it.
  if (schedule_.wants_changed(instruments_.small_multiples, tools_.target_spp())) edits_.settings = true;
  if (edits_.settings) {
    upload_pending_ = true;  // what the image shows of the same frame may change (the ambient views)
    // The probe's indirect numbers come with an ambient view and go with it.
    if (tools_.probe().tree && tools_.probe().with_indirect != tools_.shows_indirect()) tools_.refresh_probe();
    ui::RenderSettings settings = render_settings_;
    settings.target_spp = tools_.target_spp();
    const bool multiples = instruments_.small_multiples;
    if (const std::uint64_t generation = schedule_.send_settings(progressive_settings(settings, multiples), multiples)) {
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
  // A new window aspect may widen or narrow the fitted field of view: a new camera.
  const auto& snapshot = schedule_.snapshot();
  if (snapshot && !same_camera(view_camera(), snapshot->scene().camera)) edits_.camera = true;
  const bool dragging = interacting_ || edits_.while_active;
  if (formulas_.sync_rules()) edits_.view = true;  // the formulas that render changed: a new snapshot
  const RenderSchedule::Sent sent = schedule_.send_scene(
      {edits_.scene || edits_.camera || edits_.replaced || edits_.view, edits_.replaced, dragging, width, height, frame_start},
      [&] {
        Scene snapshot_scene = scene;
        snapshot_scene.camera = view_camera();
        // The depth cut changes what is rendered, never the scene: history and file keep max_depth.
        apply_depth_cut(snapshot_scene, ui::depth_cut_of(rays_));
        return snapshot_scene;
      });
  // Latency counts from the oldest edit this snapshot carries.
  if (sent.scene) note_restart(sent.generation, sent.edit_time);
  if (sent.restarted && tools_.probe().tree) tools_.refresh_probe();
  renderer_.set_interacting(interacting_ || edits_.while_active);
  // A live edit (a slider held, a light dragged) shows in the UI frame that made it: its image
  // takes a few milliseconds, far less than the wait for the next frame. The frame waits only
  // as long as its period leaves after drawing, and only when the last live image took no longer.
  const auto left = std::chrono::duration<double>(frame_start + kFramePeriod - kDrawTime - glfwGetTime());
  const auto wait = std::min(std::chrono::duration_cast<std::chrono::milliseconds>(left), kLiveImageWait);
  if (sent.scene && dragging && wait.count() > 0 &&
      renderer_.wait_for_live_image(schedule_.sent_generation(), wait, wait)) {
    poll_render_frame();
  }
  edits_.scene = edits_.camera = edits_.replaced = edits_.settings = edits_.view = false;
  formulas_.poll_check();
  tools_.take_a_when_final();
  update_title();
}

float Viewer::image_exposure_ev() const {
  // The heat map's colours are final: exposure does not apply to them.
  return tools_.heat_shown() ? 0.0f : display_.exposure_ev;
}

void Viewer::upload_images(int view_w, int view_h) {
  const float exposure_ev = image_exposure_ev();
  const bool has_frame = shown_.width > 0 && shown_.height > 0;
  if (upload_pending_) {
    heat_max_ = tools_.heat_shown() ? heat_max(shown_.pixels) : 0;
    if (shown_.generation != drawn_generation_) first_image_generation_ = shown_.generation;
    drawn_generation_ = shown_.generation;
    drawn_serial_ = shown_.stats.serial;
  }
  // A new image, or new display settings for the one on screen: encoded and uploaded again. A
  // coarse level filling the view is widened into its blocks: the blit is then a plain copy.
  if (has_frame && (upload_pending_ || !image_view_.shows(exposure_ev, display_.srgb))) {
    DisplayBlocks blocks;
    if (!instruments_.small_multiples && shown_.divisor > 1) blocks = {shown_.divisor, view_w, view_h};
    image_view_.upload(shown_.width, shown_.height, tools_.display_pixels(), exposure_ev, display_.srgb, blocks);
  }
  // The small multiples' cells: the five term images of the same samples, when it has them.
  for (std::size_t i = 0; i < terms_.views.size(); ++i) {
    if (has_frame && !shown_.terms[i].empty() &&
        (upload_pending_ || !terms_.views[i].shows(display_.exposure_ev, display_.srgb))) {
      terms_.views[i].upload(shown_.width, shown_.height, shown_.terms[i], display_.exposure_ev, display_.srgb);
    }
  }
  upload_pending_ = false;
}

bool Viewer::images_stale() const {
  if (upload_pending_ || (shown_.width > 0 && !image_view_.shows(image_exposure_ev(), display_.srgb))) return true;
  for (std::size_t i = 0; i < terms_.views.size(); ++i) {
    if (!shown_.terms[i].empty() && !terms_.views[i].shows(display_.exposure_ev, display_.srgb)) return true;
  }
  return false;
}

bool Viewer::frame_changed(int fb_width, int fb_height) {
  // What decides the pixels besides the image: ImGui's draw data, the window and the view.
  serialize_draw_data(*ImGui::GetDrawData(), frame_bytes_);
  const std::array<float, 7> layout{static_cast<float>(fb_width), static_cast<float>(fb_height), viewport_.x, viewport_.y,
                                    viewport_.width, viewport_.height, instruments_.small_multiples ? 1.0f : 0.0f};
  const auto* bytes = reinterpret_cast<const unsigned char*>(layout.data());
  frame_bytes_.insert(frame_bytes_.end(), bytes, bytes + sizeof layout);
  const bool refresh = platform_.take_refresh();
  const bool changed = refresh || images_stale() || frame_bytes_ != drawn_bytes_;
  std::swap(frame_bytes_, drawn_bytes_);
  return changed;
}

void Viewer::draw_gl(int fb_width, int fb_height, const std::string& screenshot) {
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  const int view_w = static_cast<int>(std::lround(viewport_.width * scale.x));
  const int view_h = static_cast<int>(std::lround(viewport_.height * scale.y));
  const int view_x = static_cast<int>(std::lround(viewport_.x * scale.x));
  const int view_y = fb_height - view_h - static_cast<int>(std::lround(viewport_.y * scale.y));  // GL counts from the bottom
  upload_images(view_w, view_h);
  glViewport(0, 0, fb_width, fb_height);
  // The sidebar, when shown, runs from the view's right edge to the window's (Sidebar::draw_sidebar).
  const int panel_x = static_cast<int>(std::lround(viewport_.width * scale.x));
  const bool panel = sidebar_visible_ && panel_x < fb_width;
  // The image copied over the whole view, up to the panel or the window's edge, leaves nothing to clear.
  const bool covered = !instruments_.small_multiples && view_x == 0 && view_y == 0 && view_h == fb_height &&
                       view_w == (panel ? panel_x : fb_width) && image_view_.width() == view_w &&
                       image_view_.height() == view_h;
  if (!covered) {
    glClearColor(kClear[0], kClear[1], kClear[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  if (panel) {
    // The panel's background as ImGui would blend it over the clear colour (Sidebar draws none).
    const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glEnable(GL_SCISSOR_TEST);
    glScissor(panel_x, 0, fb_width - panel_x, fb_height);
    glClearColor(bg.x * bg.w + kClear[0] * (1 - bg.w), bg.y * bg.w + kClear[1] * (1 - bg.w),
                 bg.z * bg.w + kClear[2] * (1 - bg.w), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
  }
  if (instruments_.small_multiples) {
    // 3 x 2 cells, top row first; GL rows count from the bottom.
    const int cell_w = view_w / kMultiplesColumns;
    const int cell_h = view_h / kMultiplesRows;
    for (int cell = 0; cell < kMultiplesColumns * kMultiplesRows; ++cell) {
      const int x = view_x + (cell % kMultiplesColumns) * cell_w;
      const int y = view_y + (kMultiplesRows - 1 - cell / kMultiplesColumns) * cell_h;
      if (cell == kTermCells) {
        image_view_.draw(x, y, cell_w, cell_h, shown_.divisor > 1);
        continue;
      }
      const auto i = static_cast<std::size_t>(cell);
      if (terms_.views[i].has_image()) {
        terms_.views[i].draw(x, y, cell_w, cell_h, shown_.divisor > 1);
      }
    }
  } else {
    // Coarse levels as crisp blocks; a reduced-resolution final image is smoothed.
    const bool nearest = shown_.divisor > 1 || image_view_.width() == view_w;
    image_view_.draw(view_x, view_y, view_w, view_h, nearest);
  }
  glViewport(0, 0, fb_width, fb_height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!screenshot.empty()) {
    files_.save_window_screenshot(screenshot, fb_width, fb_height);
  }
}

void Viewer::after_swap() {
  const double now = glfwGetTime();
  if (stats_.log && drawn_generation_ != 0) {
    // Levels are counted while the hand is on: scripted input or edits under way, a drag, a
    // held slider; not the refinement after it lets go.
    const bool hand_on = (client_ && client_->hand_on()) || interacting_ ||
                         edits_.while_active;
    if (hand_on) ++stats_.frames_at_level[level_key(shown_)];
    // An edit is seen at full resolution once an exact image of it, or of a later edit, is.
    while (level_key(shown_) == 1 && !stats_.full_pending.empty() && stats_.full_pending.front().first <= drawn_generation_) {
      stats_.edit_to_full_ms.push_back((now - stats_.full_pending.front().second) * 1e3);
      stats_.full_pending.pop_front();
    }
  }
  if (first_image_generation_ == 0) return;
  for (const auto& [generation, edit_time] : restart_times_) {
    if (generation != first_image_generation_) continue;
    stats_.last_latency_ms = (now - edit_time) * 1e3;
    stats_.last_first_image = std::string(shown_.stats.live       ? "live"
                                          : shown_.stats.reshaded ? "reshaded"
                                          : shown_.quads          ? "quads"
                                                                  : "traced") +
                              " 1/" + std::to_string(shown_.divisor);
    // The renderer's share: restart to publication of this image.
    if (stats_.log) {
      stats_.latencies_ms.push_back(stats_.last_latency_ms);
      stats_.log << "latency " << generation << " " << stats_.last_latency_ms << " 1/" << shown_.divisor << " render_ms "
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
         drawn_generation_ == status.generation && !upload_pending_;
}

void Viewer::write_stats_summary(const std::string& label) {
  if (!stats_.log) return;
  stats_.log << "summary " << label << " ui_frames " << stats_.busy_frame_ms.size() << " mean_ms " << mean(stats_.busy_frame_ms)
             << " p50_ms " << percentile(stats_.busy_frame_ms, 0.5) << " p95_ms " << percentile(stats_.busy_frame_ms, 0.95)
             << " p99_ms " << percentile(stats_.busy_frame_ms, 0.99) << " max_ms " << percentile(stats_.busy_frame_ms, 1.0) << "\n";
  stats_.log << "summary " << label << " edit_to_image n " << stats_.latencies_ms.size() << " mean_ms " << mean(stats_.latencies_ms)
             << " p50_ms " << percentile(stats_.latencies_ms, 0.5) << " p95_ms " << percentile(stats_.latencies_ms, 0.95)
             << " max_ms " << percentile(stats_.latencies_ms, 1.0) << "\n";
  const auto frames_at = [&](int divisor) {
    const auto it = stats_.frames_at_level.find(divisor);
    return it == stats_.frames_at_level.end() ? 0 : it->second;
  };
  stats_.log << "levels " << label << " full=" << frames_at(1) << " half=" << frames_at(2) << " quarter=" << frames_at(4)
             << " eighth=" << frames_at(8) << "\n";
  stats_.log << "levels " << label << " rung quads=" << frames_at(0) << "\n";
  // Cores taken since the reset: the UI thread's (drawing included, llvmpipe being on it) and
  // the whole previewer's.
  const CpuClock cpu = CpuClock::now();
  const double wall = cpu.wall - stats_.cpu_mark.wall;
  if (stats_.cpu_mark.wall > 0 && wall > 0) {
    stats_.log << "summary " << label << " cores ui " << (cpu.thread - stats_.cpu_mark.thread) / wall << " all "
               << (cpu.process - stats_.cpu_mark.process) / wall << " drawn_frames " << stats_.frames_drawn << "\n";
  }
  stats_.log << "summary " << label << " edit_to_full n " << stats_.edit_to_full_ms.size() << " p50_ms "
             << percentile(stats_.edit_to_full_ms, 0.5) << " p95_ms " << percentile(stats_.edit_to_full_ms, 0.95) << "\n";
  // The passes' ray rates by level, each as a share of the full-resolution median (issue 14's
  // "small passes as efficient as large ones", as the stats overlay shows them).
  const auto full = stats_.pass_mrays.find(1);
  const double full_median = full != stats_.pass_mrays.end() ? percentile(full->second, 0.5) : 0;
  for (const auto& [divisor, mrays] : stats_.pass_mrays) {
    const double median = percentile(mrays, 0.5);
    stats_.log << "summary " << label << " passes " << (divisor == 0 ? "quads" : "1/" + std::to_string(divisor)) << " n " << mrays.size() << " median_mrays " << median
               << " of_full " << (full_median > 0 ? median / full_median : 0) << "\n";
  }
  stats_.log.flush();
}

void Viewer::apply_edit(const Edit& edit) {
  session_.apply(edit);
  edits_.scene = true;  // a restart, as for any edit a panel reports
}

void Viewer::undo() {
  if (session_.undo()) restored();
}

void Viewer::redo() {
  if (session_.redo()) restored();
}

void Viewer::restored() {
  const Scene& scene = session_.scene();
  selected_light_ = std::min(selected_light_, static_cast<int>(scene.lights.size()) - 1);
  if (selected_object_ >= ui::object_count(scene)) selected_object_ = -1;
  builder_.notice() = ui::EditNotice{};
  edits_.scene = true;
}

}  // namespace phonglab
