// Acceleration structures against brute force: the project's BVH must give bit-identical answers
// (same object, same t) on seeded random scenes and rays, including the cases that break slab
// tests: zero direction components, origins exactly on box faces and zero-thickness boxes.
// With Embree built, its single-ray accelerator must agree within float tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <thread>
#include <string>
#include <utility>
#include <vector>

#include "core/accel/accel.h"
#include "core/accel/bvh.h"
#include "core/accel/prepared_scene.h"
#include "core/geometry/geometry.h"
#include "io/obj_io.h"
#include "tests/support/obj_mesh.h"
#include "core/scene/scene.h"
#include "core/shading/shading.h"

#ifdef PHONGLAB_HAVE_EMBREE
#include "apps/bench/embree_accel.h"
#endif

using namespace phonglab;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct RandomScene {
  Scene scene;
  std::vector<Aabb> boxes;  // of every bounded primitive, for origins on box faces
};

// Spheres, loose triangles (some lying in a coordinate plane: flat boxes) and one mesh: a
// jittered grid with a flat strip in z = const, plus sometimes a ground plane.
RandomScene make_random_scene(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-5, 5), radius(0.05, 1.2), unit(0, 1);
  RandomScene r;
  Scene& s = r.scene;
  s.materials.resize(1);
  const int spheres = 1 + static_cast<int>(rng() % 12);
  for (int i = 0; i < spheres; ++i) s.spheres.push_back(Sphere{Vec3(pos(rng), pos(rng), pos(rng)), radius(rng), 0});
  const int triangles = static_cast<int>(rng() % 12);
  for (int i = 0; i < triangles; ++i) {
    const Vec3 a(pos(rng), pos(rng), pos(rng));
    Vec3 b = a + Vec3(pos(rng), pos(rng), pos(rng)) * 0.4;
    Vec3 c = a + Vec3(pos(rng), pos(rng), pos(rng)) * 0.4;
    if (i % 3 == 0) {
      const int axis = static_cast<int>(rng() % 3);  // flat: zero thickness along `axis`
      b[axis] = a[axis];
      c[axis] = a[axis];
    }
    s.triangles.push_back(Triangle{a, b, c, 0});
  }
  // The mesh: an n x n grid over [x0, x0 + 4] x [y0, y0 + 4]; rows below n/2 flat in z = z0.
  const int n = 4 + static_cast<int>(rng() % 12);
  const Vec3 o(pos(rng), pos(rng), pos(rng));
  std::vector<Vec3> grid(static_cast<std::size_t>((n + 1) * (n + 1)));
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double z = j < n / 2 ? 0.0 : 0.3 * (unit(rng) - 0.5);
      grid[static_cast<std::size_t>(j * (n + 1) + i)] = o + Vec3(4.0 * i / n, 4.0 * j / n, z);
    }
  }
  std::vector<Triangle> mesh_tris;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Vec3& a = grid[static_cast<std::size_t>(j * (n + 1) + i)];
      const Vec3& b = grid[static_cast<std::size_t>(j * (n + 1) + i + 1)];
      const Vec3& c = grid[static_cast<std::size_t>((j + 1) * (n + 1) + i)];
      const Vec3& d = grid[static_cast<std::size_t>((j + 1) * (n + 1) + i + 1)];
      mesh_tris.push_back(Triangle{a, b, d, 0});
      mesh_tris.push_back(Triangle{a, d, c, 0});
    }
  }
  Mesh mesh;
  mesh.geometry = make_mesh_geometry(mesh_tris, {});
  s.meshes.push_back(mesh);
  if (rng() % 2) s.planes.push_back(Plane{Vec3(0, -6, 0), Vec3(0, 1, 0), 0});
  for (const Sphere& sp : s.spheres) r.boxes.push_back(sphere_bounds(sp));
  for (const Triangle& t : s.triangles) r.boxes.push_back(triangle_bounds(t));
  for (const Triangle& t : mesh.geometry->triangles) r.boxes.push_back(triangle_bounds(t));
  return r;
}

struct RandomRay {
  Ray ray;
  double t_max = kInf;
};

