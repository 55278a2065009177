// The packet tracer: a tile's primary rays traced together, one recursion level at a time.
//
// All rays of a level go through each stage as one batch: nearest hits, the light loop with its
// shadow rays (one batch per light), then the reflected and the refracted rays as the next
// level's batches. The intersection tests, the camera rays and the light geometry run many lanes
// wide in the packet kernels (packet_kernels.h: one source, an instance per instruction set:
// AVX-512, AVX2, SIMD128 in the page, NEON, chosen at run time); hit records, pow and the
// recursion set-up reuse the scalar renderer's own functions. The image is bit-identical to
// render_sample's, pixel by pixel, on every instance (tests/core/test_packet.cpp,
// tests/web/simd_check.cpp), so the packet tracer is purely a matter of speed.
//
// It serves the full image and the five term images ("move your head" included) of scenes
// traced by brute force (no acceleration structure: a few spheres and triangles, any planes, no
// mesh) and of scenes with the project's own SceneBvh (meshes, larger scenes: walked a packet
// at a time), with the production numerics, where the CPU runs an instance; render_pass falls
// back to the scalar renderer for everything else (another accelerator, the numerics variants,
// the debug views).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/packet/packet_lanes.h"
#include "core/scene/camera.h"
#include "core/shading/term.h"
#include "core/scene/scene.h"
#include "core/shading/shading.h"

namespace phonglab {

// Whether this CPU runs an instance of the packet kernels (packet_kernels.h), chosen once.
bool packet_cpu_supported();
// The instance has the whole powers' kernel (packet::specular_powers needs a fused multiply-add).
bool packet_fma_supported();
// The instance running: its name ("AVX-512", "AVX2", "SIMD128", "NEON"; "" for none) and lanes.
const char* packet_simd_target();
const char* packet_simd_key();  // as packet_simd_targets names it
int packet_simd_lanes();
// The instances this build has and this CPU runs, best first, by key ("avx512", "avx2",
// "simd128", "neon", then "off": none, the scalar renderer).
std::vector<std::string> packet_simd_targets();
// Runs another of them from now on (PHONGLAB_SIMD=KEY in the environment chooses at start);
// false, changing nothing, for a key not among them. For benchmarks and tests: not while a
// render runs.
bool set_packet_simd_target(std::string_view key);
// The specular exponent n as the whole number packet::specular_powers raises to, or -1 where the
// lanes take std::pow: n not whole, above 4096, or more than kWholePowerSteps squarings and
// products (docs/speed.md).
constexpr int kWholePowerSteps = 24;
int whole_power_exponent(double n);

// Whether the packet tracer can render `scene` (prepared) on this CPU.
bool packet_tracing_applies(const PreparedScene& prepared);

// What PacketTracer::record_tile tells of a tile's ray trees, level by level: what a
// TraceRecorder hears of the scalar tracer's, hit by hit (RayTrees keeps both the same way).
// `pixel` counts the tile's pixels row by row; `parent` is the node whose child the ray is (-1:
// a primary ray).
class PacketTreeSink {
 public:
  virtual ~PacketTreeSink() = default;
  virtual void missed(int pixel, std::int32_t parent, TraceRecorder::Child kind) = 0;
  // A hit: its node (what light() and bounced() name).
  virtual std::int32_t hit(int pixel, std::int32_t parent, TraceRecorder::Child kind, int depth, int material,
                           bool entering, const Vec3& p, const Vec3& n, const Vec3& ng, const Vec3& dir,
                           double offset) = 0;
  virtual void light(std::int32_t node, int index, LightSeen seen, double n_dot_l, double cos_spec, double spec) = 0;
  virtual void bounced(std::int32_t node, double fresnel) = 0;
};

// Traces tiles of one scene. One per thread: it owns its batch buffers, reused tile to tile.
class PacketTracer {
 public:
  explicit PacketTracer(const PreparedScene& prepared);  // the scene must outlive the tracer
  // The same, reusing the ray and hit buffers of a tracer of another scene (left empty): they are
  // a fair part of a small pass's set-up, and every edit in the previewer makes a new scene.
  PacketTracer(const PreparedScene& prepared, PacketTracer&& recycled);
  ~PacketTracer();
  PacketTracer(const PacketTracer&) = delete;
  PacketTracer& operator=(const PacketTracer&) = delete;

  // Whether render_tile draws `term`: the full image and its five terms (not the debug views).
  static bool draws(Term term);

  // Sample `sample_index` of pixels [x0, x1) x [y0, y1), row by row into `out`
  // ((x1 - x0) * (y1 - y0) colours): the value render_sample(term, ..., shading_eye) gives each
  // pixel, for a term that draws() accepts. With `terms_out` (room for as many), every term of
  // the primary hits is computed and kept there too (zero on a miss): render_sample_terms.
  void render_tile(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::uint32_t sample_index,
                   std::uint32_t seed, Color* out, RayCounts& counts, Term term = Term::kFull,
                   const Vec3* shading_eye = nullptr, Terms* terms_out = nullptr);

  // The quad-shaded rung's two steps (core/render/quad_shading.h), at sample 0 of the full
  // image. find_surfaces: the nearest hits of pixels [x0, x1) x [y0, y1), row by row, kept; per
  // pixel the surface it shows (-1: none; one number for one object and material, the material
  // in the low 32 bits). shade_found: render_tile's value (bit for bit) of the pixels lanes[0 ..
  // m) of the last find_surfaces, each of which has a hit, from their kept hits into out[0 .. m).
  void find_surfaces(const CameraFrame& frame, int x0, int y0, int x1, int y1, std::int64_t* surface, RayCounts& counts);
  void shade_found(const int* lanes, int m, const Vec3* shading_eye, Color* out, RayCounts& counts);

  // render_tile of the full image at the pixel centres, telling `sink` of every tree as
  // trace_recorded tells its recorder: every light at every hit (muted or not, whatever the
  // material), the shadow rays of all of them. The values are render_tile's, bit for bit.
  void record_tile(const CameraFrame& frame, int x0, int y0, int x1, int y1, const Vec3* shading_eye,
                   PacketTreeSink& sink, Color* out, RayCounts& counts);

  // occluded(prepared, ray i, t_max[i]) for n rays given as structure of arrays, each array
  // with room for a multiple of 4 (padding lanes with t_max 0 hold no ray): blocked[i] = 1 where
  // something blocks ray i, the same answers as the scalar query.
  void occluded(const double* ox, const double* oy, const double* oz, const double* dx, const double* dy,
                const double* dz, const double* t_max, int n, std::uint8_t* blocked);
  // The same for shadow rays that all go towards `light`, one of the scene's: only the spheres
  // that the bundle from their origins to the light can meet are tested, as in the tracer's own
  // light loop (the answers are the same; fewer tests).
  void occluded_towards(const Light& light, const double* ox, const double* oy, const double* oz, const double* dx,
                        const double* dy, const double* dz, const double* t_max, int n, std::uint8_t* blocked);

  // The nearest hits of the pixel-centre rays of pixels [x0, x1) x [y0, y1), without shading
  // (the benchmark of primary rays alone). Returns how many rays hit something.
  int cast_primary(const CameraFrame& frame, int x0, int y0, int x1, int y1);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// This thread's packet tracer for `prepared` (packet_tracing_applies), kept from call to call of
// the same snapshot: its set-up is a fair part of a small pass. A tracer of a new scene takes
// over the previous one's buffers.
PacketTracer& packet_tracer_for(const PreparedScene& prepared);

}  // namespace phonglab
