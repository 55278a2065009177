#include "apps/bench/bench_accel.h"
#include "apps/bench/bench_common.h"
#include "apps/bench/bench_yardsticks.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "core/accel/accel.h"
#include "core/base/threads.h"
#include "core/scene/camera.h"
#include "io/embedded_scenes.h"
#include "core/packet/packet.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"

#ifdef PHONGLAB_HAVE_EMBREE
#include "apps/bench/embree_accel.h"
#endif

namespace phonglab {
namespace {

using namespace bench;

constexpr double kTargetRatioVsEmbree = 3.0;  // issue 6: lecture at least 3x Embree single-ray
constexpr double kTargetMeshVsLecture = 3.0;  // issue 6: the big mesh frame within 3x lecture's

std::string mib(std::size_t bytes) { return fmt("%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0)); }

// One accelerator under test: the scene prepared with it.
struct Contender {
  std::string name;
  PreparedScene scene;
  bool packets = true;  // RenderOptions::packets
};

// Largest channel difference and number of pixels that differ at all.
std::pair<double, std::size_t> image_difference(const std::vector<Color>& a, const std::vector<Color>& b) {
  double m = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = max_abs(a[i] - b[i]);
    m = std::max(m, d);
    n += d > 0 ? 1 : 0;
  }
  return {m, n};
}

struct PrimaryCast {
  double seconds = 0;
  std::uint64_t rays = 0;
  std::uint64_t hits = 0;
};

// Runs cast(rays, hits) on `threads` threads (the caller's among them), each adding its own
// counts, and times the whole.
template <class Cast>
PrimaryCast timed_cast(int threads, const Cast& cast) {
  std::atomic<std::uint64_t> rays{0}, hits{0};
  const auto worker = [&] {
    std::uint64_t my_rays = 0, my_hits = 0;
    cast(my_rays, my_hits);
    rays += my_rays;
    hits += my_hits;
  };
  const auto t0 = Clock::now();
  run_workers(threads, [&](int) { worker(); });
  return PrimaryCast{seconds_since(t0), rays.load(), hits.load()};
}

// The pixel-centre primary rays of a w x h frame through intersect() (the scene's accelerator),
// 4x4 pixel blocks handed out as the packet caster does, so only the query differs.
PrimaryCast cast_primary(const PreparedScene& scene, int w, int h, int threads) {
  const CameraFrame frame = make_camera_frame(scene.scene().camera, w, h);
  constexpr int kSide = 4;
  constexpr int kBlocksPerTask = 16;
  const int blocks_x = (w + kSide - 1) / kSide;
  const int blocks = blocks_x * ((h + kSide - 1) / kSide);
  std::atomic<int> next{0};
  return timed_cast(threads, [&](std::uint64_t& rays, std::uint64_t& hits) {
    for (;;) {
      const int first = next.fetch_add(kBlocksPerTask, std::memory_order_relaxed);
      if (first >= blocks) break;
      for (int blk = first; blk < std::min(blocks, first + kBlocksPerTask); ++blk) {
        const int x0 = (blk % blocks_x) * kSide, y0 = (blk / blocks_x) * kSide;
        for (int k = 0; k < kSide * kSide; ++k) {
          const int x = x0 + k % kSide, y = y0 + k / kSide;
          if (x >= w || y >= h) continue;
          ++rays;
          if (intersect(scene, camera_ray(frame, x, y, 0.5, 0.5))) ++hits;
        }
      }
    }
  });
}

// The same rays through the packet tracer's kernels (camera rays and nearest hits, four lanes
// wide), in its own 16x16-pixel tiles.
PrimaryCast cast_primary_packets(const PreparedScene& scene, int w, int h, int threads) {
  const CameraFrame frame = make_camera_frame(scene.scene().camera, w, h);
  constexpr int kTile = 16;
  const int tiles_x = (w + kTile - 1) / kTile;
  const int tiles = tiles_x * ((h + kTile - 1) / kTile);
  std::atomic<int> next{0};
  return timed_cast(threads, [&](std::uint64_t& rays, std::uint64_t& hits) {
    PacketTracer tracer(scene);
    for (int t = next.fetch_add(1); t < tiles; t = next.fetch_add(1)) {
      const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
      const int x1 = std::min(w, x0 + kTile), y1 = std::min(h, y0 + kTile);
      rays += static_cast<std::uint64_t>((x1 - x0) * (y1 - y0));
      hits += static_cast<std::uint64_t>(tracer.cast_primary(frame, x0, y0, x1, y1));
    }
  });
}

// Timings of one scene's Whitted frame by contender and thread count.
struct SceneRun {
  std::string scene;
  std::vector<std::string> names;
  std::vector<double> ms[2];     // [0]: 1 thread, [1]: `threads` threads
  std::vector<RayCounts> rays;   // per contender (from its last frame)
  std::vector<std::pair<double, std::size_t>> diff;  // image difference against contender 0
};

SceneRun run_frames(const std::string& scene_name, const std::vector<Contender>& cs, int w, int h, int threads,
                    int frames_multi, int frames_single) {
  SceneRun run;
  run.scene = scene_name;
  const std::size_t n = cs.size();
  for (const Contender& c : cs) run.names.push_back(c.name);
  run.rays.resize(n);
  run.diff.resize(n);
  // The first frame of each contender gives its image; the contenders alternate frame by frame
  // so a change of machine load affects them alike.
  std::vector<std::vector<Color>> images(n);
  for (std::size_t i = 0; i < n; ++i) {
    Frame f = render_frame(cs[i].scene, w, h, threads, cs[i].packets);
    run.rays[i] = f.rays;
    images[i] = std::move(f.image);
  }
  for (std::size_t i = 0; i < n; ++i) run.diff[i] = image_difference(images[i], images[0]);
  // The 1-thread and the multi-thread frames alternate too, so the scaling figure is not the
  // ratio of two stretches of time under different load (this virtual machine's share of the
  // host drifts over seconds).
  const int counts[2] = {1, threads};
  const int frames[2] = {frames_single, frames_multi};
  std::vector<std::vector<double>> ms[2];
  ms[0].resize(n);
  ms[1].resize(n);
  for (int f = 0; f < std::max(frames[0], frames[1]); ++f) {
    for (int k = 0; k < 2; ++k) {
      if (f >= frames[k]) continue;
      for (std::size_t i = 0; i < n; ++i) {
        ms[k][i].push_back(render_frame(cs[i].scene, w, h, counts[k], cs[i].packets).ms);
      }
    }
  }
  for (int k = 0; k < 2; ++k) {
    for (std::size_t i = 0; i < n; ++i) run.ms[k].push_back(median(ms[k][i]));
  }
  return run;
}

bool same_counts(const RayCounts& a, const RayCounts& b) {
  return a.primary == b.primary && a.shadow == b.shadow && a.reflection == b.reflection && a.refraction == b.refraction;
}

}  // namespace

namespace {

// Point (ring i, segment j) of the bumpy sphere: radius 1 with a smooth ripple of +-6 % (7 waves
// pole to pole, 9 around), curved everywhere, so no two triangles are coplanar.
Vec3 bumpy_point(int i, int j, int rings, int segments) {
  const double pi = std::numbers::pi;
  const double theta = pi * i / rings;
  const double phi = 2 * pi * (j % segments) / segments;
  const double r = 1 + 0.06 * std::sin(7 * theta) * std::cos(9 * phi);
  return Vec3(r * std::sin(theta) * std::cos(phi), r * std::cos(theta), r * std::sin(theta) * std::sin(phi));
}

// The same sphere as an OBJ file with shared vertices (one per ring and segment, one per pole),
// as a modeller would write it. Returns false when it cannot be written.
bool write_bumpy_sphere_obj(const std::string& path, int rings, int segments) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return false;
  std::fprintf(f, "# phonglab bench: bumpy sphere, %d rings x %d segments\n", rings, segments);
  const Vec3 north = bumpy_point(0, 0, rings, segments), south = bumpy_point(rings, 0, rings, segments);
  std::fprintf(f, "v %.9g %.9g %.9g\nv %.9g %.9g %.9g\n", north.x, north.y, north.z, south.x, south.y, south.z);
  for (int i = 1; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const Vec3 p = bumpy_point(i, j, rings, segments);
      std::fprintf(f, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    }
  }
  // 1-based: 1 north, 2 south, then ring i (1..rings-1), segment j at 3 + (i-1) segments + j.
  const auto id = [&](int i, int j) {
    if (i == 0) return 1L;
    if (i == rings) return 2L;
    return 3L + static_cast<long>(i - 1) * segments + (j % segments);
  };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      if (i > 0) std::fprintf(f, "f %ld %ld %ld\n", id(i, j), id(i, j + 1), id(i + 1, j + 1));
      if (i < rings - 1) std::fprintf(f, "f %ld %ld %ld\n", id(i, j), id(i + 1, j + 1), id(i + 1, j));
    }
  }
  return std::fclose(f) == 0;
}

}  // namespace

