// Pass 4 of the scene loader: the Validator walks the JSON DOM and the position index together,
// collecting every independent error with its file:line:col and JSON path, and builds the Scene;
// load_text runs the four passes over one text.
#include "io/scene/scene_load.h"
#include "io/scene/scene_reader.h"

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
#include "core/scene/camera.h"
#include "io/embedded_scenes.h"
#include "io/obj_io.h"

namespace phonglab::scene_load {

namespace {

// Pass 4: validation.



constexpr std::array<std::string_view, 11> kSceneKeys = {
    "camera", "image", "ambient", "background", "max_depth", "min_weight", "specular_model", "indirect",
    "lights", "materials", "objects"};
constexpr std::array<std::string_view, 2> kImageKeys = {"width", "height"};
constexpr std::array<std::string_view, 1> kIndirectKeys = {"bounces"};
constexpr std::array<std::string_view, 2> kSpecularModels = {"phong", "blinn"};
constexpr std::array<std::string_view, 4> kObjectTypes = {"sphere", "plane", "triangle", "mesh"};
constexpr std::array<std::string_view, 5> kSphereKeys = {"type", "name", "center", "radius", "material"};
constexpr std::array<std::string_view, 5> kPlaneKeys = {"type", "name", "point", "normal", "material"};
constexpr std::array<std::string_view, 5> kTriangleKeys = {"type", "name", "vertices", "normals",
                                                           "material"};
constexpr std::array<std::string_view, 6> kMeshKeys = {"type", "name", "file", "material", "transform", "ns"};
constexpr std::array<std::string_view, 3> kTransformKeys = {"scale", "rotate_deg", "translate"};
constexpr std::array<std::string_view, 2> kNsMappings = {"as_is", "blinn_to_phong"};




// Pass 4 proper: the scene's own members, read through JsonReader.
class Validator : private SceneMembers {
 public:
  Validator(std::string_view original, const PosIndex& index, const Json& root,
            const std::vector<Overflow>& overflows, Issues& issues, const SceneFiles& files, Issues& warnings)
      : SceneMembers(original, index, root, overflows, issues), files_(files), warnings_(warnings) {}

  Scene run() {
    Scene s;
    const Val root{&root_, 0, ""};
    if (!root_.is_object()) {
      report(root, "the scene must be a JSON object (got " + shown(root) + ")");
      return s;
    }
    const Fields top = fields(root, kSceneKeys);
    if (const Val* v = top.find("camera")) read_camera(*v, s.camera);
    if (const Val* v = top.find("image")) image(*v, s);
    if (const Val* v = top.find("ambient")) set(s.ambient, read_color(*v));
    if (const Val* v = top.find("background")) set(s.background, read_color(*v));
    if (const Val* v = top.find("max_depth")) set(s.max_depth, read_int(*v, 0, kMaxDepthLimit));
    if (const Val* v = top.find("min_weight")) set(s.min_weight, read_at_least_zero(*v));
    if (const Val* v = top.find("specular_model")) {
      if (auto name = read_choice(*v, kSpecularModels, "specular model")) {
        s.specular_model = (*name == "blinn") ? SpecularModel::kBlinn : SpecularModel::kPhong;
      }
    }
    if (const Val* v = top.find("indirect")) indirect(*v, s);
    if (const Val* v = top.find("lights")) lights(*v, s);
    // Materials before objects: objects refer to them by name.
    if (const Val* v = top.find("materials")) materials(*v, s);
    if (const Val* v = top.find("objects")) objects(*v, s);
    return s;
  }

 private:
  void image(const Val& v, Scene& s) {
    if (!expect_object(v)) return;
    const Fields f = fields(v, kImageKeys);
    if (const Val* w = f.find("width")) set(s.width, read_int(*w, 1, kMaxImageSide));
    if (const Val* h = f.find("height")) set(s.height, read_int(*h, 1, kMaxImageSide));
  }

