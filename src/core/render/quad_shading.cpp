#include "core/render/quad_shading.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/packet/packet.h"
#include "core/render/tile_work.h"
#include "core/scene/camera.h"
#include "core/scene/display8.h"
#include "core/shading/shading.h"

namespace phonglab {

namespace {

constexpr int kQuadTile = 32;  // even: a tile holds whole quads
// Shaded points further apart than this many display codes (sRGB, any channel) are not
// interpolated between.
constexpr int kSmoothCodes = 2;
constexpr std::int64_t kNoSurface = -1;

// The surface a scalar hit is on: one sphere, plane or loose triangle, or one mesh (its triangles
// share the surface; quads over two of its materials are told apart by the material).
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

// The scalar tracer's two steps of a tile (the packet tracer's find_surfaces and shade_found):
// the region's primary rays and nearest hits, kept; then the values of some of them.
class ScalarFound {
 public:
  void find(const PreparedScene& prepared, const CameraFrame& frame, int x0, int y0, int x1, int y1,
            std::int64_t* surface, RayCounts& rays) {
    ray_.clear(), hit_.clear();
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) {
        double u = 0, v = 0;
        sample_offset(x, y, 0, u, v, 0);
        ray_.push_back(camera_ray(frame, x, y, u, v));
        hit_.push_back(intersect(prepared, ray_.back()));
        surface[ray_.size() - 1] = hit_.back() ? surface_of(*hit_.back()) : kNoSurface;
      }
    }
    rays.primary += ray_.size();
  }
  void shade_found(const PreparedScene& prepared, const Vec3* eye, const int* lanes, int m, Color* out,
                   RayCounts& rays) const {
    const TraceLimits limits{prepared.scene().max_depth, prepared.scene().min_weight};
    for (int j = 0; j < m; ++j) {
      const auto k = static_cast<std::size_t>(lanes[j]);
      out[j] = shade(prepared, limits, ray_[k], *hit_[k], 0, 1.0, rays, nullptr, eye, TermsWanted{}).sum();
    }
  }

 private:
  std::vector<Ray> ray_;
  std::vector<std::optional<Hit>> hit_;
};

// A thread's buffers for a tile's region, kept from tile to tile: per pixel the surface and the
// value; the pixels to shade next and their values; the display codes of the lattice points.
struct Buffers {
  std::vector<std::int64_t> surface;
  std::vector<Color> value, out;
  std::vector<int> lanes;
  std::vector<std::uint32_t> code;  // sRGB, 8 bits a channel, at the even pixels
  ScalarFound scalar;
};

// What a pass needs of the scene, the image and the options.
struct Pass {
  const PreparedScene& prepared;
  const CameraFrame& frame;
  const Vec3* eye;
  bool packets;
  int w, h;
  Color background;  // as a first sample writes it
  const Display8Encoder& codes;
  std::atomic<std::uint64_t>& nan_count;
};

// One tile of the rung: its pixels [x0, x1) x [y0, y1) and the region it reads, one pixel more
// across and down (the next tiles' first column and row: the far corners of its last cells).
class QuadTile {
 public:
  QuadTile(const Pass& pass, Buffers& b, int x0, int y0, int x1, int y1, RayCounts& rays)
      : p_(pass), b_(b), x0_(x0), y0_(y0), x1_(x1), y1_(y1), xe_(std::min(x1 + 1, pass.w)), ye_(std::min(y1 + 1, pass.h)),
        rw_(xe_ - x0), rays_(rays) {
    const auto n = static_cast<std::size_t>(rw_) * static_cast<std::size_t>(ye_ - y0_);
    b_.surface.resize(n), b_.value.resize(n), b_.code.resize(n);
    b_.lanes.clear();
  }