std::vector<Triangle> make_bumpy_sphere(int rings, int segments, int material) {
  rings = std::max(rings, 3);
  segments = std::max(segments, 3);
  const auto point = [&](int i, int j) { return bumpy_point(i, j, rings, segments); };
  std::vector<Triangle> tris;
  tris.reserve(static_cast<std::size_t>(segments) * static_cast<std::size_t>(2 * rings - 2));
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const Vec3 a = point(i, j), b = point(i, j + 1), c = point(i + 1, j), d = point(i + 1, j + 1);
      // The first and last rings meet at a pole: one triangle per segment there.
      if (i > 0) tris.push_back(Triangle{a, b, d, material});
      if (i < rings - 1) tris.push_back(Triangle{a, d, c, material});
    }
  }
  return tris;
}

Scene make_mesh_scene(std::vector<Triangle> triangles) {
  Scene s;
  s.materials = {
      Material{.name = "floor", .ka = Color(0.04), .kd = Color(0.6), .ks = Color(0.1), .n = 10},
      Material{.name = "mesh", .ka = Color(0.08, 0.02, 0.02), .kd = Color(0.8, 0.15, 0.1), .ks = Color(0.5), .n = 20},
      Material{.name = "mirror", .ka = Color(0), .kd = Color(0.05), .ks = Color(0.6), .n = 200, .kr = Color(0.85)},
  };
  for (Triangle& t : triangles) t.material = 1;
  std::vector<int> faces(triangles.size());
  for (std::size_t i = 0; i < faces.size(); ++i) faces[i] = static_cast<int>(i);
  Mesh mesh;
  mesh.file = "(generated)";
  mesh.geometry = make_mesh_geometry(std::move(triangles), std::move(faces));
  const Aabb b = mesh.geometry->bounds;
  const Vec3 c = b.empty() ? Vec3(0) : b.centroid();
  const double r = b.empty() ? 1.0 : std::max(1e-9, 0.5 * glm::length(b.hi - b.lo));
  const double floor_y = b.empty() ? 0.0 : b.lo.y;
  s.meshes.push_back(std::move(mesh));
  s.mesh_object.push_back(0);
  s.planes.push_back(Plane{Vec3(0, floor_y, 0), Vec3(0, 1, 0), 0});
  s.plane_object.push_back(1);
  // A mirror sphere behind and right of the mesh, resting on the floor, shows it from behind.
  const double mr = 0.6 * r;
  s.spheres.push_back(Sphere{Vec3(c.x + 1.6 * r, floor_y + mr, c.z - 1.2 * r), mr, 2});
  s.sphere_object.push_back(2);
  s.lights = {Light{.type = LightType::kPoint, .position = c + r * Vec3(1.5, 4, 3), .intensity = Color(0.9)},
              Light{.type = LightType::kDirectional, .direction = Vec3(-1, -1, -0.5), .intensity = Color(0.2)}};
  s.camera.position = c + r * Vec3(0.3, 0.9, 4.2);
  s.camera.look_at = c + r * Vec3(0.4, -0.1, 0);
  s.camera.fov_y_deg = 40;
  s.background = Color(0.05, 0.06, 0.09);
  return s;
}

