#include "core/accel/accel.h"
#include "core/base/threads.h"

#include <chrono>
#include <exception>
#include <thread>
#include <utility>

namespace phonglab {

std::size_t MeshGeometry::memory_bytes() const {
  return triangles.capacity() * sizeof(Triangle) + source_face.capacity() * sizeof(int) +
         bvh.nodes.capacity() * sizeof(BvhNode) + bvh.order.capacity() * sizeof(std::uint32_t) +
         sizeof(MeshGeometry);
}

namespace {

// Meshes of fewer triangles than this are put in leaf order on one thread.
constexpr std::size_t kParallelFill = std::size_t{1} << 16;

// Rearranges `v` and `w` alike so that slot i holds what slot order[i] held, in place by following
// the permutation's cycles; `order` is used up (each slot, once filled, points at itself). No
// second copy of the triangles (200 MB for 1.3M): allocating and first touching one cost more
// than the moves. Each step's source is a cache miss, and each step's address is known only from
// the one before, so a walk kAhead steps ahead along the cycle prefetches the sources: the
// misses overlap instead of queueing (0.4 s before, on the 1.3M-triangle blob).
template <class T, class U>
void permute_in_place(std::vector<T>& v, std::vector<U>& w, std::vector<std::uint32_t>& order) {
  constexpr int kAhead = 8;
  const auto prefetch = [&](std::size_t i) {
#if defined(__GNUC__)
    const char* p = reinterpret_cast<const char*>(&v[i]);
    for (std::size_t line = 0; line < sizeof(T); line += 64) __builtin_prefetch(p + line);
    __builtin_prefetch(&w[i]);
#else
    (void)i;
#endif
  };
  for (std::size_t start = 0; start < v.size(); ++start) {
    if (order[start] == start) continue;  // in place from the outset, or filled by an earlier cycle
    // The walk ahead stops where the cycle closes; it reads only slots the cycle has not reached.
    std::size_t ahead = start;
    bool ahead_done = false;
    const auto advance = [&] {
      if (ahead_done) return;
      ahead = order[ahead];
      if (ahead == start) {
        ahead_done = true;
      } else {
        prefetch(ahead);
      }
    };
    for (int i = 0; i < kAhead; ++i) advance();
    T held_v = std::move(v[start]);
    U held_w = std::move(w[start]);
    std::size_t j = start;
    for (;;) {
      const std::size_t k = order[j];
      order[j] = static_cast<std::uint32_t>(j);
      if (k == start) {
        v[j] = std::move(held_v);
        w[j] = std::move(held_w);
        break;
      }
      v[j] = std::move(v[k]);
      w[j] = std::move(w[k]);
      j = k;
      advance();
    }
  }
}

}  // namespace

std::shared_ptr<const MeshGeometry> make_mesh_geometry(std::vector<Triangle> triangles,
                                                       std::vector<int> source_face) {
  const auto start = std::chrono::steady_clock::now();
  auto geometry = std::make_shared<MeshGeometry>();
  geometry->bvh = build_bvh(triangles.size(), [&](std::size_t i) { return triangle_bounds(triangles[i]); }, 4);
  if (!geometry->bvh.nodes.empty()) geometry->bounds = geometry->bvh.nodes[0].box;  // the union of all boxes
  // Leaves then index the triangles directly: no indirection on the hot path.
  if (source_face.size() != triangles.size()) {
    source_face.resize(triangles.size());
    for (std::size_t i = 0; i < source_face.size(); ++i) source_face[i] = static_cast<int>(i);
  }
  permute_in_place(triangles, source_face, geometry->bvh.order);
  geometry->triangles = std::move(triangles);
  geometry->source_face = std::move(source_face);
  geometry->bvh.order = {};
  geometry->build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return geometry;
}

std::shared_ptr<const MeshGeometry> make_mesh_geometry(std::size_t count, const std::function<Triangle(std::size_t)>& make,
                                                       std::vector<int> source_face, std::vector<Triangle> room,
                                                       const std::function<Aabb(std::size_t)>& box_of) {
  const auto start = std::chrono::steady_clock::now();
  auto geometry = std::make_shared<MeshGeometry>();
  if (box_of) {
    geometry->bvh = build_bvh(count, box_of, 4);
  } else {
    geometry->bvh = build_bvh(count, [&](std::size_t i) { return triangle_bounds(make(i)); }, 4);
  }
  if (!geometry->bvh.nodes.empty()) geometry->bounds = geometry->bvh.nodes[0].box;
  const std::vector<std::uint32_t>& order = geometry->bvh.order;
  if (room.size() >= count) {
    // Slots of an array that exists already: two threads fill halves of it.
    const auto fill = [&](std::size_t begin, std::size_t end) {
      for (std::size_t slot = begin; slot < end; ++slot) room[slot] = make(order[slot]);
    };
    if (count >= kParallelFill) {
      in_parallel([&] { fill(count / 2, count); }, [&] { fill(0, count / 2); });
    } else {
      fill(0, count);
    }
    room.resize(count);
    if (room.capacity() > count) room.shrink_to_fit();  // some faces were left out: no spare slots kept
    geometry->triangles = std::move(room);
  } else {
    geometry->triangles.reserve(count);
    for (const std::uint32_t i : order) geometry->triangles.push_back(make(i));
  }
  geometry->source_face.resize(count);
  for (std::size_t slot = 0; slot < count; ++slot) {
    geometry->source_face[slot] = source_face.size() == count ? source_face[order[slot]] : static_cast<int>(order[slot]);
  }
  geometry->bvh.order = {};
  geometry->build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return geometry;
}

SceneBvh::SceneBvh(const Scene& scene) : boxes_(top_level_boxes(scene)) {
  std::vector<Aabb> boxes;
  std::vector<TopPrim> prims;
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    boxes.push_back(sphere_bounds(scene.spheres[i]));
    prims.push_back({ObjectRef::Kind::kSphere, static_cast<int>(i)});
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    boxes.push_back(triangle_bounds(scene.triangles[i]));
    prims.push_back({ObjectRef::Kind::kTriangle, static_cast<int>(i)});
  }
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const MeshGeometry& g = *scene.meshes[i].geometry;
    meshes_.push_back(&g);
    if (g.triangles.empty()) continue;
    boxes.push_back(g.bounds);
    prims.push_back({ObjectRef::Kind::kMesh, static_cast<int>(i)});
  }
  has_triangles_ = !scene.triangles.empty() || !scene.meshes.empty();
  top_ = build_bvh(boxes, 2);
  prims_.reserve(prims.size());
  for (const std::uint32_t i : top_.order) prims_.push_back(prims[i]);
  top_.order = {};
}

