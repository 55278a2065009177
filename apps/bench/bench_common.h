// What the bench's sections share: timing, formatting, image metrics, renders, plots, files.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/render/render.h"
#include "io/scene/scene_io.h"

namespace phonglab::bench {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The median of v (0 when empty).
inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline std::string fmt(const char* format, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, a);
  return buf;
}

inline Scene load_embedded(std::string_view name) {
  return *load_scene_arg(std::string(name)).scene;  // embedded scenes always load (tests check it)
}

// Image metrics over per-pixel means.
std::vector<Color> means(const Accumulator& a);
// pbrt's relative MSE: mean over pixels and channels of (x - r)^2 / (r + 0.01)^2.
double rel_mse(const std::vector<Color>& x, const std::vector<Color>& ref);
double rmse(const std::vector<Color>& x, const std::vector<Color>& ref);
// PSNR of the displayed 8-bit sRGB images, in dB (99 for identical images).
double psnr_displayed(const std::vector<Color>& x, const std::vector<Color>& ref);
double max_abs_error(const std::vector<Color>& x, const std::vector<Color>& ref);
double max_value(const std::vector<Color>& x);
// Least-squares slope of log10(y) against log10(x).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);
// y at x on the piecewise log-log line through (xs, ys) (xs increasing); nullopt outside.
std::optional<double> loglog_at(const std::vector<double>& xs, const std::vector<double>& ys, double x);

struct Render {
  Accumulator accum;
  PassStats stats;
  double seconds = 0;
};

// Renders `spp` passes of `scene` at w x h (`packets`, `ambient`: RenderOptions'), timed.
Render render(const PreparedScene& scene, int w, int h, int spp, int threads, std::uint32_t seed, bool packets = true,
              Ambient ambient = Ambient::kConstant);
// The same for a scene prepared here, outside the timing.
Render render(const Scene& scene, int w, int h, int spp, int threads, std::uint32_t seed, bool packets = true);

// One Whitted frame (1 spp) of a prepared scene: its time, rays and pixel sums.
struct Frame {
  double ms = 0;
  RayCounts rays;
  std::vector<Color> image;
};
Frame render_frame(const PreparedScene& scene, int w, int h, int threads, bool packets = true);

// A log-log line chart as SVG: one polyline per series, plus dashed reference slopes.
struct Series {
  std::string name;
  std::vector<double> x, y;
};
std::string loglog_svg(const std::string& title, const std::string& x_label, const std::string& y_label,
                       const std::vector<Series>& series, const std::vector<double>& ref_slopes);

// The CPU's model name from /proc/cpuinfo ("unknown CPU" elsewhere).
std::string cpu_model();

// Writes the report's files atomically into `dir`; `ok` turns false on the first failure.
struct Writer {
  std::filesystem::path dir;
  bool ok = true;
  void write(const std::string& name, const std::string& text);
};

}  // namespace phonglab::bench