namespace {

// The acceleration section: every contender on every embedded scene and on a large generated
// mesh, the primary rays alone, and the mesh's build, memory and load from OBJ.
class AccelBench {
 public:
  explicit AccelBench(const AccelBenchOptions& options)
      : quick_(options.quick),
        threads_(resolve_thread_count(options.threads)),
        w_(quick_ ? 640 : 1280),
        h_(quick_ ? 360 : 720),
        frames_multi_(quick_ ? 3 : 9),
        frames_single_(quick_ ? 1 : 5) {}

  AccelBenchResult run() {
    std::printf("acceleration: %dx%d, median of %d frames (%d threads) and %d (1 thread)%s\n", w_, h_, frames_multi_,
                threads_, frames_single_, kEmbree ? "" : "; Embree not built");
    std::vector<SceneRun> runs;
    for (const EmbeddedScene& e : embedded_scenes()) {
      runs.push_back(run_frames(std::string(e.name), contenders(load_embedded(e.name)), w_, h_, threads_, frames_multi_,
                                frames_single_));
      std::printf("  %-10s %s %.1f ms (%d threads)\n", runs.back().scene.c_str(), runs.back().names[0].c_str(),
                  runs.back().ms[1][0], threads_);
    }
    build_mesh();
    load_mesh_obj();
    const std::string mesh_name = "bumpy sphere (" + std::to_string(mesh_.triangles) + " triangles)";
    runs.push_back(run_frames(mesh_name, mesh_.contenders, w_, h_, threads_, frames_multi_, frames_single_));
    whitted_table(runs);
    primary_table();
    big_mesh_table();
    out_.markdown = md_.str();
    return out_;
  }

