// phonglab-bench: the speed-versus-error report and the frame timer, also run as `phonglab-cli
// bench` (the CLI executes this program, installed beside it). Usage: kUsage, phonglab-bench --help.
// Exit codes: 0 success, 1 bad input, 2 bad usage.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/bench/bench_accel.h"
#include "apps/bench/bench_indirect.h"
#include "apps/bench/bench_common.h"
#include "apps/bench/bench_report.h"
#include "apps/common/args.h"
#include "apps/common/formula_args.h"
#include "check/check.h"
#include "core/scene/display8.h"
#include "core/packet/packet.h"
#include "core/render/quad_shading.h"
#include "core/render/ray_trees.h"
#include "core/render/render.h"
#include "core/scene/camera.h"
#include "io/diagnostic.h"
#include "io/image_io.h"

namespace {

using namespace phonglab;
using namespace phonglab::cli;
using bench::median;

constexpr const char* kUsage = R"(usage: phonglab-bench [--out DIR] [--quick] [--threads N]
                      [--only accel|indirect]
       phonglab-bench SCENE [--frames N] [--width W] [--height H] [--threads N]
                      [--scalar] [--edited] [--reshade shading|light|head]
                      [--formula SLOT=TEXT|@FILE ...] [--check MISTAKE] [--live]
  (also run as `phonglab-cli bench ...`, which executes phonglab-bench)

  The speed-versus-error report: report.md, CSV files and SVG plots in DIR
  (default bench-out/); --quick finishes in about a minute (default: the full
  report). --only accel: the acceleration section and the yardsticks alone
  (accel.md, accel.csv, yardsticks.csv; default: every section); --only
  indirect: the indirect light's convergence and speed (indirect.md, .csv,
  .svg).
  With SCENE: time N Whitted frames (default 15; 1 spp each) of one scene at
  W x H (default 1280 x 720, whatever the scene's size) and print the median;
  --scalar: without the packet tracer (the same image, traced ray by ray);
  --edited: a new snapshot of the scene each frame, as after every edit in the
  previewer. --reshade: record the first sample's ray trees once, then time
  re-shading an edit of kd (shading), a light's position (light) or the
  "move your head" angle (head) against render_pass of the same scene,
  checking the images are bit-identical; then the live path of a kd or a
  light-intensity slider (within 1e-12 of render_pass; default: plain frames).
  --formula: a term by a formula of your own (docs/formulas.md): the image
  with the formulas timed against the built-in re-shade of a kd edit.
  --live: each live level of a camera orbit (1/8, 1/4, 1/2, the quad-shaded
  rung, the exact image): its time and its error as shown against the exact
  image (docs/speed.md); with --out DIR, the last frame's images as shown
  (DIR/live-LEVEL.png).
  --check MISTAKE: a student's 8-bit image with that mistake (docs/checking.md)
  checked against every single mistake, timed against one 1-spp render
  (default 5 runs at 960 x 540).
  --threads N: worker threads (default 0: all hardware threads).
  SCENE is a scene file (JSON) or an embedded scene's name.
  Exit codes: 0 success, 1 bad input, 2 bad usage.
)";

// The edit of frame f: the first material's kd (shading), the first light's position (light),
// or the "move your head" angle (head, an eye turned about the look-at point).
void edit_for_frame(Scene& scene, const std::string& kind, int f, std::optional<Vec3>& eye) {
  if (kind == "light") scene.lights[0].position.x += f % 2 == 0 ? 0.25 : -0.2;
  else if (kind == "head") eye = head_eye(scene.camera, scene.camera.look_at, f % 2 == 0 ? 20.0 : -15.0);
  else scene.materials[0].kd.x = f % 2 == 0 ? 0.2 : 0.6;
}

// The largest |a - b| over the larger of |a| and |b|, channel by channel (0 where both are 0).
double relative_difference(const Accumulator& a, const Accumulator& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.sum.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double scale = std::max(std::abs(a.sum[i][c]), std::abs(b.sum[i][c]));
      if (scale > 0) worst = std::max(worst, std::abs(a.sum[i][c] - b.sum[i][c]) / scale);
    }
  }
  return worst;
}

