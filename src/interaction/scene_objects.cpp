#include "interaction/scene_objects.h"

#include <algorithm>
#include <filesystem>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/accel/accel.h"
#include "interaction/camera_control.h"
#include "interaction/numbers.h"

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

namespace {

// The finite objects' indices (spheres, triangles, meshes), objects[except] left out.
std::vector<int> finite_objects(const Scene& s, int except) {
  std::vector<int> all;
  for (int object = 0; object < object_count(s); ++object) {
    const Kind kind = object_at(s, object).kind;
    if (object != except && kind != Kind::kPlane && kind != Kind::kNone) all.push_back(object);
  }
  return all;
}

// A finite object's axis-aligned bounds (a plane's are empty).
Aabb object_bounds(const Scene& s, int object) {
  const ObjectRef r = object_at(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  Aabb box;
  switch (r.kind) {
    case Kind::kSphere:
      box.grow(s.spheres[i].center - Vec3(s.spheres[i].radius));
      box.grow(s.spheres[i].center + Vec3(s.spheres[i].radius));
      break;
    case Kind::kTriangle:
      for (const Vec3& v : {s.triangles[i].v0, s.triangles[i].v1, s.triangles[i].v2}) box.grow(v);
      break;
    case Kind::kMesh:
      if (s.meshes[i].geometry) box = s.meshes[i].geometry->bounds;
      else box.grow(s.meshes[i].transform.translate);
      break;
    default: break;
  }
  return box;
}

Vec3 unit_or(const Vec3& v, const Vec3& otherwise) {
  const double length = glm::length(v);
  return length > 1e-12 && std::isfinite(length) ? v / length : otherwise;
}

}  // namespace

std::optional<Floor> find_floor(const Scene& s, const Camera& camera, int except) {
  const Vec3 up = unit_or(camera.up, Vec3(0, 1, 0));
  const std::vector<int> objects = finite_objects(s, except);
  std::vector<Vec3> anchors;
  for (const int object : objects) anchors.push_back(object_anchor(s, object));
  if (anchors.empty()) anchors.push_back(camera.look_at);
  std::optional<Floor> best;
  double best_depth = std::numeric_limits<double>::infinity();  // how far below the look-at point
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    if (static_cast<int>(i) < static_cast<int>(s.plane_object.size()) && s.plane_object[i] == except) continue;
    Floor f;
    f.point = s.planes[i].point;
    f.normal = unit_or(s.planes[i].normal, Vec3(0));
    if (glm::dot(f.normal, up) < 0) f.normal = -f.normal;
    if (!(glm::dot(f.normal, up) >= std::cos(glm::radians(30.0)))) continue;
    const bool below_all = std::all_of(anchors.begin(), anchors.end(), [&](const Vec3& a) {
      return height_above(f, a) >= -1e-9 * std::max(1.0, max_abs(a - f.point));
    });
    if (!below_all) continue;
    const double depth = height_above(f, camera.look_at);
    if (depth < best_depth) {
      best_depth = depth;
      f.object = i < s.plane_object.size() ? s.plane_object[i] : -1;
      best = f;
    }
  }
  return best;
}

double height_above(const Floor& f, const Vec3& p) { return glm::dot(p - f.point, f.normal); }

double floor_clearance(const Scene& s, int object) {
  if (object_at(s, object).kind != Kind::kMesh) return 0;
  const Aabb box = object_bounds(s, object);
  if (box.empty()) return 0;
  const Vec3 sides = box.hi - box.lo;
  return kMeshClearance * std::max({sides.x, sides.y, sides.z});
}