 private:
#ifdef PHONGLAB_HAVE_EMBREE
  static constexpr bool kEmbree = true;
#else
  static constexpr bool kEmbree = false;
#endif

  // The generated mesh and its contenders.
  struct MeshRun {
    int rings = 0, segments = 0;
    std::size_t triangles = 0;
    double build_s = 0;
    std::size_t bytes = 0;
    std::optional<PreparedScene> scene;
    std::vector<Contender> contenders;
#ifdef PHONGLAB_HAVE_EMBREE
    EmbreeBuildStats embree_multi, embree_single;
#endif
  };
  // The same mesh loaded from an OBJ file.
  struct ObjRun {
    double load_s = 0, build_s = 0;
    std::size_t bytes = 0, triangles = 0;
  };

  void fail(const std::string& what) {
    std::printf("CHECK FAILED: %s\n", what.c_str());
    out_.checks_passed = false;
  }

  // Contenders for a scene: the default path, the scalar renderer where the default is the
  // packet tracer, the BVH forced, Embree single-ray. Each prepares the scene as loaded.
  std::vector<Contender> contenders(const Scene& raw) const {
    std::vector<Contender> cs;
    const PreparedScene s(raw);
    const std::string structure = s.accel() ? "BVH" : "brute force";
    if (packet_tracing_applies(s)) {
      cs.push_back({"default (packets, " + structure + ")", s});
      cs.push_back({"scalar " + structure, s, false});
    } else {
      cs.push_back({"default (" + structure + ")", s});
    }
    if (!s.accel()) {
      PreparedScene b(raw, [](const Scene& x) { return build_scene_accel(x, true); });
      const bool packets = packet_tracing_applies(b);
      cs.push_back({packets ? "BVH forced (packets)" : "BVH forced", std::move(b)});
    }
#ifdef PHONGLAB_HAVE_EMBREE
    cs.push_back(
        {"Embree rtcIntersect1/rtcOccluded1", PreparedScene(raw, [](const Scene& x) { return make_embree_accel(x); })});
#endif
    return cs;
  }

