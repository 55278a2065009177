// libFuzzer target: any bytes given to the scene loader. A rejected input must come with
// positioned diagnostics; an accepted one must save and load back, and render without NaN.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <utility>

#include "core/render/render.h"
#include "io/scene/scene_io.h"

using namespace phonglab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const LoadResult result = load_scene_text(text, "fuzz.json", "/nonexistent");
  if (!result.ok()) {
    if (result.errors.empty()) std::abort();  // rejected without saying why
    return 0;
  }
  const std::string saved = scene_to_json(*result.scene);
  const LoadResult again = load_scene_text(saved, "saved.json", "/nonexistent");
  if (!again.ok() || scene_to_json(*again.scene) != saved) std::abort();  // save is not lossless

  // Render a few pixels of every accepted scene: no valid input may produce NaN or Inf.
  Scene scene = *result.scene;
  scene.max_depth = std::min(scene.max_depth, 6);  // bound the ray tree of glass in glass
  const PreparedScene prepared(std::move(scene));
  Accumulator accum;
  accum.reset(5, 4);
  RenderOptions options;
  options.threads = 1;
  for (int pass = 0; pass < 2; ++pass) {
    if (render_pass(prepared, options, accum).nan_count != 0) std::abort();
  }
  return 0;
}
