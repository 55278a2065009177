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
    // The render thread only wakes the event loop; the UI takes the image itself.
    : s_(platform, options, progressive_settings(ui::RenderSettings{}, false), [] { Platform::wake(); }) {}

Viewer::~Viewer() = default;

std::string Viewer::init() {
  ImGui::GetIO().UserData = &s_.item_locations;
  if (!s_.platform.headless()) {
    std::string error = s_.image_view.init(glfwGetProcAddress);
    if (!error.empty()) return error;
    for (ImageView& view : term_views_) {
      error = view.init(glfwGetProcAddress);
      if (!error.empty()) return error;
    }
  }
  if (!s_.doc.open(s_.options.scene_arg)) {
    // The UI starts anyway, on the default scene, with the file's diagnostics on show.
    const std::string load_error = s_.doc.error_text();
    std::cerr << "phonglab: " << load_error << "\n";
    s_.doc.open("lecture");
    files_.file_state().error_text = load_error;
    files_.file_state().path_field = s_.options.scene_arg;
  } else {
    files_.file_state().status = s_.doc.status();
    files_.file_state().path_field = s_.doc.file_path();
  }
  s_.edits.replaced = true;
  s_.selected_light = s_.doc.scene().lights.empty() ? -1 : 0;
  if (!s_.options.lesson_arg.empty()) lesson_shell_.open_lesson(s_.options.lesson_arg);  // a lesson that fails to load is shown in its panel
  // A lesson's steps are nobody's file: what an earlier session kept is offered once it closes.
  files_.recovery().after_lesson = s_.lessons.lesson() != nullptr || s_.lessons.waiting() != nullptr;
  if (!files_.recovery().after_lesson) files_.find_recovery();
  if (!s_.options.script_path.empty()) {
    std::ifstream in(s_.options.script_path);
    if (!in) return "cannot read script " + s_.options.script_path;
    std::ostringstream text;
    text << in.rdbuf();
    script_.load(parse_script(text.str()));
    client_ = &script_;
  }
  if (!s_.options.stats_log_path.empty()) {
    s_.stats.log.open(s_.options.stats_log_path);
    if (!s_.stats.log) return "cannot write " + s_.options.stats_log_path;
  }
  update_title();
  return {};
}

int Viewer::run() {
  s_.stats.last_frame_start = s_.platform.now();
  while (!s_.quit) {
    wait_for_next_frame();
    if (files_.handle_signal()) break;
    const double frame_start = s_.platform.now();
    const double frame_seconds = frame_start - s_.stats.last_frame_start;
    s_.stats.last_frame_start = frame_start;
    // Frames after an idle sleep say nothing about drawing speed.
    if (!s_.stats.slept_idle) s_.stats.frame_times.emplace_back(frame_start, frame_seconds);
    while (!s_.stats.frame_times.empty() && s_.stats.frame_times.front().first < frame_start - 1.0) s_.stats.frame_times.pop_front();
    // Frames paced while the renderer works are the ones the 60 Hz target is about.
    if (s_.stats.was_rendering && s_.stats.log) {
      s_.stats.busy_frame_ms.push_back(frame_seconds * 1e3);
      s_.stats.log << "frame " << frame_start * 1e3 << " " << frame_seconds * 1e3 << "\n";
    }
    s_.stats.was_rendering = !s_.renderer.status().idle;

    // Presenter mode reads from the back of a hall: every text and marker grows with the window's
    // height (the UI font about 28 px at 1080 lines, the caption's title about 60 px).
    float presenter = 1;
    if (lesson_shell_.state().presenting) {
      int window_w = 0, window_h = 0;
      s_.platform.window_size(window_w, window_h);
      presenter = std::max(1.0f, static_cast<float>(window_h) / 1080.0f * kPresenterScale);
    }
    s_.platform.set_user_scale(s_.display.ui_size * presenter);
    s_.platform.update_scale();
    if (s_.platform.take_close_request()) {
      // Closing goes through the unsaved-changes guard like any other way of quitting.
      files_.request(FileShell::PendingAction{FileShell::PendingAction::Kind::kQuit, {}});
    }
    poll_scene_file(frame_start);

    int fb_width = 0, fb_height = 0;
    s_.platform.framebuffer_size(fb_width, fb_height);
    if (fb_width <= 0 || fb_height <= 0) continue;  // minimised: nothing to draw, keep running

    s_.platform.begin_backend_frame();
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
    s_.session.recovery().autosave(s_.doc, frame_start);
    ImGui::Render();
    // A frame that would draw the same pixels as the one on screen is not drawn: software GL
    // spends the UI thread's time (and the machine's memory traffic) on every copy and swap.
    const std::string shot = client_ ? client_->screenshot_wanted() : "";
    const auto plan = [&] {  // what lies under ImGui's draw data, for either way of drawing it
      return plan_screen(s_, fb_width, fb_height, ImGui::GetIO().DisplayFramebufferScale,
                         ImGui::GetStyle().Colors[ImGuiCol_WindowBg]);
    };
    if (s_.platform.headless()) {
      if (!shot.empty()) draw_software(plan(), fb_width, fb_height, shot);  // what the window would show, drawn on the CPU
      take_images();
      s_.upload_pending = false;
    } else if (frame_changed(fb_width, fb_height) || !shot.empty()) {
      draw_gl(plan(), fb_width, fb_height, shot);
      s_.platform.swap_buffers();
      ++s_.stats.frames_drawn;
    }
    after_swap();
  }
  write_stats_summary(s_.stats, "session");
  if (!files_.recovery().keep) s_.session.recovery().remove();  // a clean quit (saved, or the edits discarded)
  if (s_.exit_code != 0) return s_.exit_code;
  return client_ ? client_->exit_status() : 0;
}