  // The generated mesh: build times and memory, ours against Embree's.
  void build_mesh() {
    mesh_.rings = quick_ ? 128 : 636;
    mesh_.segments = quick_ ? 256 : 1024;
    std::vector<Triangle> tris = make_bumpy_sphere(mesh_.rings, mesh_.segments, 1);
    mesh_.triangles = tris.size();
    auto t0 = Clock::now();
    const Scene mesh_raw = make_mesh_scene(std::move(tris));
    const PreparedScene& scene = mesh_.scene.emplace(mesh_raw);
    mesh_.build_s = seconds_since(t0);
    mesh_.bytes = mesh_raw.meshes[0].geometry->memory_bytes();
    std::printf("  mesh: %zu triangles, our build %.2f s, %s\n", mesh_.triangles, mesh_.build_s,
                mib(mesh_.bytes).c_str());
    if (packet_tracing_applies(scene)) {
      mesh_.contenders.push_back({"default (packets, BVH)", scene});
      mesh_.contenders.push_back({"scalar BVH", scene, false});
    } else {
      mesh_.contenders.push_back({"default (BVH)", scene});
    }
#ifdef PHONGLAB_HAVE_EMBREE
    make_embree_accel(scene.scene(), EmbreeOptions{1}, &mesh_.embree_single);
    PreparedScene embree_mesh(
        mesh_raw, [&](const Scene& x) { return make_embree_accel(x, EmbreeOptions{threads_}, &mesh_.embree_multi); });
    mesh_.contenders.push_back({"Embree rtcIntersect1/rtcOccluded1", std::move(embree_mesh)});
    std::printf("  mesh: Embree build %.2f s (%d threads), %.2f s (1 thread), %s\n", mesh_.embree_multi.total_seconds,
                threads_, mesh_.embree_single.total_seconds, mib(mesh_.embree_multi.memory_bytes).c_str());
#endif
  }