std::optional<Hit> SceneBvh::intersect(const Scene& scene, const Ray& ray, double t_max) const {
  double best = t_max;
  ObjectRef obj;
  double best_b1 = 0, best_b2 = 0;
  if (const int i = nearest_plane(scene.planes, ray, best); i >= 0) obj = {ObjectRef::Kind::kPlane, i};
  const BoxRay box_ray(ray);
  const TriangleShear shear = has_triangles_ ? make_shear(ray.dir) : TriangleShear{};
  const auto test_triangle = [&](const Triangle& tri, ObjectRef ref) {
    double b1 = 0, b2 = 0;
    if (auto t = intersect_triangle(tri, ray, shear, &b1, &b2); t && replaces(*t, ref, best, obj)) {
      best = *t;
      best_b1 = b1;
      best_b2 = b2;
      obj = ref;
    }
  };
  traverse(top_, box_ray, best, [&](std::uint32_t first, std::uint32_t count) {
    for (std::uint32_t slot = first; slot < first + count; ++slot) {
      const TopPrim p = prims_[slot];
      switch (p.kind) {
        case ObjectRef::Kind::kSphere:
          if (const double t = sphere_root(scene.spheres[p.index], ray.origin, ray.dir, 0, best); t > 0) {
            best = t;
            obj = {ObjectRef::Kind::kSphere, p.index};
          }
          break;
        case ObjectRef::Kind::kTriangle:
          test_triangle(scene.triangles[p.index], {ObjectRef::Kind::kTriangle, p.index});
          break;
        case ObjectRef::Kind::kMesh: {
          const MeshGeometry& g = *scene.meshes[p.index].geometry;
          traverse(g.bvh, box_ray, best, [&](std::uint32_t f, std::uint32_t n) {
            for (std::uint32_t i = f; i < f + n; ++i) {
              test_triangle(g.triangles[i], {ObjectRef::Kind::kMesh, p.index, static_cast<int>(i)});
            }
            return false;
          });
          break;
        }
        default:
          break;
      }
    }
    return false;
  });
  if (obj.kind == ObjectRef::Kind::kNone) return std::nullopt;
  return make_hit(scene, ray, obj, best, best_b1, best_b2);
}

