#include "core/scene/camera.h"

#include <cmath>

#include "core/scene/hash.h"

namespace phonglab {

double view_up_sine(const Camera& camera) {
  return glm::length(glm::cross(glm::normalize(camera.look_at - camera.position), glm::normalize(camera.up)));
}

CameraFrame make_camera_frame(const Camera& camera, int width, int height) {
  CameraFrame f;
  f.width = width;
  f.height = height;
  f.origin = camera.position;
  f.forward = glm::normalize(camera.look_at - camera.position);
  const Vec3 right = glm::normalize(glm::cross(f.forward, camera.up));
  const Vec3 up = glm::cross(right, f.forward);
  const double h = std::tan(glm::radians(camera.fov_y_deg) / 2);
  f.right = right * (h * width / height);
  f.up = up * h;
  return f;
}

Ray camera_ray(const CameraFrame& f, int x, int y, double u, double v) {
  const double sx = 2 * (x + u) / f.width - 1;
  const double sy = 1 - 2 * (y + v) / f.height;
  return make_ray(f.origin, glm::normalize(f.forward + sx * f.right + sy * f.up));
}

namespace {

double fract(double x) { return x - std::floor(x); }

}  // namespace

void sample_offset_r2(int x, int y, std::uint32_t index, double& u, double& v, std::uint32_t seed) {
  // R2 sequence (Roberts 2018): alpha = (1/g, 1/g^2) with g the plastic number.
  constexpr double kA1 = 0.7548776662466927;
  constexpr double kA2 = 0.5698402909980532;
  const std::uint32_t h = hash32(static_cast<std::uint32_t>(x) * 0x9E3779B1U ^
                                 hash32(static_cast<std::uint32_t>(y) ^ hash32(seed)));
  const double rot_u = (h & 0xFFFFU) / 65536.0;
  const double rot_v = (h >> 16) / 65536.0;
  u = fract(0.5 + rot_u + kA1 * index);
  v = fract(0.5 + rot_v + kA2 * index);
}

Vec3 head_eye(const Camera& camera, const Vec3& pivot, double angle_deg) {
  const CameraFrame frame = make_camera_frame(camera, 1, 1);
  const Vec3 axis = glm::normalize(frame.up);
  const Vec3 d = camera.position - pivot;
  const double a = -glm::radians(angle_deg);  // about up, counter-clockwise seen from above: right is negative
  // Rodrigues' rotation of d about the axis.
  const Vec3 rotated = d * std::cos(a) + glm::cross(axis, d) * std::sin(a) + axis * glm::dot(axis, d) * (1 - std::cos(a));
  return pivot + rotated;
}

}  // namespace phonglab