// Rays aimed at the scene's primitives from random points, from points exactly on box faces
// (when `on_faces`; with a zero direction component these run exactly along edges), with zero
// direction components, and a few random t_max.
RandomRay make_random_ray(const RandomScene& r, std::mt19937& rng, bool on_faces = true) {
  std::uniform_real_distribution<double> pos(-8, 8), unit(0, 1);
  const Aabb& target = r.boxes[rng() % r.boxes.size()];
  const Vec3 aim = target.lo + Vec3(unit(rng), unit(rng), unit(rng)) * (target.hi - target.lo);
  Vec3 origin(pos(rng), pos(rng), pos(rng));
  int kind = static_cast<int>(rng() % 4);
  if (kind == 1 && !on_faces) kind = 0;
  if (kind == 1) {
    // Origin exactly on a face of some box (its coordinate on that axis is the box's bound).
    const Aabb& b = r.boxes[rng() % r.boxes.size()];
    origin = b.lo + Vec3(unit(rng), unit(rng), unit(rng)) * (b.hi - b.lo);
    const int axis = static_cast<int>(rng() % 3);
    origin[axis] = rng() % 2 ? b.lo[axis] : b.hi[axis];
  }
  Vec3 dir = aim - origin;
  if (kind == 2 || kind == 1) {
    // One or two direction components exactly zero: rays parallel to slab planes.
    const int zeros = 1 + static_cast<int>(rng() % 2);
    const int first = static_cast<int>(rng() % 3);
    // Half of them -0, as normalize gives for a negative zero: slabs crossed from above.
    for (int z = 0; z < zeros; ++z) dir[(first + z) % 3] = rng() % 2 ? 0.0 : -0.0;
    if (zeros == 2) origin[(first + 2) % 3] = aim[(first + 2) % 3] - (rng() % 2 ? 6.0 : -6.0);
  }
  if (!(glm::dot(dir, dir) > 0)) dir = Vec3(0, 0, 1);
  RandomRay out;
  out.ray = make_ray(origin, glm::normalize(dir));
  if (kind == 3) out.t_max = 20 * unit(rng);
  return out;
}

std::string describe(const Ray& ray, double t_max) {
  std::ostringstream o;
  o.precision(17);
  o << "origin (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") dir (" << ray.dir.x << ", "
    << ray.dir.y << ", " << ray.dir.z << ") t_max " << t_max;
  return o.str();
}

bool same_object(const ObjectRef& a, const ObjectRef& b) {
  return a.kind == b.kind && a.index == b.index && a.prim == b.prim;
}

}  // namespace

TEST(SceneBvh, AnswersBitIdenticallyToBruteForceOnRandomScenesAndRays) {
  int hits = 0, rays = 0;
  for (std::uint32_t seed = 1; seed <= 150; ++seed) {
    const RandomScene r = make_random_scene(seed);
    const std::shared_ptr<const Accelerator> bvh = build_scene_accel(r.scene, true);
    ASSERT_TRUE(bvh);
    std::mt19937 rng(seed * 7919u);
    for (int k = 0; k < 400; ++k) {
      const RandomRay rr = make_random_ray(r, rng);
      const std::optional<Hit> want = intersect_all(r.scene, rr.ray, rr.t_max);
      const std::optional<Hit> got = bvh->intersect(r.scene, rr.ray, rr.t_max);
      ++rays;
      ASSERT_EQ(want.has_value(), got.has_value()) << "seed " << seed << " ray " << k << ": " << describe(rr.ray, rr.t_max);
      if (want) {
        ++hits;
        ASSERT_EQ(want->t, got->t) << "seed " << seed << " ray " << k << ": " << describe(rr.ray, rr.t_max);
        ASSERT_TRUE(same_object(want->object, got->object)) << "seed " << seed << " ray " << k;
      }
      // The any-hit query up to the hit (exclusive) and just beyond it.
      const double t_occ = want ? (k % 2 ? want->t : std::nextafter(want->t, kInf)) : rr.t_max;
      ASSERT_EQ(occluded_all(r.scene, rr.ray, t_occ), bvh->occluded(r.scene, rr.ray, t_occ))
          << "seed " << seed << " ray " << k << ": " << describe(rr.ray, t_occ);
    }
  }
  // The rays are aimed: most of them must hit, or the test proves little.
  EXPECT_GT(hits, rays / 2);
}

