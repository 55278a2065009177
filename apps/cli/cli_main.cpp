// phonglab-cli: the headless side of phonglab (README).
// Exit codes: 0 success, 1 bad input (scene or files), 2 bad usage.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/common/args.h"
#include "apps/common/formula_args.h"
#include "check/check.h"
#include "check/formula.h"
#include "core/accel/accel.h"
#include "io/diagnostic.h"
#include "io/embedded_scenes.h"
#include "io/figure.h"
#include "io/handout.h"
#include "io/lesson_io.h"
#include "core/teaching/heat_map.h"
#include "io/image_io.h"
#include "io/check_report.h"
#include "io/image_read.h"
#include "core/packet/packet.h"
#include "io/probe_report.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"

namespace {

using namespace phonglab;
using namespace phonglab::cli;
using Clock = std::chrono::steady_clock;

// Samples per pixel of `render` and `figure` without --spp: enough for smooth edges (--spp 1
// renders the pixel centres only).
constexpr int kDefaultSpp = 16;
// Gathers the probe averages for the indirect term without --spp.
constexpr int kProbeIndirectSamples = 1024;

constexpr const char* kUsage = R"(usage: phonglab-cli <command> [options]

commands:
  render [SCENE] -o OUT [--width W] [--height H] [--spp N] [--term T]
         [--max-depth D] [--fov-y DEG] [--threads N] [--stats FILE.json]
         [--ambient constant|indirect] [--bounces B]
         [--formula SLOT=TEXT|@FILE ...] [--formulas FILE]
      Render to OUT (.pfm: linear float32, unclamped; .png: 8-bit sRGB).
      W x H: the image's size (default: the scene's image size, 960 x 540 in a
         file without one). N: samples per pixel (default 16, anti-aliased;
         --spp 1 renders the pixel centres only). D: the recursion depth
         (default: the scene's max_depth).
      --fov-y: the camera's vertical field of view (default: the scene's; the
         previewer's dump_state camera_fov, to match a narrow view).
      T: full (default), ambient, diffuse, specular, reflection, refraction,
         indirect, or the debug views normal, depth, rays. A .png of rays is a
         heat map (0 black .. the image's maximum pale yellow; the maximum is
         printed).
      --ambient indirect: every hit's ka*Ia replaced by the indirect light it
         stands in for, a Monte Carlo estimate (default: constant, ka*Ia);
         --term indirect: that term alone at the primary hit. B: its bounces,
         1..64 (default: the scene's "indirect": {"bounces"}, else 4).
      --stats: the times, rays by kind and Mrays/s as JSON (default: none).
      --formula: a term (ambient, diffuse or specular) by your own formula
         (docs/formulas.md); a NaN or infinite value is written as 0.
         --formulas: the formulas of a file the Formula panel saved.
  check SCENE IMAGE [--spp N] [--json] [--diff OUT.png] [--threads N]
  check [SCENE] --formula SLOT=TEXT|@FILE ... [--formulas FILE]
        [--width W] [--height H] [--spp N] [--json] [--diff OUT.png]
        [--threads N]
      A student's work against the exact image. IMAGE: what your own ray
      tracer rendered of SCENE, at its own size (PNG 8-bit sRGB; PPM P6/P3,
      maxval 255 as sRGB, other maxvals linear; PFM linear). --formula: your
      formula for the ambient, diffuse or specular term (docs/formulas.md),
      rendered in its place. Prints match or differs, the differing pixels,
      the largest difference and the nearest known mistake (docs/checking.md);
      --json: the same as one JSON object; --diff: the reference dimmed with
      the differing pixels marked (orange: yours brighter, blue: darker,
      magenta: NaN). N: samples per pixel of the reference (default 1: the
      pixel centres). Exit 0 match, 3 differs, 1 bad input.
  probe [SCENE] --pixel X,Y [--json] [--width W] [--height H] [--fov-y DEG]
        [--ambient indirect [--bounces B] [--spp N]]
      The illumination equation of that pixel's centre ray, term by term, as
      text (--json: as JSON). W x H: the image the pixel is in (default: the
      scene's image size); with the previewer's view size and its dump_state
      camera_fov as --fov-y, the pixel the previewer probed. --ambient
      indirect adds ka*Ia beside the indirect
      term's estimate at the hit, its standard error over N samples (default
      1024) and the ka that would match it.
  figure [SCENE] -o OUT.png [--width W] [--height H] [--spp N] [--threads N]
      The five term images and their sum in a labelled 3x2 grid, each W x H
      (default 320 x 180) at N samples per pixel (default 16).
  validate SCENE       Parse and check a scene only.
  scene [SCENE] [--plain] [-o OUT.json]
      The scene as phonglab reads it, every default written out: the camera,
      image, ambient, background, max_depth, min_weight, specular_model,
      every light's keys and every material's ka kd ks n kr kt ior fresnel
      (docs/your-ray-tracer.md). --plain: every number in plain decimal
      (0.000001, never 1e-06), for your own ray tracer's parser (default:
      the shortest text). Mesh objects stay as their OBJ file. Printed, or
      written to OUT.json (default: printed).
  scenes               List the embedded scenes.
  lessons              List the embedded lessons.
  lesson LESSON -o DIR [--width W] [--height H] [--spp N] [--threads N]
                       [--live URL]
      The lesson's handout: DIR/step-NN.png (each step's image; a question's
      answer as answer-NN.png) and DIR/index.html, one page holding them all
      with the captions. W x H: each image (default: its scene's image size);
      N: samples per pixel (default 4). --live: each step of an embedded
      lesson links to the web page at URL (e.g. phonglab.html beside it).
  bench [--out DIR] [--quick] [--threads N] [--only accel|indirect]
      The speed-versus-error report: report.md, CSV files and SVG plots in DIR
      (default bench-out/); --quick finishes in about a minute (default: the
      full report). --only accel: the acceleration section and the yardsticks
      alone (accel.md, accel.csv, yardsticks.csv; default: every section);
      --only indirect: the indirect light's convergence and speed.
  bench SCENE [--frames N] [--width W] [--height H] [--threads N] [--scalar]
              [--edited] [--reshade shading|light|head] [--formula SLOT=TEXT]
      Time N Whitted frames (default 15; 1 spp each) of one scene at W x H
      (default 1280 x 720, whatever the scene's size) and print the median.
      --scalar: without the packet tracer (the same image, traced ray by ray).
      --edited: a new snapshot of the scene each frame, as after every edit.
      --reshade: re-shading an edit of kd (shading), a light (light) or the
      head (head) from the first sample's ray trees, timed against a fresh
      render, then the live path of a kd or light-intensity slider (default:
      plain frames).
      --formula SLOT=TEXT: the image with your formula timed against the
      built-in re-shade of a kd edit.
      This is phonglab-bench, installed beside phonglab-cli.

--threads N: worker threads (default 0: all hardware threads); the images are
the same for every thread count.
SCENE is a scene file (JSON) or an embedded scene's name; default: lecture.
LESSON is a lesson file (JSON) or an embedded lesson's name.
Options: --help, --version.
Exit codes: 0 success, 1 bad input, 2 bad usage (check: 3 differs).
)";

constexpr int kExitDiffers = 3;



// --ambient and --bounces, shared by render and probe.
struct AmbientArgs {
  Ambient ambient = Ambient::kConstant;
  std::optional<int> bounces;  // overrides the scene's
};
AmbientArgs take_ambient(Args& args) {
  AmbientArgs out;
  const auto ambient = args.take_value("--ambient");
  out.bounces = args.take_int("--bounces", 1, kMaxIndirectBounces);
  if (!ambient || *ambient == "constant") return out;
  if (*ambient != "indirect") {
    const std::vector<std::string_view> names = {"constant", "indirect"};
    throw UsageError{"unknown --ambient '" + *ambient + "'" + suggestion_for(*ambient, names, "expected one of")};
  }
  out.ambient = Ambient::kIndirect;
  return out;
}

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

int cmd_render(Args& args) {
  const auto out = args.take_value("-o");
  const auto width = args.take_int("--width", 1, 16384);
  const auto height = args.take_int("--height", 1, 16384);
  const auto spp = args.take_int("--spp", 1, 1 << 20);
  const auto max_depth = args.take_int("--max-depth", 0, 100);
  const auto fov_y = args.take_open_range("--fov-y", 0, 180);
  const auto threads = args.take_int("--threads", 0, 1024);
  const auto term_arg = args.take_value("--term");
  const auto stats_path = args.take_value("--stats");
  const AmbientArgs ambient = take_ambient(args);
  bool with_formulas = false;
  const std::optional<LocalRules> formulas = take_formulas(args, with_formulas);
  const std::string scene_arg = args.take_positional().value_or(default_scene_name());
  if (!out) throw UsageError{"render needs -o OUT (.pfm or .png)"};
  if (!formulas) return kExitBadInput;
  if (with_formulas && ambient.ambient == Ambient::kIndirect) {
    throw UsageError{"--formula replaces the lecture's local terms: it takes --ambient constant"};
  }
  const std::string ext = out->size() >= 4 ? out->substr(out->size() - 4) : "";
  if (ext != ".pfm" && ext != ".png") throw UsageError{"-o " + *out + ": the extension must be .pfm or .png"};
  RenderOptions options;
  if (term_arg) {
    const auto term = term_from_name(*term_arg);
    if (!term) {
      std::vector<std::string_view> names;  // the equation's terms, the indirect term, then the debug views
      for (const Term t : {Term::kFull, Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection,
                           Term::kRefraction, Term::kIndirect, Term::kNormal, Term::kDepth, Term::kRays}) {
        names.push_back(term_name(t));
      }
      throw UsageError{"unknown --term '" + *term_arg + "'" + suggestion_for(*term_arg, names, "expected one of")};
    }
    options.term = *term;
  }
  options.threads = threads.value_or(0);
  options.ambient = ambient.ambient;

  const auto t_load = Clock::now();
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  const double load_ms = ms_since(t_load);
  const auto t_build = Clock::now();
  if (width) scene->width = *width;
  if (height) scene->height = *height;
  if (max_depth) scene->max_depth = *max_depth;
  if (fov_y) scene->camera.fov_y_deg = *fov_y;
  if (ambient.bounces) scene->indirect_bounces = *ambient.bounces;
  const PreparedScene built(*scene);
  // With formulas, the same geometry traced by the equation with its hooks (src/check/rules.h).
  const PreparedScene prepared = with_formulas ? prepare_with_rules(*scene, built, *formulas) : built;
  const double build_ms = ms_since(t_build);

  Accumulator accum;
  accum.reset(scene->width, scene->height);
  const auto t_render = Clock::now();
  const PassStats total = render_passes(prepared, options, accum, spp.value_or(kDefaultSpp));
  const double render_ms = ms_since(t_render);

  Image image = mean_image(accum);
  if (options.term == Term::kRays && ext == ".png") {
    // Rays per pixel as grey would be white almost everywhere: a PNG shows them as a heat map.
    // The PFM keeps the counts.
    const double max = heat_max(image.pixels);
    image.pixels = heat_map_pixels(image.pixels, max);
    std::printf("heat map: 0 (black) .. %g (pale yellow) rays per pixel\n", max);
  }
  if (std::string err = write_image(*out, image); !err.empty()) {
    std::cerr << *out << ": " << err << "\n";
    return kExitBadInput;
  }
  if (stats_path) {
    const double seconds = render_ms / 1000;
    nlohmann::json j = {{"load_ms", load_ms},
                        {"build_ms", build_ms},
                        {"render_ms", render_ms},
                        {"samples_per_pixel", accum.samples},
                        {"width", accum.width},
                        {"height", accum.height},
                        {"threads", resolve_thread_count(options.threads)},
                        {"rays",
                         {{"primary", total.rays.primary},
                          {"shadow", total.rays.shadow},
                          {"reflection", total.rays.reflection},
                          {"refraction", total.rays.refraction},
                          {"indirect", total.rays.indirect}}},
                        {"mrays_per_s", seconds > 0 ? static_cast<double>(total.rays.total()) / seconds / 1e6 : 0.0},
                        {"nan_count", total.nan_count},
                        {"tracer", total.packets ? "packet" : "scalar"}};
    if (std::string err = write_file_atomically(*stats_path, j.dump(2) + "\n"); !err.empty()) {
      std::cerr << *stats_path << ": " << err << "\n";
      return kExitBadInput;
    }
  }
  return kExitOk;
}

int cmd_check(Args& args) {
  const bool as_json = args.take_flag("--json");
  const auto diff_path = args.take_value("--diff");
  const auto spp = args.take_int("--spp", 1, 1 << 16);
  const auto threads = args.take_int("--threads", 0, 1024);
  const auto width = args.take_int("--width", 1, 16384);
  const auto height = args.take_int("--height", 1, 16384);
  bool with_formulas = false;
  const std::optional<LocalRules> formulas = take_formulas(args, with_formulas);
  if (!formulas) return kExitBadInput;  // a formula's error, or its file's, is printed
  std::vector<std::string> positional;
  while (const auto word = args.take_positional_word()) positional.push_back(*word);
  if (diff_path && (diff_path->size() < 4 || diff_path->substr(diff_path->size() - 4) != ".png")) {
    throw UsageError{"--diff " + *diff_path + ": the extension must be .png"};
  }
  if (with_formulas) {
    if (positional.size() > 1) throw UsageError{"check --formula takes SCENE only (got '" + positional[1] + "' too)"};
  } else {
    if (positional.size() != 2) {
      throw UsageError{"check needs SCENE IMAGE (your ray tracer's image of the scene) or SCENE --formula SLOT=TEXT"};
    }
    if (width || height) throw UsageError{"check SCENE IMAGE takes the image's own size (no --width, --height)"};
  }
  std::optional<Scene> scene = load_or_report(positional.empty() ? default_scene_name() : positional[0]);
  if (!scene) return kExitBadInput;
  CheckOptions options;
  options.spp = spp.value_or(1);
  options.threads = threads.value_or(0);
  CheckResult result;
  if (with_formulas) {
    if (width) scene->width = *width;
    if (height) scene->height = *height;
    result = check_formulas(*scene, *formulas, options);
  } else {
    std::string error;
    const std::optional<ReadImage> image = read_image_file(positional[1], &error);
    if (!image) {
      std::cerr << error << "\n";
      return kExitBadInput;
    }
    result = check_image(*scene, student_image(*image), options);
  }
  if (as_json) {
    std::cout << check_to_json(result, 2) << "\n";
  } else {
    std::cout << check_report_text(result);
  }
  if (diff_path) {
    Image diff;
    diff.width = result.width;
    diff.height = result.height;
    for (const Color& c : check_difference_image(result)) diff.pixels.emplace_back(c);
    if (std::string err = write_image(*diff_path, diff); !err.empty()) {
      std::cerr << *diff_path << ": " << err << "\n";
      return kExitBadInput;
    }
  }
  return result.match ? kExitOk : kExitDiffers;
}

int cmd_probe(Args& args) {
  const auto pixel = args.take_value("--pixel");
  const bool as_json = args.take_flag("--json");
  const auto width = args.take_int("--width", 1, 16384);
  const auto height = args.take_int("--height", 1, 16384);
  const auto fov_y = args.take_open_range("--fov-y", 0, 180);
  const AmbientArgs ambient = take_ambient(args);
  const auto samples = args.take_int("--spp", 1, 1 << 24);
  const std::string scene_arg = args.take_positional().value_or(default_scene_name());
  if (!pixel) throw UsageError{"probe needs --pixel X,Y"};
  if (samples && ambient.ambient != Ambient::kIndirect) throw UsageError{"probe takes --spp only with --ambient indirect"};
  int x = 0, y = 0;
  char extra = 0;
  if (std::sscanf(pixel->c_str(), "%d,%d%c", &x, &y, &extra) != 2) {
    throw UsageError{"--pixel must be X,Y (got '" + *pixel + "')"};
  }
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  if (width) scene->width = *width;
  if (height) scene->height = *height;
  if (fov_y) scene->camera.fov_y_deg = *fov_y;
  if (x < 0 || y < 0 || x >= scene->width || y >= scene->height) {
    throw UsageError{"--pixel " + *pixel + " is outside the " + std::to_string(scene->width) + "x" +
                     std::to_string(scene->height) + " image"};
  }
  if (ambient.bounces) scene->indirect_bounces = *ambient.bounces;
  const PreparedScene prepared(*scene);
  const PixelProbe probe = probe_pixel(prepared, scene->width, scene->height, x, y);
  std::optional<IndirectProbe> indirect;
  if (ambient.ambient == Ambient::kIndirect) {
    indirect = probe_indirect(prepared, scene->width, scene->height, x, y, samples.value_or(kProbeIndirectSamples));
  }
  if (as_json) {
    std::cout << probe_to_json(prepared.scene(), probe, indirect ? &*indirect : nullptr);
  } else {
    std::cout << probe_to_text(prepared.scene(), probe) << (indirect ? indirect_probe_text(*indirect) : "");
  }
  return kExitOk;
}

int cmd_figure(Args& args) {
  const auto out = args.take_value("-o");
  FigureOptions options;
  options.cell_width = args.take_int("--width", 1, 8192).value_or(options.cell_width);
  options.cell_height = args.take_int("--height", 1, 8192).value_or(options.cell_height);
  options.spp = args.take_int("--spp", 1, 1 << 16).value_or(kDefaultSpp);
  options.threads = args.take_int("--threads", 0, 1024).value_or(0);
  const std::string scene_arg = args.take_positional().value_or(default_scene_name());
  if (!out) throw UsageError{"figure needs -o OUT.png"};
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  if (std::string err = write_figure(*out, PreparedScene(*scene), options); !err.empty()) {
    std::cerr << *out << ": " << err << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

int cmd_validate(Args& args) {
  const auto scene_arg = args.take_positional();
  if (!scene_arg) throw UsageError{"validate needs SCENE"};
  // A lesson file is checked as a lesson (every step's scene with it), and said to be one.
  if (is_lesson_file(*scene_arg)) {
    const LessonLoad lesson = load_lesson_arg(*scene_arg);
    if (!lesson.ok()) {
      std::cerr << *scene_arg << " is a lesson file (it has \"steps\"):\n" << lesson.error_text() << "\n";
      return kExitBadInput;
    }
    std::cout << *scene_arg << ": ok, a lesson (" << counted(lesson.lesson->steps.size(), "step") << ": \""
              << lesson.lesson->title << "\"; open it with phonglab --lesson " << *scene_arg << ")\n";
    return kExitOk;
  }
  std::optional<Scene> scene = load_or_report(*scene_arg);
  if (!scene) return kExitBadInput;
  std::cout << *scene_arg << ": ok (" << counted(scene->spheres.size(), "sphere") << ", "
            << counted(scene->planes.size(), "plane") << ", " << counted(scene->triangles.size(), "triangle") << ", ";
  if (!scene->meshes.empty()) {
    std::size_t mesh_triangles = 0;
    for (const Mesh& m : scene->meshes) mesh_triangles += m.geometry->triangles.size();
    std::cout << counted(scene->meshes.size(), "mesh", "meshes") << " of " << counted(mesh_triangles, "triangle") << ", ";
  }
  std::cout << counted(scene->lights.size(), "light") << ", " << counted(scene->materials.size(), "material") << ")\n";
  return kExitOk;
}

// The scene with every default written out; --plain: in plain decimal numbers, for a student's
// own parser (docs/your-ray-tracer.md).
int cmd_scene(Args& args) {
  const bool plain = args.take_flag("--plain");
  const auto out = args.take_value("-o");
  const std::string scene_arg = args.take_positional().value_or(default_scene_name());
  std::optional<Scene> scene = load_or_report(scene_arg);
  if (!scene) return kExitBadInput;
  // Written to a file, the mesh files read from disk are named relative to its folder.
  std::string save_dir;
  if (out) {
    save_dir = std::filesystem::path(*out).parent_path().string();
    if (save_dir.empty()) save_dir = ".";
  }
  const std::string text = plain ? scene_to_plain_json(*scene, save_dir) : scene_to_json(*scene, save_dir);
  if (!out) {
    std::cout << text;
    return kExitOk;
  }
  if (std::string err = write_file_atomically(*out, text); !err.empty()) {
    std::cerr << err << "\n";
    return kExitBadInput;
  }
  return kExitOk;
}

int cmd_scenes(Args& args) {
  args.take_positional();
  std::size_t w = 0;
  for (const EmbeddedScene& s : embedded_scenes()) w = std::max(w, s.name.size());
  for (const EmbeddedScene& s : embedded_scenes()) {
    std::cout << s.name << std::string(w + 2 - s.name.size(), ' ') << s.description << "\n";
  }
  return kExitOk;
}

int cmd_lessons(Args& args) {
  args.take_positional();
  for (const EmbeddedLesson& l : embedded_lessons()) {
    const LessonLoad load = load_lesson_arg(std::string(l.name));
    if (!load.ok()) {
      std::cerr << load.error_text() << "\n";
      return kExitBadInput;
    }
    std::cout << l.name << std::string(l.name.size() < 12 ? 12 - l.name.size() : 1, ' ') << load.lesson->title << " ("
              << counted(load.lesson->steps.size(), "step") << "): " << load.lesson->description << "\n";
  }
  return kExitOk;
}

int cmd_lesson(Args& args) {
  const auto out = args.take_value("-o");
  HandoutOptions options;
  options.width = args.take_int("--width", 1, 8192).value_or(0);
  options.height = args.take_int("--height", 1, 8192).value_or(0);
  options.spp = args.take_int("--spp", 1, 1 << 12).value_or(options.spp);
  options.threads = args.take_int("--threads", 0, 1024).value_or(0);
  options.live_page = args.take_value("--live").value_or("");
  const auto lesson_arg = args.take_positional();
  if (!lesson_arg) throw UsageError{"lesson needs LESSON (see phonglab-cli lessons)"};
  if (!out) throw UsageError{"lesson needs -o DIR"};
  const LessonLoad load = load_lesson_arg(*lesson_arg);
  if (!load.ok()) {
    std::cerr << load.error_text() << "\n";
    return kExitBadInput;
  }
  std::vector<std::string> written;
  if (std::string err = write_handout(*load.lesson, *out, options, &written); !err.empty()) {
    std::cerr << err << "\n";
    return kExitBadInput;
  }
  for (const std::string& path : written) std::cout << path << "\n";
  return kExitOk;
}

// `phonglab-cli bench ...` is phonglab-bench (apps/bench), installed beside phonglab-cli: the
// bench links the numerics experiments and Embree, which the CLI itself never does.
int cmd_bench(char** argv) {
  std::string self = "phonglab-cli";
  if (char* path = realpath("/proc/self/exe", nullptr)) {
    self = path;
    std::free(path);
  }
  const std::string bench = self.substr(0, self.rfind('/') + 1) + "phonglab-bench";
  argv[0] = const_cast<char*>("phonglab-bench");
  execv(bench.c_str(), argv);
  std::cerr << "phonglab-cli bench: cannot run " << bench << ": " << std::strerror(errno) << "\n";
  return kExitUsage;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty()) {
    std::cerr << kUsage;
    return kExitUsage;
  }
  if (words[0] == "--help" || words[0] == "-h" || words[0] == "help") {
    std::cout << kUsage;
    return kExitOk;
  }
  if (words[0] == "--version") {
    std::cout << "phonglab-cli " << PHONGLAB_VERSION << "\n";
    return kExitOk;
  }
  const std::string command = words[0];
  if (command == "bench") return cmd_bench(argv + 1);
  words.erase(words.begin());
  if (std::find(words.begin(), words.end(), "--help") != words.end()) {
    std::cout << kUsage;
    return kExitOk;
  }
  Args args(std::move(words));
  try {
    if (command == "render") return cmd_render(args);
    if (command == "probe") return cmd_probe(args);
    if (command == "check") return cmd_check(args);
    if (command == "figure") return cmd_figure(args);
    if (command == "validate") return cmd_validate(args);
    if (command == "scene") return cmd_scene(args);
    if (command == "scenes") return cmd_scenes(args);
    if (command == "lessons") return cmd_lessons(args);
    if (command == "lesson") return cmd_lesson(args);
    throw UsageError{"unknown command '" + command + "'"};
  } catch (const UsageError& e) {
    std::cerr << "phonglab-cli: " << e.message << "\n(see phonglab-cli --help)\n";
    return kExitUsage;
  }
}
