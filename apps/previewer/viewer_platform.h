// The window system: GLFW window with a GL 3.3 core context (glad), Dear ImGui with its GLFW
// and OpenGL 3 backends, fonts sized for the monitor's content scale.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glad/gl.h>
#include <GLFW/glfw3.h>

struct ImFont;
struct ImDrawData;

namespace phonglab {

// ImGui's draw data as bytes (every vertex, index and command, the display's size and scale):
// two frames with the same bytes draw the same pixels over the image.
void serialize_draw_data(const ImDrawData& data, std::vector<unsigned char>& out);

// Wall time and the CPU time of the calling thread and of the whole process, seconds: the
// stats log's share of a core the UI thread took, and of the machine the previewer took.
struct CpuClock {
  double wall = 0;
  double thread = 0;
  double process = 0;
  static CpuClock now();
};

// A key press as GLFW reported it (repeats included), kept until the frame takes it.
struct KeyPress {
  int key = 0;   // GLFW_KEY_*
  int mods = 0;  // GLFW_MOD_* bits held
};

// A mouse button press as GLFW reported it, with the cursor where it was at that moment.
struct MousePress {
  int button = 0;  // 0 left, 1 right, 2 middle (GLFW's and ImGui's numbering)
  double x = 0;    // window coordinates
  double y = 0;
};

struct PlatformOptions {
  int width = 1280;          // window size in screen coordinates
  int height = 720;
  std::string title = "phonglab";
  // Headless: the primary monitor's size that full screen (presenter mode) fills; 0 keeps the window's.
  int screen_width = 0;
  int screen_height = 0;
};

class Platform {
 public:
  // Opens the window and sets up ImGui. Nothing (and `error` explains) when there is no
  // display or no GL 3.3 core context.
  static std::unique_ptr<Platform> create(const PlatformOptions& options, std::string& error);
  // No window and no GL: ImGui's frames at the size given, its fonts built, a clock of its own;
  // what the shell's tests run it on (tests/shell). The window calls below then act on that size.
  static std::unique_ptr<Platform> create_headless(const PlatformOptions& options);
  // Shuts ImGui down, destroys the window, terminates GLFW.
  ~Platform();
  Platform(const Platform&) = delete;
  Platform& operator=(const Platform&) = delete;

  bool headless() const { return window_ == nullptr; }
  // Seconds on the window system's clock (glfwGetTime), or the headless platform's own.
  double now() const;
  // The window's size in screen coordinates, and its framebuffer's in pixels.
  void window_size(int& width, int& height) const;
  void framebuffer_size(int& width, int& height) const;
  void set_window_size(int width, int height);
  // The window's close button (or a script's `close`): asked for, then taken once by the loop.
  void request_close();
  bool take_close_request();
  void set_title(const std::string& title);
  // Waits for events (or the timeout, seconds), handles those pending, shows the drawn frame.
  void wait_events(double timeout);
  void poll_events();
  void swap_buffers();
  // Wakes the loop's wait from any thread (the render thread's new image, a signal).
  static void wake();
  // UI scale: the monitor's (1 on a standard display, 2 on a HiDPI one) times the user's.
  float ui_scale() const { return ui_scale_; }
  // Rebuilds fonts and style when the window moved to a monitor of another scale or the
  // user size changed. Call between frames.
  void update_scale();
  // The user's size factor on top of the monitor's content scale; takes effect at update_scale.
  void set_user_scale(float factor) { user_scale_ = factor; }
  // Starts an ImGui frame (backends first). Call ImGui::NewFrame() after injecting any input.
  void begin_backend_frame();
  // now() of the last input or window event: the main loop idles when it is old.
  double last_event_time() const { return last_event_time_; }
  // Records an event now (GLFW callbacks, and script input that bypasses GLFW).
  void note_event();
  // Key presses since the last call, in order: a tap shorter than a frame is still one press.
  std::vector<KeyPress> take_key_presses();
  // Queues a press as the key callback does (GLFW, and test scripts).
  void push_key_press(KeyPress press);
  // The cursor callback's position, and a button callback's press where the cursor then was.
  void record_cursor(double x, double y);
  void record_mouse_press(int button, int action);
  // Mouse button presses since the last call, where the cursor was when each happened.
  std::vector<MousePress> take_mouse_presses();
  // The lesson captions' font: the UI font at kCaptionScale times its size (a projected hall
  // reads it from the back); nullptr before the first frame.
  ImFont* caption_font() const { return caption_font_; }
  // Full screen on the primary monitor (presenter mode), or back to the window as it was.
  void set_fullscreen(bool on);
  bool fullscreen() const { return fullscreen_; }
  // Files dropped on the window since the last call (the drop callback), in order.
  void push_drop(std::string path) { drops_.push_back(std::move(path)); }
  std::vector<std::string> take_drops();
  // Whether the window asked to be drawn again (exposed, resized, restored) since the last call.
  bool take_refresh();
  void want_refresh() { refresh_ = true; }

 private:
  Platform() = default;
  void apply_scale(float scale);

  GLFWwindow* window_ = nullptr;  // null: headless
  int headless_size_[2] = {0, 0};
  int headless_screen_[2] = {0, 0};  // the monitor full screen fills headless (0: the window's size)
  bool close_requested_ = false;  // headless: request_close() not yet taken
  bool glfw_ready_ = false;
  bool imgui_ready_ = false;
  float ui_scale_ = 0;
  float user_scale_ = 1;
  bool fonts_built_ = false;  // apply_scale ran before: the font texture exists
  ImFont* caption_font_ = nullptr;
  bool fullscreen_ = false;
  int windowed_[4] = {0, 0, 0, 0};  // x, y, width, height before full screen
  double last_event_time_ = 0;
  std::vector<KeyPress> key_presses_;  // from the key callback, taken once per frame
  std::vector<MousePress> mouse_presses_;  // from the mouse button callback, likewise
  std::vector<std::string> drops_;         // from the drop callback, likewise
  bool refresh_ = true;                    // the window's contents may be gone: draw the next frame

  double cursor_x_ = 0;  // the cursor as the last cursor event left it, window coordinates
  double cursor_y_ = 0;
};

}  // namespace phonglab