// The live path of a slider or a drag, against render_pass, alternating, from trees recorded
// once: the first material's kd (shading), the first light's intensity (light) or its position
// (moved), every frame against the same trees as while a hand drags. The first frame takes the
// per-pixel sums (or the light's hits) as well. Prints `live re-shade X ms (R× render_pass)`;
// false when the live image strays past 1e-12.
bool time_live(const Scene& loaded, const std::string& kind, int frames, int width, int height, int threads) {
  if (kind == "head") {
    std::printf("live re-shade: none for the head (V is not linear; the exact re-shade is the live image)\n");
    return true;
  }
  if (kind == "light" && !time_live(loaded, "moved", frames, width, height, threads)) return false;
  Scene scene = loaded;
  auto base = std::make_shared<const PreparedScene>(scene);
  std::unique_ptr<RayTrees> trees = RayTrees::record(base, width, height, std::nullopt, threads, std::size_t{4} << 30);
  if (!trees) return false;
  RenderOptions options;
  options.threads = threads;
  std::vector<double> live_ms, render_ms;
  double first_ms = 0, worst = 0;
  Accumulator live;  // one image, each frame written over the last, as in the previewer
  live.reset(width, height);
  for (int f = 0; f < frames; ++f) {
    if (kind == "light") scene.lights[0].intensity = loaded.lights[0].intensity * (f % 2 == 0 ? 0.5 : 1.3);
    else if (kind == "moved") scene.lights[0].position.x = loaded.lights[0].position.x + (f % 2 == 0 ? 0.25 : -0.2);
    else scene.materials[0].kd.x = f % 2 == 0 ? 0.2 : 0.6;
    const PreparedScene prepared(scene);
    Accumulator rendered;
    rendered.reset(width, height);
    live.samples = 0;
    const PassStats l = trees->recombine(prepared, Term::kFull, threads, live, nullptr, f > 0);
    const PassStats p = render_pass(prepared, options, rendered);
    if (!l.completed) return false;
    (f == 0 ? first_ms : live_ms.emplace_back()) = l.seconds * 1e3;
    render_ms.push_back(p.seconds * 1e3);
    worst = std::max(worst, relative_difference(live, rendered));
  }
  if (live_ms.empty()) live_ms.push_back(first_ms);
  std::printf("%s: live re-shade %.2f ms (%.1f\u00d7 render_pass), the first with its sums %.2f ms; "
              "largest relative difference from render_pass %.1e\n",
              kind == "light" ? "light intensity" : kind == "moved" ? "light moved" : "kd", median(live_ms), median(render_ms) / median(live_ms), first_ms,
              worst);
  return worst <= 1e-12;
}

// Re-shaded frames: the trees of the first sample recorded once, then each frame an edit (see
// edit_for_frame) re-shaded, against a fresh render_pass of the same edited scene, alternating;
// the images are compared bit for bit. Then the live path (time_live).
int time_reshading(const std::string& scene_arg, const std::string& kind, int frames, int width, int height,
                   int threads) {
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  if (scene->materials.empty() || (kind == "light" && scene->lights.empty())) {
    std::fprintf(stderr, "phonglab-bench: --reshade %s needs a material and a light\n", kind.c_str());
    return kExitBadInput;
  }
  const Scene loaded = *scene;
  auto prepared = std::make_shared<const PreparedScene>(*scene);
  std::unique_ptr<RayTrees> trees = RayTrees::record(prepared, width, height, std::nullopt, threads, std::size_t{4} << 30);
  if (!trees) {
    std::fprintf(stderr, "phonglab-bench: the trees do not fit in 4 GiB\n");
    return kExitBadInput;
  }
  const double first_record_ms = trees->record_seconds() * 1e3;
  // Recorded again over the first trees' memory, as the previewer records after each camera stop.
  trees = RayTrees::record(prepared, width, height, std::nullopt, threads, std::size_t{4} << 30, nullptr, true,
                           std::move(trees));
  RenderOptions options;
  options.threads = threads;
  Accumulator plain;
  plain.reset(width, height);
  const double pass_ms = render_pass(*prepared, options, plain).seconds * 1e3;
  const std::string thread_count = counted(static_cast<std::size_t>(resolve_thread_count(threads)), "thread");
  std::printf("scene %s, %dx%d, %s: trees recorded in %.1f ms, again over their memory %.1f ms (%.2f\u00d7 a "
              "render_pass of %.1f ms), %zu nodes, %.1f MiB\n",
              scene_arg.c_str(), width, height, thread_count.c_str(), first_record_ms, trees->record_seconds() * 1e3,
              trees->record_seconds() * 1e3 / pass_ms, pass_ms, trees->node_count(),
              static_cast<double>(trees->memory_bytes()) / (1 << 20));
  std::vector<double> reshade_ms, render_ms;
  bool identical = true;
  RayCounts recast;
  std::optional<Vec3> eye;
  for (int f = 0; f < frames; ++f) {
    edit_for_frame(*scene, kind, f, eye);
    prepared = std::make_shared<const PreparedScene>(*scene);
    Accumulator reshaded, rendered;
    reshaded.reset(width, height);
    rendered.reset(width, height);
    options.shading_eye = eye;
    const PassStats r = trees->reshade(prepared, Term::kFull, eye, threads, reshaded);
    const PassStats p = render_pass(*prepared, options, rendered);
    reshade_ms.push_back(r.seconds * 1e3);
    render_ms.push_back(p.seconds * 1e3);
    recast = r.rays;
    identical = identical && std::memcmp(reshaded.sum.data(), rendered.sum.data(), reshaded.sum.size() * sizeof(Color)) == 0;
  }
  std::printf("%s edit: median re-shade %.2f ms (shadow rays cast %llu), median render_pass %.2f ms (%.1fx); images %s\n",
              kind.c_str(), median(reshade_ms), static_cast<unsigned long long>(recast.shadow), median(render_ms),
              median(render_ms) / median(reshade_ms), identical ? "bit-identical" : "DIFFERENT");
  const bool live = time_live(loaded, kind, frames, width, height, threads);
  return identical && live ? kExitOk : kExitBadInput;
}

