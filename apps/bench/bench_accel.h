// The acceleration benchmark of `phonglab-cli bench`: the project's default path (brute force
// on small scenes), its BVH forced everywhere and Embree 3 single-ray queries, on the same
// Whitted frames with the same shading and rays; Embree's 16-wide primary packets as the limit;
// build time and memory on a generated mesh of about 1.3M triangles.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace phonglab {

struct AccelBenchOptions {
  bool quick = false;  // 640x360, few frames, a 65k-triangle mesh: seconds, for CI
  int threads = 0;     // the multi-threaded runs (0: all hardware threads); 1 thread is always run too
};

struct AccelBenchResult {
  std::string markdown;      // a "## Acceleration" section for report.md
  std::string csv;           // accel.csv: one row per scene, accelerator and thread count
  bool checks_passed = true; // false after a "CHECK FAILED" line (printed to stdout)
};

// Runs every measurement; progress goes to stdout.
AccelBenchResult run_accel_bench(const AccelBenchOptions& options);

// `phonglab-cli bench --only accel`: the section alone as accel.md and accel.csv in `out_dir`.
// Returns a process exit code (1 when a file cannot be written).
int write_accel_report(const AccelBenchOptions& options, const std::string& out_dir);

// A closed, bumpy sphere of radius about 1 around the origin: `segments` around, `rings` from
// pole to pole, segments * (2 rings - 2) triangles (1024 x 636: 1,300,480).
std::vector<Triangle> make_bumpy_sphere(int rings, int segments, int material);

// A lit scene around a mesh made of `triangles` (material 1; any triangles, e.g. an OBJ's):
// a floor under it, a mirror sphere beside it, a point and a directional light, the camera
// framing it. The mesh's BVH is built here (make_mesh_geometry); the scene is prepared.
Scene make_mesh_scene(std::vector<Triangle> triangles);

}  // namespace phonglab
