// The previewer's shell run headless in a test: no window and no GL (Platform::create_headless),
// the same components, panels and script commands as under a window, ImGui's frames at the size
// given; what a script's dump_state writes read back as key=value pairs.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "tests/support/test_folder.h"

namespace phonglab::test {

struct ShellRun {
  int exit_status = -1;  // the previewer's: 0, or 3 when a script command failed
};

struct ShellOptions {
  int width = 1280;  // the window's size
  int height = 720;
  int screen_width = 0;  // the monitor full screen fills (presenter mode); 0: the window's size
  int screen_height = 0;
  std::string lesson;     // presented from the start (--lesson), with no scene named on the command line
  std::string stats_log;  // --stats-log
};

// Runs `script` (the previewer's script commands, docs/previewer.md) on `scene`, with the state
// folder (recovery, recent files) inside `folder`; "$OUT/" in the script stands for `folder`'s path.
ShellRun run_shell(const TestFolder& folder, const std::string& scene, const std::string& script,
                   const ShellOptions& options = {});

// A dump_state file's values by key.
std::map<std::string, std::string> read_state(const std::string& path);

// A dump_state vector ("x y z") as three numbers.
std::array<double, 3> vec3_of(const std::string& text);
// Whether two dump_state rectangles ("x y w h") do not overlap.
bool rects_apart(const std::string& a, const std::string& b);
// A file's bytes (empty when it cannot be read).
std::string file_bytes(const std::string& path);

// A screenshot (the headless screen's, ui::SoftwareScreen) as 8-bit codes, and statistics of its
// regions ("x y w h" in pixels), each channel as code / 255.
struct Shot {
  int width = 0, height = 0;
  std::vector<double> rgb;  // width x height x 3 codes, rows from the top
};
struct Region {
  int x = 0, y = 0, width = 0, height = 0;
};
// The window's view below the stats overlay, left of the 400-pixel panels at 1280 x 720.
inline constexpr Region kSceneRegion{0, 280, 880, 440};
Shot read_shot(const std::string& path);  // empty (width 0) when unreadable
// RMS of the channels' differences, as ImageMagick's `compare -metric RMSE` normalises it.
double rmse(const Shot& a, const Region& ra, const Shot& b, const Region& rb);
inline double rmse(const Shot& a, const Shot& b, const Region& r) { return rmse(a, r, b, r); }
double mean(const Shot& shot, const Region& r);            // of every channel
double luma_stddev(const Shot& shot, const Region& r);     // of Rec. 709 luma: 0 when uniform
// The share of the region's pixels whose channels (r, g, b in [0, 1]) pass `test`.
double share(const Shot& shot, const Region& r, const std::function<bool(double, double, double)>& test);
// Copies the screenshot DIR/NAME (DIR ending in '/') to $PHONGLAB_SCREENSHOTS/NAME when that is set
// (tools/readme_images.sh takes the README's pictures from there).
void keep_screenshot(const std::string& dir, const std::string& name);

}  // namespace phonglab::test
