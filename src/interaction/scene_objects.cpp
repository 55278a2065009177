#include "interaction/scene_objects.h"

#include <array>
#include <cmath>
#include <sstream>

namespace phonglab::ui {

namespace {

using Kind = ObjectRef::Kind;

constexpr std::array<std::string_view, 4> kKindNames = {"sphere", "plane", "triangle", "mesh"};

// Each kind's file indices, by kind.
constexpr std::array<std::vector<int> Scene::*, 4> kIndices = {&Scene::sphere_object, &Scene::plane_object,
                                                               &Scene::triangle_object, &Scene::mesh_object};
std::vector<int>& indices_of(Scene& s, Kind kind) { return s.*kIndices[static_cast<std::size_t>(kind)]; }
const std::vector<int>& indices_of(const Scene& s, Kind kind) { return s.*kIndices[static_cast<std::size_t>(kind)]; }

// The Scene's file indices, filled in where a scene built in code left them out (in vector order
// after the indexed ones, as the writer orders them).
void complete_indices(Scene& s) {
  const std::array<std::pair<std::vector<int>*, std::size_t>, 4> all = {
      std::pair{&s.sphere_object, s.spheres.size()}, std::pair{&s.plane_object, s.planes.size()},
      std::pair{&s.triangle_object, s.triangles.size()}, std::pair{&s.mesh_object, s.meshes.size()}};
  int next = 0;
  for (const auto& [v, n] : all) {
    for (const int i : *v) next = std::max(next, i + 1);
  }
  for (const auto& [v, n] : all) {
    while (v->size() < n) v->push_back(next++);
  }
}

std::string object_name(int object) { return "objects[" + std::to_string(object) + "]"; }

std::string no_such_object(const Scene& s, int object) {
  const int n = object_count(s);
  if (n == 0) return "the scene has no objects";
  return "no " + object_name(object) + " (the scene has " + std::to_string(n) + (n == 1 ? " object" : " objects") +
         ", 0.." + std::to_string(n - 1) + ")";
}

bool finite(const Vec3& v) { return all_finite(v) && max_abs(v) <= 1e100; }

// After removing file index `gone`, every later index moves down by one.
void close_gap(Scene& s, int gone) {
  for (std::vector<int>* v : {&s.sphere_object, &s.plane_object, &s.triangle_object, &s.mesh_object}) {
    for (int& i : *v) {
      if (i > gone) --i;
    }
  }
}

template <class T>
void erase_at(std::vector<T>& v, int i) {
  v.erase(v.begin() + i);
}

bool collinear(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = glm::cross(b - a, c - a);
  return !(glm::dot(n, n) > 0) || !all_finite(n);
}

Vec3 vec(const std::vector<double>& v) { return Vec3(v[0], v[1], v[2]); }

std::size_t i_file(int object) { return static_cast<std::size_t>(object); }

std::string shown(double v) {
  std::ostringstream text;
  text << v;
  return text.str();
}

}  // namespace

int object_count(const Scene& s) {
  return static_cast<int>(s.spheres.size() + s.planes.size() + s.triangles.size() + s.meshes.size());
}

ObjectRef object_at(const Scene& s, int object) {
  for (const Kind kind : {Kind::kSphere, Kind::kPlane, Kind::kTriangle, Kind::kMesh}) {
    const std::vector<int>& v = indices_of(s, kind);
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (v[i] == object) return ObjectRef{kind, static_cast<int>(i), -1};
    }
  }
  return ObjectRef{};
}

void complete_object_indices(Scene& s) { complete_indices(s); }

int file_object_of(const Scene& s, const ObjectRef& ref) {
  if (ref.kind == Kind::kNone) return -1;
  const std::vector<int>& v = indices_of(s, ref.kind);
  return ref.index >= 0 && static_cast<std::size_t>(ref.index) < v.size() ? v[static_cast<std::size_t>(ref.index)] : -1;
}

std::string_view kind_name(Kind kind) {
  const auto k = static_cast<std::size_t>(kind);
  return k < kKindNames.size() ? kKindNames[k] : std::string_view("nothing");
}

Kind kind_from_name(std::string_view name) {
  for (std::size_t k = 0; k < kKindNames.size(); ++k) {
    if (kKindNames[k] == name) return static_cast<Kind>(k);
  }
  return Kind::kNone;
}

