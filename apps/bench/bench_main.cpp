// phonglab-bench: the speed-versus-error report and the frame timer, run as `phonglab-cli bench`
// (the CLI executes this program, installed beside it). Usage in phonglab-cli --help.
// Exit codes: 0 success, 1 bad input, 2 bad usage.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "apps/bench/bench_accel.h"
#include "apps/bench/bench_common.h"
#include "apps/bench/bench_report.h"
#include "apps/common/args.h"
#include "core/packet/packet.h"
#include "core/render/render.h"

namespace {

using namespace phonglab;
using namespace phonglab::cli;
using bench::median;

constexpr const char* kUsage = R"(usage: phonglab-cli bench [--out DIR] [--quick] [--threads N] [--only accel]
       phonglab-cli bench SCENE [--frames N] [--width W] [--height H] [--threads N] [--scalar] [--edited]
  The speed-versus-error report: report.md, CSV files and SVG plots in DIR
  (default bench-out/); --quick finishes in about a minute. --only accel: the
  acceleration section and the yardsticks alone (accel.md, accel.csv, yardsticks.csv). With SCENE: time Whitted
  frames (1 spp) of one scene and print the median; --scalar: without the packet
  tracer (the same image, traced ray by ray); --edited: a new snapshot of the scene each
  frame, as after every edit in the previewer.
)";

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
  std::printf("scene %s, %dx%d, 1 spp, %d threads, %zu frames%s, %s tracer\n", scene_arg.c_str(), width, height,
              resolve_thread_count(options.threads), ms.size(), edited ? " (a new snapshot each)" : "",
              options.packets && packet_tracing_applies(*fresh) ? "packet (AVX2)" : "scalar");
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
  const auto positional = args.take_positional();
  if (only) {
    if (*only != "accel" || positional) throw UsageError{"bench --only takes 'accel' and no SCENE"};
    return write_accel_report(AccelBenchOptions{quick, threads.value_or(0)}, out_dir.value_or("bench-out"));
  }
  if (!positional) {  // no SCENE: the whole speed-versus-error report
    BenchReportOptions report;
    report.out_dir = out_dir.value_or(report.out_dir);
    report.quick = quick;
    report.threads = threads.value_or(0);
    return run_bench_report(report);
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
    std::cerr << "phonglab-cli bench: " << e.message << "\n(see phonglab-cli --help)\n";
    return kExitUsage;
  }
}
