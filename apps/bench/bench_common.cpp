#include "apps/bench/bench_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/image_io.h"

namespace phonglab::bench {

// Small image helpers over accumulators.
std::vector<Color> means(const Accumulator& a) {
  std::vector<Color> m(a.sum.size());
  for (std::size_t i = 0; i < m.size(); ++i) m[i] = a.sum[i] / static_cast<double>(std::max(1u, a.samples));
  return m;
}

// pbrt's relative MSE: mean over pixels and channels of (x - r)^2 / (r + 0.01)^2.
double rel_mse(const std::vector<Color>& x, const std::vector<Color>& ref) {
  double s = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double d = x[i][c] - ref[i][c];
      const double r = ref[i][c] + 0.01;
      s += d * d / (r * r);
    }
  }
  return s / (3.0 * static_cast<double>(x.size()));
}

double rmse(const std::vector<Color>& x, const std::vector<Color>& ref) {
  double s = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Color d = x[i] - ref[i];
    s += glm::dot(d, d);
  }
  return std::sqrt(s / (3.0 * static_cast<double>(x.size())));
}

// PSNR of the displayed 8-bit sRGB images, in dB (99 for identical images).
double psnr_displayed(const std::vector<Color>& x, const std::vector<Color>& ref) {
  double s = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double d = double(linear_to_srgb8(x[i][c])) - double(linear_to_srgb8(ref[i][c]));
      s += d * d;
    }
  }
  const double mse = s / (3.0 * static_cast<double>(x.size()));
  return mse > 0 ? 10 * std::log10(255.0 * 255.0 / mse) : 99.0;
}

double max_abs_error(const std::vector<Color>& x, const std::vector<Color>& ref) {
  double m = 0;
  for (std::size_t i = 0; i < x.size(); ++i) m = std::max(m, max_abs(x[i] - ref[i]));
  return m;
}

double max_value(const std::vector<Color>& x) {
  double m = 0;
  for (const Color& c : x) m = std::max(m, max_channel(c));
  return m;
}


// Least-squares slope of log10(y) against log10(x).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log10(x[i]), ly = std::log10(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// y at x on the piecewise log-log line through (xs, ys) (xs increasing); nullopt outside.
std::optional<double> loglog_at(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    if (x >= xs[i] && x <= xs[i + 1] && xs[i] > 0 && ys[i] > 0 && ys[i + 1] > 0 && xs[i + 1] > xs[i]) {
      const double f = (std::log(x) - std::log(xs[i])) / (std::log(xs[i + 1]) - std::log(xs[i]));
      return std::exp(std::log(ys[i]) + f * (std::log(ys[i + 1]) - std::log(ys[i])));
    }
  }
  return std::nullopt;
}




// Renders `spp` passes of `scene` at w x h (`packets`: RenderOptions::packets).
Render render(const PreparedScene& scene, int w, int h, int spp, int threads, std::uint32_t seed, bool packets,
              Ambient ambient) {
  Render r;
  r.accum.reset(w, h);
  RenderOptions opt;
  opt.threads = threads;
  opt.seed = seed;
  opt.packets = packets;
  opt.ambient = ambient;
  const auto t0 = Clock::now();
  r.stats = render_passes(scene, opt, r.accum, spp);
  r.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  return r;
}
// The same for a scene prepared here, outside the timing.
Render render(const Scene& scene, int w, int h, int spp, int threads, std::uint32_t seed, bool packets) {
  return render(PreparedScene(scene), w, h, spp, threads, seed, packets);
}

