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

constexpr int kQuadTile = 32;  // even: a tile holds whole quads
// Shaded corners further apart than this many display codes (sRGB, any channel) are not
// interpolated between.
constexpr int kSmoothCodes = 2;
constexpr std::int64_t kNoSurface = -1;

// The surface a scalar hit is on: one sphere, plane or loose triangle, or one mesh (its triangles
// share the surface; quads over two of its materials are told apart by the material, in the low
// 32 bits as the packet tracer's find_surfaces gives it).
std::int64_t surface_of(const Hit& hit) {
  const auto kind = static_cast<std::int64_t>(hit.object.kind);
  return kind << 56 | static_cast<std::int64_t>(hit.object.index) << 32 | static_cast<std::uint32_t>(hit.material);
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

// A thread's buffers for a tile's region: per pixel the surface and the value; the pixels to
// shade next, and their values.
struct Buffers {
  std::vector<std::int64_t> surface;
  std::vector<Color> value, out;
  std::vector<int> lanes;
};

// The scalar tracer's two steps of a tile (the packet tracer's find_surfaces and shade_found):
// the region's primary rays and nearest hits, kept; then the values of some of them.
class ScalarFound {
 public:
  ScalarFound(const PreparedScene& prepared, const CameraFrame& frame, const Vec3* eye)
      : prepared_(prepared), frame_(frame), eye_(eye),
        limits_{prepared.scene().max_depth, prepared.scene().min_weight} {}
  void find(int x0, int y0, int x1, int y1, std::int64_t* surface, RayCounts& rays) {
    ray_.clear(), hit_.clear();
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        double u = 0, v = 0;
        sample_offset(x, y, 0, u, v, 0);
        ray_.push_back(camera_ray(frame_, x, y, u, v));
        hit_.push_back(intersect(prepared_, ray_.back()));
        surface[ray_.size() - 1] = hit_.back() ? surface_of(*hit_.back()) : kNoSurface;
      }
    }
    rays.primary += ray_.size();
  }
  void shade_found(const int* lanes, int m, Color* out, RayCounts& rays) const {
    for (int j = 0; j < m; ++j) {
      const auto k = static_cast<std::size_t>(lanes[j]);
      out[j] = shade(prepared_, limits_, ray_[k], *hit_[k], 0, 1.0, rays, nullptr, eye_, TermsWanted{}).sum();
    }
  }

 private:
  const PreparedScene& prepared_;
  const CameraFrame& frame_;
  const Vec3* eye_;
  TraceLimits limits_;
  std::vector<Ray> ray_;
  std::vector<std::optional<Hit>> hit_;
};

}  // namespace

