#include "apps/bench/bench_float.h"

#include <chrono>

#include "core/accel/accel.h"
#include "core/base/threads.h"
#include "core/scene/camera.h"

namespace phonglab {

bool float_loop::cpu_supported() {
#if defined(PHONGLAB_FLOAT_LOOP_AVX2)
  static const bool supported = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return supported;
#else
  return false;
#endif
}

namespace bench {

namespace {

void put(float* out, const Vec3& v) {
  out[0] = static_cast<float>(v.x);
  out[1] = static_cast<float>(v.y);
  out[2] = static_cast<float>(v.z);
}

float_loop::Triangle to_float(const Triangle& t) {
  float_loop::Triangle f{};
  put(f.v0, t.v0);
  put(f.e1, t.v1 - t.v0);
  put(f.e2, t.v2 - t.v0);
  f.material = t.material;
  return f;
}

}  // namespace

FloatLoop::FloatLoop(const Scene& scene, int width, int height) {
  for (const Sphere& s : scene.spheres) {
    float_loop::Sphere f{};
    put(f.c, s.center);
    f.r = static_cast<float>(s.radius);
    f.material = s.material;
    spheres_.push_back(f);
  }
  for (const Plane& p : scene.planes) {
    float_loop::Plane f{};
    put(f.p, p.point);
    put(f.n, glm::normalize(p.normal));
    f.material = p.material;
    planes_.push_back(f);
  }
  for (const Triangle& t : scene.triangles) triangles_.push_back(to_float(t));
  for (const Mesh& m : scene.meshes) {
    for (const Triangle& t : m.geometry->triangles) triangles_.push_back(to_float(t));
  }
  for (const Light& l : scene.lights) {
    if (!l.enabled) continue;
    float_loop::Light f{};
    f.point = l.type == LightType::kPoint;
    put(f.v, f.point ? l.position : -glm::normalize(l.direction));
    put(f.intensity, l.intensity);
    lights_.push_back(f);
  }
  for (const Material& m : scene.materials) {
    float_loop::Material f{};
    put(f.ka, m.ka);
    put(f.kd, m.kd);
    put(f.ks, m.ks);
    put(f.kr, m.kr);
    put(f.kt, m.kt);
    f.n = static_cast<float>(m.n);
    f.ior = static_cast<float>(m.ior);
    f.fresnel = m.fresnel;
    materials_.push_back(f);
  }
  scene_.spheres = spheres_.data();
  scene_.sphere_count = static_cast<int>(spheres_.size());
  scene_.planes = planes_.data();
  scene_.plane_count = static_cast<int>(planes_.size());
  scene_.triangles = triangles_.data();
  scene_.triangle_count = static_cast<int>(triangles_.size());
  scene_.lights = lights_.data();
  scene_.light_count = static_cast<int>(lights_.size());
  scene_.materials = materials_.data();
  put(scene_.ambient, scene.ambient);
  put(scene_.background, scene.background);
  scene_.max_depth = scene.max_depth;
  scene_.min_weight = static_cast<float>(scene.min_weight);
  scene_.blinn = scene.specular_model == SpecularModel::kBlinn;
  const CameraFrame cam = make_camera_frame(scene.camera, width, height);
  put(scene_.eye, cam.origin);
  put(scene_.forward, cam.forward);
  put(scene_.right, cam.right);
  put(scene_.up, cam.up);
  scene_.width = width;
  scene_.height = height;
}

FloatLoop::Frame FloatLoop::frame(int threads) const {
  Frame f;
  f.rgb.assign(static_cast<std::size_t>(scene_.width) * static_cast<std::size_t>(scene_.height) * 3, 0.0f);
  std::vector<std::uint64_t> rays(static_cast<std::size_t>(std::max(1, threads)), 0);
  const auto t0 = std::chrono::steady_clock::now();
  run_workers(threads, [&](int i) {
    float_loop::render_rows(scene_, i, std::max(1, threads), f.rgb.data(), &rays[static_cast<std::size_t>(i)]);
  });
  f.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  for (const std::uint64_t r : rays) f.rays += r;
  return f;
}

}  // namespace bench
}  // namespace phonglab