int object_material(const Scene& s, int object) {
  const ObjectRef r = object_at(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  switch (r.kind) {
    case Kind::kSphere: return s.spheres[i].material;
    case Kind::kPlane: return s.planes[i].material;
    case Kind::kTriangle: return s.triangles[i].material;
    case Kind::kMesh: return find_material(s, s.meshes[i].material_override);
    default: return -1;
  }
}

Vec3 object_anchor(const Scene& s, int object) {
  const ObjectRef r = object_at(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  switch (r.kind) {
    case Kind::kSphere: return s.spheres[i].center;
    case Kind::kPlane: return s.planes[i].point;
    case Kind::kTriangle: return (s.triangles[i].v0 + s.triangles[i].v1 + s.triangles[i].v2) / 3.0;
    case Kind::kMesh: return s.meshes[i].transform.translate;
    default: return Vec3(0);
  }
}

std::string object_name_of(const Scene& s, int object) {
  const auto i = static_cast<std::size_t>(object);
  return object >= 0 && i < s.object_names.size() ? s.object_names[i] : std::string();
}

std::string object_label(const Scene& s, int object) {
  const ObjectRef r = object_at(s, object);
  if (r.kind == Kind::kNone) return object_name(object);
  const std::string name = object_name_of(s, object);
  std::string label = object_name(object) + (name.empty() ? "" : " \"" + name + "\"") + ": " + std::string(kind_name(r.kind));
  const int m = object_material(s, object);
  if (m >= 0 && m < static_cast<int>(s.materials.size())) label += ", " + s.materials[static_cast<std::size_t>(m)].name;
  if (r.kind == Kind::kMesh) label += " (" + s.meshes[static_cast<std::size_t>(r.index)].file + ")";
  return label;
}

Placement placement_in_front_of(const Camera& c) {
  Placement p;
  p.at = c.look_at;
  const Vec3 view = c.look_at - c.position;
  const double distance = glm::length(view);
  p.size = distance > 0 && std::isfinite(distance) ? distance / 10 : 1;
  const Vec3 forward = distance > 0 ? view / distance : Vec3(0, 0, -1);
  Vec3 right = glm::cross(forward, c.up);
  right = glm::length(right) > 0 ? glm::normalize(right) : Vec3(1, 0, 0);
  p.right = right;
  p.up = glm::cross(right, forward);
  p.towards_eye = -forward;
  return p;
}

int add_primitive(Scene& s, Kind kind, const Placement& where, int material) {
  complete_indices(s);
  const int object = object_count(s);
  const double r = where.size;
  switch (kind) {
    case Kind::kSphere:
      s.spheres.push_back(Sphere{where.at, r, material});
      s.sphere_object.push_back(object);
      break;
    case Kind::kPlane:
      // Through the look-at point, facing up as the camera sees it (a floor or a table).
      s.planes.push_back(Plane{where.at, where.up, material});
      s.plane_object.push_back(object);
      break;
    case Kind::kTriangle: {
      // Facing the eye, counter-clockwise as the camera sees it (Ng towards the eye).
      Triangle t;
      t.v0 = where.at + r * (-where.right - 0.6 * where.up);
      t.v1 = where.at + r * (where.right - 0.6 * where.up);
      t.v2 = where.at + r * (1.2 * where.up);
      t.material = material;
      s.triangles.push_back(t);
      s.triangle_object.push_back(object);
      break;
    }
    default:
      return -1;
  }
  return object;
}

int append_mesh_object(Scene& s, Mesh mesh) {
  complete_indices(s);
  const int object = object_count(s);
  s.meshes.push_back(std::move(mesh));
  s.mesh_object.push_back(object);
  return object;
}

std::string delete_object(Scene& s, int object) {
  complete_indices(s);
  const ObjectRef r = object_at(s, object);
  if (r.kind == Kind::kNone) return no_such_object(s, object);
  switch (r.kind) {
    case Kind::kSphere: erase_at(s.spheres, r.index); break;
    case Kind::kPlane: erase_at(s.planes, r.index); break;
    case Kind::kTriangle: erase_at(s.triangles, r.index); break;
    default: erase_at(s.meshes, r.index); break;
  }
  erase_at(indices_of(s, r.kind), r.index);
  close_gap(s, object);
  if (static_cast<std::size_t>(object) < s.object_names.size()) erase_at(s.object_names, object);
  return {};
}

std::string duplicate_object(Scene& s, int object, int& copy) {
  complete_indices(s);
  const ObjectRef r = object_at(s, object);
  if (r.kind == Kind::kNone) return no_such_object(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  copy = object_count(s);
  switch (r.kind) {
    case Kind::kSphere: s.spheres.push_back(s.spheres[i]); break;
    case Kind::kPlane: s.planes.push_back(s.planes[i]); break;
    case Kind::kTriangle: s.triangles.push_back(s.triangles[i]); break;
    default: s.meshes.push_back(s.meshes[i]); break;  // shares the geometry: it stands in the same place
  }
  indices_of(s, r.kind).push_back(copy);
  const std::string name = object_name_of(s, object);
  if (!name.empty()) {
    s.object_names.resize(static_cast<std::size_t>(copy) + 1);
    s.object_names[static_cast<std::size_t>(copy)] = name + " copy";
  }
  return {};
}

std::string move_object(Scene& s, int object, const Vec3& delta) {
  const ObjectRef r = object_at(s, object);
  if (r.kind == Kind::kNone) return no_such_object(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  const Vec3 anchor = object_anchor(s, object) + delta;
  if (!finite(anchor)) return object_name(object) + " would leave the range of numbers a scene may hold";
  switch (r.kind) {
    case Kind::kSphere: s.spheres[i].center += delta; break;
    case Kind::kPlane: s.planes[i].point += delta; break;
    case Kind::kTriangle:
      s.triangles[i].v0 += delta;
      s.triangles[i].v1 += delta;
      s.triangles[i].v2 += delta;
      break;
    default: s.meshes[i].transform.translate += delta; break;
  }
  return {};
}

bool moves_mesh_geometry(const std::string& field) {
  return field == "translate" || field == "rotate_deg" || field == "scale";
}

std::string set_object_field(Scene& s, int object, const std::string& field, const std::vector<double>& values,
                             const std::string& text) {
  const ObjectRef r = object_at(s, object);
  if (r.kind == Kind::kNone) return no_such_object(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  const std::string what = object_name(object) + " is a " + std::string(kind_name(r.kind));
  if (field == "name") {
    if (s.object_names.size() <= i_file(object)) s.object_names.resize(i_file(object) + 1);
    s.object_names[i_file(object)] = text;
    while (!s.object_names.empty() && s.object_names.back().empty()) s.object_names.pop_back();
    return {};
  }
  if (field == "material") {
    const int m = find_material(s, text);
    if (m < 0) return "no material named '" + text + "'";
    switch (r.kind) {
      case Kind::kSphere: s.spheres[i].material = m; break;
      case Kind::kPlane: s.planes[i].material = m; break;
      case Kind::kTriangle: s.triangles[i].material = m; break;
      default: s.meshes[i].material_override = text; break;  // its geometry must be loaded again
    }
    return {};
  }
  const bool one = field == "radius" || (field == "scale" && values.size() == 1);
  if (values.size() != (one ? 1u : 3u)) return field + " takes " + (one ? "one number" : "three numbers");
  for (const double v : values) {
    if (!std::isfinite(v) || std::abs(v) > 1e100) return field + ": every number must be finite and at most 1e100";
  }
  const Vec3 v = one ? Vec3(values[0]) : vec(values);
  const auto not_here = [&] { return what + ": it has no " + field; };
  if (field == "center" || field == "radius") {
    if (r.kind != Kind::kSphere) return not_here();
    if (field == "radius" && !(values[0] > 0)) return "radius must be > 0 (got " + shown(values[0]) + ")";
    if (field == "radius") s.spheres[i].radius = values[0];
    else s.spheres[i].center = v;
    return {};
  }
  if (field == "point" || field == "normal") {
    if (r.kind != Kind::kPlane) return not_here();
    if (field == "normal" && !(glm::dot(v, v) > 0)) return "normal must not be zero";
    (field == "point" ? s.planes[i].point : s.planes[i].normal) = v;
    return {};
  }
  if (field == "v0" || field == "v1" || field == "v2") {
    if (r.kind != Kind::kTriangle) return not_here();
    Triangle t = s.triangles[i];
    (field == "v0" ? t.v0 : field == "v1" ? t.v1 : t.v2) = v;
    if (collinear(t.v0, t.v1, t.v2)) return "degenerate triangle: the corners would lie on one line (kept as it was)";
    s.triangles[i] = t;
    return {};
  }
  if (moves_mesh_geometry(field)) {
    if (r.kind != Kind::kMesh) return not_here();
    MeshTransform& t = s.meshes[i].transform;
    if (field == "scale" && (v.x == 0 || v.y == 0 || v.z == 0)) return "scale must not be zero on any axis";
    (field == "translate" ? t.translate : field == "rotate_deg" ? t.rotate_deg : t.scale) = v;
    return {};
  }
  return "unknown field '" + field + "' (center, radius, point, normal, v0, v1, v2, translate, rotate_deg, scale, material, name)";
}

int find_material(const Scene& s, const std::string& name) {
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    if (s.materials[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

std::string unused_material_name(const Scene& s, const std::string& base) {
  if (find_material(s, base) < 0) return base;
  for (int k = 2;; ++k) {
    const std::string name = base + " " + std::to_string(k);
    if (find_material(s, name) < 0) return name;
  }
}

std::string new_material(Scene& s, const std::string& name, int& index) {
  if (name.empty()) return "a material needs a name";
  if (find_material(s, name) >= 0) return "a material named '" + name + "' exists already";
  Material m;
  m.name = name;
  m.ka = Color(0.05);
  m.kd = Color(0.6);
  m.ks = Color(0.3);
  m.n = 32;
  index = static_cast<int>(s.materials.size());
  s.materials.push_back(m);
  return {};
}

std::string duplicate_material(Scene& s, int material, int& copy) {
  if (material < 0 || material >= static_cast<int>(s.materials.size())) return "no such material";
  Material m = s.materials[static_cast<std::size_t>(material)];
  m.name = unused_material_name(s, m.name + " copy");
  m.source.clear();  // the copy is the scene file's own
  copy = static_cast<int>(s.materials.size());
  s.materials.push_back(std::move(m));
  return {};
}

std::string rename_material(Scene& s, int material, const std::string& name) {
  if (material < 0 || material >= static_cast<int>(s.materials.size())) return "no such material";
  Material& m = s.materials[static_cast<std::size_t>(material)];
  if (!m.source.empty()) return "'" + m.name + "' comes from " + m.source + "'s MTL file: rename it there";
  if (name.empty()) return "a material needs a name";
  if (name == m.name) return {};
  if (find_material(s, name) >= 0) return "a material named '" + name + "' exists already";
  for (Mesh& mesh : s.meshes) {
    if (mesh.material_override == m.name) mesh.material_override = name;
  }
  m.name = name;
  return {};
}

bool uses_material(const Scene& s, int object, int material) {
  const ObjectRef r = object_at(s, object);
  if (r.kind != Kind::kMesh) return r.kind != Kind::kNone && object_material(s, object) == material;
  const Mesh& mesh = s.meshes[static_cast<std::size_t>(r.index)];
  const Material& m = s.materials[static_cast<std::size_t>(material)];
  return mesh.material_override.empty() ? !m.source.empty() && m.source == mesh.file : mesh.material_override == m.name;
}

int material_users(const Scene& s, int material) {
  int users = 0;
  for (int object = 0; object < object_count(s); ++object) users += uses_material(s, object, material);
  return users;
}

std::string delete_material(Scene& s, int material) {
  if (material < 0 || material >= static_cast<int>(s.materials.size())) return "no such material";
  for (int object = 0; object < object_count(s); ++object) {
    if (uses_material(s, object, material)) {
      return "'" + s.materials[static_cast<std::size_t>(material)].name + "' is in use by " + object_label(s, object) +
             ": give that object another material first";
    }
  }
  s.materials.erase(s.materials.begin() + material);
  const auto renumber = [&](int& m) {
    if (m > material) --m;
  };
  for (Sphere& x : s.spheres) renumber(x.material);
  for (Plane& x : s.planes) renumber(x.material);
  for (Triangle& x : s.triangles) renumber(x.material);
  // A mesh's triangles carry their MTL materials' indices: the caller loads meshes again.
  return {};
}

}  // namespace phonglab::ui
