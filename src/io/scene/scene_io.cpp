// Scene files (docs/scene-format.md). Loading runs in four passes over the text, none of them recursive:
//   1. prescan: rejects NUL bytes and nesting deeper than kMaxNesting, and finds number tokens
//      that overflow double (nlohmann throws on those instead of returning inf);
//   2. nlohmann parses (syntax errors are translated into positioned plain messages);
//   3. PosIndex maps every value of the now valid text to its byte offsets (nlohmann keeps none);
//   4. Validator walks the DOM and the index together, collecting every independent error.
#include "io/scene/scene_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <new>
#include <span>
#include <sstream>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "core/accel/accel.h"
#include "io/embedded_scenes.h"
#include "io/obj_io.h"

#include "io/scene/scene_load.h"

namespace phonglab {

using namespace scene_load;  // the loader's own parts (src/io/scene/scene_load.h)

std::string LoadResult::error_text() const { return diagnostics_text(errors); }

namespace {

LoadResult load_scene_text_from(const std::string& text, const std::string& file_name, const SceneFiles& files) {
  try {
    return load_text(text, file_name, files);
  } catch (const std::bad_alloc&) {
    return fail(file_name, "out of memory while loading the scene");
  } catch (const std::exception& e) {
    return fail(file_name, std::string("internal error while loading the scene: ") + e.what());
  }
}

// An OBJ opened on its own: its MTL materials, a camera that frames it from the front (+z)
// and above, a white point light above the camera, a dim ambient term.
LoadResult load_obj_scene(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  const SceneFiles files{dir.empty() ? "." : dir, false};
  const std::string name = std::filesystem::path(path).filename().string();
  MeshLoad loaded = load_mesh(files, name, MeshTransform{}, NsMapping::kAsIs, -1, 0, {});
  LoadResult r;
  // The mesh's own problems name the OBJ by the path it was opened with, an MTL's the MTL's path.
  const auto diagnostic = [&](Diagnostic d) {
    d.file = d.file.empty() || d.file == name ? path : (std::filesystem::path(dir) / d.file).string();
    return d;
  };
  for (const Diagnostic& w : loaded.warnings) r.warnings.push_back(diagnostic(w));
  set_severity(r.warnings, Diagnostic::Severity::kWarning);
  for (const Diagnostic& e : loaded.errors) r.errors.push_back(diagnostic(e));
  if (!r.errors.empty()) return r;
  Scene scene;
  scene.ambient = Color(0.2);
  scene.materials = std::move(loaded.materials);
  Mesh mesh;
  mesh.file = name;
  mesh.resolved_path = files.resolve(name);
  mesh.geometry = std::move(loaded.geometry);
  const Aabb box = mesh.geometry->bounds;
  scene.meshes.push_back(std::move(mesh));
  scene.mesh_object.push_back(0);
  const Vec3 centre = box.centroid();
  const double radius = std::max(0.5 * glm::length(box.hi - box.lo), 1e-12);
  Camera& cam = scene.camera;
  cam.look_at = centre;
  // The bounding sphere fits the vertical field of view with a 10 % margin, seen slightly
  // from above (1 in 4).
  const double distance = 1.1 * radius / std::sin(glm::radians(cam.fov_y_deg) / 2);
  cam.position = centre + distance * glm::normalize(Vec3(0, 0.25, 1));
  Light light;
  light.position = cam.position + Vec3(0, radius, 0);
  scene.lights.push_back(light);
  r.scene = std::move(scene);
  return r;
}

}  // namespace

bool is_obj_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = to_lower(c);
  return ext == ".obj";
}

LoadResult load_scene_text(const std::string& text, const std::string& file_name,
                           const std::string& base_dir, bool embedded_meshes) {
  return load_scene_text_from(text, file_name, SceneFiles{embedded_meshes ? "" : base_dir, embedded_meshes});
}

LoadResult load_scene_text_with(const std::string& text, const std::string& file_name, const FileReader& files) {
  SceneFiles from;
  from.reader = &files;
  return load_scene_text_from(text, file_name, from);
}

LoadResult reload_meshes(const Scene& scene, const std::string& base_dir, bool embedded) {
  const std::string dir = base_dir.empty() ? "." : base_dir;
  LoadResult result = load_scene_text_from(scene_to_json(scene, embedded ? "" : dir), "the edited scene",
                                           SceneFiles{embedded ? "" : dir, embedded});
  if (!result.ok()) return result;
  for (Material& m : result.scene->materials) {
    if (m.source.empty()) continue;
    for (const Material& before : scene.materials) {
      if (before.name == m.name && before.source == m.source) {
        const std::string source = m.source;
        m = before;
        m.source = source;
      }
    }
  }
  return result;
}

LoadResult load_scene_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = to_lower(c);
  if (ext == ".mtl") {
    return fail(path, "a material library (MTL) holds an OBJ mesh's materials and is not a scene: open the .obj "
                      "file that names it (its mtllib line), or a scene .json with a mesh object");
  }
  if (is_obj_path(path)) {
    try {
      return load_obj_scene(path);
    } catch (const std::bad_alloc&) {
      return fail(path, "out of memory while loading the mesh");
    }
  }
  std::string error;
  const std::optional<std::string> text = read_text_file(path, kMaxFileBytes, error);
  if (!text) return fail(path, error);
  std::string dir = std::filesystem::path(path).parent_path().string();
  return load_scene_text(*text, path, dir.empty() ? "." : dir);
}

LoadResult load_scene_arg(const std::string& scene_arg) {
  if (const EmbeddedScene* s = find_embedded_scene(scene_arg)) {
    return load_scene_text_from(std::string(s->json), std::string(s->name), SceneFiles{"", true});
  }
  LoadResult result = load_scene_file(scene_arg);
  // A bare word that is neither a file nor an embedded scene was most likely meant as a name.
  const bool looks_like_name = scene_arg.find_first_of("/.") == std::string::npos;
  if (!result.ok() && looks_like_name && result.errors.size() == 1 && result.errors[0].line == 0) {
    std::vector<std::string_view> names;
    for (const EmbeddedScene& e : embedded_scenes()) names.push_back(e.name);
    result.errors[0].message += "; not an embedded scene either" + suggestion(scene_arg, names, "embedded scenes");
  }
  return result;
}


}  // namespace phonglab
