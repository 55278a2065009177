#include "apps/bench/bench_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "apps/bench/bench_accel.h"
#include "apps/bench/bench_indirect.h"  // issue 6: the acceleration section
#include "apps/bench/bench_common.h"
#include "apps/bench/bench_yardsticks.h"
#include "io/embedded_scenes.h"
#include "io/image_io.h"
#include "experiments/numerics_variants.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"

namespace phonglab {
namespace {

using namespace bench;

constexpr double kReferenceMinWeight = 1e-6;  // path-weight cut-off of the converged references

// 4. Numerical precision: each numerics choice of the renderer against the naive one, on
// scenes that stress it, against a reference image.
struct PrecisionConfig {
  std::string name;
  std::string short_name;  // for the plot's legend
  NumericsVariant variant;
};

std::vector<PrecisionConfig> precision_configs() {
  std::vector<PrecisionConfig> c(8);
  c[0].name = "production: double, robust sphere, per-primitive offsets, exact Fresnel";
  c[1].name = "float geometry";
  c[1].variant.float_geometry = true;
  c[2].name = "textbook sphere";
  c[2].variant.textbook_sphere = true;
  c[3].name = "fixed offset 1e-4";
  c[3].variant.fixed_offset = 1e-4;
  c[4].name = "fixed offset 1e-3";
  c[4].variant.fixed_offset = 1e-3;
  c[5].name = "Schlick Fresnel";
  c[5].variant.schlick_fresnel = true;
  c[6].name = "float geometry + fixed offset 1e-3";
  c[6].variant.float_geometry = true;
  c[6].variant.fixed_offset = 1e-3;
  c[7].name = "naive: float, textbook sphere, fixed offset 1e-3, Schlick";
  c[7].variant.float_geometry = true;
  c[7].variant.textbook_sphere = true;
  c[7].variant.fixed_offset = 1e-3;
  c[7].variant.schlick_fresnel = true;
  for (PrecisionConfig& ci : c) ci.short_name = ci.name;
  c[0].short_name = "production";
  c[7].short_name = "naive: float, textbook, 1e-3, Schlick";
  return c;
}

// A unit sphere `dist` away along (0.48, 0.6, 0.64), 5/6 of the image tall (docs/accuracy.md S1, S2).
Scene far_sphere_scene(double dist) {
  Scene s;
  const Vec3 axis = glm::normalize(Vec3(0.48, 0.6, 0.64));
  s.camera = Camera{Vec3(0), dist * axis, Vec3(0, 0, 1), 2 * std::asin(1 / dist) * 180 / 3.14159265358979323846 * 1.2};
  s.ambient = Color(1);
  s.background = Color(0.05, 0.06, 0.09);
  Material m;
  m.ka = Color(0.05);
  m.kd = Color(0.7, 0.5, 0.3);
  m.ks = Color(0.4);
  m.n = 40;
  s.materials = {m};
  s.spheres = {Sphere{dist * axis, 1, 0}};
  Light l;
  l.position = dist * axis + Vec3(-3, 2, 4);
  l.intensity = Color(0.9);
  s.lights = {l};
  return s;
}

// A small scatter plot: speed (x, linear) against pixels off summed over the scenes (y, log of
// 1 + n), one labelled point per configuration, red when unusable.
struct ScatterPoint {
  std::string label;
  double x = 0, y = 0;
  bool bad = false;
};

std::string scatter_svg(const std::string& title, const std::string& x_label, const std::string& y_label,
                        const std::vector<ScatterPoint>& pts) {
  const double w = 820, h = 440, left = 80, right = 310, top = 40, bottom = 50;
  double x1 = 0, y1 = 1;
  for (const ScatterPoint& p : pts) {
    x1 = std::max(x1, p.x);
    y1 = std::max(y1, std::log10(1 + p.y));
  }
  x1 = std::ceil(x1 * 1.1 + 1e-9);
  y1 = std::ceil(y1);
  auto px = [&](double x) { return left + x / x1 * (w - left - right); };
  auto py = [&](double n) { return top + (y1 - std::log10(1 + n)) / y1 * (h - top - bottom); };
  std::ostringstream o;
  o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << w << "' height='" << h
    << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  o << "<text x='" << (left + w - right) / 2 << "' y='22' text-anchor='middle' font-size='15'>" << title << "</text>\n";
  for (int e = -1; e <= static_cast<int>(y1); ++e) {
    const double n = e < 0 ? 0 : std::pow(10.0, e);
    o << "<line x1='" << left << "' x2='" << w - right << "' y1='" << py(n) << "' y2='" << py(n)
      << "' stroke='#ddd'/><text x='" << left - 6 << "' y='" << py(n) + 4 << "' text-anchor='end'>" << n << "</text>\n";
  }
  const double step = x1 > 20 ? 10 : (x1 > 8 ? 2 : 1);
  for (double x = 0; x <= x1 + 1e-9; x += step) {
    o << "<line y1='" << top << "' y2='" << h - bottom << "' x1='" << px(x) << "' x2='" << px(x)
      << "' stroke='#ddd'/><text y='" << h - bottom + 16 << "' x='" << px(x) << "' text-anchor='middle'>" << x
      << "</text>\n";
  }
  o << "<text x='" << (left + w - right) / 2 << "' y='" << h - 12 << "' text-anchor='middle'>" << x_label
    << "</text>\n<text transform='translate(16," << (top + h - bottom) / 2 << ") rotate(-90)' text-anchor='middle'>"
    << y_label << "</text>\n";
  for (std::size_t k = 0; k < pts.size(); ++k) {
    const ScatterPoint& p = pts[k];
    const char* c = p.bad ? "#d62728" : "#1f77b4";
    o << "<circle cx='" << px(p.x) << "' cy='" << py(p.y) << "' r='5' fill='" << c << "'/><text x='" << px(p.x) + 7
      << "' y='" << py(p.y) + 4 << "' fill='" << c << "'>" << k + 1 << "</text>\n<text x='" << w - right + 12
      << "' y='" << top + 18.0 * static_cast<double>(k + 1) << "' fill='" << c << "'>" << k + 1 << ". " << p.label
      << (p.bad ? " (unusable)" : "") << "</text>\n";
  }
  o << "</svg>\n";
  return o.str();
}

void precision_section(std::ostringstream& md, Writer& out, bool quick, int threads) {
  const int w = quick ? 160 : 640, h = quick ? 90 : 360, frames = quick ? 1 : 5;
  std::printf("precision: %dx%d, median of %d frames\n", w, h, frames);
  struct PrecisionScene {
    std::string name;
    Scene scene;
    std::string reference_name;
    std::vector<Color> reference;
  };
  const Scene lecture = load_embedded("lecture");
  const Scene glass = load_embedded("glass");
  const std::vector<Color> lecture_ref = means(render(lecture, w, h, 1, threads, 0).accum);
  std::vector<PrecisionScene> scenes = {
      {"lecture", lecture, "itself", lecture_ref},
      {"lecture x1e-4", transformed_scene(lecture, 1e-4, Vec3(0)), "lecture", lecture_ref},
      {"lecture x1e4", transformed_scene(lecture, 1e4, Vec3(0)), "lecture", lecture_ref},
      {"lecture moved 1e5", transformed_scene(lecture, 1, Vec3(1e5)), "lecture", lecture_ref},
      {"glass", glass, "itself", means(render(glass, w, h, 1, threads, 0).accum)},
  };
  for (const double dist : {1e4, 1e6, 1e7}) {
    const Scene far = far_sphere_scene(dist);
    scenes.push_back({"far sphere 1e" + std::to_string(std::lround(std::log10(dist))), far, "itself", means(render(far, w, h, 1, threads, 0).accum)});
  }
  md << "\n## Numerical precision\n\nEach numerics choice of the renderer against the common naive one, on scenes"
        " that stress it, at " << w << "x" << h << " pixels, 1 spp (pixel centres), " << threads
     << " threads, median of " << frames << " frames, every configuration traced by the scalar renderer (the"
        " variants exist only there; the packet tracer gives the production image bit for bit, faster).\n\n"
        "- **Reference**: the production configuration rendering the unit-scale `lecture` near the origin (for the"
        " scaled and moved copies, whose ideal image is the same), or the same scene (`glass`, and a unit sphere"
        " 1e4, 1e6 and 1e7 away filling 5/6 of the image, docs/accuracy.md S1/S2). The production's own pixel-centre values agree"
        " with independent long-double references to 1e-6 there (tests/core/test_hardcases.cpp); on the scenes"
        " compared with themselves its error is 0 by construction.\n"
        "- **max error**: the largest channel difference from the reference, linear radiance. **pixels off**:"
        " pixels whose largest channel differs by more than 1/255.\n"
        "- **acne**: a shadow, reflection or refraction ray that leaves a primitive towards a side from which it"
        " cannot meet that primitive again (either side of a plane or triangle, the outside of a sphere) and still"
        " reports that primitive as its occluder or nearest hit; counted on every pixel's centre ray tree (pixels"
        " with at least one such ray, and the rays). **NaN**: samples that were NaN or Inf (PassStats::nan_count).\n"
        "- A configuration with acne or NaN on any scene is **unusable**, not traded off.\n"
        "- Float geometry runs the same tests in float (hit points too; shading stays double). Textbook sphere:"
        " b^2 - 4ac and (-b -+ sqrt(disc))/2a, no re-projection of the hit point. Fixed offset: secondary rays start"
        " that far along the normal instead of the per-primitive offset. Schlick: R0 + (1 - R0)(1 - cos)^5 with the"
        " incident cosine on both sides. The variants run through a separate, unoptimised code path, so their"
        " Mrays/s compare implementations of equal care only roughly.\n\n"
        "| configuration | scene | Mrays/s | max error | pixels off | acne pixels (rays) | NaN | verdict |\n"
        "|---|---|---|---|---|---|---|---|\n";
  std::string csv = "configuration,scene,width,height,mrays_per_s,max_error,pixels_off,acne_pixels,acne_rays,nan,usable\n";
  struct Summary {
    double mrays_lecture = 0, worst_error = 0;
    std::uint64_t pixels_off = 0, acne = 0, nan = 0;
    std::string acne_scenes, worst_scene;
    std::uint64_t worst_pixels = 0;
  };
  const std::vector<PrecisionConfig> configs = precision_configs();
  std::vector<Summary> summary(configs.size());
  for (std::size_t ci = 0; ci < configs.size(); ++ci) {
    for (const PrecisionScene& ps : scenes) {
      const PreparedScene v = prepare_variant(ps.scene, configs[ci].variant);
      std::vector<double> ms;
      Render r;
      for (int f = 0; f < frames; ++f) {
        r = render(v, w, h, 1, threads, 0, /*packets=*/false);  // like with like: the variants are scalar
        ms.push_back(r.seconds * 1000);
      }
      const double mrays = static_cast<double>(r.stats.rays.total()) / (median(ms) / 1000) / 1e6;
      const std::vector<Color> img = means(r.accum);
      const double err = max_abs_error(img, ps.reference);
      std::uint64_t off = 0;
      for (std::size_t i = 0; i < img.size(); ++i) off += max_channel(glm::abs(img[i] - ps.reference[i])) > 1.0 / 255 ? 1 : 0;
      const AcneCount acne = count_acne(v, w, h, threads);
      const std::uint64_t nan = r.stats.nan_count;
      const bool usable = acne.pixels == 0 && nan == 0;
      const std::string verdict = usable ? "usable" : (acne.pixels ? "**unusable** (acne)" : "**unusable** (NaN)");
      md << "| " << configs[ci].name << " | " << ps.name << " | " << fmt("%.1f", mrays) << " | " << fmt("%.3g", err)
         << " | " << off << fmt(" (%.3f %%)", 100.0 * static_cast<double>(off) / static_cast<double>(img.size()))
         << " | " << acne.pixels << " (" << acne.rays << ") | " << nan << " | " << verdict << " |\n";
      csv += "\"" + configs[ci].name + "\"," + ps.name + "," + std::to_string(w) + "," + std::to_string(h) + "," +
             fmt("%.3f", mrays) + "," + fmt("%.6e", err) + "," + std::to_string(off) + "," +
             std::to_string(acne.pixels) + "," + std::to_string(acne.rays) + "," + std::to_string(nan) + "," +
             (usable ? "yes" : "no") + "\n";
      Summary& sm = summary[ci];
      if (ps.name == "lecture") sm.mrays_lecture = mrays;
      sm.worst_error = std::max(sm.worst_error, err);
      sm.pixels_off += off;
      if (off > sm.worst_pixels || sm.worst_scene.empty()) {
        sm.worst_pixels = off;
        sm.worst_scene = ps.name;
      }
      sm.acne += acne.pixels;
      sm.nan += nan;
      if (acne.pixels) sm.acne_scenes += (sm.acne_scenes.empty() ? "" : ", ") + ps.name;
      if (ci == 0) {  // the production renderer must pass its own bar (docs/accuracy.md O5)
        if (!usable) std::printf("CHECK FAILED: production configuration has acne or NaN on %s\n", ps.name.c_str());
        if (static_cast<double>(off) > 1e-4 * static_cast<double>(img.size()))
          std::printf("CHECK FAILED: production differs on %s in more than 0.01 %% of the pixels\n", ps.name.c_str());
      }
    }
    std::printf("  %-60s acne %llu, NaN %llu, pixels off %llu\n", configs[ci].name.c_str(),
                static_cast<unsigned long long>(summary[ci].acne), static_cast<unsigned long long>(summary[ci].nan),
                static_cast<unsigned long long>(summary[ci].pixels_off));
  }
  out.write("precision.csv", csv);
  std::ostringstream table;
  table << "| # | configuration | Mrays/s on lecture | worst max error | pixels off, all scenes (worst scene) | acne pixels (scenes) | NaN | verdict |\n"
        "|---|---|---|---|---|---|---|---|\n";
  std::vector<ScatterPoint> pts;
  for (std::size_t ci = 0; ci < configs.size(); ++ci) {
    const Summary& sm = summary[ci];
    const bool usable = sm.acne == 0 && sm.nan == 0;
    table << "| " << ci + 1 << " | " << configs[ci].name << " | " << fmt("%.1f", sm.mrays_lecture) << " | "
       << fmt("%.3g", sm.worst_error) << " | " << sm.pixels_off << " (" << sm.worst_scene << ") | " << sm.acne
       << (sm.acne_scenes.empty() ? "" : " (" + sm.acne_scenes + ")") << " | " << sm.nan << " | "
       << (usable ? "usable" : "**unusable**") << " |\n";
    pts.push_back({configs[ci].short_name, sm.mrays_lecture, static_cast<double>(sm.pixels_off), !usable});
  }
  md << "\n### Precision summary\n\nWorst over the " << scenes.size() << " scenes above.\n\n" << table.str();
  out.write("precision_summary.md", table.str());
  out.write("precision.svg", scatter_svg("Numerics: speed against pixels off (all precision scenes)",
                                         "Mrays/s on lecture", "pixels off by > 1/255 (sum over scenes)", pts));
  md << "\n![Speed against pixels off](precision.svg)\n";
}

// 5. Model only what a scene needs: the measured saving of each work-skipping rule, by turning
// it off (the NumericsVariant ablations of src/experiments/); the image must stay bit-identical.
void savings_section(std::ostringstream& md, Writer& out, bool quick, int threads) {
  const int w = quick ? 320 : 1280, h = quick ? 180 : 720, frames = quick ? 3 : 7;
  std::printf("savings: %dx%d, median of %d frames\n", w, h, frames);
  struct Ablation {
    const char* rule;  // what production does
    bool NumericsVariant::*flag;
  };
  const Ablation ablations[] = {
      {"no shadow rays towards lights behind the surface (N.L <= 0)", &NumericsVariant::shadow_rays_behind},
      {"no refraction rays for opaque materials (kt = 0)", &NumericsVariant::refraction_for_opaque},
      {"shadow rays as any-hit queries (not nearest-hit)", &NumericsVariant::nearest_hit_shadows},
  };
  md << "\n## Savings of modelling only what a scene needs\n\nEach rule the renderer follows, turned off one at a"
        " time (the naive tracer's way), on every embedded scene: the Whitted frame at " << w << "x" << h
     << ", 1 spp, " << threads << " threads, median of " << frames
     << " frames (interleaved with the production frames, so load drifts hit both alike), all traced by the scalar"
        " renderer, where the switches live (the packet tracer follows the same rules). 'identical' compares"
        " the pixel sums bit for bit. The pruning of the ray tree by path weight is measured above.\n\n";
  std::ostringstream table;
  table << "| scene | production rule | rays with the rule | rays without | shadow / refraction rays without (with) | ms with | ms without | time saved | image |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  std::string csv = "scene,rule,width,height,rays_with,rays_without,primary,shadow_with,shadow_without,reflection_with,"
                    "reflection_without,refraction_with,refraction_without,ms_with,ms_without,saved_percent,identical\n";
  for (const EmbeddedScene& e : embedded_scenes()) {
    const Scene base = load_embedded(e.name);
    std::vector<PreparedScene> variants(1, PreparedScene(base));
    for (const Ablation& a : ablations) {
      NumericsVariant v;
      v.*(a.flag) = true;
      variants.push_back(prepare_variant(base, v));
    }
    std::vector<std::vector<double>> ms(variants.size());
    std::vector<Render> last(variants.size());
    for (int f = 0; f < frames; ++f) {
      for (std::size_t k = 0; k < variants.size(); ++k) {
        last[k] = render(variants[k], w, h, 1, threads, 0, /*packets=*/false);  // the ablations are scalar
        ms[k].push_back(last[k].seconds * 1000);
      }
    }
    const double ms_base = median(ms[0]);
    const RayCounts& rb = last[0].stats.rays;
    for (std::size_t k = 1; k < variants.size(); ++k) {
      const RayCounts& ra = last[k].stats.rays;
      const double ms_k = median(ms[k]);
      const bool identical = last[k].accum.sum == last[0].accum.sum;
      if (!identical) std::printf("CHECK FAILED: %s: turning off '%s' changed the image\n", std::string(e.name).c_str(),
                                  ablations[k - 1].rule);
      const bool applies = ra.total() != rb.total() || ablations[k - 1].flag == &NumericsVariant::nearest_hit_shadows;
      const double saved = 100.0 * (ms_k - ms_base) / ms_k;
      table << "| " << e.name << " | " << ablations[k - 1].rule << " | " << rb.total() << " | " << ra.total() << " | "
         << ra.shadow << " (" << rb.shadow << ") / " << ra.refraction << " (" << rb.refraction << ") | "
         << fmt("%.1f", ms_base) << " | " << fmt("%.1f", ms_k) << " | "
         << (applies ? fmt("%.1f %%", saved) : std::string("does not apply")) << " | "
         << (identical ? "identical" : "**differs**") << " |\n";
      csv += std::string(e.name) + ",\"" + ablations[k - 1].rule + "\"," + std::to_string(w) + "," + std::to_string(h) +
             "," + std::to_string(rb.total()) + "," + std::to_string(ra.total()) + "," + std::to_string(rb.primary) +
             "," + std::to_string(rb.shadow) + "," + std::to_string(ra.shadow) + "," + std::to_string(rb.reflection) +
             "," + std::to_string(ra.reflection) + "," + std::to_string(rb.refraction) + "," +
             std::to_string(ra.refraction) + "," + fmt("%.3f", ms_base) + "," + fmt("%.3f", ms_k) + "," +
             fmt("%.2f", saved) + "," + (identical ? "yes" : "no") + "\n";
    }
    std::printf("  %-10s %.1f ms; without the rules: %.1f, %.1f, %.1f ms\n", std::string(e.name).c_str(), ms_base,
                median(ms[1]), median(ms[2]), median(ms[3]));
  }
  md << table.str();
  out.write("savings.md", table.str());
  out.write("savings.csv", csv);
}

// 1. Speed: the Whitted frame of every embedded scene, by ray kind and thread count.
void speed_section(std::ostringstream& md, Writer& out, bool quick, int threads) {
  const int speed_w = quick ? 640 : 1280, speed_h = quick ? 360 : 720, frames = quick ? 3 : 9;
  std::printf("speed: %dx%d, median of %d frames\n", speed_w, speed_h, frames);
  md << "## Speed\n\nThe Whitted frame at " << speed_w << "x" << speed_h << ", 1 spp, median of " << frames
     << " frames (1 and " << threads << " threads alternating).\n\n| scene | rays per frame | primary | shadow | reflection | refraction | 1 thread ms | "
     << threads << " threads ms | Mrays/s (" << threads << " threads) | scaling |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::string speed_csv = "scene,width,height,threads,median_ms,mrays_per_s,primary,shadow,reflection,refraction\n";
  for (const EmbeddedScene& e : embedded_scenes()) {
    const PreparedScene s(load_embedded(e.name));
    double ms_by_threads[2] = {0, 0};
    RayCounts rays;
    const int counts[2] = {1, threads};
    std::vector<double> ms[2];
    for (int f = 0; f < frames; ++f) {  // 1 and all threads alternate, so load drifts hit both alike
      for (int k = 0; k < 2; ++k) {
        const Render r = render(s, speed_w, speed_h, 1, counts[k], 0);
        ms[k].push_back(r.seconds * 1000);
        rays = r.stats.rays;
      }
    }
    for (int k = 0; k < 2; ++k) {
      ms_by_threads[k] = median(ms[k]);
      const double mrays = static_cast<double>(rays.total()) / (ms_by_threads[k] / 1000) / 1e6;
      speed_csv += std::string(e.name) + "," + std::to_string(speed_w) + "," + std::to_string(speed_h) + "," +
                   std::to_string(counts[k]) + "," + fmt("%.3f", ms_by_threads[k]) + "," + fmt("%.3f", mrays) + "," +
                   std::to_string(rays.primary) + "," + std::to_string(rays.shadow) + "," +
                   std::to_string(rays.reflection) + "," + std::to_string(rays.refraction) + "\n";
    }
    const double mrays = static_cast<double>(rays.total()) / (ms_by_threads[1] / 1000) / 1e6;
    md << "| " << e.name << " | " << rays.total() << " | " << rays.primary << " | " << rays.shadow << " | "
       << rays.reflection << " | " << rays.refraction << " | " << fmt("%.1f", ms_by_threads[0]) << " | "
       << fmt("%.1f", ms_by_threads[1]) << " | " << fmt("%.1f", mrays) << " | "
       << fmt("%.2f", ms_by_threads[0] / ms_by_threads[1]) << "x |\n";
    std::printf("  %-10s %.1f ms (1 thread), %.1f ms (%d threads)\n", std::string(e.name).c_str(), ms_by_threads[0],
                ms_by_threads[1], threads);
  }
  out.write("speed.csv", speed_csv);
}

// Equal time and time to target, read off the mean error-against-time curves (log-log
// interpolation between measured points; '-' where this run's range ends).
void equal_time_table(std::ostringstream& md, const std::vector<Series>& plot_time, int cw, int ch, int threads) {
  const double target = 1e-3;
  md << "\n### Equal time and time to target\n\nrelMSE reached after a given render time, and the time to"
        " reach relMSE " << target << ", at " << cw << "x" << ch << " pixels with " << threads
     << " threads ('-': outside the range this run measured).\n\n| scene | after 0.01 s | after 0.1 s | after 1 s |"
        " time to relMSE 1e-3 |\n|---|---|---|---|---|\n";
  for (const Series& sr : plot_time) {
    md << "| " << sr.name;
    for (double t : {0.01, 0.1, 1.0}) {
      const auto e = loglog_at(sr.x, sr.y, t);
      md << " | " << (e ? fmt("%.3g", *e) : std::string("-"));
    }
    // Time is the x axis of the curve; swap the axes to read the time at an error.
    std::vector<double> err_rev(sr.y.rbegin(), sr.y.rend()), time_rev(sr.x.rbegin(), sr.x.rend());
    const auto t = loglog_at(err_rev, time_rev, target);
    md << " | " << (t ? fmt("%.3g s", *t) : std::string("-")) << " |\n";
  }
}

// 2. Convergence against a converged reference, over independent seeds.
void convergence_section(std::ostringstream& md, Writer& out, bool quick, int threads) {
  const int cw = quick ? 96 : 240, ch = quick ? 54 : 135;
  // The reference is the mean of two independent halves (seeds 1000 and 2000); their difference
  // measures its noise, so no third render is needed (this halves the full run's longest part).
  const int ref_spp = quick ? 256 : 2048;
  const int half_spp = ref_spp / 2;
  const int max_spp = quick ? 32 : 128;
  const int seeds = 8;
  std::printf("convergence: %dx%d, reference %d spp, %d seeds up to %d spp\n", cw, ch, ref_spp, seeds, max_spp);
  md << "\n## Convergence\n\nError of the mean of N samples per pixel against a converged reference (" << ref_spp
     << " spp, max_depth 64, min_weight 1e-6 (an unpruned tree of glass is exponential), exact Fresnel as the scene says; " << cw << "x" << ch
     << " pixels), mean over " << seeds
     << " independent sample sets (seeds). relMSE is pbrt's (x-r)^2/(r+0.01)^2, RMSE is on linear radiance,"
        " PSNR on the displayed 8-bit sRGB image. Sample 0 of every seed is the pixel centre, so at 1 spp"
        " all seeds agree. The reference is the mean of two independent halves of " << half_spp << " spp (seeds"
        " 1000 and 2000); its own noise is estimated from them (a quarter of their relMSE: each half's noise"
        " is half their relMSE, and the mean of two halves has half of that) and must be 10x below the"
        " smallest error plotted.\n\n"
     << "| scene | relMSE at 1 spp | relMSE at " << max_spp << " spp (min..max over seeds) | RMSE at " << max_spp
     << " spp | PSNR at " << max_spp << " spp | fitted slope (spp 2.." << max_spp
     << ") relMSE / RMSE | reference noise (relMSE) | 10x below? |\n|---|---|---|---|---|---|---|---|\n";
  std::string conv_csv = "scene,spp,seed,rel_mse,rmse,psnr_db,seconds\n";
  std::vector<Series> plot_spp, plot_time;
  for (const EmbeddedScene& e : embedded_scenes()) {
    Scene s = load_embedded(e.name);
    Scene ref_scene = s;
    ref_scene.max_depth = 64;
    // Not 0: glass with Fresnel splits every ray in two, and an unpruned tree of depth 64 is
    // 2^64 rays. 1e-6 bounds the pruning error at 1e-6 of the scene's radiance.
    ref_scene.min_weight = kReferenceMinWeight;
    const PreparedScene reference(std::move(ref_scene));
    const std::vector<Color> half1 = means(render(reference, cw, ch, half_spp, threads, 1000).accum);
    const std::vector<Color> half2 = means(render(reference, cw, ch, half_spp, threads, 2000).accum);
    std::vector<Color> ref(half1.size());
    for (std::size_t i = 0; i < ref.size(); ++i) ref[i] = 0.5 * (half1[i] + half2[i]);
    const double ref_noise = rel_mse(half1, half2) / 4;
    std::vector<double> spps, mean_err, mean_rmse, mean_time;
    std::vector<double> final_errs;
    double err_at_1 = 0, rmse_final = 0, psnr_final = 0;
    for (int spp = 1; spp <= max_spp; spp *= 2) spps.push_back(spp);
    mean_err.assign(spps.size(), 0);
    mean_rmse.assign(spps.size(), 0);
    mean_time.assign(spps.size(), 0);
    const PreparedScene prepared(s);
    for (int seed = 0; seed < seeds; ++seed) {
      Accumulator acc;
      acc.reset(cw, ch);
      RenderOptions opt;
      opt.threads = threads;
      opt.seed = static_cast<std::uint32_t>(seed);
      double elapsed = 0;
      std::size_t k = 0;
      for (int spp = 1; spp <= max_spp; ++spp) {
        elapsed += render_pass(prepared, opt, acc).seconds;
        if (k < spps.size() && spp == static_cast<int>(spps[k])) {
          const std::vector<Color> m = means(acc);
          const double e_rel = rel_mse(m, ref), e_rms = rmse(m, ref), e_psnr = psnr_displayed(m, ref);
          conv_csv += std::string(e.name) + "," + std::to_string(spp) + "," + std::to_string(seed) + "," +
                      fmt("%.6e", e_rel) + "," + fmt("%.6e", e_rms) + "," + fmt("%.3f", e_psnr) + "," +
                      fmt("%.6f", elapsed) + "\n";
          mean_err[k] += e_rel / seeds;
          mean_rmse[k] += e_rms / seeds;
          mean_time[k] += elapsed / seeds;
          if (spp == 1) err_at_1 = e_rel;
          if (spp == max_spp) {
            final_errs.push_back(e_rel);
            rmse_final += e_rms / seeds;
            psnr_final += e_psnr / seeds;
          }
          ++k;
        }
      }
    }
    const std::vector<double> fit_x(spps.begin() + 1, spps.end()), fit_y(mean_err.begin() + 1, mean_err.end());
    const double slope = loglog_slope(fit_x, fit_y);
    const double rmse_slope =
        loglog_slope(fit_x, std::vector<double>(mean_rmse.begin() + 1, mean_rmse.end()));
    const double smallest = mean_err.back();
    md << "| " << e.name << " | " << fmt("%.3g", err_at_1) << " | " << fmt("%.3g", smallest) << " ("
       << fmt("%.3g", *std::min_element(final_errs.begin(), final_errs.end())) << ".."
       << fmt("%.3g", *std::max_element(final_errs.begin(), final_errs.end())) << ") | " << fmt("%.3g", rmse_final)
       << " | " << fmt("%.1f dB", psnr_final) << " | " << fmt("%.2f", slope) << " / " << fmt("%.2f", rmse_slope)
       << " | " << fmt("%.2g", ref_noise)
       << " | " << (ref_noise * 10 <= smallest ? "yes" : "**no**") << " |\n";
    if (ref_noise * 10 > smallest) std::printf("CHECK FAILED: %s reference noise not 10x below\n", std::string(e.name).c_str());
    plot_spp.push_back({std::string(e.name), spps, mean_rmse});
    plot_time.push_back({std::string(e.name), mean_time, mean_err});
    std::printf("  %-10s slope %.2f, relMSE %.3g at %d spp\n", std::string(e.name).c_str(), slope, smallest, max_spp);
  }
  out.write("convergence.csv", conv_csv);
  out.write("convergence_spp.svg", loglog_svg("RMSE against samples per pixel (mean of 8 seeds)",
                                              "samples per pixel", "RMSE", plot_spp, {-0.5, -0.75}));
  // relMSE is a squared error: the RMSE slopes -1/2 and -3/4 appear as -1 and -3/2.
  out.write("convergence_time.svg", loglog_svg("relMSE against render time (mean of 8 seeds)", "seconds", "relMSE",
                                               plot_time, {-1.0, -1.5}));
  md << "\n![RMSE against spp](convergence_spp.svg)\n![relMSE against time](convergence_time.svg)\n";

  equal_time_table(md, plot_time, cw, ch, threads);
}

// 3. Model only what a scene needs: ray-tree pruning by path weight on facing mirrors.
void pruning_section(std::ostringstream& md, Writer& out, bool quick, int threads) {
  const int pw = quick ? 96 : 320, ph = quick ? 54 : 180;
  std::printf("pruning: mirrors at %dx%d\n", pw, ph);
  Scene mirrors = load_embedded("mirrors");
  mirrors.max_depth = 64;
  mirrors.min_weight = 0;
  const Render exact = render(mirrors, pw, ph, 1, threads, 0);
  const std::vector<Color> exact_img = means(exact.accum);
  const double max_radiance = max_value(exact_img);
  md << "\n## Pruning the ray tree (model only what a scene needs)\n\n`mirrors` (two facing mirrors, kr 0.9) at "
     << pw << "x" << ph << ", 1 spp, against max_depth 64 with min_weight 0 (max radiance " << fmt("%.4g", max_radiance)
     << "). The bound to hold: max error <= min_weight x max radiance.\n\n"
     << "| max_depth | min_weight | rays | reflection rays | time ms | max error | bound | holds |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  std::string prune_csv = "max_depth,min_weight,rays,reflection_rays,ms,max_error\n";
  for (int depth : {2, 4, 8, 16, 32, 64}) {
    for (double mw : {0.0, 1e-3, 1e-2}) {
      Scene s = mirrors;
      s.max_depth = depth;
      s.min_weight = mw;
      const Render r = render(s, pw, ph, 1, threads, 0);
      const double err = max_abs_error(means(r.accum), exact_img);
      const bool bounded = mw > 0 && depth == 64;
      md << "| " << depth << " | " << mw << " | " << r.stats.rays.total() << " | " << r.stats.rays.reflection << " | "
         << fmt("%.1f", r.seconds * 1000) << " | " << fmt("%.3g", err) << " | "
         << (bounded ? fmt("%.3g", mw * max_radiance) : std::string("-")) << " | "
         << (bounded ? (err <= mw * max_radiance ? "yes" : "**no**") : "-") << " |\n";
      if (bounded && err > mw * max_radiance) std::printf("CHECK FAILED: pruning error above its bound\n");
      prune_csv += std::to_string(depth) + "," + fmt("%g", mw) + "," + std::to_string(r.stats.rays.total()) + "," +
                   std::to_string(r.stats.rays.reflection) + "," + fmt("%.3f", r.seconds * 1000) + "," +
                   fmt("%.6e", err) + "\n";
    }
  }
  out.write("pruning.csv", prune_csv);
}

}  // namespace

int run_bench_report(const BenchReportOptions& options) {
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec) {
    std::fprintf(stderr, "%s: cannot create the folder: %s\n", options.out_dir.c_str(), ec.message().c_str());
    return 1;
  }
  Writer out{options.out_dir};
  const bool quick = options.quick;
  const int threads = resolve_thread_count(options.threads);
  std::ostringstream md;
  md << "# phonglab: speed against error\n\nMade by `phonglab-cli bench" << (quick ? " --quick" : "")
     << "` on a machine with " << std::thread::hardware_concurrency() << " hardware threads (" << cpu_model() << ")"
     << "; every figure below comes from this one run.\n\n";

  speed_section(md, out, quick, threads);
  convergence_section(md, out, quick, threads);
  pruning_section(md, out, quick, threads);

  // 4. Acceleration (issue 6): apps/bench/bench_accel.cpp measures and writes this section.
  const AccelBenchResult accel = run_accel_bench(AccelBenchOptions{quick, options.threads});
  md << accel.markdown;
  out.write("accel.csv", accel.csv);
  const YardstickResult yardsticks = run_yardsticks(quick, threads);
  md << yardsticks.markdown;
  out.write("yardsticks.csv", yardsticks.csv);
  precision_section(md, out, quick, threads);
  savings_section(md, out, quick, threads);
  const bench::IndirectBenchResult indirect = bench::run_indirect_bench(quick, threads);
  md << indirect.markdown;
  out.write("indirect.csv", indirect.csv);
  out.write("indirect_spp.svg", indirect.plot_svg);
  out.write("report.md", md.str());
  std::printf("wrote %s/report.md\n", options.out_dir.c_str());
  return out.ok ? 0 : 1;
}

}  // namespace phonglab
