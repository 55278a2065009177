#include "apps/previewer/viewer_platform.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <thread>
#include <utility>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

namespace phonglab {

CpuClock CpuClock::now() {
  const auto seconds = [](clockid_t clock) {
    timespec t{};
    clock_gettime(clock, &t);
    return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
  };
  return {seconds(CLOCK_MONOTONIC), seconds(CLOCK_THREAD_CPUTIME_ID), seconds(CLOCK_PROCESS_CPUTIME_ID)};
}

namespace {

// Readable proportional fonts with Greek and maths glyphs (the equation's sigma and eta);
// the built-in bitmap font is the fallback.
constexpr std::array<const char*, 3> kFontCandidates = {
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
};
// Latin-1, Greek and Coptic, super- and subscripts (the a of I_a, the l of I_l), arrows,
// mathematical operators; zero-terminated as ImGui wants.
constexpr std::array<ImWchar, 11> kGlyphRanges = {0x0020, 0x00FF, 0x0370, 0x03FF, 0x2070, 0x209F,
                                                  0x2190, 0x21FF, 0x2200, 0x22FF, 0};
constexpr float kFontPixels = 15.0f;  // at scale 1
constexpr float kCaptionScale = 2.2f;  // lesson captions: this many times the UI font

// Software OpenGL (Mesa's llvmpipe: a machine or VM without a GPU) rasterises on as many threads
// as there are cores by default, and those threads take the cores the ray tracer's threads need:
// on 2 cores they took more than one core's time while a camera drag was traced. Drawing a blit
// and the panels is light work, so llvmpipe draws on the UI thread alone; a user's own
// LP_NUM_THREADS is kept. Drivers of real GPUs ignore the variable.
void keep_software_gl_on_the_ui_thread() { setenv("LP_NUM_THREADS", "0", /*overwrite=*/0); }

std::string glfw_error_text() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  if (code == GLFW_NO_ERROR) return "unknown error";
  return description != nullptr ? description : "GLFW error " + std::to_string(code);
}

// Whether GLFW runs (a window was made): only then can another thread post it an event.
std::atomic<bool> glfw_running{false};
// The headless platform's clock starts with the process's first use of it.
const auto kHeadlessEpoch = std::chrono::steady_clock::now();

float window_content_scale(GLFWwindow* window) {
  if (window == nullptr) return 1.0f;  // headless
  float x = 1, y = 1;
  glfwGetWindowContentScale(window, &x, &y);
  const float s = std::max(x, y);
  return s > 0 ? s : 1.0f;
}

// Every input or window event refreshes Platform::last_event_time(). Installed before ImGui's
// backend, which then chains to these for the callbacks it also needs.
void note(GLFWwindow* window) {
  if (auto* p = static_cast<Platform*>(glfwGetWindowUserPointer(window))) p->note_event();
}

// An event for the next frame; a frame that never comes (minimised) keeps the newest 256.
template <typename Event>
void push_bounded(std::vector<Event>& queue, const Event& event) {
  constexpr std::size_t kMaxQueued = 256;
  if (queue.size() >= kMaxQueued) queue.erase(queue.begin());
  queue.push_back(event);
}

}  // namespace

void Platform::record_cursor(double x, double y) {
  cursor_x_ = x;
  cursor_y_ = y;
}

void Platform::record_mouse_press(int button, int action) {
  if (action != GLFW_PRESS || button < 0 || button > 2) return;
  MousePress press;
  press.button = button;
  // The cursor as the events so far left it (glfwGetCursorPos would ask the X server for where
  // the pointer is now, after moves not yet delivered).
  press.x = cursor_x_;
  press.y = cursor_y_;
  push_bounded(mouse_presses_, press);
}