bool SceneBvh::occluded(const Scene& scene, const Ray& ray, double t_max) const {
  if (any_plane(scene.planes, ray, t_max)) return true;
  const BoxRay box_ray(ray);
  const TriangleShear shear = has_triangles_ ? make_shear(ray.dir) : TriangleShear{};
  const auto blocks = [&](const Triangle& tri) {
    const auto t = intersect_triangle(tri, ray, shear, nullptr, nullptr);
    return t && *t < t_max;
  };
  bool found = false;
  traverse(top_, box_ray, t_max, [&](std::uint32_t first, std::uint32_t count) {
    for (std::uint32_t slot = first; slot < first + count && !found; ++slot) {
      const TopPrim p = prims_[slot];
      switch (p.kind) {
        case ObjectRef::Kind::kSphere:
          found = sphere_root(scene.spheres[p.index], ray.origin, ray.dir, 0, t_max) > 0;
          break;
        case ObjectRef::Kind::kTriangle:
          found = blocks(scene.triangles[p.index]);
          break;
        case ObjectRef::Kind::kMesh: {
          const MeshGeometry& g = *scene.meshes[p.index].geometry;
          traverse(g.bvh, box_ray, t_max, [&](std::uint32_t f, std::uint32_t n) {
            for (std::uint32_t i = f; i < f + n && !found; ++i) found = blocks(g.triangles[i]);
            return found;
          });
          break;
        }
        default:
          break;
      }
    }
    return found;
  });
  return found;
}

bool SceneBvh::matches(const Scene& scene) const {
  if (scene.meshes.size() != meshes_.size()) return false;
  for (std::size_t i = 0; i < meshes_.size(); ++i) {
    if (scene.meshes[i].geometry.get() != meshes_[i]) return false;
  }
  const std::vector<Aabb> now = top_level_boxes(scene);
  if (now.size() != boxes_.size()) return false;
  for (std::size_t i = 0; i < now.size(); ++i) {
    if (now[i].lo != boxes_[i].lo || now[i].hi != boxes_[i].hi) return false;
  }
  return true;
}

// Boxes of the spheres, then the loose triangles, as matches() compares them.
std::vector<Aabb> SceneBvh::top_level_boxes(const Scene& scene) {
  std::vector<Aabb> boxes;
  boxes.reserve(scene.spheres.size() + scene.triangles.size());
  for (const Sphere& s : scene.spheres) boxes.push_back(sphere_bounds(s));
  for (const Triangle& t : scene.triangles) boxes.push_back(triangle_bounds(t));
  return boxes;
}

std::shared_ptr<const Accelerator> build_scene_accel(const Scene& scene, bool force_bvh) {
  // A handful of spheres and triangles is cheaper to test in a row than through any structure
  // (callgrind on `lecture`, 320x180: a hierarchy over its 5 spheres cost 5 % more instructions,
  // and even a flat accelerator's extra calls 4 %).
  constexpr std::size_t kBruteForceLimit = 8;
  if (!force_bvh && scene.meshes.empty() && scene.spheres.size() + scene.triangles.size() <= kBruteForceLimit) {
    return nullptr;
  }
  return std::make_shared<SceneBvh>(scene);
}

Aabb scene_bounds(const Scene& scene) {
  Aabb b;
  for (const Sphere& s : scene.spheres) b.grow(sphere_bounds(s));
  for (const Triangle& t : scene.triangles) b.grow(triangle_bounds(t));
  for (const Mesh& m : scene.meshes) b.grow(m.geometry->bounds);
  return b;
}

const Triangle& triangle_of(const Scene& scene, const ObjectRef& obj) {
  if (obj.kind == ObjectRef::Kind::kMesh) return scene.meshes[obj.index].geometry->triangles[obj.prim];
  return scene.triangles[obj.index];
}

}  // namespace phonglab