bool Viewer::poll_render_frame() {
  if (!s_.renderer.take_frame(s_.shown)) return false;
  s_.upload_pending = true;
  if (s_.stats.log && s_.shown.stats.serial != s_.stats.last_pass_serial && s_.shown.stats.pass_ms > 0) {
    s_.stats.last_pass_serial = s_.shown.stats.serial;
    s_.stats.pass_mrays[level_key(s_.shown)].push_back(s_.shown.stats.mrays_per_s);
  }
  return true;
}

void Viewer::wait_for_next_frame() {
  const ProgressiveStatus status = s_.renderer.status();
  const double now = s_.platform.now();
  const bool script_running = client_ && client_->busy();
  const bool busy = !status.idle || s_.upload_pending || now - s_.platform.last_event_time() < kActivityWindow ||
                    script_running || files_.guard_visible() || files_.browser().visible() || s_.drag.mode != DragMode::kNone;
  s_.stats.slept_idle = !busy;
  if (!busy) {
    // Nothing moves: sleep until an event, a new image (the render thread posts an empty
    // event) or the next file poll.
    s_.platform.wait_events(kIdleWait);
    poll_render_frame();
    return;
  }
  const double deadline = s_.stats.last_frame_start + kFramePeriod;
  for (;;) {
    poll_render_frame();
    // The first image after an edit goes up at once: that is the latency users feel.
    const bool first_image = s_.upload_pending && s_.shown.generation != s_.drawn_generation;
    const double t = s_.platform.now();
    const double early = s_.stats.last_frame_start + kEarlyFrameGap;
    if (first_image && t >= early) break;
    if (t >= deadline) break;
    s_.platform.wait_events(first_image ? early - t : deadline - t);
  }
  s_.platform.poll_events();
}

void Viewer::poll_scene_file(double now) {
  if (now < next_file_poll_) return;
  next_file_poll_ = now + kFilePollPeriod;
  files_.poll_file();
}

void Viewer::layout() {
  const ImGuiIO& io = ImGui::GetIO();
  const float sidebar = s_.sidebar_visible ? std::min(kSidebarWidth * s_.platform.ui_scale(), io.DisplaySize.x * 0.5f) : 0;
  s_.viewport = ViewportRect{0, 0, std::max(io.DisplaySize.x - sidebar, 0.0f), io.DisplaySize.y};
  // A lesson's caption lies below the image, never over it: the image leaves it its strip.
  s_.viewport.height = std::max(s_.viewport.height - lesson_shell_.caption_strip_height(s_.viewport.width, io.DisplaySize.y), 0.0f);
}

void Viewer::note_restart(std::uint64_t generation, double edit_time) {
  restart_times_.emplace_back(generation, edit_time);
  if (s_.stats.log) s_.stats.full_pending.emplace_back(generation, edit_time);
  constexpr std::size_t kKeep = 256;  // a few seconds of drag frames; older ones never show
  while (restart_times_.size() > kKeep) restart_times_.pop_front();
}