  void indirect(const Val& v, Scene& s) {
    if (!expect_object(v)) return;
    const Fields f = fields(v, kIndirectKeys);
    if (const Val* b = f.find("bounces")) set(s.indirect_bounces, read_int(*b, 1, kMaxIndirectBounces));
  }

  void lights(const Val& v, Scene& s) {
    if (!expect_array(v)) return;
    const std::size_t count = element_count(v);
    for (std::size_t i = 0; i < count && !issues_.full(); ++i) {
      if (auto light = read_light(element(v, i))) s.lights.push_back(*light);
    }
  }

  void materials(const Val& v, Scene& s) {
    has_materials_ = true;
    if (!expect_object(v)) {
      materials_unusable_ = true;
      return;
    }
    for (auto& [name, m] : members(v)) {
      if (issues_.full()) break;
      material_index_.emplace(name, static_cast<int>(s.materials.size()));
      material_names_.push_back(name);
      Material mat;
      mat.name = name;
      read_material_fields(m, mat);
      s.materials.push_back(std::move(mat));
    }
  }

  // The index of the material an object names; one error per bad reference, none when the
  // "materials" section itself was broken (that error says it all).
  std::optional<int> material_ref(const Val& v) {
    const auto name = read_string(v);
    if (!name) return std::nullopt;
    if (!has_materials_) {
      // Every object would repeat this; once is enough.
      if (!reported_no_materials_) {
        report(v, "unknown material " + shown(v) + " (the scene has no \"materials\")");
        reported_no_materials_ = true;
      }
      return std::nullopt;
    }
    if (materials_unusable_) return std::nullopt;
    if (const auto it = material_index_.find(*name); it != material_index_.end()) return it->second;
    std::vector<std::string_view> names(material_names_.begin(), material_names_.end());
    report(v, "unknown material " + shown(v) + suggestion(*name, names, "defined materials"));
    return std::nullopt;
  }

  void objects(const Val& v, Scene& s) {
    if (!expect_array(v)) return;
    const std::size_t count = element_count(v);
    for (std::size_t i = 0; i < count && !issues_.full(); ++i) {
      const Val e = element(v, i);
      if (!expect_object(e)) continue;
      const auto type = type_of(e);
      if (!type) continue;
      const std::string& t = type->second;
      const int object = static_cast<int>(i);
      if (t == "sphere") {
        sphere(e, s, object);
      } else if (t == "plane") {
        plane(e, s, object);
      } else if (t == "triangle") {
        triangle(e, s, object);
      } else if (t == "mesh") {
        mesh(e, s, object);
      } else {
        report(type->first, "unknown object type " + shown(type->first) +
                                suggestion(t, kObjectTypes, "expected one of"));
      }
    }
  }

  // An object's optional "name": shown and edited by the previewer, kept on save.
  bool name(const Fields& f, Scene& s, int object) {
    const Val* x = f.find("name");
    if (x == nullptr) return true;
    const std::optional<std::string> text = read_string(*x);
    if (!text) return false;
    if (s.object_names.size() <= static_cast<std::size_t>(object)) s.object_names.resize(static_cast<std::size_t>(object) + 1);
    s.object_names[static_cast<std::size_t>(object)] = *text;
    return true;
  }

  void sphere(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kSphereKeys);
    if (!name(f, s, object)) return;
    bool ok = require(e, f, {"center", "radius", "material"});
    Sphere sp;
    if (const Val* x = f.find("center")) ok = assign(sp.center, read_vec3(*x)) && ok;
    if (const Val* x = f.find("radius")) ok = assign(sp.radius, read_positive(*x)) && ok;
    if (const Val* x = f.find("material")) ok = assign(sp.material, material_ref(*x)) && ok;
    if (!ok) return;
    s.spheres.push_back(sp);
    s.sphere_object.push_back(object);
  }

  void plane(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kPlaneKeys);
    if (!name(f, s, object)) return;
    bool ok = require(e, f, {"point", "normal", "material"});
    Plane pl;
    if (const Val* x = f.find("point")) ok = assign(pl.point, read_vec3(*x)) && ok;
    if (const Val* x = f.find("normal")) ok = assign(pl.normal, read_direction(*x)) && ok;
    if (const Val* x = f.find("material")) ok = assign(pl.material, material_ref(*x)) && ok;
    if (!ok) return;
    s.planes.push_back(pl);
    s.plane_object.push_back(object);
  }