// A formula edit against the built-in re-shade (docs/formulas.md): the trees of the first sample
// recorded once; each frame, alternating, an Ia edit re-shaded from them (a built-in edit that
// shades every pixel again, as a formula edit does) and the image with the formulas re-shaded
// from the same trees (what a keystroke in the Formula panel costs: every local term the
// formulas give is evaluated again, lane by lane). The traced image with the formulas, once at
// the end, must be the re-shade's bit for bit.
int time_formula(const std::string& scene_arg, const LocalRules& formulas, int frames, int width, int height,
                 int threads) {
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  auto prepared = std::make_shared<const PreparedScene>(*scene);
  std::unique_ptr<RayTrees> trees = RayTrees::record(prepared, width, height, std::nullopt, threads, std::size_t{4} << 30);
  if (!trees) {
    std::fprintf(stderr, "phonglab-bench: the trees do not fit in 4 GiB\n");
    return kExitBadInput;
  }
  std::vector<double> reshade_ms, formula_ms;
  Scene edited = *scene;
  Accumulator formula_image;
  for (int f = 0; f < frames; ++f) {
    edited.ambient.x = f % 2 == 0 ? 0.15 : 0.25;
    const auto reshaded_scene = std::make_shared<const PreparedScene>(edited);
    Accumulator reshaded;
    reshaded.reset(width, height);
    reshade_ms.push_back(trees->reshade(reshaded_scene, Term::kFull, std::nullopt, threads, reshaded).seconds * 1e3);
    // A keystroke: the formulas compiled again, a new snapshot with them.
    auto with_formulas = std::make_shared<const PreparedScene>(prepare_with_rules(*scene, *prepared, formulas));
    formula_image.reset(width, height);
    formula_ms.push_back(trees->reshade(with_formulas, Term::kFull, std::nullopt, threads, formula_image).seconds * 1e3);
  }
  RenderOptions options;
  options.threads = threads;
  Accumulator traced;
  traced.reset(width, height);
  const PreparedScene with_formulas = prepare_with_rules(*scene, *prepared, formulas);
  const double traced_ms = render_pass(with_formulas, options, traced).seconds * 1e3;
  const bool identical =
      std::memcmp(formula_image.sum.data(), traced.sum.data(), traced.sum.size() * sizeof(Color)) == 0;
  const std::string thread_count = counted(static_cast<std::size_t>(resolve_thread_count(threads)), "thread");
  std::printf("scene %s, %dx%d, %s, %s\n", scene_arg.c_str(), width, height, thread_count.c_str(),
              counted(static_cast<std::size_t>(frames), "frame").c_str());
  std::printf("formula re-shade %.2f ms (%.1fx the built-in re-shade of %.2f ms, an Ia edit: every pixel); "
              "%s the traced formula render of %.2f ms\n",
              median(formula_ms), median(formula_ms) / median(reshade_ms), median(reshade_ms),
              identical ? "bit-identical to" : "DIFFERENT from", traced_ms);
  return identical ? kExitOk : kExitBadInput;
}