void Viewer::apply_edits(double frame_start) {
  const ImGuiIO& io = ImGui::GetIO();
  if (s_.edits.frame_requested && s_.viewport.height > 0) {
    // Framed for the scene's own image: the view's fitting keeps that in any window.
    const Scene& scene = s_.session.scene();
    const double framed = scene.height > 0 ? static_cast<double>(scene.width) / scene.height : 1;
    Camera camera = scene.camera;
    if (ui::frame_scene(camera, scene, framed)) move_camera(s_, camera);
  }
  if (s_.edits.reset_requested) move_camera(s_, s_.doc.loaded_camera());
  const Scene& scene = s_.session.scene();
  s_.edits.frame_requested = s_.edits.reset_requested = false;
  // Any change the lesson did not make itself leaves its step as written: exploring.
  if (s_.lessons.lesson() && !lesson_shell_.state().applied && (s_.edits.scene || s_.edits.camera || s_.edits.settings || s_.edits.view)) {
    s_.lessons.explored();
  }
  lesson_shell_.state().applied = false;
  if (s_.edits.scene) s_.session.recovery().edited(frame_start);
  if (s_.edits.replaced) {
    dolly_limit_ = ui::dolly_limit(scene, s_.doc.loaded_camera());
    s_.session.reset_history();
    s_.solo = ui::LightSolo{};
  }
  // One undo step per gesture: a slider drag, a light drag or an object drag commits when it ends.
  s_.session.settle(ImGui::IsAnyItemActive() || s_.drag.mode != DragMode::kNone);

  // "Move your head": a new shading eye (angle, probe or camera changed) re-shades; while a
  // slider is held, the next eye waits for the last one's image (RenderSchedule::offer_eye).
  if (s_.schedule.offer_eye(tools_.head_eye(), s_.interacting || s_.edits.while_active || ImGui::IsAnyItemActive())) {
    s_.edits.settings = true;
    if (tools_.probe().tree) tools_.refresh_probe();
  }
  // The small multiples, turned on or off from anywhere (panel, M, script): term images or none;
  // a lesson's difference keeps the live image at A's samples: the target follows it.
  if (s_.schedule.wants_changed(s_.instruments.small_multiples, tools_.target_spp())) s_.edits.settings = true;
  if (s_.edits.settings) {
    s_.upload_pending = true;  // what the image shows of the same frame may change (the ambient views)
    // The probe's indirect numbers come with an ambient view and go with it.
    if (tools_.probe().tree && tools_.probe().with_indirect != tools_.shows_indirect()) tools_.refresh_probe();
    ui::RenderSettings settings = s_.render_settings;
    settings.target_spp = tools_.target_spp();
    const bool multiples = s_.instruments.small_multiples;
    if (const std::uint64_t generation = s_.schedule.send_settings(progressive_settings(settings, multiples), multiples)) {
      note_restart(generation, frame_start);
    }
  }

  const float resolution = s_.render_settings.resolution_scale;
  int width = static_cast<int>(std::lround(s_.viewport.width * io.DisplayFramebufferScale.x * resolution));
  int height = static_cast<int>(std::lround(s_.viewport.height * io.DisplayFramebufferScale.y * resolution));
  if (s_.instruments.small_multiples) {
    width /= kMultiplesColumns;
    height /= kMultiplesRows;
  }
  if (s_.viewport.width >= 1 && s_.viewport.height >= 1) {
    width = std::max(width, 1);
    height = std::max(height, 1);
  } else {
    width = height = 0;  // nothing visible: the renderer idles
  }
  // A new window aspect may widen or narrow the fitted field of view: a new camera.
  const auto& snapshot = s_.schedule.snapshot();
  if (snapshot && !same_camera(view_camera(s_), snapshot->scene().camera)) s_.edits.camera = true;
  const bool dragging = s_.interacting || s_.edits.while_active;
  if (formulas_.sync_rules()) s_.edits.view = true;  // the formulas that render changed: a new snapshot
  // The scene's own edits reach the schedule as the document's version; the frame says what
  // changed in its view.
  const RenderSchedule::Sent sent = s_.schedule.send_scene({s_.edits.camera || s_.edits.replaced || s_.edits.view, s_.edits.replaced,
                                                            dragging, width, height, frame_start, view_camera(s_),
                                                            ui::depth_cut_of(s_.rays)},
                                                           scene, s_.doc.version());
  // Latency counts from the oldest edit this snapshot carries.
  if (sent.scene) note_restart(sent.generation, sent.edit_time);
  if (sent.restarted && tools_.probe().tree) tools_.refresh_probe();
  s_.renderer.set_interacting(s_.interacting || s_.edits.while_active);
  // A live edit (a slider held, a light dragged) shows in the UI frame that made it: its image
  // takes a few milliseconds, far less than the wait for the next frame. The frame waits only
  // as long as its period leaves after drawing, and only when the last live image took no longer.
  const auto left = std::chrono::duration<double>(frame_start + kFramePeriod - kDrawTime - s_.platform.now());
  const auto wait = std::min(std::chrono::duration_cast<std::chrono::milliseconds>(left), kLiveImageWait);
  if (sent.scene && dragging && wait.count() > 0 &&
      s_.renderer.wait_for_live_image(s_.schedule.sent_generation(), wait, wait)) {
    poll_render_frame();
  }
  s_.edits.scene = s_.edits.camera = s_.edits.replaced = s_.edits.settings = s_.edits.view = false;
  formulas_.poll_check();
  tools_.take_a_when_final();
  update_title();
}

