// Intel Embree 3 behind the renderer's Accelerator interface: the yardstick of the acceleration
// benchmark (docs/speed.md) and a third opinion in the tests. Built only when CMake finds Embree
// (PHONGLAB_EMBREE; the target phonglab_embree defines PHONGLAB_HAVE_EMBREE). Never in renderer/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/scene/scene.h"

namespace phonglab {

struct EmbreeOptions {
  int build_threads = 0;  // threads Embree's builder may use; 0: all hardware threads
};

// What building the Embree structures cost.
struct EmbreeBuildStats {
  double commit_seconds = 0;  // rtcCommitScene alone (the BVH build)
  double total_seconds = 0;   // device, geometry buffers and commit
  std::size_t memory_bytes = 0;  // bytes the device holds after the build (its memory monitor)
};

// Embree single-ray queries (rtcIntersect1, rtcOccluded1) over a prepared scene:
// - triangles and mesh triangles as Embree triangles, in float (Embree has no double mode);
//   hits keep Embree's float t, u and v;
// - spheres as user geometry whose callback runs the renderer's exact double sphere_root on the
//   original double ray, so spheres stay exact and the rays are the renderer's own;
// - planes (infinite) tested apart, in double, as the project's BVH does.
// Triangle hits closer than a float rounding margin of the ray origin are ignored (Embree's
// float test would see the surface a ray leaves). Thread-safe for concurrent queries. Throws
// std::runtime_error when Embree cannot make a device.
std::shared_ptr<const Accelerator> make_embree_accel(const Scene& scene, const EmbreeOptions& options = {},
                                                     EmbreeBuildStats* stats = nullptr);

// Embree single-ray queries over Embree's own float primitives, what a user who picks Embree
// gets: spheres as built-in sphere points, triangles and meshes as its triangles, planes as two
// triangles of a square 1e4 times the scene's size. Hits keep Embree's float t, u and v (the hit
// record is then the renderer's make_hit); no query is exact, and images differ from the
// renderer's where float rounding moves a hit. Self-hits are kept off by the same float margin
// on tnear as make_embree_accel's.
std::shared_ptr<const Accelerator> make_embree_native_accel(const Scene& scene);

// Primary rays of a w x h frame (pixel centres: camera_ray's formula, evaluated in float),
// cast by Embree as 16-wide packets (rtcIntersect16, 4x4 pixels each, coherent context) over
// Embree's own float primitives: spheres as built-in sphere points, planes as two triangles of a
// square 1e4 times the scene's size. The upper bound a packet tracer reaches on this machine.
struct PacketCast {
  double seconds = 0;       // wall time of the whole frame (ray set-up included)
  std::uint64_t rays = 0;   // rays cast
  std::uint64_t hits = 0;   // rays that hit something
};
// One warm-up cast (thread start-up, caches), then `casts` timed ones, all on one device.
std::vector<PacketCast> embree_cast_primary_packets(const Scene& scene, int width, int height, int threads, int casts);

}  // namespace phonglab