std::string loglog_svg(const std::string& title, const std::string& x_label, const std::string& y_label,
                       const std::vector<Series>& series, const std::vector<double>& ref_slopes) {
  const double w = 640, h = 420, left = 70, right = 150, top = 40, bottom = 50;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Series& s : series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!(s.y[i] > 0)) continue;
      x0 = std::min(x0, std::log10(s.x[i]));
      x1 = std::max(x1, std::log10(s.x[i]));
      y0 = std::min(y0, std::log10(s.y[i]));
      y1 = std::max(y1, std::log10(s.y[i]));
    }
  }
  if (!(x1 > x0)) x1 = x0 + 1;
  y0 = std::floor(y0);
  y1 = std::ceil(y1);
  if (!(y1 > y0)) y1 = y0 + 1;
  auto px = [&](double lx) { return left + (lx - x0) / (x1 - x0) * (w - left - right); };
  auto py = [&](double ly) { return top + (y1 - ly) / (y1 - y0) * (h - top - bottom); };
  const char* colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf"};
  std::ostringstream o;
  o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << w << "' height='" << h
    << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  o << "<text x='" << w / 2 << "' y='22' text-anchor='middle' font-size='15'>" << title << "</text>\n";
  for (double ly = y0; ly <= y1 + 1e-9; ly += 1) {
    o << "<line x1='" << left << "' x2='" << w - right << "' y1='" << py(ly) << "' y2='" << py(ly)
      << "' stroke='#ddd'/><text x='" << left - 6 << "' y='" << py(ly) + 4 << "' text-anchor='end'>1e"
      << static_cast<int>(ly) << "</text>\n";
  }
  for (double lx = std::ceil(x0 - 1e-9); lx <= x1 + 1e-9; lx += 1) {
    o << "<line y1='" << top << "' y2='" << h - bottom << "' x1='" << px(lx) << "' x2='" << px(lx)
      << "' stroke='#ddd'/><text y='" << h - bottom + 16 << "' x='" << px(lx) << "' text-anchor='middle'>"
      << std::pow(10.0, lx) << "</text>\n";
  }
  o << "<text x='" << (left + w - right) / 2 << "' y='" << h - 12 << "' text-anchor='middle'>" << x_label
    << "</text>\n<text transform='translate(16," << (top + h - bottom) / 2 << ") rotate(-90)' text-anchor='middle'>"
    << y_label << "</text>\n";
  // Reference slopes through the first series' first point.
  if (!series.empty() && !series[0].x.empty()) {
    const double ax = std::log10(series[0].x[0]), ay = std::log10(series[0].y[0]);
    for (double slope : ref_slopes) {
      const double by = ay + slope * (x1 - ax);
      o << "<line x1='" << px(ax) << "' y1='" << py(ay) << "' x2='" << px(x1) << "' y2='" << py(by)
        << "' stroke='#888' stroke-dasharray='5,4'/><text x='" << px(x1) + 4 << "' y='" << py(by) + 4
        << "' fill='#666'>slope " << slope << "</text>\n";
    }
  }
  for (std::size_t k = 0; k < series.size(); ++k) {
    const Series& s = series[k];
    const char* c = colours[k % 7];
    o << "<polyline fill='none' stroke='" << c << "' stroke-width='2' points='";
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (s.y[i] > 0) o << px(std::log10(s.x[i])) << "," << py(std::log10(s.y[i])) << " ";
    }
    o << "'/>\n<text x='" << w - right + 40 << "' y='" << top + 18.0 * static_cast<double>(k + 1) << "' fill='" << c << "'>" << s.name
      << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

// The CPU's model name from /proc/cpuinfo ("unknown CPU" elsewhere).
std::string cpu_model() {
  std::FILE* f = std::fopen("/proc/cpuinfo", "r");
  if (!f) return "unknown CPU";
  char line[512];
  std::string model = "unknown CPU";
  while (std::fgets(line, sizeof line, f)) {
    const std::string l(line);
    if (l.rfind("model name", 0) == 0) {
      const std::size_t colon = l.find(':');
      if (colon != std::string::npos) model = l.substr(colon + 2, l.size() - colon - 3);
      break;
    }
  }
  std::fclose(f);
  return model;
}

Frame render_frame(const PreparedScene& scene, int w, int h, int threads, bool packets) {
  Accumulator accum;
  accum.reset(w, h);
  RenderOptions options;
  options.threads = threads;
  options.packets = packets;
  const PassStats st = render_pass(scene, options, accum);
  return Frame{st.seconds * 1000, st.rays, std::move(accum.sum)};
}

void Writer::write(const std::string& name, const std::string& text) {
  if (std::string err = write_file_atomically((dir / name).string(), text); !err.empty()) {
    std::fprintf(stderr, "%s\n", err.c_str());
    ok = false;
  }
}

}  // namespace phonglab::bench