float Viewer::image_exposure_ev() const {
  // The heat map's colours are final: exposure does not apply to them.
  return tools_.heat_shown() ? 0.0f : s_.display.exposure_ev;
}

void Viewer::take_images() {
  if (!s_.upload_pending) return;
  s_.heat_max = tools_.heat_shown() ? heat_max(s_.shown.pixels) : 0;
  if (s_.shown.generation != s_.drawn_generation) first_image_generation_ = s_.shown.generation;
  s_.drawn_generation = s_.shown.generation;
  s_.drawn_serial = s_.shown.stats.serial;
}

void Viewer::upload_images(const DisplayBlocks& blocks) {
  const float exposure_ev = image_exposure_ev();
  const bool has_frame = s_.shown.width > 0 && s_.shown.height > 0;
  take_images();
  // A new image, or new display settings for the one on screen: encoded and uploaded again.
  if (has_frame && (s_.upload_pending || !s_.image_view.shows(exposure_ev, s_.display.srgb))) {
    s_.image_view.upload(s_.shown.width, s_.shown.height, tools_.display_pixels(), exposure_ev, s_.display.srgb, blocks);
  }
  // The small multiples' cells: the five term images of the same samples, when it has them.
  for (std::size_t i = 0; i < term_views_.size(); ++i) {
    if (has_frame && !s_.shown.terms[i].empty() &&
        (s_.upload_pending || !term_views_[i].shows(s_.display.exposure_ev, s_.display.srgb))) {
      term_views_[i].upload(s_.shown.width, s_.shown.height, s_.shown.terms[i], s_.display.exposure_ev, s_.display.srgb);
    }
  }
  s_.upload_pending = false;
}

bool Viewer::images_stale() const {
  if (s_.upload_pending || (s_.shown.width > 0 && !s_.image_view.shows(image_exposure_ev(), s_.display.srgb))) return true;
  for (std::size_t i = 0; i < term_views_.size(); ++i) {
    if (!s_.shown.terms[i].empty() && !term_views_[i].shows(s_.display.exposure_ev, s_.display.srgb)) return true;
  }
  return false;
}

bool Viewer::frame_changed(int fb_width, int fb_height) {
  // What decides the pixels besides the image: ImGui's draw data, the window and the view.
  serialize_draw_data(*ImGui::GetDrawData(), frame_bytes_);
  const std::array<float, 7> layout{static_cast<float>(fb_width), static_cast<float>(fb_height), s_.viewport.x, s_.viewport.y,
                                    s_.viewport.width, s_.viewport.height, s_.instruments.small_multiples ? 1.0f : 0.0f};
  const auto* bytes = reinterpret_cast<const unsigned char*>(layout.data());
  frame_bytes_.insert(frame_bytes_.end(), bytes, bytes + sizeof layout);
  const bool refresh = s_.platform.take_refresh();
  const bool changed = refresh || images_stale() || frame_bytes_ != drawn_bytes_;
  std::swap(frame_bytes_, drawn_bytes_);
  return changed;
}

