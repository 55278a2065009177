#include "tests/shell/shell_harness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

#include "apps/previewer/viewer_app.h"
#include "io/image_read.h"

namespace phonglab::test {

ShellRun run_shell(const TestFolder& folder, const std::string& scene, const std::string& script, const ShellOptions& shell) {
  const std::string script_path = (folder.path() / "script.txt").string();
  std::string text = script;
  const std::string out = folder.path().string() + "/";
  for (std::size_t at = text.find("$OUT/"); at != std::string::npos; at = text.find("$OUT/", at + out.size())) {
    text.replace(at, 5, out);
  }
  std::ofstream(script_path) << text;
  setenv("XDG_STATE_HOME", (folder.path() / "state").c_str(), 1);  // nothing of the user's read or written
  ViewerOptions options;
  if (shell.lesson.empty()) {
    options.scene_arg = scene;
    options.scene_given = true;
  }
  options.lesson_arg = shell.lesson;
  options.stats_log_path = shell.stats_log;
  options.width = shell.width;
  options.height = shell.height;
  options.script_path = script_path;
  PlatformOptions platform_options;
  platform_options.width = shell.width;
  platform_options.height = shell.height;
  platform_options.screen_width = shell.screen_width;
  platform_options.screen_height = shell.screen_height;
  const std::unique_ptr<Platform> platform = Platform::create_headless(platform_options);
  ShellRun run;
  {
    Viewer viewer(*platform, options);
    if (!viewer.init().empty()) return run;
    run.exit_status = viewer.run();
  }
  return run;
}

std::map<std::string, std::string> read_state(const std::string& path) {
  std::map<std::string, std::string> values;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) values.emplace(line.substr(0, eq), line.substr(eq + 1));
  }
  return values;
}

std::array<double, 3> vec3_of(const std::string& text) {
  std::array<double, 3> v{};
  std::istringstream in(text);
  in >> v[0] >> v[1] >> v[2];
  return v;
}

bool rects_apart(const std::string& a, const std::string& b) {
  double ax = 0, ay = 0, aw = 0, ah = 0, bx = 0, by = 0, bw = 0, bh = 0;
  std::istringstream(a) >> ax >> ay >> aw >> ah;
  std::istringstream(b) >> bx >> by >> bw >> bh;
  return ax + aw <= bx || bx + bw <= ax || ay + ah <= by || by + bh <= ay;
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Shot read_shot(const std::string& path) {
  std::string error;
  const std::optional<ReadImage> image = read_image_file(path, &error);
  if (!image || image->kind != ReadImage::Kind::kSrgb8) {
    ADD_FAILURE() << "cannot read the screenshot " << path << ": " << error;
    return {};
  }
  return {image->width, image->height, image->rgb};
}

namespace {

// Calls `visit(index of the pixel's red)` for each pixel of the region inside the shot.
template <typename Visit>
std::size_t for_region(const Shot& shot, const Region& r, Visit visit) {
  std::size_t n = 0;
  for (int y = std::max(r.y, 0); y < std::min(r.y + r.height, shot.height); ++y) {
    for (int x = std::max(r.x, 0); x < std::min(r.x + r.width, shot.width); ++x, ++n) {
      visit((static_cast<std::size_t>(y) * static_cast<std::size_t>(shot.width) + static_cast<std::size_t>(x)) * 3);
    }
  }
  return n;
}

}  // namespace

double rmse(const Shot& a, const Region& ra, const Shot& b, const Region& rb) {
  if (ra.width != rb.width || ra.height != rb.height) return -1;
  double sum = 0;
  std::size_t n = 0;
  for (int y = 0; y < ra.height; ++y) {
    for (int x = 0; x < ra.width; ++x) {
      const auto at = [](const Shot& s, int px, int py) {
        return (static_cast<std::size_t>(py) * static_cast<std::size_t>(s.width) + static_cast<std::size_t>(px)) * 3;
      };
      const std::size_t i = at(a, ra.x + x, ra.y + y), j = at(b, rb.x + x, rb.y + y);
      if (i + 2 >= a.rgb.size() || j + 2 >= b.rgb.size()) return -1;
      for (int c = 0; c < 3; ++c) {
        const double d = (a.rgb[i + static_cast<std::size_t>(c)] - b.rgb[j + static_cast<std::size_t>(c)]) / 255.0;
        sum += d * d;
        ++n;
      }
    }
  }
  return n == 0 ? -1 : std::sqrt(sum / static_cast<double>(n));
}

double mean(const Shot& shot, const Region& r) {
  double sum = 0;
  const std::size_t n = for_region(shot, r, [&](std::size_t i) { sum += shot.rgb[i] + shot.rgb[i + 1] + shot.rgb[i + 2]; });
  return n == 0 ? -1 : sum / (3.0 * 255.0 * static_cast<double>(n));
}

double luma_stddev(const Shot& shot, const Region& r) {
  double sum = 0, squares = 0;
  const std::size_t n = for_region(shot, r, [&](std::size_t i) {
    const double luma = (0.2126 * shot.rgb[i] + 0.7152 * shot.rgb[i + 1] + 0.0722 * shot.rgb[i + 2]) / 255.0;
    sum += luma;
    squares += luma * luma;
  });
  if (n == 0) return -1;
  const double m = sum / static_cast<double>(n);
  return std::sqrt(std::max(0.0, squares / static_cast<double>(n) - m * m));
}

double share(const Shot& shot, const Region& r, const std::function<bool(double, double, double)>& test) {
  std::size_t hits = 0;
  const std::size_t n = for_region(shot, r, [&](std::size_t i) {
    hits += test(shot.rgb[i] / 255.0, shot.rgb[i + 1] / 255.0, shot.rgb[i + 2] / 255.0) ? 1 : 0;
  });
  return n == 0 ? -1 : static_cast<double>(hits) / static_cast<double>(n);
}

void keep_screenshot(const std::string& dir, const std::string& name) {
  const char* kept = std::getenv("PHONGLAB_SCREENSHOTS");
  if (kept == nullptr || *kept == 0) return;
  std::error_code ec;
  std::filesystem::create_directories(kept, ec);
  std::filesystem::copy_file(dir + name, std::filesystem::path(kept) / name, std::filesystem::copy_options::overwrite_existing, ec);
}

}  // namespace phonglab::test