// The live levels of a camera drag against their error (docs/speed.md, "The camera drag"): a
// camera orbiting the look-at point 2 degrees a frame; each frame, in turn, the exact image
// (render_pass at full resolution), the 1/8, 1/4 and 1/2 levels (shown widened into blocks, as
// the previewer shows them) and the quad-shaded rung (exact visibility, a quarter of the
// shading). Per level: the median time and the RMSE of the image as shown against the exact
// image of the same camera, in display sRGB (0..1), and each as a ratio to the full pass's.
// With `out_dir`: the last frame's image of each level as the hall sees it (a coarse level
// widened into its blocks, 100 % zoom) as DIR/live-LEVEL.png, to be looked at side by side.
int time_live_levels(const std::string& scene_arg, int frames, int width, int height, int threads,
                     const std::optional<std::string>& out_dir) {
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  struct Level {
    const char* name;
    int divisor;  // 0: the quad-shaded rung
    std::vector<double> ms, rmse;
    std::uint64_t shadow_rays = 0;
  };
  std::vector<Level> levels = {{"full", 1, {}, {}}, {"quads", 0, {}, {}}, {"half", 2, {}, {}},
                               {"quarter", 4, {}, {}}, {"eighth", 8, {}, {}}};
  RenderOptions options;
  options.threads = threads;
  const Display8Encoder& srgb = Display8Encoder::srgb();
  for (int f = 0; f < frames; ++f) {
    Scene s = *scene;
    const double angle = glm::radians(2.0 * f);
    const Vec3 arm = s.camera.position - s.camera.look_at;
    s.camera.position = s.camera.look_at + Vec3(std::cos(angle) * arm.x + std::sin(angle) * arm.z, arm.y,
                                                 -std::sin(angle) * arm.x + std::cos(angle) * arm.z);
    const PreparedScene prepared(s);
    std::vector<std::uint8_t> exact;
    for (Level& level : levels) {
      const int d = std::max(level.divisor, 1);
      const int lw = (width + d - 1) / d, lh = (height + d - 1) / d;
      Accumulator a;
      a.reset(lw, lh);
      const PassStats pass = level.divisor == 0 ? render_quad_shaded(prepared, options, a) : render_pass(prepared, options, a);
      level.ms.push_back(pass.seconds * 1e3);
      level.shadow_rays += pass.rays.shadow;
      std::vector<std::uint8_t> shown(static_cast<std::size_t>(width) * height * 3);
      Image widened{width, height, std::vector<glm::vec3>(static_cast<std::size_t>(width) * height)};
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          const Color c = a.sum[static_cast<std::size_t>(y / d) * lw + x / d];
          widened.at(x, y) = glm::vec3(c);
          for (int k = 0; k < 3; ++k) shown[(static_cast<std::size_t>(y) * width + x) * 3 + k] = srgb(static_cast<float>(c[k]));
        }
      }
      if (out_dir && f + 1 == frames) {
        const std::string path = *out_dir + "/live-" + level.name + ".png";
        const std::string error = write_image(path, widened);
        if (!error.empty()) {
          std::fprintf(stderr, "phonglab-bench: %s\n", error.c_str());
          return kExitBadInput;
        }
      }
      if (level.divisor == 1) exact = shown;
      double sq = 0;
      for (std::size_t i = 0; i < shown.size(); ++i) {
        const double e = (static_cast<double>(shown[i]) - exact[i]) / 255.0;
        sq += e * e;
      }
      level.rmse.push_back(std::sqrt(sq / static_cast<double>(shown.size())));
    }
  }
  const std::string thread_count = counted(static_cast<std::size_t>(resolve_thread_count(threads)), "thread");
  std::printf("scene %s, %dx%d, %s, %s of a camera orbit (2 degrees a frame)\n", scene_arg.c_str(), width, height,
              thread_count.c_str(), counted(static_cast<std::size_t>(frames), "frame").c_str());
  const double full_ms = median(levels[0].ms);
  const double half_rmse = median(levels[2].rmse);
  for (Level& level : levels) {
    std::printf("live %-7s ms %7.2f rmse %.5f  (%.2fx the full pass's time, %.2fx its shadow rays; %.2fx the half "
                "level's rmse)\n",
                level.name, median(level.ms), median(level.rmse), median(level.ms) / full_ms,
                static_cast<double>(level.shadow_rays) / static_cast<double>(std::max<std::uint64_t>(levels[0].shadow_rays, 1)),
                half_rmse > 0 ? median(level.rmse) / half_rmse : 0.0);
  }
  return kExitOk;
}