TEST(SceneBvh, BoxTestNeverRejectsAFlatBoxTheRayCrossesOrStartsOn) {
  // A zero-thickness box in z = 1 and rays along axes that start on its faces or cross it.
  const Aabb flat{Vec3(0, 0, 1), Vec3(2, 2, 1)};
  const Ray down = make_ray(Vec3(1, 1, 3), Vec3(0, 0, -1));
  EXPECT_TRUE(hits_box(flat, BoxRay(down), kInf));
  const Ray along_face = make_ray(Vec3(-1, 1, 1), Vec3(1, 0, 0));  // in the box's plane
  EXPECT_TRUE(hits_box(flat, BoxRay(along_face), kInf));
  const Ray on_edge = make_ray(Vec3(0, -1, 1), Vec3(0, 1, 0));  // along its x = 0 edge
  EXPECT_TRUE(hits_box(flat, BoxRay(on_edge), kInf));
  const Ray beside = make_ray(Vec3(-1, 1, 1.5), Vec3(1, 0, 0));
  EXPECT_FALSE(hits_box(flat, BoxRay(beside), kInf));
  // Direction components of -0 (normalize(-0, 0, -4) gives them): 1 / -0 is -inf, so the slab
  // must be taken as crossed from above, or its computed entry is +inf and every box is missed.
  const Ray negative_zero = make_ray(Vec3(1, 1, 3), Vec3(-0.0, -0.0, -1));
  EXPECT_TRUE(hits_box(flat, BoxRay(negative_zero), kInf));
  const Aabb cube{Vec3(0), Vec3(2)};
  EXPECT_TRUE(hits_box(cube, BoxRay(make_ray(Vec3(1, 1, 3), Vec3(0, -0.0, -1))), kInf));
  EXPECT_TRUE(hits_box(cube, BoxRay(make_ray(Vec3(1, 3, 1), Vec3(-0.0, -1, 0))), kInf));
}

TEST(SceneBvh, BuiltOnlyWhenAskedForAHandfulOfSpheres) {
  Scene s;
  s.materials.resize(1);
  s.spheres.push_back(Sphere{Vec3(0), 1, 0});
  EXPECT_FALSE(build_scene_accel(s));
  EXPECT_TRUE(build_scene_accel(s, true));
}

// A mesh large enough for the build to split its top levels over threads (2^16 triangles and
// more): every triangle lands in exactly one leaf, and queries equal brute force. Also run under
// ThreadSanitizer.
TEST(SceneBvh, AParallelBuildOfALargeMeshKeepsEveryTriangleOnceAndEqualsBruteForce) {
  const std::uint32_t seed = 20261123;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-10, 10), step(-0.2, 0.2);
  std::vector<Triangle> tris;
  for (int i = 0; i < 90000; ++i) {
    const Vec3 a(pos(rng), pos(rng), pos(rng));
    tris.push_back(Triangle{a, a + Vec3(step(rng), step(rng), step(rng)), a + Vec3(step(rng), step(rng), step(rng)), 0});
  }
  std::vector<int> faces(tris.size());
  for (std::size_t i = 0; i < faces.size(); ++i) faces[i] = static_cast<int>(i);
  Scene scene;
  scene.materials.resize(1);
  Mesh mesh;
  mesh.geometry = make_mesh_geometry(tris, faces);
  const MeshGeometry& g = *mesh.geometry;
  ASSERT_EQ(g.triangles.size(), tris.size());
  std::vector<int> seen(tris.size(), 0);
  for (std::size_t slot = 0; slot < g.triangles.size(); ++slot) {
    const int face = g.source_face[slot];
    ASSERT_GE(face, 0);
    ++seen[static_cast<std::size_t>(face)];
    EXPECT_EQ(g.triangles[slot].v0, tris[static_cast<std::size_t>(face)].v0) << "slot " << slot;
  }
  for (std::size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "face " << i;
  scene.meshes.push_back(std::move(mesh));
  scene.mesh_object.push_back(0);
  const PreparedScene prepared(std::move(scene));
  ASSERT_TRUE(prepared.accel());
  std::uniform_real_distribution<double> dir(-1, 1);
  for (int i = 0; i < 300; ++i) {
    const Ray ray = make_ray(Vec3(pos(rng), pos(rng), pos(rng)), glm::normalize(Vec3(dir(rng), dir(rng), dir(rng))));
    const auto fast = intersect(prepared, ray);
    const auto slow = intersect_all(prepared.scene(), ray);
    ASSERT_EQ(fast.has_value(), slow.has_value()) << "seed " << seed << ", ray " << i;
    if (fast) {
      EXPECT_EQ(fast->t, slow->t) << "seed " << seed << ", ray " << i;
      EXPECT_EQ(fast->object.prim, slow->object.prim) << "seed " << seed << ", ray " << i;
    }
  }
}

