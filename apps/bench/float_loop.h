// The bench's first yardstick: a plain float brute-force Whitted loop, what a student writes in
// an afternoon. Fixed epsilon (1e-3 along the normal), no robustness, no acceleration, the same
// equation (Phong or Blinn, hard shadows, mirrors, glass with Snell, total internal reflection
// and, where the material asks, the exact Fresnel in float), the same pruning by path weight.
// Its kernel is compiled with AVX2 and FMA (float_loop_avx2.cpp, entered only where the CPU has
// them); this interface is plain data, as the packet tracer's kernels are.
#pragma once

#include <cstdint>

namespace phonglab::float_loop {

struct Material {
  float ka[3], kd[3], ks[3], kr[3], kt[3];
  float n, ior;
  bool fresnel;
};
struct Sphere {
  float c[3], r;
  int material;
};
struct Plane {
  float p[3], n[3];
  int material;
};
struct Triangle {
  float v0[3], e1[3], e2[3];
  int material;
};
struct Light {
  bool point;
  float v[3];  // point: position; directional: the unit direction towards the light
  float intensity[3];
};
struct Scene {
  const Sphere* spheres;
  int sphere_count;
  const Plane* planes;
  int plane_count;
  const Triangle* triangles;
  int triangle_count;
  const Light* lights;
  int light_count;
  const Material* materials;
  float ambient[3], background[3];
  int max_depth;
  float min_weight;
  bool blinn;
  // The camera: origin, forward, right and up scaled as CameraFrame's, the image size.
  float eye[3], forward[3], right[3], up[3];
  int width, height;
};

// Whether this CPU runs the loop's AVX2/FMA build.
bool cpu_supported();

// Pixel-centre radiance of rows y0, y0 + step, ... into rgb (width * height * 3 floats, row-major
// from the top-left); rays cast are added to *rays.
void render_rows(const Scene& scene, int y0, int step, float* rgb, std::uint64_t* rays);

}  // namespace phonglab::float_loop