namespace {

// A window event after which its contents must be drawn again.
void refresh(GLFWwindow* win) {
  note(win);
  if (auto* p = static_cast<Platform*>(glfwGetWindowUserPointer(win))) p->want_refresh();
}

void install_activity_callbacks(Platform* platform, GLFWwindow* w) {
  glfwSetWindowUserPointer(w, platform);
  glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
    note(win);
    if (auto* p = static_cast<Platform*>(glfwGetWindowUserPointer(win))) p->record_cursor(x, y);
  });
  glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int) {
    note(win);
    if (auto* p = static_cast<Platform*>(glfwGetWindowUserPointer(win))) p->record_mouse_press(button, action);
  });
  glfwSetScrollCallback(w, [](GLFWwindow* win, double, double) { note(win); });
  glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int mods) {
    note(win);
    auto* p = static_cast<Platform*>(glfwGetWindowUserPointer(win));
    if (p != nullptr && key != GLFW_KEY_UNKNOWN && (action == GLFW_PRESS || action == GLFW_REPEAT)) {
      p->push_key_press(KeyPress{key, mods});
    }
  });
  glfwSetCharCallback(w, [](GLFWwindow* win, unsigned int) { note(win); });
  glfwSetDropCallback(w, [](GLFWwindow* win, int count, const char** paths) {
    note(win);
    auto* p = static_cast<Platform*>(glfwGetWindowUserPointer(win));
    for (int i = 0; p != nullptr && i < count; ++i) p->push_drop(paths[i]);
  });
  glfwSetWindowSizeCallback(w, [](GLFWwindow* win, int, int) { refresh(win); });
  glfwSetFramebufferSizeCallback(w, [](GLFWwindow* win, int, int) { refresh(win); });
  glfwSetWindowRefreshCallback(w, [](GLFWwindow* win) { refresh(win); });
  glfwSetWindowFocusCallback(w, [](GLFWwindow* win, int) { note(win); });
  glfwSetCursorEnterCallback(w, [](GLFWwindow* win, int) { note(win); });
  glfwSetWindowIconifyCallback(w, [](GLFWwindow* win, int) { refresh(win); });
  glfwSetWindowContentScaleCallback(w, [](GLFWwindow* win, float, float) { refresh(win); });
}

}  // namespace

void Platform::note_event() { last_event_time_ = now(); }

double Platform::now() const {
  if (window_ != nullptr) return glfwGetTime();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - kHeadlessEpoch).count();
}

void Platform::window_size(int& width, int& height) const {
  if (window_ != nullptr) return glfwGetWindowSize(window_, &width, &height);
  width = headless_size_[0];
  height = headless_size_[1];
}

void Platform::framebuffer_size(int& width, int& height) const {
  if (window_ != nullptr) return glfwGetFramebufferSize(window_, &width, &height);
  width = headless_size_[0];
  height = headless_size_[1];
}

void Platform::set_window_size(int width, int height) {
  if (window_ != nullptr) return glfwSetWindowSize(window_, width, height);
  headless_size_[0] = std::max(width, 0);
  headless_size_[1] = std::max(height, 0);
  want_refresh();
  note_event();
}

void Platform::request_close() {
  if (window_ != nullptr) return glfwSetWindowShouldClose(window_, GLFW_TRUE);  // as the window manager's button
  close_requested_ = true;
}

bool Platform::take_close_request() {
  if (window_ == nullptr) return std::exchange(close_requested_, false);
  if (glfwWindowShouldClose(window_) == 0) return false;
  glfwSetWindowShouldClose(window_, GLFW_FALSE);  // the loop decides (through the unsaved-changes guard)
  return true;
}

void Platform::set_title(const std::string& title) {
  if (window_ != nullptr) glfwSetWindowTitle(window_, title.c_str());
}

void Platform::wait_events(double timeout) {
  if (window_ != nullptr) return glfwWaitEventsTimeout(timeout);
  // Nothing wakes a headless loop: it looks again every few milliseconds.
  std::this_thread::sleep_for(std::chrono::duration<double>(std::clamp(timeout, 0.0, 0.005)));
}

void Platform::poll_events() {
  if (window_ != nullptr) glfwPollEvents();
}

void Platform::swap_buffers() {
  if (window_ != nullptr) glfwSwapBuffers(window_);
}

void Platform::wake() {
  if (glfw_running) glfwPostEmptyEvent();  // GLFW allows it from any thread
}

bool Platform::take_refresh() { return std::exchange(refresh_, false); }

void serialize_draw_data(const ImDrawData& data, std::vector<unsigned char>& out) {
  out.clear();
  const auto put = [&out](const void* bytes, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(bytes);
    out.insert(out.end(), p, p + n);
  };
  put(&data.DisplayPos, sizeof data.DisplayPos);
  put(&data.DisplaySize, sizeof data.DisplaySize);
  put(&data.FramebufferScale, sizeof data.FramebufferScale);
  for (int i = 0; i < data.CmdListsCount; ++i) {
    const ImDrawList& list = *data.CmdLists[i];
    put(list.VtxBuffer.Data, static_cast<std::size_t>(list.VtxBuffer.Size) * sizeof(ImDrawVert));
    put(list.IdxBuffer.Data, static_cast<std::size_t>(list.IdxBuffer.Size) * sizeof(ImDrawIdx));
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      put(&cmd.ClipRect, sizeof cmd.ClipRect);
      put(&cmd.TextureId, sizeof cmd.TextureId);
      put(&cmd.VtxOffset, sizeof cmd.VtxOffset);
      put(&cmd.IdxOffset, sizeof cmd.IdxOffset);
      put(&cmd.ElemCount, sizeof cmd.ElemCount);
      put(&cmd.UserCallback, sizeof cmd.UserCallback);
    }
  }
}

