// libFuzzer target: any bytes as an OBJ and its MTL (split at the first line "#MTL"), loaded as a
// scene's mesh object through the scene loader (load_scene_text_with: the same path as a mesh
// file on disk). A rejected mesh must come with diagnostics; an accepted one is framed and a few
// pixels of it rendered, which must not be NaN.
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "core/accel/accel.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"

using namespace phonglab;

namespace {

constexpr const char* kScene = R"({
  "lights": [{"type": "point", "position": [0, 5, 5]}, {"type": "directional", "direction": [0, -1, -1]}],
  "objects": [{"type": "mesh", "file": "f.obj"}]
})";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::size_t split = bytes.find("#MTL\n");
  const std::string obj = "mtllib f.mtl\n" + bytes.substr(0, split);
  const std::string mtl = split == std::string::npos ? std::string() : bytes.substr(split + 5);
  const FileReader files = [&](const std::string& path, std::string& error) -> std::optional<std::string> {
    if (path == "f.obj") return obj;
    if (path == "f.mtl") return mtl;
    error = "no such file";
    return std::nullopt;
  };
  const LoadResult result = load_scene_text_with(kScene, "fuzz.json", files);
  if (!result.ok()) {
    if (result.errors.empty()) std::abort();  // rejected without saying why
    return 0;
  }
  for (const Diagnostic& w : result.warnings) {
    if (w.message.empty()) std::abort();
  }
  // Frame the mesh and render a few pixels: no accepted mesh may produce NaN or Inf.
  Scene scene = *result.scene;
  if (scene.meshes.empty()) std::abort();
  const Aabb box = scene.meshes[0].geometry->bounds;
  const Vec3 centre = box.centroid();
  const double radius = std::max(glm::length(box.hi - box.lo), 1e-6);
  scene.camera.look_at = centre;
  scene.camera.position = centre + Vec3(0.3, 0.4, 1.0) * (2 * radius);
  scene.max_depth = std::min(scene.max_depth, 4);
  if (!(view_up_sine(scene.camera) > kMinViewUpSine) || !all_finite(scene.camera.position)) return 0;
  const PreparedScene prepared(std::move(scene));
  Accumulator accum;
  accum.reset(5, 4);
  RenderOptions options;
  options.threads = 1;
  if (render_pass(prepared, options, accum).nan_count != 0) std::abort();
  return 0;
}