// The two ways to make a mesh's geometry, from stored triangles (permuted in place) and from
// triangles made on demand (made in their leaf slots, into room made ahead or not), give the same nodes and the same
// triangles in the same slots, bit for bit, on a mesh large enough for the parallel root passes.
TEST(SceneBvh, MeshGeometryFromTrianglesMadeOnDemandEqualsTheStoredOnes) {
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> pos(-10, 10), step(-0.2, 0.2);
  std::vector<Triangle> tris;
  for (int i = 0; i < 80000; ++i) {
    const Vec3 a(pos(rng), pos(rng), pos(rng));
    Triangle t{a, a + Vec3(step(rng), step(rng), step(rng)), a + Vec3(step(rng), step(rng), step(rng)), i % 3};
    if (i % 2 == 0) {
      t.has_vertex_normals = true;
      t.n0 = Vec3(0, 0, 1);
      t.n1 = Vec3(0, 1, 0);
      t.n2 = Vec3(1, 0, 0);
    }
    tris.push_back(t);
  }
  std::vector<int> faces(tris.size());
  for (std::size_t i = 0; i < faces.size(); ++i) faces[i] = static_cast<int>(i / 2);
  const auto stored = make_mesh_geometry(tris, faces);
  const auto made = make_mesh_geometry(tris.size(), [&](std::size_t i) { return tris[i]; }, faces);
  // Into room made ahead (filled by two threads), with spare slots as when faces are left out.
  const auto in_room = make_mesh_geometry(tris.size(), [&](std::size_t i) { return tris[i]; }, faces,
                                          std::vector<Triangle>(tris.size() + 5));
  ASSERT_EQ(in_room->triangles.size(), tris.size());
  EXPECT_EQ(in_room->triangles.capacity(), tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) {
    const Triangle& a = made->triangles[i];
    const Triangle& b = in_room->triangles[i];
    ASSERT_TRUE(a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2 && a.material == b.material &&
                a.has_vertex_normals == b.has_vertex_normals && a.n0 == b.n0 && a.n1 == b.n1 && a.n2 == b.n2)
        << "slot " << i;
  }
  EXPECT_EQ(in_room->source_face, made->source_face);
  ASSERT_EQ(stored->bvh.nodes.size(), made->bvh.nodes.size());
  EXPECT_EQ(stored->bvh.depth, made->bvh.depth);
  for (std::size_t i = 0; i < stored->bvh.nodes.size(); ++i) {
    const BvhNode& a = stored->bvh.nodes[i];
    const BvhNode& b = made->bvh.nodes[i];
    ASSERT_TRUE(a.box.lo == b.box.lo && a.box.hi == b.box.hi && a.first == b.first && a.count == b.count &&
                a.axis == b.axis)
        << "node " << i;
  }
  ASSERT_EQ(stored->triangles.size(), made->triangles.size());
  for (std::size_t i = 0; i < stored->triangles.size(); ++i) {
    const Triangle& a = stored->triangles[i];
    const Triangle& b = made->triangles[i];
    ASSERT_TRUE(a.v0 == b.v0 && a.v1 == b.v1 && a.v2 == b.v2 && a.material == b.material &&
                a.has_vertex_normals == b.has_vertex_normals && a.n0 == b.n0 && a.n1 == b.n1 && a.n2 == b.n2)
        << "slot " << i;
    ASSERT_EQ(stored->source_face[i], made->source_face[i]) << "slot " << i;
  }
  EXPECT_TRUE(stored->bounds.lo == made->bounds.lo && stored->bounds.hi == made->bounds.hi);
  // Every node's box holds its subtree's triangles (the leaves' boxes are exact).
  const auto& nodes = made->bvh.nodes;
  for (const BvhNode& node : nodes) {
    if (node.count == 0) continue;
    for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
      const Aabb b = triangle_bounds(made->triangles[i]);
      ASSERT_TRUE(node.box.lo.x <= b.lo.x && node.box.lo.y <= b.lo.y && node.box.lo.z <= b.lo.z &&
                  b.hi.x <= node.box.hi.x && b.hi.y <= node.box.hi.y && b.hi.z <= node.box.hi.z);
    }
  }
}