  // The same mesh from an OBJ file: what `phonglab my.obj` or a scene's mesh object costs.
  void load_mesh_obj() {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("phonglab-bench-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string obj = (dir / "bumpy.obj").string();
    if (write_bumpy_sphere_obj(obj, mesh_.rings, mesh_.segments)) {
      std::error_code size_ec;
      obj_.bytes = static_cast<std::size_t>(fs::file_size(obj, size_ec));
      const auto t_load = Clock::now();
      LoadResult loaded = load_scene_file(obj);
      obj_.load_s = seconds_since(t_load);
      if (loaded.ok() && !loaded.scene->meshes.empty()) {
        obj_.build_s = loaded.scene->meshes[0].geometry->build_seconds;
        obj_.triangles = loaded.scene->meshes[0].geometry->triangles.size();
      } else {
        fail("the generated OBJ did not load: " + loaded.error_text());
      }
    } else {
      fail("cannot write " + obj);
    }
    std::error_code rm_ec;
    fs::remove_all(dir, rm_ec);
    std::printf("  mesh from OBJ: %zu triangles, %.1f MB file, load %.2f s (BVH build %.2f s of it)\n", obj_.triangles,
                static_cast<double>(obj_.bytes) / 1e6, obj_.load_s, obj_.build_s);
  }

  // The Whitted frames of every scene and contender.
  void whitted_table(const std::vector<SceneRun>& runs) {
    md_ << "\n## Acceleration\n\nThe Whitted frame at " << w_ << "x" << h_ << ", 1 spp, median of " << frames_multi_
        << " frames with " << threads_ << " threads and " << frames_single_
        << " with 1 thread, the contenders and the thread counts alternating frame by frame: the project's default "
           "path (PreparedScene:"
           " brute force for a few spheres and triangles, else its BVH; traced by the packet tracer where the CPU runs"
           " its kernels, a batch of rays at a time, through the BVH too), the scalar renderer where the default is the packet "
           "tracer"
           " (the same image, ray by ray), its BVH forced on every scene, and "
        << (kEmbree ? "Embree 3 single-ray queries (rtcIntersect1 for the nearest hit, rtcOccluded1 for shadow rays; "
                      "float triangles, spheres as user geometry running the renderer's exact double test, planes in "
                      "double outside Embree), all with the same shading and rays."
                    : "(Embree not built: configure with Embree 3 installed to compare against it).")
        << " Differences are against the default path's image (largest channel difference of the linear radiance,"
           " and the number of pixels that differ at all).\n\n"
        << "| scene | accelerator | rays | 1 thread ms | " << threads_ << " threads ms | Mrays/s (" << threads_
        << " threads) | scaling | speed vs Embree | max difference | pixels differing | same ray counts |\n"
        << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    out_.csv =
        "scene,accelerator,width,height,threads,median_ms,mrays_per_s,rays,primary,shadow,reflection,refraction,"
        "max_abs_diff,pixels_differing\n";
    double lecture_ratio = 0;
    for (const SceneRun& r : runs) {
      const std::size_t n = r.names.size();
      const double embree_ms = kEmbree ? r.ms[1][n - 1] : 0;
      for (std::size_t i = 0; i < n; ++i) {
        const RayCounts& rc = r.rays[i];
        const double mrays = static_cast<double>(rc.total()) / r.ms[1][i] / 1e3;
        const bool is_embree = kEmbree && i == n - 1;
        const bool same = same_counts(rc, r.rays[0]);
        md_ << "| " << r.scene << " | " << r.names[i] << " | " << rc.total() << " | " << fmt("%.1f", r.ms[0][i])
            << " | " << fmt("%.1f", r.ms[1][i]) << " | " << fmt("%.1f", mrays) << " | "
            << fmt("%.2fx", r.ms[0][i] / r.ms[1][i]) << " | "
            << (kEmbree ? fmt("%.2fx", embree_ms / r.ms[1][i]) : std::string("-")) << " | "
            << fmt("%.3g", r.diff[i].first) << " | " << r.diff[i].second << " | " << (same ? "yes" : "**no**")
            << " |\n";
        for (int k = 0; k < 2; ++k) {
          const int tc = k == 0 ? 1 : threads_;
          out_.csv += r.scene + "," + r.names[i] + "," + std::to_string(w_) + "," + std::to_string(h_) + "," +
                      std::to_string(tc) + "," + fmt("%.3f", r.ms[k][i]) + "," +
                      fmt("%.3f", static_cast<double>(rc.total()) / r.ms[k][i] / 1e3) + "," +
                      std::to_string(rc.total()) + "," + std::to_string(rc.primary) + "," + std::to_string(rc.shadow) +
                      "," + std::to_string(rc.reflection) + "," + std::to_string(rc.refraction) + "," +
                      fmt("%.6e", r.diff[i].first) + "," + std::to_string(r.diff[i].second) + "\n";
        }
        // The BVH and the scalar renderer must answer exactly as the default path: the same image
        // and the same rays.
        if (!is_embree && i > 0 && (!same || r.diff[i].second != 0))
          fail(r.scene + ": " + r.names[i] + " differs from the default path");
      }
      if (r.scene == "lecture") {
        lecture_ms_ = r.ms[1][0];
        if (kEmbree) lecture_ratio = embree_ms / r.ms[1][0];
      }
      if (&r == &runs.back()) mesh_ms_ = r.ms[1][0];
    }
    if (kEmbree) {
      md_ << "\nOn `lecture`, " << threads_ << " threads: the default path is " << fmt("%.2fx", lecture_ratio)
          << " the speed of Embree single-ray (target " << fmt("%.0fx", kTargetRatioVsEmbree) << ": "
          << (lecture_ratio >= kTargetRatioVsEmbree ? "met" : "**not met**") << ").\n";
    }
  }

  // Primary rays alone: how far single-ray double precision is from Embree's packets.
  void primary_table() {
    // Primary rays alone: how far single-ray double precision is from Embree's packets.
    md_ << "\n### Primary rays alone\n\nThe " << w_ << "x" << h_ << " pixel-centre camera rays, nearest hit only, "
        << threads_ << " threads, 4x4-pixel blocks, median of " << frames_multi_ << " casts. "
        << (kEmbree ? "Embree's packets use its own float primitives (spheres as sphere points, the plane as two"
                      " triangles of a square 1e4 times the scene) and a coherent context: the limit to aim for.\n\n"
                    : "(Embree not built: no packet figure.)\n\n")
        << "| scene | query | Mrays/s | rays that hit | share of the packet figure |\n|---|---|---|---|---|\n";
    out_.csv += "\nprimary_scene,query,threads,median_ms,mrays_per_s,hits\n";
    const Scene lecture = load_embedded("lecture");
    primary_rows("lecture", contenders(lecture), PreparedScene(lecture));
    primary_rows("bumpy sphere", mesh_.contenders, *mesh_.scene);
  }

  void primary_rows(const std::string& name, const std::vector<Contender>& cs, const PreparedScene& base) {
    std::vector<std::pair<std::string, PrimaryCast>> rows;
    for (const Contender& c : cs) {
      if (c.packets && packet_tracing_applies(c.scene)) continue;  // single rays: the scalar contender's row
      std::vector<double> secs;
      PrimaryCast last = cast_primary(c.scene, w_, h_, threads_);  // warm-up
      for (int f = 0; f < frames_multi_; ++f) {
        last = cast_primary(c.scene, w_, h_, threads_);
        secs.push_back(last.seconds);
      }
      last.seconds = median(secs);
      rows.push_back({c.name + " single-ray", last});
    }
    if (packet_tracing_applies(base)) {
      std::vector<double> secs;
      PrimaryCast last = cast_primary_packets(base, w_, h_, threads_);  // warm-up
      for (int f = 0; f < frames_multi_; ++f) {
        last = cast_primary_packets(base, w_, h_, threads_);
        secs.push_back(last.seconds);
      }
      last.seconds = median(secs);
      rows.push_back({"packet tracer kernels (" + std::string(packet_simd_target()) + ", " +
                          std::to_string(packet_simd_lanes()) + " lanes, 16x16 tiles)",
                      last});
    }
#ifdef PHONGLAB_HAVE_EMBREE
    {
      std::vector<double> secs;
      const std::vector<PacketCast> casts = embree_cast_primary_packets(base.scene(), w_, h_, threads_, frames_multi_);
      for (const PacketCast& pc : casts) secs.push_back(pc.seconds);
      rows.push_back(
          {"Embree rtcIntersect16 packets", PrimaryCast{median(secs), casts.back().rays, casts.back().hits}});
    }
#else
    (void)base;
#endif
    const double limit = static_cast<double>(rows.back().second.rays) / rows.back().second.seconds / 1e6;
    for (const auto& [query, pc] : rows) {
      const double mrays = static_cast<double>(pc.rays) / pc.seconds / 1e6;
      md_ << "| " << name << " | " << query << " | " << fmt("%.1f", mrays) << " | " << pc.hits << " | "
          << (kEmbree ? fmt("%.0f %%", 100 * mrays / limit) : std::string("-")) << " |\n";
      out_.csv += name + "," + query + "," + std::to_string(threads_) + "," + fmt("%.3f", pc.seconds * 1000) + "," +
                  fmt("%.3f", mrays) + "," + std::to_string(pc.hits) + "\n";
      std::printf("  primary %-10s %-45s %.1f Mrays/s\n", name.c_str(), query.c_str(), mrays);
    }
  }

  // The big mesh: build, memory and frame time.
  void big_mesh_table() {
    md_ << "\n### A large mesh\n\nA generated closed bumpy sphere of " << mesh_.triangles
        << " triangles (the hook `make_mesh_scene` takes any triangles, e.g. an OBJ's) on a floor, with a mirror "
           "sphere,"
           " a point and a directional light.\n\n| | ours | Embree |\n|---|---|---|\n"
        << "| load from OBJ | " << fmt("%.2f s", obj_.load_s) << " for a "
        << fmt("%.1f MB", static_cast<double>(obj_.bytes) / 1e6) << " file of " << obj_.triangles
        << " triangles (`load_scene_file`: read, tinyobjloader, transform, BVH; target < 2 s: "
        << (obj_.load_s < 2 ? "met" : "**not met**") << ") | - |\n"
        << "| build | " << fmt("%.2f s", mesh_.build_s)
        << " (make_mesh_geometry, 2 threads at the top two levels, double boxes, 16-bin SAH) | ";
#ifdef PHONGLAB_HAVE_EMBREE
    md_ << fmt("%.2f s", mesh_.embree_multi.total_seconds) << " with " << threads_ << " threads ("
        << fmt("%.2f s", mesh_.embree_multi.commit_seconds) << " in rtcCommitScene), "
        << fmt("%.2f s", mesh_.embree_single.total_seconds) << " with 1 thread |\n"
        << "| memory | " << mib(mesh_.bytes) << " (MeshGeometry::memory_bytes: double triangles, BVH) | "
        << mib(mesh_.embree_multi.memory_bytes) << " (the device's memory monitor: float vertices, indices, BVH) |\n";
#else
    md_ << "Embree not built |\n| memory | " << mib(mesh_.bytes)
        << " (MeshGeometry::memory_bytes) | Embree not built |\n";
#endif
    md_ << "\nThe mesh frame with " << threads_ << " threads takes " << fmt("%.1f ms", mesh_ms_) << ", "
        << fmt("%.2fx", mesh_ms_ / lecture_ms_) << " the lecture frame's " << fmt("%.1f ms", lecture_ms_)
        << " (target <= " << fmt("%.0fx", kTargetMeshVsLecture) << ": "
        << (mesh_ms_ <= kTargetMeshVsLecture * lecture_ms_ ? "met" : "**not met**") << ").\n";
  }

  AccelBenchResult out_;
  std::ostringstream md_;
  bool quick_;
  int threads_, w_, h_, frames_multi_, frames_single_;
  MeshRun mesh_;
  ObjRun obj_;
  double lecture_ms_ = 0, mesh_ms_ = 0;
};

}  // namespace

AccelBenchResult run_accel_bench(const AccelBenchOptions& options) { return AccelBench(options).run(); }

int write_accel_report(const AccelBenchOptions& options, const std::string& out_dir) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    std::fprintf(stderr, "%s: cannot create the folder: %s\n", out_dir.c_str(), ec.message().c_str());
    return 1;
  }
  const AccelBenchResult r = run_accel_bench(options);
  const YardstickResult y = run_yardsticks(options.quick, resolve_thread_count(options.threads));
  int code = 0;
  const std::string md = "# phonglab: acceleration\n\nMade by `phonglab-cli bench --only accel" +
                         std::string(options.quick ? " --quick" : "") + "` on a machine with " +
                         std::to_string(std::thread::hardware_concurrency()) + " hardware threads.\n" + r.markdown +
                         y.markdown;
  for (const auto& [name, text] : {std::pair<std::string, const std::string&>{"accel.md", md}, {"accel.csv", r.csv},
                                   {"yardsticks.csv", y.csv}}) {
    if (std::string err = write_file_atomically((std::filesystem::path(out_dir) / name).string(), text); !err.empty()) {
      std::fprintf(stderr, "%s\n", err.c_str());
      code = 1;
    }
  }
  std::printf("wrote %s/accel.md\n", out_dir.c_str());
  return code;
}

}  // namespace phonglab
