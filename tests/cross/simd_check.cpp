// The packet kernels' instance of a build the native test suite cannot run against that build's
// own scalar renderer, bit for bit: the page's SIMD128 instance (Emscripten's libm) under
// Node.js, and the aarch64 build's NEON instance under qemu-aarch64 (tests/cross/CMakeLists.txt).
// The kernels' NaN rule and whole powers (tests/support/kernel_checks.h), every embedded scene (where the build
// has the scene files: PHONGLAB_CHECK_EMBEDDED_SCENES), then seeded random scenes traced by brute
// force and through the hierarchy (tests/support/random_scenes.h), each rendered with packets and
// without. Prints one line per failure and a summary; exit 0 when none differ.
//
//   node phonglab_simd_check.js                      the check
//   node phonglab_simd_check.js bench SCENE W H N    N frames of SCENE with packets and without,
//                                                    alternating: the medians (the kernels' speed
//                                                    in the page's engine, without the page)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>
#include <cstring>
#include <string>

#include "core/packet/packet.h"
#include "core/render/render.h"
#if defined(PHONGLAB_CHECK_EMBEDDED_SCENES)
#include "io/embedded_scenes.h"
#include "io/scene/scene_io.h"
#endif
#include "tests/support/kernel_checks.h"
#include "tests/support/random_scenes.h"

using namespace phonglab;

namespace {

struct Image {
  Accumulator accum;
  RayCounts rays;
};

Image render(const PreparedScene& scene, int w, int h, int passes, bool packets, std::uint32_t seed) {
  Image out;
  out.accum.reset(w, h);
  RenderOptions opt;
  opt.packets = packets;
  opt.threads = 1;
  opt.seed = seed;
  render_passes(scene, opt, out.accum, passes);
  return out;
}

int traced = 0;  // scenes the packet tracer served

// 0 when the two images have the same bits and ray counts, else 1 (and a line saying where).
int compare(const std::string& what, const PreparedScene& scene, int w, int h, int passes, std::uint32_t seed) {
  if (!packet_tracing_applies(scene)) return 0;
  ++traced;
  const Image a = render(scene, w, h, passes, true, seed);
  const Image b = render(scene, w, h, passes, false, seed);
  for (std::size_t i = 0; i < a.accum.sum.size(); ++i) {
    if (std::memcmp(&a.accum.sum[i], &b.accum.sum[i], sizeof(Color)) != 0) {
      std::printf("%s: pixel %zu differs: packets %.17g %.17g %.17g, scalar %.17g %.17g %.17g\n", what.c_str(), i,
                  a.accum.sum[i].x, a.accum.sum[i].y, a.accum.sum[i].z, b.accum.sum[i].x, b.accum.sum[i].y,
                  b.accum.sum[i].z);
      return 1;
    }
  }
  if (a.rays.total() != b.rays.total()) {
    std::printf("%s: ray counts differ\n", what.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

#if defined(PHONGLAB_CHECK_EMBEDDED_SCENES)
int bench(const char* name, int w, int h, int frames) {
  LoadResult loaded = load_scene_arg(name);
  if (!loaded.ok()) return 2;
  const PreparedScene scene(std::move(*loaded.scene));
  std::vector<double> ms[2];
  for (int f = 0; f < frames; ++f) {
    for (int packets = 0; packets < 2; ++packets) {
      const auto start = std::chrono::steady_clock::now();
      render(scene, w, h, 1, packets == 1, 0);
      ms[packets].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
  }
  for (auto& v : ms) std::sort(v.begin(), v.end());
  const double scalar = ms[0][ms[0].size() / 2], packets = ms[1][ms[1].size() / 2];
  std::printf("%s %dx%d: packets (%s) %.1f ms, scalar %.1f ms: %.2fx\n", name, w, h, packet_simd_target(), packets,
              scalar, scalar / packets);
  return 0;
}
#endif

int main([[maybe_unused]] int argc, [[maybe_unused]] char** argv) {
#if defined(PHONGLAB_CHECK_EMBEDDED_SCENES)
  if (argc == 6 && std::string(argv[1]) == "bench") {
    return bench(argv[2], std::atoi(argv[3]), std::atoi(argv[4]), std::atoi(argv[5]));
  }
#endif
  if (!packet_cpu_supported()) {
    std::printf("simd-check: this build has no packet kernels\n");
    return 1;
  }
  int scenes = 0, failed = 0;
  std::string kernel_failures = test::nan_bounds_failures();
  if (packet_fma_supported()) kernel_failures += test::check_powers(4).failures;
  std::printf("%s", kernel_failures.c_str());
  failed += !kernel_failures.empty();
#if defined(PHONGLAB_CHECK_EMBEDDED_SCENES)
  for (const EmbeddedScene& e : embedded_scenes()) {
    LoadResult loaded = load_scene_arg(std::string(e.name));
    if (!loaded.ok()) continue;
    const PreparedScene scene(std::move(*loaded.scene));
    failed += compare(std::string(e.name), scene, 97, 61, 2, 0);
    ++scenes;
  }
#endif
  for (std::uint32_t seed = 1; seed <= 120; ++seed) {
    failed += compare("random " + std::to_string(seed), random_scene(seed), 29, 17, 2, seed);
    const PreparedScene with_bvh(random_scene_data(seed, seed % 4 != 0),
                                 [](const Scene& s) { return build_scene_accel(s, /*force_bvh=*/true); });
    failed += compare("hierarchy " + std::to_string(seed), with_bvh, 23, 19, 2, seed);
    scenes += 2;
  }
  std::printf("simd-check (%s, %d lanes): %d scenes, %d traced in packets, %d differ\n", packet_simd_target(),
              packet_simd_lanes(), scenes, traced, failed);
  return failed == 0 && traced > scenes * 3 / 4 ? 0 : 1;
}