// An OBJ's prescan runs on a thread of its own beside tinyobjloader: a large file loads into the
// same triangles as its faces say, and a file the prescan rejects reports its errors only. Also
// run under ThreadSanitizer.
TEST(MeshObjLoad, ThePrescanThreadBesideTinyobjloaderGivesTheFileAndItsErrors) {
  std::ostringstream obj;
  constexpr int kSide = 120;
  for (int j = 0; j < kSide; ++j) {
    for (int i = 0; i < kSide; ++i) obj << "v " << i * 0.25 << " " << j * 0.5 << " " << (i * j) % 7 * 0.125 << "\n";
  }
  for (int j = 0; j + 1 < kSide; ++j) {
    for (int i = 0; i + 1 < kSide; ++i) {
      const int a = j * kSide + i + 1;
      obj << "f " << a << " " << a + 1 << " " << a + kSide + 1 << " " << a + kSide << "\n";
    }
  }
  const ObjMesh mesh = load_obj(obj.str(), "grid.obj", nullptr);
  ASSERT_TRUE(mesh.errors.empty());
  ASSERT_EQ(mesh.triangles.size(), std::size_t{2} * (kSide - 1) * (kSide - 1));
  EXPECT_EQ(mesh.triangles[0].v0, Vec3(0, 0, 0));
  EXPECT_EQ(mesh.triangles[0].v1, Vec3(0.25, 0, 0));
  EXPECT_EQ(mesh.source_face.back(), (kSide - 1) * (kSide - 1) - 1);
  // As scene loading does it: room for the triangles made by the prescan's thread, then filled.
  std::vector<Triangle> room;
  const ObjIndexedMesh indexed = load_obj_indexed(obj.str(), "grid.obj", nullptr, NsMapping::kAsIs,
                                                  [&](std::size_t n) { room.resize(n); });
  ASSERT_EQ(room.size(), mesh.triangles.size());
  std::vector<int> faces;
  for (const ObjIndexedTriangle& t : indexed.triangles) faces.push_back(t.face);
  const auto geometry = make_mesh_geometry(indexed.triangles.size(), [&](std::size_t i) { return indexed.triangle(i); },
                                           faces, std::move(room));
  const auto reference = make_mesh_geometry(mesh.triangles, mesh.source_face);
  ASSERT_EQ(geometry->triangles.size(), reference->triangles.size());
  for (std::size_t i = 0; i < geometry->triangles.size(); ++i) {
    ASSERT_EQ(geometry->triangles[i].v0, reference->triangles[i].v0) << "slot " << i;
    ASSERT_EQ(geometry->triangles[i].v2, reference->triangles[i].v2) << "slot " << i;
  }
  EXPECT_EQ(geometry->source_face, reference->source_face);
  const ObjMesh bad = load_obj(obj.str() + "f 1 2 0\n", "grid.obj", nullptr);
  ASSERT_EQ(bad.errors.size(), 1u);
  EXPECT_EQ(bad.errors[0].line, kSide * kSide + (kSide - 1) * (kSide - 1) + 1);
  EXPECT_TRUE(bad.warnings.empty());
  EXPECT_TRUE(bad.triangles.empty());
}

#ifdef PHONGLAB_HAVE_EMBREE

// Above Embree's self-hit margin for these scenes (2^-16 of coordinates up to about 16).
constexpr double kEmbreeMargin = 1e-3;
// Rays closer than this cosine to a triangle's plane: float vertices tilt the plane by ~1e-7.
constexpr double kGrazing = 1e-4;