  // Three vectors (`what` each: points or directions), as for "vertices" and "normals".
  std::optional<std::array<Vec3, 3>> read_three(const Val& v, bool directions) {
    if (!v.json->is_array() || v.json->size() != 3) {
      report(v, std::string("must be an array of 3 ") + (directions ? "directions" : "points") +
                    " (got " + shown(v) + ")");
      return std::nullopt;
    }
    std::array<Vec3, 3> out;
    bool ok = true;
    if (element_count(v) != 3) return std::nullopt;
    for (std::size_t i = 0; i < 3; ++i) {
      const Val e = element(v, i);
      ok = assign(out[i], directions ? read_direction(e) : read_vec3(e)) && ok;
    }
    return ok ? std::optional<std::array<Vec3, 3>>(out) : std::nullopt;
  }

  void triangle(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kTriangleKeys);
    if (!name(f, s, object)) return;
    bool ok = require(e, f, {"vertices", "material"});
    Triangle tri;
    if (const Val* x = f.find("vertices")) {
      if (const auto v = read_three(*x, false)) {
        tri.v0 = (*v)[0];
        tri.v1 = (*v)[1];
        tri.v2 = (*v)[2];
        if (!normalizable(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0))) {
          report(*x, "degenerate triangle: the vertices are collinear (got " + shown(*x) + ")");
          ok = false;
        }
      } else {
        ok = false;
      }
    }
    if (const Val* x = f.find("normals")) {
      if (const auto n = read_three(*x, true)) {
        tri.has_vertex_normals = true;
        tri.n0 = (*n)[0];
        tri.n1 = (*n)[1];
        tri.n2 = (*n)[2];
      } else {
        ok = false;
      }
    }
    if (const Val* x = f.find("material")) ok = assign(tri.material, material_ref(*x)) && ok;
    if (!ok) return;
    s.triangles.push_back(tri);
    s.triangle_object.push_back(object);
  }

  // A mesh transform: "scale" (a number or 3, none zero), "rotate_deg", "translate".
  bool transform(const Val& v, MeshTransform& out) {
    if (!expect_object(v)) return false;
    const Fields f = fields(v, kTransformKeys);
    bool ok = true;
    if (const Val* x = f.find("scale")) {
      std::optional<Vec3> scale;
      if (x->json->is_number()) {
        if (const auto k = read_number(*x)) scale = Vec3(*k);
      } else {
        scale = read_vec3(*x);
      }
      if (scale && (scale->x == 0 || scale->y == 0 || scale->z == 0)) {
        report(*x, "must not be zero (got " + shown(*x) + ")");
        scale.reset();
      }
      ok = assign(out.scale, scale) && ok;
    }
    if (const Val* x = f.find("rotate_deg")) ok = assign(out.rotate_deg, read_vec3(*x)) && ok;
    if (const Val* x = f.find("translate")) ok = assign(out.translate, read_vec3(*x)) && ok;
    return ok;
  }

  void mesh(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kMeshKeys);
    if (!name(f, s, object)) return;
    bool ok = require(e, f, {"file"});
    Mesh mesh;
    const Val* file = f.find("file");
    if (file) {
      if (auto name = read_string(*file)) {
        mesh.file = *name;
        if (mesh.file.empty()) {
          report(*file, "must name an OBJ file (got \"\")");
          ok = false;
        }
      } else {
        ok = false;
      }
    }
    int override_material = -1;
    if (const Val* x = f.find("material")) {
      const auto m = material_ref(*x);
      ok = m.has_value() && ok;
      if (m) {
        override_material = *m;
        mesh.material_override = s.materials[static_cast<std::size_t>(*m)].name;
      }
    }
    if (const Val* x = f.find("transform")) ok = transform(*x, mesh.transform) && ok;
    NsMapping ns = NsMapping::kAsIs;
    if (const Val* x = f.find("ns")) {
      const auto choice = read_choice(*x, kNsMappings, "Ns mapping");
      ok = choice.has_value() && ok;
      if (choice && *choice == "blinn_to_phong") ns = NsMapping::kBlinnToPhong;
    }
    if (!ok || file == nullptr) return;
    MeshLoad loaded = load_mesh(files_, mesh.file, mesh.transform, ns, override_material,
                                static_cast<int>(s.materials.size()), material_index_);
    for (const Diagnostic& w : loaded.warnings) warnings_.add({index_.begin(file->node), file->path, w.to_string()});
    if (!loaded.errors.empty()) {
      for (const Diagnostic& problem : loaded.errors) report(*file, problem.to_string());
      return;
    }
    mesh.geometry = std::move(loaded.geometry);
    mesh.ns = ns;
    mesh.resolved_path = files_.resolve(mesh.file);
    for (Material& m : loaded.materials) s.materials.push_back(std::move(m));
    s.meshes.push_back(std::move(mesh));
    s.mesh_object.push_back(object);
  }

  const SceneFiles& files_;
  Issues& warnings_;  // problems that do not stop the scene from loading (mesh files' quirks)
  bool has_materials_ = false;       // the scene has a "materials" member
  bool materials_unusable_ = false;  // ... but it is not an object
  bool reported_no_materials_ = false;
  std::unordered_map<std::string, int> material_index_;
  std::vector<std::string> material_names_;  // file order, for suggestions
};

}  // namespace