  // Every pixel's hit; the lattice points (even x and y) shaded; each quad's other pixels
  // interpolated between them or shaded; the tile's pixels written.
  void render(Color* image) {
    if (p_.packets) packet_tracer_for(p_.prepared).find_surfaces(p_.frame, x0_, y0_, xe_, ye_, b_.surface.data(), rays_);
    else b_.scalar.find(p_.prepared, p_.frame, x0_, y0_, xe_, ye_, b_.surface.data(), rays_);
    for (int y = y0_; y < ye_; y += 2) {
      for (int x = x0_; x < xe_; x += 2) list(x, y);
    }
    shade_listed();
    code_lattice();
    quads();
    shade_listed();
    for (int y = y0_; y < y1_; ++y) {
      std::copy_n(b_.value.data() + at(x0_, y), x1_ - x0_,
                  image + static_cast<std::size_t>(y) * static_cast<std::size_t>(p_.w) + static_cast<std::size_t>(x0_));
    }
  }
  // With `floats`: the tile's pixels as floats too (a first pass's image for the screen).
  void write_floats(glm::vec3* floats) const {
    for (int y = y0_; y < y1_; ++y) {
      glm::vec3* row = floats + static_cast<std::size_t>(y) * static_cast<std::size_t>(p_.w);
      for (int x = x0_; x < x1_; ++x) row[x] = glm::vec3(b_.value[at(x, y)]);
    }
  }

 private:
  std::size_t at(int x, int y) const {
    return static_cast<std::size_t>(y - y0_) * static_cast<std::size_t>(rw_) + static_cast<std::size_t>(x - x0_);
  }
  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < p_.w && y < p_.h; }
  std::int64_t surface(int x, int y) const { return b_.surface[at(x, y)]; }

  // The pixel to be shaded (a miss is the background, without a trace).
  void list(int x, int y) {
    const std::size_t i = at(x, y);
    if (b_.surface[i] == kNoSurface) b_.value[i] = p_.background;
    else b_.lanes.push_back(static_cast<int>(i));
  }

  // The listed pixels' values, as render_pass writes a first sample: NaN and infinities as 0
  // (counted once, where the pixel is the tile's own), before anything is interpolated from them.
  void shade_listed() {
    const int m = static_cast<int>(b_.lanes.size());
    b_.out.resize(static_cast<std::size_t>(m));
    if (p_.packets) packet_tracer_for(p_.prepared).shade_found(b_.lanes.data(), m, p_.eye, b_.out.data(), rays_);
    else b_.scalar.shade_found(p_.prepared, p_.eye, b_.lanes.data(), m, b_.out.data(), rays_);
    for (int j = 0; j < m; ++j) {
      const auto i = static_cast<std::size_t>(b_.lanes[static_cast<std::size_t>(j)]);
      Color c = b_.out[static_cast<std::size_t>(j)];
      if (!all_finite(c)) {
        c = Color(0);
        const bool own = static_cast<int>(i % static_cast<std::size_t>(rw_)) < x1_ - x0_ &&
                         static_cast<int>(i / static_cast<std::size_t>(rw_)) < y1_ - y0_;
        if (own) p_.nan_count.fetch_add(1, std::memory_order_relaxed);
      }
      b_.value[i] = Color(0) + c;  // what render_pass adds to the empty sum
    }
    b_.lanes.clear();
  }

  // The display codes of the lattice points.
  void code_lattice() {
    for (int y = y0_; y < ye_; y += 2) {
      for (int x = x0_; x < xe_; x += 2) {
        const Color& c = b_.value[at(x, y)];
        b_.code[at(x, y)] = static_cast<std::uint32_t>(p_.codes(static_cast<float>(c.r))) |
                            static_cast<std::uint32_t>(p_.codes(static_cast<float>(c.g))) << 8 |
                            static_cast<std::uint32_t>(p_.codes(static_cast<float>(c.b))) << 16;
      }
    }
  }
  // Whether the coded points are within kSmoothCodes of each other in every channel.
  bool smooth(const std::uint32_t* packed, int n) const {
    for (int c = 0; c < 3; ++c) {
      int lo = 255, hi = 0;
      for (int k = 0; k < n; ++k) {
        const int v = static_cast<int>(packed[k] >> (8 * c) & 0xff);
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
      if (hi - lo > kSmoothCodes) return false;
    }
    return true;
  }

  // The quads (top-left on the lattice): one on a single surface has its other three pixels
  // interpolated between the lattice points of that surface at the corners of the cell
  // around it (bilinear; corners on another surface left out), or listed to be shaded where
  // those corners are not within kSmoothCodes of each other. A quad on more than one surface, or
  // cut by the image's edge, is shaded whole.
  void quads() {
    for (int qy = y0_; qy < y1_; qy += 2) {
      for (int qx = x0_; qx < x1_; qx += 2) {
        const std::int64_t own = surface(qx, qy);
        const bool one = qx + 1 < p_.w && qy + 1 < p_.h && own != kNoSurface && surface(qx + 1, qy) == own &&
                         surface(qx, qy + 1) == own && surface(qx + 1, qy + 1) == own;
        if (!one) {
          for (int k = 1; k < 4; ++k) {
            if (qx + (k & 1) < x1_ && qy + (k >> 1) < y1_) list(qx + (k & 1), qy + (k >> 1));
          }
          continue;
        }
        Color corner[4] = {};
        bool valid[4];
        std::uint32_t packed[4];
        int n = 0;
        for (int k = 0; k < 4; ++k) {
          const int sx = qx + 2 * (k & 1), sy = qy + 2 * (k >> 1);
          valid[k] = inside(sx, sy) && surface(sx, sy) == own;
          if (!valid[k]) continue;
          corner[k] = b_.value[at(sx, sy)];
          packed[n++] = b_.code[at(sx, sy)];
        }
        if (!smooth(packed, n)) {
          for (int k = 1; k < 4; ++k) list(qx + (k & 1), qy + (k >> 1));
          continue;
        }
        if (valid[1] && valid[2] && valid[3]) {
          // The general sums below when every corner counts (term by term; the weights add to 1).
          b_.value[at(qx + 1, qy)] = Color(0) + 0.5 * corner[0] + 0.5 * corner[1];
          b_.value[at(qx, qy + 1)] = Color(0) + 0.5 * corner[0] + 0.5 * corner[2];
          b_.value[at(qx + 1, qy + 1)] = Color(0) + 0.25 * corner[0] + 0.25 * corner[1] + 0.25 * corner[2] + 0.25 * corner[3];
          continue;
        }
        for (int k = 1; k < 4; ++k) {
          const double fx = (k & 1) * 0.5, fy = (k >> 1) * 0.5;
          Color sum(0);
          double weight = 0;
          for (int c = 0; c < 4; ++c) {
            const double wgt = ((c & 1) ? fx : 1 - fx) * ((c >> 1) ? fy : 1 - fy);
            if (!valid[c] || wgt == 0) continue;
            sum += wgt * corner[c];
            weight += wgt;
          }
          b_.value[at(qx + (k & 1), qy + (k >> 1))] = sum / weight;  // the quad's own top-left is always among them
        }
      }
    }
  }

  const Pass& p_;
  Buffers& b_;
  const int x0_, y0_, x1_, y1_, xe_, ye_, rw_;
  RayCounts& rays_;
};

}  // namespace