TEST(EmbreeAccel, AgreesWithBvhAndBruteForceWithinFloatTolerance) {
  int compared = 0, disagreements = 0, hits = 0;
  std::string example;
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    const RandomScene r = make_random_scene(seed);
    const std::shared_ptr<const Accelerator> bvh = build_scene_accel(r.scene, true);
    const std::shared_ptr<const Accelerator> embree = make_embree_accel(r.scene);
    ASSERT_TRUE(embree->matches(r.scene));
    std::mt19937 rng(seed * 104729u);
    for (int k = 0; k < 400; ++k) {
      // Not along edges: float vertices decide those either way (the BVH test covers them).
      const RandomRay rr = make_random_ray(r, rng, false);
      const std::optional<Hit> want = intersect_all(r.scene, rr.ray, rr.t_max);
      const std::optional<Hit> mid = bvh->intersect(r.scene, rr.ray, rr.t_max);
      const std::optional<Hit> got = embree->intersect(r.scene, rr.ray, rr.t_max);
      ASSERT_EQ(want.has_value(), mid.has_value());
      // Embree ignores triangle hits within its float self-hit margin of the origin (by design),
      // and a ray (nearly) in a triangle's plane is ill-conditioned in float.
      if (want && (want->t < kEmbreeMargin || std::abs(glm::dot(want->ng, rr.ray.dir)) < kGrazing)) continue;
      ++compared;
      bool agree = want.has_value() == got.has_value();
      if (agree && want) {
        ++hits;
        // Float triangles: t to a few float ulps of the coordinates' size (scene within 16). A
        // ray through a shared edge, or in the plane of a flat patch, hits the same surface at
        // the same distance through either neighbour.
        const bool same_surface = want->object.kind == got->object.kind && want->object.index == got->object.index &&
                                  (want->object.kind == ObjectRef::Kind::kMesh || same_object(want->object, got->object));
        agree = same_surface && std::abs(want->t - got->t) <= 1e-5 * (16 + want->t);
        if (want->object.kind == ObjectRef::Kind::kSphere || want->object.kind == ObjectRef::Kind::kPlane) {
          agree = agree && want->t == got->t;  // exact double tests outside Embree's float
        }
      }
      if (!agree) {
        ++disagreements;
        if (example.empty()) example = "seed " + std::to_string(seed) + " ray " + std::to_string(k) + ": " + describe(rr.ray, rr.t_max);
      }
    }
  }
  // Float vertices move edges by ~1e-7: a ray that brushes an edge may pick the neighbour or
  // slip past. Such rays are rare among these; anything systematic would show in thousands.
  EXPECT_LE(disagreements, compared / 500) << disagreements << " of " << compared << ", e.g. " << example;
  EXPECT_GT(hits, compared / 2);
}

TEST(EmbreeAccel, ShadowQueriesAgreeWithBruteForceAwayFromTheEnds) {
  int compared = 0, disagreements = 0;
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    const RandomScene r = make_random_scene(seed);
    const std::shared_ptr<const Accelerator> embree = make_embree_accel(r.scene);
    std::mt19937 rng(seed * 15485863u);
    for (int k = 0; k < 400; ++k) {
      const RandomRay rr = make_random_ray(r, rng, false);
      const std::optional<Hit> first = intersect_all(r.scene, rr.ray, rr.t_max);
      // Segments ending well before or well after the first hit: no float-tolerance ties.
      const double t_max = first ? (k % 2 ? 0.99 * first->t : 1.01 * first->t) : rr.t_max;
      ++compared;
      if (occluded_all(r.scene, rr.ray, t_max) != embree->occluded(r.scene, rr.ray, t_max)) ++disagreements;
    }
  }
  EXPECT_LE(disagreements, compared / 500) << disagreements << " of " << compared;
}

TEST(EmbreeAccel, ConcurrentQueriesGiveTheSameAnswers) {
  const RandomScene r = make_random_scene(3);
  const std::shared_ptr<const Accelerator> embree = make_embree_accel(r.scene);
  std::mt19937 rng(99);
  std::vector<RandomRay> rays;
  for (int k = 0; k < 2000; ++k) rays.push_back(make_random_ray(r, rng));
  std::vector<double> serial(rays.size()), parallel(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const auto h = embree->intersect(r.scene, rays[i].ray, rays[i].t_max);
    serial[i] = h ? h->t : -1;
  }
  std::vector<std::thread> pool;
  for (int t = 0; t < 4; ++t) {
    pool.emplace_back([&, t] {
      for (std::size_t i = static_cast<std::size_t>(t); i < rays.size(); i += 4) {
        const auto h = embree->intersect(r.scene, rays[i].ray, rays[i].t_max);
        parallel[i] = h ? h->t : -1;
      }
    });
  }
  for (std::thread& th : pool) th.join();
  EXPECT_EQ(serial, parallel);
}

#endif  // PHONGLAB_HAVE_EMBREE