PassStats render_quad_shaded(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                             const std::atomic<bool>* cancel) {
  if (options.term != Term::kFull || options.ambient != Ambient::kConstant) return render_pass(prepared, options, accum, cancel);
  const auto start = std::chrono::steady_clock::now();
  const Scene& scene = prepared.scene();
  const int w = accum.width, h = accum.height;
  const CameraFrame frame = make_camera_frame(scene.camera, w, h);
  const Vec3* eye = options.shading_eye ? &*options.shading_eye : nullptr;
  const bool packets = options.packets && packet_tracing_applies(prepared);
  const Display8Encoder& codes = Display8Encoder::srgb();
  const Tiles tiles(w, h);
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> nan_count{0};
  std::vector<RayCounts> counts;

  // Tile by tile, in one pass: the nearest hit of every pixel of the tile and of the lattice
  // points of the next tiles' first column and row (a quad's corners); the lattice points and
  // the pixels of quads not on one surface shaded; each other pixel interpolated between the
  // shaded corners of its surface in the 2x2 cell around it, or shaded itself where those
  // corners are not within kSmoothCodes of each other.
  const bool done = for_each_index(static_cast<std::size_t>(tiles.count), options.threads, cancel, stop, counts,
                                   [&](std::size_t t, RayCounts& rays) {
    int x0, y0, x1, y1;
    tiles.bounds(t, x0, y0, x1, y1);
    const int xe = std::min(x1 + 1, w), ye = std::min(y1 + 1, h), rw = xe - x0;
    const auto n = static_cast<std::size_t>(rw) * static_cast<std::size_t>(ye - y0);
    // The thread's buffers, kept from tile to tile (and taken once: a thread_local's every use
    // would ask whether it is constructed yet).
    thread_local Buffers buffers;
    std::vector<std::int64_t>& surface = buffers.surface;
    std::vector<Color>& value = buffers.value;
    std::vector<Color>& out = buffers.out;
    std::vector<int>& lanes = buffers.lanes;
    surface.resize(n), value.resize(n);
    const auto local = [&](int x, int y) { return static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(rw) + static_cast<std::size_t>(x - x0); };
    std::optional<ScalarFound> scalar;
    if (packets) {
      packet_tracer_for(prepared).find_surfaces(frame, x0, y0, xe, ye, surface.data(), rays);
    } else {
      scalar.emplace(prepared, frame, eye);
      scalar->find(x0, y0, xe, ye, surface.data(), rays);
    }
    // Values of the listed pixels of the region; misses are the background without a trace.
    const auto shade_listed = [&] {
      const int m = static_cast<int>(lanes.size());
      out.resize(static_cast<std::size_t>(m));
      if (packets) packet_tracer_for(prepared).shade_found(lanes.data(), m, eye, out.data(), rays);
      else scalar->shade_found(lanes.data(), m, out.data(), rays);
      // As render_pass writes a first sample: NaN and infinities as 0 (counted once, where the
      // pixel is the tile's own), before anything is interpolated from them.
      for (int j = 0; j < m; ++j) {
        const auto i = static_cast<std::size_t>(lanes[static_cast<std::size_t>(j)]);
        Color c = out[static_cast<std::size_t>(j)];
        if (!all_finite(c)) {
          c = Color(0);
          if (static_cast<int>(i % static_cast<std::size_t>(rw)) < x1 - x0 && static_cast<int>(i / static_cast<std::size_t>(rw)) < y1 - y0) {
            nan_count.fetch_add(1, std::memory_order_relaxed);
          }
        }
        value[i] = Color(0) + c;  // what render_pass adds to the empty sum
      }
      lanes.clear();
    };
    const Color background = Color(0) + scene.background;
    const auto list = [&](std::size_t i) {
      if (surface[i] == kNoSurface) value[i] = background;
      else lanes.push_back(static_cast<int>(i));
    };
    // The quads (top-left qx, qy) on one surface, one flag each, row by row.
    const int quads_across = (x1 - x0 + 1) / 2;
    std::array<std::uint8_t, (kQuadTile / 2) * (kQuadTile / 2)> one_surface{};
    lanes.clear();
    for (int y = y0; y < ye; y += 2) {
      for (int x = x0; x < xe; x += 2) {
        const std::size_t i = local(x, y);
        if (x >= x1 || y >= y1) {
          list(i);  // a corner of the next tiles' quads
          continue;
        }
        const std::int64_t s = surface[i];
        const bool one = x + 1 < w && y + 1 < h && s != kNoSurface && surface[i + 1] == s &&
                         surface[i + static_cast<std::size_t>(rw)] == s && surface[i + static_cast<std::size_t>(rw) + 1] == s;
        one_surface[static_cast<std::size_t>((y - y0) / 2 * quads_across + (x - x0) / 2)] = one;
        list(i);
        if (one) continue;
        for (int k = 1; k < 4; ++k) {  // cut by the image's edge or on more than one surface: shaded whole
          if (x + (k & 1) < x1 && y + (k >> 1) < y1) list(local(x + (k & 1), y + (k >> 1)));
        }
      }
    }
    shade_listed();
    // The display codes of the lattice points (sRGB, packed 8 bits a channel), each taken once.
    constexpr int kSide = kQuadTile / 2 + 1;
    std::array<std::uint32_t, kSide * kSide> code{};
    const int side_x = (xe - x0 + 1) / 2;
    for (int y = y0; y < ye; y += 2) {
      for (int x = x0; x < xe; x += 2) {
        const Color& c = value[local(x, y)];
        code[static_cast<std::size_t>((y - y0) / 2 * side_x + (x - x0) / 2)] =
            static_cast<std::uint32_t>(codes(static_cast<float>(c.r))) | static_cast<std::uint32_t>(codes(static_cast<float>(c.g))) << 8 |
            static_cast<std::uint32_t>(codes(static_cast<float>(c.b))) << 16;
      }
    }
    const auto channel = [](std::uint32_t packed, int c) { return static_cast<int>(packed >> (8 * c) & 0xff); };
    for (int qy = y0; qy < y1; qy += 2) {
      for (int qx = x0; qx < x1; qx += 2) {
        if (!one_surface[static_cast<std::size_t>((qy - y0) / 2 * quads_across + (qx - x0) / 2)]) continue;  // shaded whole
        // The shaded corners of the cell on the quad's surface, and whether they are within
        // kSmoothCodes of each other.
        const std::int64_t own = surface[local(qx, qy)];
        const std::size_t lattice = static_cast<std::size_t>((qy - y0) / 2 * side_x + (qx - x0) / 2);
        Color corner[4];
        bool valid[4];
        int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
        for (int k = 0; k < 4; ++k) {
          const int sx = qx + 2 * (k & 1), sy = qy + 2 * (k >> 1);
          valid[k] = sx < w && sy < h && surface[local(sx, sy)] == own;
          if (!valid[k]) continue;
          corner[k] = value[local(sx, sy)];
          const std::uint32_t packed = code[lattice + static_cast<std::size_t>((k & 1) + (k >> 1) * side_x)];
          for (int c = 0; c < 3; ++c) {
            lo[c] = std::min(lo[c], channel(packed, c));
            hi[c] = std::max(hi[c], channel(packed, c));
          }
        }
        const bool smooth = hi[0] - lo[0] <= kSmoothCodes && hi[1] - lo[1] <= kSmoothCodes && hi[2] - lo[2] <= kSmoothCodes;
        if (smooth && valid[1] && valid[2] && valid[3]) {
          // The loop below when every corner counts (its sums, term by term; the weights add to 1).
          value[local(qx + 1, qy)] = Color(0) + 0.5 * corner[0] + 0.5 * corner[1];
          value[local(qx, qy + 1)] = Color(0) + 0.5 * corner[0] + 0.5 * corner[2];
          value[local(qx + 1, qy + 1)] = Color(0) + 0.25 * corner[0] + 0.25 * corner[1] + 0.25 * corner[2] + 0.25 * corner[3];
          continue;
        }
        for (int p = 1; p < 4; ++p) {
          const int x = qx + (p & 1), y = qy + (p >> 1);
          if (!smooth) {
            lanes.push_back(static_cast<int>(local(x, y)));
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
          value[local(x, y)] = sum / weight;  // the quad's own top-left is always among them
        }
      }
    }
    shade_listed();
    // The tile's pixels: every value above is as render_pass writes a first sample.
    for (int y = y0; y < y1; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x0);
      std::copy_n(value.data() + local(x0, y), x1 - x0, accum.sum.data() + row);
      if (options.first_sample_image) {
        for (int x = x0; x < x1; ++x) options.first_sample_image[row + static_cast<std::size_t>(x - x0)] = glm::vec3(value[local(x, y)]);
      }
    }
  });
  PassStats stats;
  for (const RayCounts& c : counts) stats.rays += c;
  stats.completed = done;
  stats.packets = packets;
  stats.nan_count = nan_count.load();
  if (done) accum.samples = 1;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace phonglab