// A student's image checked (docs/checking.md): the scene rendered at the pixel centres with
// `mistake` made (the check's own variant, as a student's program would make it), then checked
// against every single mistake, against one render of the scene (1 spp), alternating.
int time_check(const std::string& scene_arg, const std::string& mistake_name, int frames, int width, int height,
               int threads) {
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  const std::optional<Mistake> mistake = mistake_from_name(mistake_name);
  if (!mistake) {
    std::fprintf(stderr, "phonglab-bench: no mistake named '%s'\n", mistake_name.c_str());
    return kExitUsage;
  }
  scene->width = width;
  scene->height = height;
  const PreparedScene prepared(*scene);
  const std::vector<MistakeVariant> variants = mistake_variants({*mistake}, *scene);
  if (variants.empty()) return kExitUsage;
  const MistakeVariant& v = variants.front();
  const PreparedScene made = prepare_with_rules(v.scene_of(*scene), prepared, v.rules);
  StudentImage student;
  student.width = width;
  student.height = height;
  student.units = StudentImage::Units::kCodes8;
  student.rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const int sy = v.flipped_y ? height - 1 - y : y;
      const Color c = shade_pixel(made, x, sy, 1, v.pixel_corner).value;
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
      for (int k = 0; k < 3; ++k) {
        const Display8Encoder& encode = v.linear_png ? Display8Encoder::linear() : Display8Encoder::srgb();
        student.rgb[i + static_cast<std::size_t>(k)] = encode(static_cast<float>(c[k]));
      }
    }
  }
  CheckOptions options;
  options.threads = threads;
  options.pairs = false;  // the issue's measure: against all single mistakes
  RenderOptions render_options;
  render_options.threads = threads;
  std::vector<double> check_ms, render_ms;
  std::string named;
  for (int f = 0; f < frames; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    const CheckResult r = check_image(*scene, student, options);
    check_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    named = r.mistake;
    // One render as phonglab-cli render does it: the scene prepared, the image's sums, one pass.
    const auto t1 = std::chrono::steady_clock::now();
    Accumulator accum;
    accum.reset(width, height);
    render_pass(PreparedScene(*scene), render_options, accum);
    render_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count());
  }
  std::printf("scene %s, %dx%d, %s, a %s image, %s each, alternating\n", scene_arg.c_str(), width, height,
              counted(static_cast<std::size_t>(resolve_thread_count(threads)), "thread").c_str(), mistake_name.c_str(),
              counted(static_cast<std::size_t>(frames), "run").c_str());
  std::printf("check %.1f ms (%.2fx render of %.1f ms: the scene prepared, its sums, one pass); named: %s\n", median(check_ms),
              median(check_ms) / median(render_ms), median(render_ms), named.empty() ? "none" : named.c_str());
  return kExitOk;
}