void Viewer::draw_gl(const ScreenPlan& plan, int fb_width, int fb_height, const std::string& screenshot) {
  upload_images(plan.view_blocks);
  glViewport(0, 0, fb_width, fb_height);
  if (plan.clear) {
    glClearColor(plan.clear_color.r, plan.clear_color.g, plan.clear_color.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  const auto gl_y = [fb_height](const ui::PixelRect& r) { return fb_height - r.y - r.height; };  // GL counts from the bottom
  if (plan.panel) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(plan.panel_rect.x, gl_y(plan.panel_rect), plan.panel_rect.width, plan.panel_rect.height);
    glClearColor(plan.panel_color.r, plan.panel_color.g, plan.panel_color.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
  }
  for (const ScreenPlan::Image& image : plan.images) {
    ImageView& view = image.source < 0 ? s_.image_view : term_views_[static_cast<std::size_t>(image.source)];
    view.draw(image.rect.x, gl_y(image.rect), image.rect.width, image.rect.height, image.nearest);
  }
  glViewport(0, 0, fb_width, fb_height);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (!screenshot.empty()) {
    if (!files_.save_window_screenshot(screenshot, read_framebuffer_rgb8(fb_width, fb_height), fb_width, fb_height) && client_) {
      client_->screenshot_failed();
    }
  }
}

// The headless screen: what draw_gl would put in the window, drawn on the CPU (ui::SoftwareScreen).
void Viewer::draw_software(const ScreenPlan& plan, int fb_width, int fb_height, const std::string& screenshot) {
  take_images();
  ui::SoftwareScreen screen(fb_width, fb_height);
  if (plan.clear) screen.fill({0, 0, fb_width, fb_height}, plan.clear_color);
  if (plan.panel) screen.fill(plan.panel_rect, plan.panel_color);
  std::vector<unsigned char> codes;
  for (const ScreenPlan::Image& image : plan.images) {
    const bool view = image.source < 0;
    std::vector<glm::vec3> display;  // the view's pixels as shown (a term image is read where it is)
    if (view) display = tools_.display_pixels();
    const std::vector<glm::vec3>& pixels = view ? display : s_.shown.terms[static_cast<std::size_t>(image.source)];
    const DisplayBlocks blocks = view ? plan.view_blocks : DisplayBlocks{1, s_.shown.width, s_.shown.height};
    const float exposure_ev = view ? image_exposure_ev() : s_.display.exposure_ev;
    codes.resize(static_cast<std::size_t>(blocks.width) * static_cast<std::size_t>(blocks.height) * 4);
    const Display8Encoder& encoder = s_.display.srgb ? Display8Encoder::srgb() : Display8Encoder::linear();
    if (pixels.empty() || !encoder.encode_bgra_blocks(pixels.data(), s_.shown.width, s_.shown.height, std::exp2(exposure_ev),
                                                      blocks, false, codes.data())) {
      continue;  // no image yet (or no term images): the cell stays as cleared
    }
    screen.blit(codes.data(), blocks.width, blocks.height, image.rect, image.nearest);
  }
  unsigned char* atlas = nullptr;
  int atlas_w = 0, atlas_h = 0;
  ImGui::GetIO().Fonts->GetTexDataAsRGBA32(&atlas, &atlas_w, &atlas_h);
  screen.draw(*ImGui::GetDrawData(), atlas, atlas_w, atlas_h);
  if (!files_.save_window_screenshot(screenshot, screen.rgb(), fb_width, fb_height) && client_) {
    client_->screenshot_failed();
  }
}

void Viewer::after_swap() {
  const double now = s_.platform.now();
  if (s_.stats.log && s_.drawn_generation != 0) {
    // Levels are counted while the hand is on: scripted input or edits under way, a drag, a
    // held slider; not the refinement after it lets go.
    const bool hand_on = (client_ && client_->hand_on()) || s_.interacting ||
                         s_.edits.while_active;
    if (hand_on) ++s_.stats.frames_at_level[level_key(s_.shown)];
    // An edit is seen at full resolution once an exact image of it, or of a later edit, is.
    while (level_key(s_.shown) == 1 && !s_.stats.full_pending.empty() && s_.stats.full_pending.front().first <= s_.drawn_generation) {
      s_.stats.edit_to_full_ms.push_back((now - s_.stats.full_pending.front().second) * 1e3);
      s_.stats.full_pending.pop_front();
    }
  }
  if (first_image_generation_ == 0) return;
  for (const auto& [generation, edit_time] : restart_times_) {
    if (generation != first_image_generation_) continue;
    s_.stats.last_latency_ms = (now - edit_time) * 1e3;
    s_.stats.last_first_image = std::string(s_.shown.stats.live       ? "live"
                                          : s_.shown.stats.reshaded ? "reshaded"
                                          : s_.shown.quads          ? "quads"
                                                                  : "traced") +
                              " 1/" + std::to_string(s_.shown.divisor);
    // The renderer's share: restart to publication of this image.
    if (s_.stats.log) {
      s_.stats.latencies_ms.push_back(s_.stats.last_latency_ms);
      s_.stats.log << "latency " << generation << " " << s_.stats.last_latency_ms << " 1/" << s_.shown.divisor << " render_ms "
                 << s_.shown.stats.ms_since_restart << " pass_ms " << s_.shown.stats.pass_ms << "\n";
    }
    break;
  }
  // Edits up to this one are on screen or were overtaken by it.
  while (!restart_times_.empty() && restart_times_.front().first <= first_image_generation_) restart_times_.pop_front();
  first_image_generation_ = 0;
}

void Viewer::update_title() {
  std::string title = "phonglab - " + s_.doc.source() + (s_.doc.dirty() ? " *" : "");
  if (title == title_) return;
  title_ = std::move(title);
  s_.platform.set_title(title_);
}

}  // namespace phonglab
