#include "core/render/quad_shading.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

#include "core/packet/packet.h"
#include "core/render/tile_work.h"
#include "core/scene/camera.h"
#include "core/scene/display8.h"
#include "core/shading/shading.h"

namespace phonglab {

namespace {

constexpr int kQuadTile = 16;  // even: a tile holds whole quads
// Shaded corners further apart than this many display codes (sRGB, any channel) are not
// interpolated between.
constexpr int kSmoothCodes = 2;
constexpr std::int64_t kNoSurface = -1;

// The surface a scalar hit is on: one sphere, plane or loose triangle, or one mesh (its triangles
// share the surface; quads over two of its materials are told apart by the material).
std::int64_t surface_of(const Hit& hit) {
  const auto kind = static_cast<std::int64_t>(hit.object.kind);
  return kind << 56 | static_cast<std::int64_t>(hit.object.index) << 24 | (hit.material & 0xffffff);
}

// The image's tiles, row by row.
struct Tiles {
  int w, h, across, count;
  Tiles(int width, int height)
      : w(width), h(height), across((width + kQuadTile - 1) / kQuadTile), count(across * ((height + kQuadTile - 1) / kQuadTile)) {}
  void bounds(std::size_t t, int& x0, int& y0, int& x1, int& y1) const {
    x0 = static_cast<int>(t % static_cast<std::size_t>(across)) * kQuadTile;
    y0 = static_cast<int>(t / static_cast<std::size_t>(across)) * kQuadTile;
    x1 = std::min(x0 + kQuadTile, w);
    y1 = std::min(y0 + kQuadTile, h);
  }
};

}  // namespace

PassStats render_quad_shaded(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                             const std::atomic<bool>* cancel) {
  if (options.term != Term::kFull || options.ambient != Ambient::kConstant) return render_pass(prepared, options, accum, cancel);
  const auto start = std::chrono::steady_clock::now();
  const Scene& scene = prepared.scene();
  const int w = accum.width, h = accum.height;
  const CameraFrame frame = make_camera_frame(scene.camera, w, h);
  const TraceLimits limits{scene.max_depth, scene.min_weight};
  const Vec3* eye = options.shading_eye ? &*options.shading_eye : nullptr;
  const bool packets = options.packets && packet_tracing_applies(prepared);
  const std::size_t pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  // Per pixel: the surface its primary ray meets; shaded (1), or to interpolate or shade in pass
  // 2. Kept by the calling thread from pass to pass (no page faults for 8 MB at 1280x720).
  thread_local std::vector<std::int64_t> surface_store;
  thread_local std::vector<std::uint8_t> shaded_store;
  surface_store.resize(pixels);
  shaded_store.resize(pixels);
  std::int64_t* const surface = surface_store.data();
  std::uint8_t* const shaded = shaded_store.data();
  Color* value = accum.sum.data();  // the pass writes every pixel once: values go straight there
  const Tiles tiles(w, h);
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> nan_count{0};
  std::vector<RayCounts> counts, fill_counts;
  const auto index = [&](int x, int y) { return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + x; };

  // The scalar tracer's pixel: its primary ray and hit; its value.
  const auto scalar_pixel = [&](int x, int y, std::optional<Hit>& hit, Ray& ray) {
    double u = 0, v = 0;
    sample_offset(x, y, 0, u, v, 0);
    ray = camera_ray(frame, x, y, u, v);
    hit = intersect(prepared, ray);
  };
  const auto scalar_value = [&](const Ray& ray, const std::optional<Hit>& hit, RayCounts& rays) {
    return hit ? shade(prepared, limits, ray, *hit, 0, 1.0, rays, nullptr, eye, TermsWanted{}).sum() : scene.background;
  };

  // Pass 1, tile by tile: every pixel's surface; the pixels that must be shaded, shaded.
  bool done = for_each_index(static_cast<std::size_t>(tiles.count), options.threads, cancel, stop, counts,
                             [&](std::size_t t, RayCounts& rays) {
    int x0, y0, x1, y1;
    tiles.bounds(t, x0, y0, x1, y1);
    const int tw = x1 - x0, n = tw * (y1 - y0);
    if (packets) {
      thread_local std::vector<Color> out;
      thread_local std::vector<std::int64_t> ids;
      thread_local std::vector<std::uint8_t> on;
      out.resize(static_cast<std::size_t>(n)), ids.resize(static_cast<std::size_t>(n)), on.resize(static_cast<std::size_t>(n));
      packet_tracer_for(prepared).render_quads_tile(frame, x0, y0, x1, y1, eye, out.data(), ids.data(), on.data(), rays);
      for (int i = 0; i < n; ++i) {
        const std::size_t at = index(x0 + i % tw, y0 + i / tw);
        surface[at] = ids[static_cast<std::size_t>(i)];
        shaded[at] = on[static_cast<std::size_t>(i)];
        if (shaded[at]) value[at] = out[static_cast<std::size_t>(i)];
      }
      return;
    }
    for (int qy = y0; qy < y1; qy += 2) {
      for (int qx = x0; qx < x1; qx += 2) {
        std::optional<Hit> hit[4];
        Ray ray[4];
        bool inside[4];
        for (int k = 0; k < 4; ++k) {
          const int x = qx + (k & 1), y = qy + (k >> 1);
          inside[k] = x < x1 && y < y1;
          if (!inside[k]) continue;
          ++rays.primary;
          scalar_pixel(x, y, hit[k], ray[k]);
          surface[index(x, y)] = hit[k] ? surface_of(*hit[k]) : kNoSurface;
        }
        // One surface under all four (the packet tracer's mask_quads, the same rule), neither
        // mirror nor glass.
        const std::int64_t s = surface[index(qx, qy)];
        bool uniform = inside[3] && s != kNoSurface && !has_children(scene.materials[static_cast<std::size_t>(hit[0]->material)]);
        for (int k = 1; uniform && k < 4; ++k) uniform = surface[index(qx + (k & 1), qy + (k >> 1))] == s;
        for (int k = 0; k < 4; ++k) {
          if (!inside[k]) continue;
          const std::size_t at = index(qx + (k & 1), qy + (k >> 1));
          shaded[at] = !uniform || k == 0;
          if (shaded[at]) value[at] = scalar_value(ray[k], hit[k], rays);
        }
      }
    }
  });
  // Pass 2, tile by tile: each pixel not shaded, from the shaded pixels of its surface at the
  // corners of the 2x2 cell around it (bilinear, corners on another surface left out), or shaded
  // itself where those corners are not within kSmoothCodes of each other.
  if (done) {
    const Display8Encoder& codes = Display8Encoder::srgb();
    done = for_each_index(static_cast<std::size_t>(tiles.count), options.threads, cancel, stop, fill_counts,
                          [&](std::size_t t, RayCounts& rays) {
      int x0, y0, x1, y1;
      tiles.bounds(t, x0, y0, x1, y1);
      thread_local std::vector<int> xs, ys;
      thread_local std::vector<Color> out;
      xs.clear(), ys.clear();
      // The display codes of the shaded pixels at the quads' corners (the tile's and the next
      // tiles' first row and column), each taken once.
      constexpr int kSide = kQuadTile / 2 + 1;
      std::array<std::array<int, 3>, kSide * kSide> lattice;
      std::array<bool, kSide * kSide> coded{};
      const auto codes_at = [&](int sx, int sy, const Color& c) -> const std::array<int, 3>& {
        const int k = (sy - y0) / 2 * kSide + (sx - x0) / 2;
        if (!coded[static_cast<std::size_t>(k)]) {
          for (int ch = 0; ch < 3; ++ch) lattice[static_cast<std::size_t>(k)][static_cast<std::size_t>(ch)] = codes(static_cast<float>(c[ch]));
          coded[static_cast<std::size_t>(k)] = true;
        }
        return lattice[static_cast<std::size_t>(k)];
      };
      for (int qy = y0; qy < y1; qy += 2) {
        for (int qx = x0; qx < x1; qx += 2) {
          if (qx + 1 >= x1 || qy + 1 >= y1 || shaded[index(qx + 1, qy)]) continue;  // a quad shaded whole
          // The shaded corners of the cell on the quad's surface, and whether they are within
          // kSmoothCodes of each other.
          const std::int64_t own = surface[index(qx, qy)];
          Color corner[4];
          bool valid[4];
          int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
          for (int k = 0; k < 4; ++k) {
            const int sx = qx + 2 * (k & 1), sy = qy + 2 * (k >> 1);
            valid[k] = sx < w && sy < h && shaded[index(sx, sy)] && surface[index(sx, sy)] == own;
            if (!valid[k]) continue;
            corner[k] = value[index(sx, sy)];
            const std::array<int, 3>& code = codes_at(sx, sy, corner[k]);
            for (int c = 0; c < 3; ++c) {
              lo[c] = std::min(lo[c], code[static_cast<std::size_t>(c)]);
              hi[c] = std::max(hi[c], code[static_cast<std::size_t>(c)]);
            }
          }
          const bool smooth = hi[0] - lo[0] <= kSmoothCodes && hi[1] - lo[1] <= kSmoothCodes && hi[2] - lo[2] <= kSmoothCodes;
          for (int p = 1; p < 4; ++p) {
            const int x = qx + (p & 1), y = qy + (p >> 1);
            if (!smooth) {
              xs.push_back(x), ys.push_back(y);
              continue;
            }
            const double fx = (p & 1) * 0.5, fy = (p >> 1) * 0.5;
            Color sum(0);
            double weight = 0;
            for (int k = 0; k < 4; ++k) {
              const double wgt = ((k & 1) ? fx : 1 - fx) * ((k >> 1) ? fy : 1 - fy);
              if (!valid[k] || wgt == 0) continue;
              sum += wgt * corner[k];
              weight += wgt;
            }
            value[index(x, y)] = sum / weight;  // the quad's own top-left is always among them
          }
        }
      }
      const int n = static_cast<int>(xs.size());
      if (n > 0 && packets) {
        out.resize(static_cast<std::size_t>(n));
        packet_tracer_for(prepared).render_pixels(frame, x0, y0, x1, y1, xs.data(), ys.data(), n, eye, out.data(), rays);
        for (int i = 0; i < n; ++i) value[index(xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(i)])] = out[static_cast<std::size_t>(i)];
      } else {
        for (int i = 0; i < n; ++i) {
          std::optional<Hit> hit;
          Ray ray;
          ++rays.primary;
          scalar_pixel(xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(i)], hit, ray);
          value[index(xs[static_cast<std::size_t>(i)], ys[static_cast<std::size_t>(i)])] = scalar_value(ray, hit, rays);
        }
      }
      // The tile's pixels as render_pass writes a first sample: NaN and infinities as 0 (counted).
      for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
          Color& c = value[index(x, y)];
          if (!all_finite(c)) {
            c = Color(0);
            nan_count.fetch_add(1, std::memory_order_relaxed);
          }
          c = Color(0) + c;  // what render_pass adds to the empty sum
        }
      }
    });
  }
  PassStats stats;
  for (const RayCounts& c : counts) stats.rays += c;
  for (const RayCounts& c : fill_counts) stats.rays += c;
  stats.completed = done;
  stats.packets = packets;
  stats.nan_count = nan_count.load();
  if (done) accum.samples = 1;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace phonglab