std::vector<KeyPress> Platform::take_key_presses() { return std::exchange(key_presses_, {}); }

std::vector<MousePress> Platform::take_mouse_presses() { return std::exchange(mouse_presses_, {}); }

std::vector<std::string> Platform::take_drops() { return std::exchange(drops_, {}); }

void Platform::push_key_press(KeyPress press) { push_bounded(key_presses_, press); }

std::unique_ptr<Platform> Platform::create(const PlatformOptions& options, std::string& error) {
  std::unique_ptr<Platform> p(new Platform());
  keep_software_gl_on_the_ui_thread();
  if (glfwInit() != GLFW_TRUE) {
    error = "cannot initialise the window system (" + glfw_error_text() + ")";
    return nullptr;
  }
  p->glfw_ready_ = true;
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);  // required by macOS, harmless elsewhere
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);       // HiDPI: window size in logical units
  p->window_ = glfwCreateWindow(std::max(options.width, 1), std::max(options.height, 1), options.title.c_str(),
                                nullptr, nullptr);
  if (p->window_ == nullptr) {
    error = "cannot create a window with an OpenGL 3.3 core context (" + glfw_error_text() + ")";
    return nullptr;
  }
  glfwMakeContextCurrent(p->window_);
  if (gladLoadGL(glfwGetProcAddress) == 0) {
    error = "cannot load the OpenGL 3.3 core functions";
    return nullptr;
  }
  glfwSwapInterval(1);  // vsync where there is one; the main loop paces itself otherwise
  glfw_running = true;
  install_activity_callbacks(p.get(), p->window_);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in the user's working directory: the layout is fixed
  // No keyboard navigation: with it, a focused panel would take F, R and H away from the
  // viewport; text fields still get the keyboard while they are being edited.
  // The app installs its own GLFW callbacks first; ImGui chains to them.
  ImGui_ImplGlfw_InitForOpenGL(p->window_, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  p->imgui_ready_ = true;
  p->apply_scale(window_content_scale(p->window_));
  return p;
}

std::unique_ptr<Platform> Platform::create_headless(const PlatformOptions& options) {
  std::unique_ptr<Platform> p(new Platform());
  p->headless_size_[0] = std::max(options.width, 1);
  p->headless_size_[1] = std::max(options.height, 1);
  p->headless_screen_[0] = options.screen_width;
  p->headless_screen_[1] = options.screen_height;
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  // Keys are GLFW's codes, as under a window (the GLFW backend maps them the same way), so the
  // script's key events mean the same headless.
  const std::array<std::pair<ImGuiKey, int>, 22> keys = {{
      {ImGuiKey_Tab, GLFW_KEY_TAB},         {ImGuiKey_LeftArrow, GLFW_KEY_LEFT}, {ImGuiKey_RightArrow, GLFW_KEY_RIGHT},
      {ImGuiKey_UpArrow, GLFW_KEY_UP},      {ImGuiKey_DownArrow, GLFW_KEY_DOWN}, {ImGuiKey_PageUp, GLFW_KEY_PAGE_UP},
      {ImGuiKey_PageDown, GLFW_KEY_PAGE_DOWN}, {ImGuiKey_Home, GLFW_KEY_HOME},  {ImGuiKey_End, GLFW_KEY_END},
      {ImGuiKey_Insert, GLFW_KEY_INSERT},   {ImGuiKey_Delete, GLFW_KEY_DELETE}, {ImGuiKey_Backspace, GLFW_KEY_BACKSPACE},
      {ImGuiKey_Space, GLFW_KEY_SPACE},     {ImGuiKey_Enter, GLFW_KEY_ENTER},    {ImGuiKey_Escape, GLFW_KEY_ESCAPE},
      {ImGuiKey_KeyPadEnter, GLFW_KEY_KP_ENTER}, {ImGuiKey_A, GLFW_KEY_A},     {ImGuiKey_C, GLFW_KEY_C},
      {ImGuiKey_V, GLFW_KEY_V},             {ImGuiKey_X, GLFW_KEY_X},            {ImGuiKey_Y, GLFW_KEY_Y},
      {ImGuiKey_Z, GLFW_KEY_Z},
  }};
  for (const auto& [key, code] : keys) io.KeyMap[key] = code;
  p->imgui_ready_ = true;
  p->apply_scale(1.0f);
  return p;
}