// Frames of one scene, timed.
int time_frames(const std::string& scene_arg, int frames, int width, int height, int threads, bool scalar,
                bool edited) {
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  scene->width = width;
  scene->height = height;
  std::optional<PreparedScene> fresh(std::in_place, *scene);
  RenderOptions options;
  options.threads = threads;
  options.packets = !scalar;
  std::vector<double> ms;
  std::vector<double> mrays;
  RayCounts rays;
  for (int f = 0; f < frames; ++f) {
    // --edited: a new snapshot every frame, as the previewer makes one after every edit (its
    // preparation is not timed; the pass's set-up for a scene it has not seen is).
    if (edited && f > 0) fresh.emplace(*scene);
    const PreparedScene& prepared = *fresh;
    Accumulator accum;
    accum.reset(width, height);
    const PassStats pass = render_pass(prepared, options, accum);
    ms.push_back(pass.seconds * 1000);
    mrays.push_back(static_cast<double>(pass.rays.total()) / pass.seconds / 1e6);
    rays = pass.rays;
  }
  std::printf("scene %s, %dx%d, 1 spp, %s, %s%s, %s tracer\n", scene_arg.c_str(), width, height,
              counted(static_cast<std::size_t>(resolve_thread_count(options.threads)), "thread").c_str(),
              counted(ms.size(), "frame").c_str(), edited ? " (a new snapshot each)" : "",
              options.packets && packet_tracing_applies(*fresh)
                  ? ("packet (" + std::string(packet_simd_target()) + ", " + std::to_string(packet_simd_lanes()) + " lanes)").c_str()
                  : "scalar");
  std::printf("rays per frame: %llu (primary %llu, shadow %llu, reflection %llu, refraction %llu)\n",
              static_cast<unsigned long long>(rays.total()), static_cast<unsigned long long>(rays.primary),
              static_cast<unsigned long long>(rays.shadow), static_cast<unsigned long long>(rays.reflection),
              static_cast<unsigned long long>(rays.refraction));
  std::printf("median frame: %.2f ms, median %.1f Mrays/s (min %.2f ms, max %.2f ms)\n", median(ms), median(mrays),
              *std::min_element(ms.begin(), ms.end()), *std::max_element(ms.begin(), ms.end()));
  return kExitOk;
}

int run(Args& args) {
  const auto frames = args.take_int("--frames", 1, 10000);
  const auto width = args.take_int("--width", 1, 16384);
  const auto height = args.take_int("--height", 1, 16384);
  const auto threads = args.take_int("--threads", 0, 1024);
  const auto out_dir = args.take_value("--out");
  const bool quick = args.take_flag("--quick");
  const auto only = args.take_value("--only");
  const bool scalar = args.take_flag("--scalar");
  const bool edited = args.take_flag("--edited");
  const auto reshade = args.take_value("--reshade");
  const bool live = args.take_flag("--live");
  bool with_formulas = false;
  const std::optional<LocalRules> formulas = take_formulas(args, with_formulas);
  const auto check = args.take_value("--check");
  const auto positional = args.take_positional();
  if (!formulas) return kExitBadInput;
  if (only) {
    if ((*only != "accel" && *only != "indirect") || positional) {
      throw UsageError{"--only takes 'accel' or 'indirect' and no SCENE"};
    }
    if (*only == "indirect") return bench::write_indirect_report(quick, threads.value_or(0), out_dir.value_or("bench-out"));
    return write_accel_report(AccelBenchOptions{quick, threads.value_or(0)}, out_dir.value_or("bench-out"));
  }
  if (!positional) {  // no SCENE: the whole speed-versus-error report
    BenchReportOptions report;
    report.out_dir = out_dir.value_or(report.out_dir);
    report.quick = quick;
    report.threads = threads.value_or(0);
    return run_bench_report(report);
  }
  if (check) {
    return time_check(*positional, *check, frames.value_or(5), width.value_or(960), height.value_or(540),
                      threads.value_or(0));
  }
  if (with_formulas) {
    return time_formula(*positional, *formulas, frames.value_or(15), width.value_or(1280), height.value_or(720),
                        threads.value_or(0));
  }
  if (live) {
    return time_live_levels(*positional, frames.value_or(5), width.value_or(1280), height.value_or(720),
                            threads.value_or(0), out_dir);
  }
  if (reshade) {
    if (*reshade != "shading" && *reshade != "light" && *reshade != "head") {
      throw UsageError{"--reshade takes 'shading', 'light' or 'head'"};
    }
    return time_reshading(*positional, *reshade, frames.value_or(15), width.value_or(1280), height.value_or(720),
                          threads.value_or(0));
  }
  return time_frames(*positional, frames.value_or(15), width.value_or(1280), height.value_or(720),
                     threads.value_or(0), scalar, edited);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> words(argv + 1, argv + argc);
  if (std::find(words.begin(), words.end(), "--help") != words.end()) {
    std::cout << kUsage;
    return kExitOk;
  }
  Args args(std::move(words));
  try {
    return run(args);
  } catch (const UsageError& e) {
    std::cerr << "phonglab-bench: " << e.message << "\n(see phonglab-bench --help)\n";
    return kExitUsage;
  }
}
