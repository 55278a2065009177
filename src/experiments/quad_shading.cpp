#include "experiments/quad_shading.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "core/render/tile_work.h"
#include "core/scene/camera.h"
#include "core/scene/display8.h"
#include "core/shading/shading.h"

namespace phonglab {

namespace {

// Which object a pixel shows: kind, index and triangle in one number; kMissed for the background.
constexpr std::uint64_t kMissed = ~std::uint64_t{0};
std::uint64_t object_key(const ObjectRef& o) {
  return (static_cast<std::uint64_t>(o.kind) << 56) ^ (static_cast<std::uint64_t>(static_cast<std::uint32_t>(o.index)) << 24) ^
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(o.prim + 1));
}
// Shaded corners further apart than this many display codes (sRGB, any channel) are not
// interpolated between.
constexpr int kSmoothCodes = 2;

// Mesh triangles of one mesh count as one object (the quad's shading varies smoothly over them).
std::uint64_t surface_key(const ObjectRef& o) {
  ObjectRef surface = o;
  if (surface.kind == ObjectRef::Kind::kMesh) surface.prim = -1;
  return object_key(surface);
}

}  // namespace

PassStats render_quad_shaded(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                             const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  const Scene& scene = prepared.scene();
  const int w = accum.width, h = accum.height;
  const CameraFrame frame = make_camera_frame(scene.camera, w, h);
  const TraceLimits limits{scene.max_depth, scene.min_weight};
  const Vec3* eye = options.shading_eye ? &*options.shading_eye : nullptr;
  const TermsWanted wanted = terms_wanted(options.term);
  const std::size_t pixels = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<Color> value(pixels);
  std::vector<std::uint64_t> key(pixels, kMissed);
  std::vector<std::uint8_t> shaded(pixels, 0);
  const int quads_x = (w + 1) / 2, quads_y = (h + 1) / 2;
  std::atomic<bool> stop{false};
  std::vector<RayCounts> counts;
  // Pass 1, a row of quads at a time: every pixel's primary hit; shading where it is needed.
  bool done = for_each_index(static_cast<std::size_t>(quads_y), options.threads, cancel, stop, counts,
                             [&](std::size_t qy, RayCounts& rays) {
    for (int qx = 0; qx < quads_x; ++qx) {
      const int x0 = 2 * qx, y0 = 2 * static_cast<int>(qy);
      struct Corner {
        int x, y;
        Ray ray;
        std::optional<Hit> hit;
      };
      Corner c[4];
      int n = 0;
      for (int dy = 0; dy < 2; ++dy) {
        for (int dx = 0; dx < 2; ++dx) {
          if (x0 + dx >= w || y0 + dy >= h) continue;
          Corner& k = c[n++];
          k.x = x0 + dx, k.y = y0 + dy;
          double u = 0, v = 0;
          sample_offset(k.x, k.y, 0, u, v, options.seed);
          k.ray = camera_ray(frame, k.x, k.y, u, v);
          ++rays.primary;
          k.hit = intersect(prepared, k.ray);
          key[static_cast<std::size_t>(k.y) * w + k.x] = k.hit ? surface_key(k.hit->object) : kMissed;
        }
      }
      // One surface under all four, neither mirror nor glass: the top-left alone is shaded.
      bool uniform = n == 4 && c[0].hit;
      for (int i = 1; uniform && i < 4; ++i) uniform = c[i].hit && surface_key(c[i].hit->object) == surface_key(c[0].hit->object);
      uniform = uniform && !has_children(scene.materials[static_cast<std::size_t>(c[0].hit->material)]);
      for (int i = 0; i < (uniform ? 1 : n); ++i) {
        const std::size_t at = static_cast<std::size_t>(c[i].y) * w + c[i].x;
        value[at] = c[i].hit ? term_value(shade(prepared, limits, c[i].ray, *c[i].hit, 0, 1.0, rays, nullptr, eye, wanted),
                                          options.term)
                             : miss_value(scene, options.term);
        shaded[at] = 1;
      }
    }
  });
  // Pass 2: each pixel not shaded, from the shaded pixels of its surface at the corners of the
  // 2x2 cell around it (bilinear, the corners on another surface left out); where those corners
  // differ by more than a display step (a shadow's edge, a highlight), the pixel is shaded itself.
  if (done) {
    const Display8Encoder& codes = Display8Encoder::srgb();
    std::vector<RayCounts> fill_counts;
    done = for_each_index(static_cast<std::size_t>(h), options.threads, cancel, stop, fill_counts,
                          [&](std::size_t yy, RayCounts& rays) {
      const int y = static_cast<int>(yy);
      for (int x = 0; x < w; ++x) {
        const std::size_t at = static_cast<std::size_t>(y) * w + x;
        if (shaded[at]) continue;
        const int x0 = x & ~1, y0 = y & ~1;
        const double fx = (x - x0) * 0.5, fy = (y - y0) * 0.5;
        Color sum(0);
        double weight = 0;
        int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
        for (int j = 0; j < 2; ++j) {
          for (int i = 0; i < 2; ++i) {
            const int sx = x0 + 2 * i, sy = y0 + 2 * j;
            if (sx >= w || sy >= h) continue;
            const std::size_t s = static_cast<std::size_t>(sy) * w + sx;
            if (!shaded[s] || key[s] != key[at]) continue;
            for (int k = 0; k < 3; ++k) {
              const int code = codes(static_cast<float>(value[s][k]));
              lo[k] = std::min(lo[k], code), hi[k] = std::max(hi[k], code);
            }
            const double wgt = (i ? fx : 1 - fx) * (j ? fy : 1 - fy);
            sum += wgt * value[s];
            weight += wgt;
          }
        }
        const bool smooth = hi[0] - lo[0] <= kSmoothCodes && hi[1] - lo[1] <= kSmoothCodes && hi[2] - lo[2] <= kSmoothCodes;
        if (smooth) {
          value[at] = sum / weight;  // the quad's own top-left is always there
          continue;
        }
        double u = 0, v = 0;
        sample_offset(x, y, 0, u, v, options.seed);
        const Ray ray = camera_ray(frame, x, y, u, v);
        const std::optional<Hit> hit = intersect(prepared, ray);  // its primary ray again (counted once)
        value[at] = hit ? term_value(shade(prepared, limits, ray, *hit, 0, 1.0, rays, nullptr, eye, wanted), options.term)
                        : miss_value(scene, options.term);
      }
    });
    for (const RayCounts& c : fill_counts) counts.push_back(c);
  }
  PassStats stats;
  for (const RayCounts& c : counts) stats.rays += c;
  stats.completed = done;
  if (done) {
    for (std::size_t i = 0; i < pixels; ++i) {
      Color c = value[i];
      if (!all_finite(c)) {
        c = Color(0);
        ++stats.nan_count;
      }
      accum.sum[i] = Color(0) + c;
    }
    accum.samples = 1;
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace phonglab