Platform::~Platform() {
  if (imgui_ready_) {
    if (window_ != nullptr) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
    }
    ImGui::DestroyContext();
  }
  if (window_ != nullptr) {
    glfw_running = false;
    glfwDestroyWindow(window_);
  }
  if (glfw_ready_) glfwTerminate();
}

void Platform::apply_scale(float scale) {
  ui_scale_ = scale;
  ImGuiIO& io = ImGui::GetIO();
  io.Fonts->Clear();
  bool loaded = false;
  caption_font_ = nullptr;
  for (const char* path : kFontCandidates) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) continue;
    if (io.Fonts->AddFontFromFileTTF(path, kFontPixels * scale, nullptr, kGlyphRanges.data()) != nullptr) {
      caption_font_ = io.Fonts->AddFontFromFileTTF(path, kFontPixels * kCaptionScale * scale, nullptr, kGlyphRanges.data());
      loaded = true;
      break;
    }
  }
  if (!loaded) {
    ImFontConfig config;
    config.SizePixels = 13.0f * scale;  // the built-in font's native size
    io.Fonts->AddFontDefault(&config);
    config.SizePixels = 13.0f * kCaptionScale * scale;
    caption_font_ = io.Fonts->AddFontDefault(&config);
  }
  // The first time, the backend builds the font texture with its other GL objects on the
  // first frame; later, the texture is replaced here.
  if (window_ == nullptr) {
    io.Fonts->Build();  // headless: the atlas without a texture
  } else if (fonts_built_) {
    ImGui_ImplOpenGL3_DestroyFontsTexture();
    ImGui_ImplOpenGL3_CreateFontsTexture();
  }
  fonts_built_ = true;

  ImGuiStyle style;
  ImGui::StyleColorsDark(&style);
  style.WindowRounding = 0;
  style.FrameRounding = 3;
  style.GrabRounding = 3;
  style.WindowBorderSize = 0;
  style.FramePadding = ImVec2(6, 4);
  style.ItemSpacing = ImVec2(8, 6);
  style.Colors[ImGuiCol_WindowBg].w = 0.97f;
  // A thin, half-transparent slider grab: the value's digits stay readable under it.
  style.GrabMinSize = 4;
  style.Colors[ImGuiCol_SliderGrab].w = 0.55f;
  style.Colors[ImGuiCol_SliderGrabActive].w = 0.75f;
  style.ScaleAllSizes(scale);
  ImGui::GetStyle() = style;
}

void Platform::update_scale() {
  const float scale = window_content_scale(window_) * user_scale_;
  if (scale != ui_scale_) apply_scale(scale);
}

void Platform::set_fullscreen(bool on) {
  if (on == fullscreen_) return;
  if (window_ == nullptr) {  // headless: the monitor's size given, and back
    if (headless_screen_[0] > 0 && headless_screen_[1] > 0) {
      if (on) {
        windowed_[2] = headless_size_[0], windowed_[3] = headless_size_[1];
        headless_size_[0] = headless_screen_[0], headless_size_[1] = headless_screen_[1];
      } else {
        headless_size_[0] = windowed_[2], headless_size_[1] = windowed_[3];
      }
    }
    fullscreen_ = on;
    note_event();
    return;
  }
  GLFWmonitor* monitor = glfwGetPrimaryMonitor();
  const GLFWvidmode* mode = monitor != nullptr ? glfwGetVideoMode(monitor) : nullptr;
  if (on && mode == nullptr) return;  // no monitor to fill
  if (on) {
    glfwGetWindowPos(window_, &windowed_[0], &windowed_[1]);
    glfwGetWindowSize(window_, &windowed_[2], &windowed_[3]);
    glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
  } else {
    glfwSetWindowMonitor(window_, nullptr, windowed_[0], windowed_[1], windowed_[2], windowed_[3], 0);
  }
  fullscreen_ = on;
  note_event();
}

void Platform::begin_backend_frame() {
  if (window_ == nullptr) {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(headless_size_[0]), static_cast<float>(headless_size_[1]));
    io.DisplayFramebufferScale = ImVec2(1, 1);
    io.DeltaTime = 1.0f / 60.0f;
    return;
  }
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
}

}  // namespace phonglab