double lowest_above(const Scene& s, int object, const Floor& f) {
  const ObjectRef r = object_at(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  switch (r.kind) {
    case Kind::kSphere: return height_above(f, s.spheres[i].center) - s.spheres[i].radius;
    case Kind::kTriangle:
      return std::min({height_above(f, s.triangles[i].v0), height_above(f, s.triangles[i].v1),
                       height_above(f, s.triangles[i].v2)});
    case Kind::kMesh: {
      const Mesh& m = s.meshes[i];
      if (!m.geometry || m.geometry->triangles.empty()) return height_above(f, m.transform.translate);
      double low = std::numeric_limits<double>::infinity();
      for (const Triangle& t : m.geometry->triangles) {
        low = std::min({low, height_above(f, t.v0), height_above(f, t.v1), height_above(f, t.v2)});
      }
      return low;
    }
    default: return -std::numeric_limits<double>::infinity();
  }
}

double typical_size(const Scene& s, const Camera& camera, int except) {
  std::vector<double> diameters;
  Aabb bounds;
  for (const int object : finite_objects(s, except)) {
    const ObjectRef r = object_at(s, object);
    if (r.kind == Kind::kSphere) diameters.push_back(2 * s.spheres[static_cast<std::size_t>(r.index)].radius);
    bounds.grow(object_bounds(s, object));
  }
  double size = 0;
  if (!diameters.empty()) {
    std::sort(diameters.begin(), diameters.end());
    const std::size_t n = diameters.size();
    size = n % 2 == 1 ? diameters[n / 2] : 0.5 * (diameters[n / 2 - 1] + diameters[n / 2]);
  } else if (!bounds.empty()) {
    const Vec3 sides = bounds.hi - bounds.lo;
    size = std::max({sides.x, sides.y, sides.z}) / 4;
  }
  if (!(size > 0) || !std::isfinite(size) || size > 1e100) {
    const double distance = glm::length(camera.look_at - camera.position);
    size = distance > 0 && std::isfinite(distance) ? distance / 5 : 1;
  }
  return significant(size, 2);
}

namespace {

// Where a placed object would be seen: inside the view (a margin of 2 % of the image), and not
// hidden by a nearer object (its middle inside the rectangle that object's bounds cover on screen).
class ViewChecks {
 public:
  ViewChecks(const Scene& s, const Camera& camera, double aspect, int object) : camera_(camera) {
    const double framed = s.width > 0 && s.height > 0 ? static_cast<double>(s.width) / s.height : 1;
    w_ = std::max(1, static_cast<int>(std::lround(1000 * (aspect > 0 && std::isfinite(aspect) ? aspect : framed))));
    for (const int other : finite_objects(s, object)) seen_.push_back(on_screen(object_bounds(s, other), object_anchor(s, other)));
  }
  bool in_view(const Aabb& box) const {
    for (int corner = 0; corner < 8; ++corner) {
      const std::optional<ViewportPoint> at = project(camera_, corner_of(box, corner), w_, h_);
      if (!at || at->x < 0.02 * w_ || at->x > 0.98 * w_ || at->y < 0.02 * h_ || at->y > 0.98 * h_) return false;
    }
    return true;
  }
  bool hidden(const Aabb& box) const {
    const OnScreen me = on_screen(box, box.centroid());
    return std::any_of(seen_.begin(), seen_.end(), [&](const OnScreen& o) { return o.depth < me.depth && o.covers(me.anchor); });
  }

 private:
  struct OnScreen {
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, depth = 0;
    std::optional<ViewportPoint> anchor;
    bool covers(const std::optional<ViewportPoint>& p) const { return p && p->x > x0 && p->x < x1 && p->y > y0 && p->y < y1; }
  };
  static Vec3 corner_of(const Aabb& box, int corner) {
    return Vec3(corner & 1 ? box.hi.x : box.lo.x, corner & 2 ? box.hi.y : box.lo.y, corner & 4 ? box.hi.z : box.lo.z);
  }
  OnScreen on_screen(const Aabb& box, const Vec3& anchor) const {
    OnScreen o;
    for (int corner = 0; corner < 8; ++corner) {
      if (const std::optional<ViewportPoint> at = project(camera_, corner_of(box, corner), w_, h_)) {
        o.x0 = std::min(o.x0, at->x), o.x1 = std::max(o.x1, at->x), o.y0 = std::min(o.y0, at->y), o.y1 = std::max(o.y1, at->y);
      }
    }
    o.depth = view_depth(camera_, anchor);
    o.anchor = project(camera_, anchor, w_, h_);
    return o;
  }

  const Camera& camera_;
  int w_ = 1;
  int h_ = 1000;
  std::vector<OnScreen> seen_;
};

// A mesh scaled to `size` (its largest side, to three significant digits): the factor, its
// middle, half sides and largest half side, and how far above a floor of normal `n` (when there is
// one) its middle stands for its lowest point to clear the floor.
struct MeshFit {
  double k = 1;
  Vec3 middle{0};
  Vec3 half{0};
  double radius = 0;
  double lift = 0;
};
MeshFit fit_mesh(const MeshGeometry& g, double size, const Vec3* n) {
  MeshFit fit;
  const Vec3 sides = g.bounds.hi - g.bounds.lo;
  const double largest = std::max({sides.x, sides.y, sides.z});
  fit.k = significant(largest > 0 && std::isfinite(largest) ? size / largest : 1, 3);
  fit.middle = g.bounds.centroid();
  fit.half = 0.5 * fit.k * sides;
  fit.radius = std::max({fit.half.x, fit.half.y, fit.half.z});
  fit.lift = fit.radius;
  if (n != nullptr) {
    double low = std::numeric_limits<double>::infinity();
    for (const Triangle& t : g.triangles) {
      for (const Vec3& v : {t.v0, t.v1, t.v2}) low = std::min(low, glm::dot(v - fit.middle, *n));
    }
    fit.lift = std::isfinite(low) ? -fit.k * low + kMeshClearance * 2 * fit.radius : 0;  // floor_clearance
  }
  return fit;
}

// The search grid's points, nearest first: the right before the left, the nearer row before the
// further.
std::vector<std::pair<int, int>> search_grid() {
  constexpr int kReach = 60;
  std::vector<std::pair<int, int>> grid;
  for (int j = -kReach; j <= kReach; ++j) {
    for (int i = -kReach; i <= kReach; ++i) grid.emplace_back(i, j);
  }
  std::stable_sort(grid.begin(), grid.end(), [](const auto& a, const auto& b) {
    const int da = a.first * a.first + a.second * a.second, db = b.first * b.first + b.second * b.second;
    if (da != db) return da < db;
    if (std::abs(a.second) != std::abs(b.second)) return std::abs(a.second) < std::abs(b.second);
    if (a.first != b.first) return a.first > b.first;
    return a.second > b.second;
  });
  return grid;
}

}  // namespace

std::string place_new_object(Scene& s, const Camera& camera, double aspect, int object) {
  complete_indices(s);
  const ObjectRef r = object_at(s, object);
  if (r.kind == Kind::kNone) return no_such_object(s, object);
  if (r.kind == Kind::kPlane) return {};
  const auto index = static_cast<std::size_t>(r.index);
  if (r.kind == Kind::kMesh && !s.meshes[index].geometry) return object_name(object) + ": its mesh is not loaded";
  const std::optional<Floor> floor = find_floor(s, camera, object);
  const double size = typical_size(s, camera, object);
  // The search's frame: along the floor, the view's right and the way towards the eye; without a
  // floor, the view plane's right and up.
  const Vec3 forward = unit_or(camera.look_at - camera.position, Vec3(0, 0, -1));
  const Vec3 view_right = unit_or(glm::cross(forward, camera.up), Vec3(1, 0, 0));
  const Vec3 view_up = glm::cross(view_right, forward);
  Vec3 base = camera.look_at, across = view_right, along = view_up, n(0);
  if (floor) {
    n = floor->normal;
    base = camera.look_at - height_above(*floor, camera.look_at) * n;
    // Looking straight down, the top of the image is the way away from the eye.
    const Vec3 ahead = unit_or(forward - glm::dot(forward, n) * n, unit_or(view_up - glm::dot(view_up, n) * n, Vec3(0, 0, -1)));
    across = glm::normalize(glm::cross(ahead, n));
    along = -ahead;
  }
  // The new object's middle for a point p of the floor (or the view plane), its half sides and
  // the step of the search.
  double radius = size / 2;
  Vec3 half(radius);
  double lift = radius;  // how far above the floor its middle is
  double k = 1;          // a mesh's scale factor
  Vec3 mesh_middle(0);
  if (r.kind == Kind::kTriangle) {
    half = Vec3(0);  // its corners' box, about p
    lift = 0;
  } else if (r.kind == Kind::kMesh) {
    const MeshFit fit = fit_mesh(*s.meshes[index].geometry, size, floor ? &n : nullptr);
    k = fit.k, mesh_middle = fit.middle, half = fit.half, radius = fit.radius, lift = fit.lift;
  }
  if (!floor) lift = 0;
  const auto triangle_at = [&](const Vec3& p) {
    Triangle t = s.triangles[index];
    if (floor) {  // standing on its base edge, facing the eye (Ng = along)
      t.v0 = p - radius * across;
      t.v1 = p + radius * across;
      t.v2 = p + 1.8 * radius * n;
    } else {      // facing the eye, counter-clockwise as the camera sees it
      t.v0 = p + radius * (-across - 0.6 * along);
      t.v1 = p + radius * (across - 0.6 * along);
      t.v2 = p + radius * (1.2 * along);
    }
    return t;
  };
  const auto middle_at = [&](const Vec3& p) { return p + lift * n; };
  const auto box_at = [&](const Vec3& p) {
    Aabb box;
    if (r.kind == Kind::kTriangle) {
      const Triangle t = triangle_at(p);
      for (const Vec3& v : {t.v0, t.v1, t.v2}) box.grow(v);
    } else {
      box.grow(middle_at(p) - half);
      box.grow(middle_at(p) + half);
    }
    return box;
  };
  std::vector<Aabb> others;
  for (const int other : finite_objects(s, object)) others.push_back(object_bounds(s, other));
  const double step = (radius > 0 ? radius : size / 2) / 2;
  const double gap = 0.04 * step;
  const auto free = [&](const Aabb& box) {
    return std::none_of(others.begin(), others.end(), [&](const Aabb& o) {
      return !o.empty() && box.lo.x < o.hi.x + gap && o.lo.x < box.hi.x + gap && box.lo.y < o.hi.y + gap &&
             o.lo.y < box.hi.y + gap && box.lo.z < o.hi.z + gap && o.lo.z < box.hi.z + gap;
    });
  };
  const ViewChecks view(s, camera, aspect, object);
  const std::vector<std::pair<int, int>> grid = search_grid();
  const auto point = [&](const std::pair<int, int>& g) {
    Vec3 p = base + (g.first * step) * across + (g.second * step) * along;
    p = Vec3(tidy_float(p.x), tidy_float(p.y), tidy_float(p.z));
    if (floor) p -= height_above(*floor, p) * n;  // on the floor exactly
    return p;
  };
  std::optional<Vec3> found;
  // In view, not hidden by another object, not behind the look-at point; then also behind it;
  // then hidden, not behind it; then anywhere in view; then free anywhere.
  for (int pass = 0; pass < 5 && !found; ++pass) {
    for (const auto& g : grid) {
      if ((pass == 0 || pass == 2) && floor && g.second < 0) continue;
      const Vec3 p = point(g);
      const Aabb box = box_at(p);
      if (free(box) && (pass == 4 || view.in_view(box)) && (pass >= 2 || !view.hidden(box))) {
        found = p;
        break;
      }
    }
  }
  const Vec3 p = found ? *found : point({0, 0});
  switch (r.kind) {
    case Kind::kSphere:
      s.spheres[index].center = middle_at(p);
      s.spheres[index].radius = radius;
      break;
    case Kind::kTriangle: {
      const Triangle t = triangle_at(p);
      s.triangles[index].v0 = t.v0;
      s.triangles[index].v1 = t.v1;
      s.triangles[index].v2 = t.v2;
      break;
    }
    default: {  // the mesh's points x go to k (x - its middle) + the new middle
      MeshTransform& t = s.meshes[index].transform;
      t.scale *= k;
      t.translate = k * (t.translate - mesh_middle) + middle_at(p);
      break;
    }
  }
  return {};
}

std::optional<Vec3> drag_over_floor(const Scene& s, int object, const Floor& floor, const Vec3& anchor_start,
                                    const Vec3& grab, const Vec3& origin, const Vec3& dir, bool vertical) {
  const Vec3 n = floor.normal;
  const double reach = 50 * glm::length(grab - origin);  // no further than this from the eye
  Vec3 target = anchor_start;
  if (!vertical) {
    const double across = glm::dot(dir, n);
    if (!(std::abs(across) > 1e-12 * glm::length(dir))) return std::nullopt;
    const double t = glm::dot(grab - origin, n) / across;
    if (!(t > 0) || t * glm::length(dir) > reach) return std::nullopt;
    Vec3 delta = origin + t * dir - grab;
    delta -= glm::dot(delta, n) * n;  // the height kept exactly
    target = anchor_start + delta;
  } else {
    // The points grab + a n and origin + t dir nearest to each other.
    const Vec3 w0 = grab - origin;
    const double b = glm::dot(n, dir), c = glm::dot(dir, dir), d = glm::dot(n, w0), e = glm::dot(dir, w0);
    const double denominator = c - b * b;
    if (!(denominator > 1e-12 * c)) return std::nullopt;  // the ray runs along the normal
    const double a = (b * e - c * d) / denominator, t = (e - b * d) / denominator;
    if (!(t > 0) || std::abs(a) > reach) return std::nullopt;
    target = anchor_start + a * n;
  }
  return keep_above_floor(s, object, floor, anchor_start, target);
}

Vec3 keep_above_floor(const Scene& s, int object, const Floor& floor, const Vec3& anchor_start, const Vec3& anchor) {
  const double low_now = lowest_above(s, object, floor);
  if (!std::isfinite(low_now)) return anchor;  // a plane
  const double below_anchor = low_now - height_above(floor, object_anchor(s, object));
  const double allowed = std::min(floor_clearance(s, object), height_above(floor, anchor_start) + below_anchor);
  const double low = height_above(floor, anchor) + below_anchor;
  return low < allowed ? anchor + (allowed - low) * floor.normal : anchor;
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

void own_edited_mtl_materials(const Scene& before, Scene& after) {
  const std::size_t n = std::min(before.materials.size(), after.materials.size());
  for (std::size_t i = 0; i < n; ++i) {
    Material& m = after.materials[i];
    const Material& was = before.materials[i];
    if (m.source.empty() || m.source != was.source || m.name != was.name) continue;
    Material a = m, b = was;
    a.source.clear();
    b.source.clear();
    if (!(a == b)) m.source.clear();  // the scene file's own from now on
  }
}

std::string mtl_origin(const Scene& scene, int material) {
  if (material < 0 || material >= static_cast<int>(scene.materials.size())) return {};
  const Material& m = scene.materials[static_cast<std::size_t>(material)];
  if (!m.source.empty()) return m.source;
  for (const Mesh& mesh : scene.meshes) {
    const std::string stem = std::filesystem::path(mesh.file).stem().string() + "/";
    if (mesh.material_override.empty() && m.name.rfind(stem, 0) == 0) return mesh.file;
  }
  return {};
}

std::string rename_material(Scene& s, int material, const std::string& name) {
  if (material < 0 || material >= static_cast<int>(s.materials.size())) return "no such material";
  Material& m = s.materials[static_cast<std::size_t>(material)];
  if (const std::string origin = mtl_origin(s, material); !origin.empty()) {
    return "'" + m.name + "' comes from " + origin + "'s MTL file: rename it there";
  }
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
