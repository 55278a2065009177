// Files a scene names: reading a text file with a size limit, and loading a mesh object's OBJ
// (and MTL) from disk or from the embedded files, placed by its transform.
#include "io/scene/scene_load.h"

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

namespace phonglab::scene_load {

std::string os_reason(int err) { return std::generic_category().message(err); }

// A whole file as text, or nullopt and the reason; files over `limit` bytes are refused
// (reading /dev/zero must not hang or exhaust memory).
std::optional<std::string> read_text_file(const std::string& path, std::size_t limit, std::string& error) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    error = "cannot read file: " + os_reason(errno);
    return std::nullopt;
  }
  std::string text;
  // Room for the whole file up front (when its size is known and within the limit): a 55 MB
  // mesh grown by doubling is copied about twice over, and each copy touches fresh pages.
  std::error_code size_ec;
  const std::uintmax_t size = std::filesystem::file_size(path, size_ec);
  if (!size_ec && size <= limit) text.reserve(static_cast<std::size_t>(size) + 1);
  std::array<char, 1 << 16> buffer;
  bool too_large = false;
  int read_error = 0;
  for (;;) {
    const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), f);
    text.append(buffer.data(), got);
    if (text.size() > limit) {
      too_large = true;
      break;
    }
    if (got < buffer.size()) {
      if (std::ferror(f)) read_error = errno != 0 ? errno : EIO;
      break;
    }
  }
  std::fclose(f);
  if (read_error != 0) {
    error = "cannot read file: " + os_reason(read_error);
    return std::nullopt;
  }
  if (too_large) {
    error = "cannot read file: larger than " + std::to_string(limit >> 20) + " MiB";
    return std::nullopt;
  }
  return text;
}


