// Progressive rendering: one pass adds one sample to every pixel, tiles spread over threads.
// The image is a function of the scene and the sample count only, never of the thread count.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/base/threads.h"
#include "core/scene/camera.h"
#include "core/scene/scene.h"
#include "core/shading/shading.h"
#include "core/shading/term.h"

namespace phonglab {

struct RenderOptions {
  Term term = Term::kFull;
  int threads = 0;  // 0: all hardware threads
  int tile_size = 16;  // pixels per tile side
  std::uint32_t seed = 0;  // sample set (sample 0 is the centre for every seed)
  // "Move your head": the eye used for V at the primary hit (the view rays stay the camera's;
  // reflection and refraction children use their own -D). nullopt: V = -D, the plain equation.
  std::optional<Vec3> shading_eye;
  // Trace full images in packets (src/core/packet/packet.h) where the scene and the CPU allow it.
  // The image is bit-identical either way; off forces the scalar renderer (tests, comparisons).
  bool packets = true;
  // ka·Ia at every hit, or the indirect light's estimate with the scene's bounces (traced by the
  // scalar renderer: gather rays are incoherent).
  Ambient ambient = Ambient::kConstant;
  // With a first pass (an accumulator at 0 samples): room for width x height floats, where each
  // pixel's mean after the pass (its one sample, as float) is written as its tile finishes, so
  // the conversion a viewer makes of the image overlaps the pass. Null: none.
  glm::vec3* first_sample_image = nullptr;
};

// Sums of samples per pixel, row-major from the top-left, plus the sample count.
struct Accumulator {
  int width = 0;
  int height = 0;
  std::uint32_t samples = 0;  // samples every pixel has
  std::vector<Color> sum;     // width * height running sums (double, so 1e6 samples stay exact)
  // With term images (reset(w, h, true)): per pixel, the sums of the primary hit's five terms,
  // from the same samples as `sum` (the small multiples: one trace, five sums). Empty: none.
  std::vector<Terms> terms;
  void reset(int w, int h, bool with_terms = false);
  // The same size and no samples, the old sums left in place: a first pass (render_pass at
  // samples 0, a re-shade) writes every pixel, so clearing them first is work for nothing (22 MB
  // at 1280x720). A pass cancelled midway leaves such an accumulator to be reset.
  void reset_for_first_pass(int w, int h, bool with_terms = false);
  bool has_terms() const { return !terms.empty(); }
  Color mean(int x, int y) const;  // sum / samples (0 before the first pass)
};

// Adds one sample's terms to a pixel's sums, term by term.
void add_terms(Terms& sum, const Terms& sample);

struct PassStats {
  RayCounts rays;
  std::uint64_t nan_count = 0;  // samples that were NaN or Inf (replaced by 0; should stay 0)
  double seconds = 0;           // wall-clock time of the pass
  bool completed = true;        // false when cancelled midway (accum must then be reset)
  bool packets = false;         // traced by the packet tracer (else by the scalar renderer)
};

// The radiance (or term, or debug value) of one primary ray; `ambient` as in RenderOptions.
Color render_sample(const PreparedScene& prepared, const CameraFrame& frame, Term term, int x, int y,
                    std::uint32_t sample_index, RayCounts& counts, std::uint32_t seed = 0,
                    const Vec3* shading_eye = nullptr, Ambient ambient = Ambient::kConstant);

// The same sample, also giving the primary hit's five terms (zero on a miss) in `terms`: every
// term is computed, and `term`'s value (or the full image's) is read off them, bit for bit what
// render_sample gives. A debug view's value is cast separately. For Term::kIndirect the terms
// are the lecture's (ka·Ia in the ambient's place) and the value is the indirect term: the two
// side by side from one pass.
Color render_sample_terms(const PreparedScene& prepared, const CameraFrame& frame, Term term, int x, int y,
                          std::uint32_t sample_index, RayCounts& counts, Terms& terms, std::uint32_t seed = 0,
                          const Vec3* shading_eye = nullptr, Ambient ambient = Ambient::kConstant);

// Adds sample number `accum.samples` to every pixel (and its terms, if accum.has_terms()). When `cancel` becomes true the pass stops between tiles; `accum` is then
// partly updated and must be reset before further use. Returns the pass's statistics.
PassStats render_pass(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                      const std::atomic<bool>* cancel = nullptr);

// `passes` passes in a row (no cancel); their statistics summed (rays, NaNs, seconds).
PassStats render_passes(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum, int passes);


}  // namespace phonglab

namespace phonglab {

// The full ray tree of one pixel's centre ray (sample 0), for the `probe` command and panel.
struct PixelProbe {
  int x = 0, y = 0;
  ProbeNode root;   // the primary ray; root.total is the pixel's value at 1 spp
  RayCounts rays;   // rays the tree cast
};

// Replays pixel (x, y)'s centre ray of a width x height image, recording everything
// (`shading_eye` as in RenderOptions).
PixelProbe probe_pixel(const PreparedScene& prepared, int width, int height, int x, int y,
                       const std::optional<Vec3>& shading_eye = std::nullopt);

}  // namespace phonglab