// Positions every issue (1-based line; column in characters, a UTF-8 BOM not counted) in one
// sweep over the text, in text order.
std::vector<Diagnostic> to_diagnostics(std::string_view t, std::vector<Issue> issues,
                                       bool truncated, const std::string& file) {
  std::stable_sort(issues.begin(), issues.end(),
                   [](const Issue& a, const Issue& b) { return a.offset < b.offset; });
  std::vector<Diagnostic> out;
  std::size_t pos = has_bom(t) ? 3 : 0;
  int line = 1, column = 1;
  for (Issue& issue : issues) {
    Diagnostic d;
    d.file = file;
    d.path = std::move(issue.path);
    d.message = std::move(issue.message);
    if (issue.offset != kNoOffset) {
      const std::size_t target = std::min(issue.offset, t.size());
      for (; pos < target; ++pos) {
        if (t[pos] == '\n') {
          ++line;
          column = 1;
        } else if ((static_cast<unsigned char>(t[pos]) & 0xC0) != 0x80) {
          ++column;
        }
      }
      d.line = line;
      d.column = column;
    }
    out.push_back(std::move(d));
  }
  if (truncated) {
    Diagnostic d;
    d.file = file;
    d.message = "too many errors; stopped after the first " + std::to_string(kMaxIssues);
    out.push_back(std::move(d));
  }
  return out;
}

LoadResult fail(const std::string& file, std::string message) {
  LoadResult r;
  Diagnostic d;
  d.file = file;
  d.message = std::move(message);
  r.errors.push_back(std::move(d));
  return r;
}

LoadResult load_text(const std::string& text, const std::string& file_name, const SceneFiles& files) {
  Issues issues, warnings;
  const auto finish = [&](std::optional<Scene> scene) {
    LoadResult r;
    const bool truncated = issues.full();
    r.errors = to_diagnostics(text, std::move(issues.list()), truncated, file_name);
    r.warnings = to_diagnostics(text, std::move(warnings.list()), false, file_name);
    set_severity(r.warnings, Diagnostic::Severity::kWarning);
    if (r.errors.empty()) r.scene = std::move(scene);
    return r;
  };

  ParsedText parsed;
  if (!parse_text(text, "a scene file", issues, parsed)) return finish(std::nullopt);
  Validator validator(text, *parsed.index, parsed.root, parsed.overflows, issues, files, warnings);
  Scene scene = validator.run();
  return finish(std::move(scene));
}

}  // namespace phonglab::scene_load