// The rotation of a mesh transform: about x, then y, then z (degrees, right-handed).
glm::dmat3 rotation_of(const MeshTransform& t) {
  const Vec3 r = glm::radians(t.rotate_deg);
  const double cx = std::cos(r.x), sx = std::sin(r.x);
  const double cy = std::cos(r.y), sy = std::sin(r.y);
  const double cz = std::cos(r.z), sz = std::sin(r.z);
  const glm::dmat3 rx(1, 0, 0, 0, cx, sx, 0, -sx, cx);  // glm is column-major
  const glm::dmat3 ry(cy, 0, -sy, 0, 1, 0, sy, 0, cy);
  const glm::dmat3 rz(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
  return rz * ry * rx;
}


// Reads an OBJ (and its MTL) and places it in the world. MTL materials get indices from
// `material_base` on, except those the scene file defines itself under the MTL material's name
// ("stem/name": an MTL material edited and saved), whose faces use the scene's; with
// `override_material` >= 0 every face uses that instead.
MeshLoad load_mesh(const SceneFiles& files, const std::string& file, const MeshTransform& transform,
                   NsMapping ns, int override_material, int material_base,
                   const std::unordered_map<std::string, int>& defined) {
  MeshLoad out;
  std::string error;
  const std::optional<std::string> text = files.read(file, error);
  if (!text) {
    out.errors.push_back(line_diagnostic("", 0, "cannot load mesh '" + file + "': " + error));
    return out;
  }
  const std::string obj_dir = std::filesystem::path(file).parent_path().generic_string();
  const FileReader read_mtl = [&](const std::string& mtl, std::string& err) {
    return files.read(obj_dir.empty() ? mtl : obj_dir + "/" + mtl, err);
  };
  // The room for the mesh's Triangles is allocated and first touched (0.15 s for 1.3M of them)
  // on the prescan's thread, which finishes well before tinyobjloader's parse on this one.
  std::vector<Triangle> room;
  ObjIndexedMesh obj = load_obj_indexed(*text, file, read_mtl, ns, [&](std::size_t n) { room.resize(n); });
  out.warnings = std::move(obj.warnings);
  out.errors = std::move(obj.errors);
  if (!out.errors.empty()) return out;
  if (obj.triangles.empty()) {
    out.errors.push_back(line_diagnostic(file, 0, "no faces (a mesh needs at least one triangle of non-zero area)"));
    return out;
  }
  const std::string stem = std::filesystem::path(file).stem().string();
  std::vector<int> slot(obj.materials.size(), override_material);  // each MTL material's index in the scene
  if (override_material < 0) {
    int next = material_base;
    for (std::size_t j = 0; j < obj.materials.size(); ++j) {
      Material& m = obj.materials[j];
      m.name = stem + "/" + m.name;
      if (const auto own = defined.find(m.name); own != defined.end()) {
        slot[j] = own->second;  // the scene file's own version of it
        continue;
      }
      slot[j] = next++;
      m.source = file;
      out.materials.push_back(std::move(m));
    }
  }
  const glm::dmat3 rotation = rotation_of(transform);
  const glm::dmat3 linear = rotation * glm::dmat3(glm::scale(glm::dmat4(1), transform.scale));
  const glm::dmat3 normal_matrix = rotation * glm::dmat3(glm::scale(glm::dmat4(1), 1.0 / transform.scale));
  const auto place = [&](const Vec3& p) { return linear * p + transform.translate; };
  // Each vertex and normal is placed once (the same arithmetic as placing every triangle's
  // corners, a vertex being shared by six triangles or so), and the triangles stay indices until
  // make_mesh_geometry makes each once, in its leaf slot: a 1.3M-triangle mesh is 200 MB of
  // Triangles, made and copied three times over before.
  for (Vec3& v : obj.vertices) v = place(v);
  for (Vec3& n : obj.normals) n = normal_matrix * n;
  std::vector<ObjIndexedTriangle>& placed = obj.triangles;
  std::size_t kept = 0;
  // A mirroring transform (an odd number of negative scales) reverses the winding: swapping two
  // vertices keeps Ng on the side the OBJ's winding put it (outward for a closed mesh).
  const bool mirrored = glm::determinant(linear) < 0;
  int degenerate = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const ObjIndexedTriangle t = placed[i];
    const Vec3& v0 = obj.vertices[t.v[0]];
    const Vec3& v1 = obj.vertices[t.v[1]];
    const Vec3& v2 = obj.vertices[t.v[2]];
    if (!all_finite(v0) || !all_finite(v1) || !all_finite(v2)) {
      out.errors.push_back(line_diagnostic(
          file, 0, "the transform takes face " + std::to_string(t.face + 1) + " beyond the range of doubles"));
      return out;
    }
    const Vec3 cross = glm::cross(v1 - v0, v2 - v0);
    if (!(glm::dot(cross, cross) > 0)) {
      ++degenerate;
      continue;
    }
    placed[kept++] = t;
  }
  placed.resize(kept);
  if (degenerate > 0) {
    out.warnings.push_back(line_diagnostic(
        file, 0, counted(static_cast<std::size_t>(degenerate), "triangle") + (degenerate == 1 ? " has" : " have") +
                  " zero area after the transform; left out", Diagnostic::Severity::kWarning));
  }
  if (placed.empty()) {
    out.errors.push_back(line_diagnostic(file, 0, "no triangle of non-zero area after the transform"));
    return out;
  }
  for (Emitter e : obj.emitters) {
    e.centroid = place(e.centroid);
    std::ostringstream hint;
    hint << "material '" << e.material << "' emits light (Ke " << e.ke.x << " " << e.ke.y << " "
         << e.ke.z << ") from " << e.faces << " face(s); phonglab has point lights only: place one near ["
         << e.centroid.x << ", " << e.centroid.y << ", " << e.centroid.z << "], their centre";
    out.warnings.push_back(line_diagnostic(file, 0, hint.str(), Diagnostic::Severity::kWarning));
    out.emitters.push_back(e);
  }
  std::vector<int> faces(placed.size());
  for (std::size_t i = 0; i < placed.size(); ++i) faces[i] = placed[i].face;
  const auto make = [&](std::size_t i) {
    Triangle t = obj.triangle(i);
    if (mirrored) {
      std::swap(t.v1, t.v2);
      std::swap(t.n1, t.n2);
    }
    t.material = slot[static_cast<std::size_t>(t.material)];
    return t;
  };
  // triangle_bounds(make(i)) without making the Triangle: its corners grown in the same order.
  const auto box_of = [&](std::size_t i) {
    const ObjIndexedTriangle& t = placed[i];
    Aabb b;
    b.grow(obj.vertices[t.v[0]]);
    b.grow(obj.vertices[t.v[mirrored ? 2 : 1]]);
    b.grow(obj.vertices[t.v[mirrored ? 1 : 2]]);
    return b;
  };
  out.geometry = make_mesh_geometry(placed.size(), make, std::move(faces), std::move(room), box_of);
  return out;
}

}  // namespace phonglab::scene_load