PassStats render_quad_shaded(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                             const std::atomic<bool>* cancel) {
  if (!quad_rung_draws(options.term, options.ambient, accum.has_terms())) return render_pass(prepared, options, accum, cancel);
  const auto start = std::chrono::steady_clock::now();
  const Scene& scene = prepared.scene();
  const CameraFrame frame = make_camera_frame(scene.camera, accum.width, accum.height);
  std::atomic<std::uint64_t> nan_count{0};
  const Pass pass{prepared,
                  frame,
                  options.shading_eye ? &*options.shading_eye : nullptr,
                  options.packets && packet_tracing_applies(prepared),
                  accum.width,
                  accum.height,
                  Color(0) + scene.background,
                  Display8Encoder::srgb(),
                  nan_count};
  const Tiles tiles(accum.width, accum.height);
  std::atomic<bool> stop{false};
  std::vector<RayCounts> counts;
  const bool done = for_each_index(static_cast<std::size_t>(tiles.count), options.threads, cancel, stop, counts,
                                   [&](std::size_t t, RayCounts& rays) {
    int x0, y0, x1, y1;
    tiles.bounds(t, x0, y0, x1, y1);
    thread_local Buffers buffers;  // taken once a tile: a thread_local's every use asks whether it is built yet
    QuadTile tile(pass, buffers, x0, y0, x1, y1, rays);
    tile.render(accum.sum.data());
    if (options.first_sample_image) tile.write_floats(options.first_sample_image);
  });
  PassStats stats;
  for (const RayCounts& c : counts) stats.rays += c;
  stats.completed = done;
  stats.packets = pass.packets;
  stats.nan_count = nan_count.load();
  if (done) accum.samples = 1;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace phonglab
