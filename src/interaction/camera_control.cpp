#include "interaction/camera_control.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <glm/gtc/constants.hpp>

#include "core/accel/accel.h"
#include "core/scene/camera.h"
#include "core/teaching/ray_tree_view.h"
#include "interaction/scene_objects.h"

namespace phonglab::ui {

namespace {

// Closest the view direction may come to the up vector, radians (about 0.6 degrees): keeps
// F x up well away from zero so the camera frame stays defined.
constexpr double kPoleMargin = 0.01;
// Smallest allowed camera-to-look_at distance relative to the scene's coordinates: far above
// double rounding, so normalize(look_at - position) stays accurate.
constexpr double kMinRelativeDistance = 1e-9;
// Widest vertical field of view fitting may give: a 1-pixel-wide window stays a usable camera.
constexpr double kMaxFittedFovDeg = 170;
// What F leaves free on each side of the framed objects: this fraction of the image's width or height.
constexpr double kFrameMargin = 0.04;
// How far the wheel may take the eye: this many times the scene's size (or the file's distance).
constexpr double kDollyLimitFactor = 20;

// Rodrigues' rotation of v about the unit axis k by `angle` radians.
Vec3 rotate_about(const Vec3& v, const Vec3& k, double angle) {
  const double c = std::cos(angle);
  const double s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1 - c);
}

double min_distance(const Camera& camera) {
  return kMinRelativeDistance * std::max(1.0, max_abs(camera.look_at));
}

}  // namespace

std::string camera_problem(const Camera& camera) {
  if (!all_finite(camera.position) || !all_finite(camera.look_at) || !all_finite(camera.up)) {
    return "every coordinate must be a finite number";
  }
  if (!(camera.fov_y_deg > 0 && camera.fov_y_deg < 180)) {
    std::ostringstream text;
    text << "fov y must be between 0 and 180 degrees (got " << camera.fov_y_deg << ")";
    return text.str();
  }
  const Vec3 view = camera.look_at - camera.position;
  const double distance = glm::length(view);
  if (!(distance > min_distance(camera))) return "look at must differ from the position";
  if (!(glm::length(camera.up) > 0)) return "up must not be the zero vector";
  if (!(view_up_sine(camera) > kMinViewUpSine)) return "up must not point along the view direction";
  return {};
}

bool camera_is_valid(const Camera& camera) { return camera_problem(camera).empty(); }

void orbit(Camera& camera, double yaw_rad, double pitch_rad) {
  const Vec3 up = glm::normalize(camera.up);
  Vec3 offset = camera.position - camera.look_at;
  const double distance = glm::length(offset);
  offset = rotate_about(offset, up, yaw_rad);
  // Polar angle of the camera measured from up; pitching towards up makes it smaller.
  const double polar = std::acos(clamp_unit(glm::dot(offset / distance, up)));
  const double new_polar = std::clamp(polar - pitch_rad, kPoleMargin, glm::pi<double>() - kPoleMargin);
  // Rotating about up x offset by a positive angle moves the eye away from up: turn by the
  // growth of the polar angle, so the clamp above is what the eye does.
  const Vec3 right = glm::normalize(glm::cross(up, offset));
  offset = rotate_about(offset, right, new_polar - polar);
  Camera moved = camera;
  moved.position = camera.look_at + offset;
  if (camera_is_valid(moved)) camera = moved;
}

void orbit_above(Camera& camera, double yaw_rad, double pitch_rad, const Vec3& floor_point, const Vec3& floor_normal) {
  const auto height = [&](const Camera& c) { return glm::dot(c.position - floor_point, floor_normal); };
  const double before = height(camera);
  Camera moved = camera;
  orbit(moved, yaw_rad, pitch_rad);
  // A hair above the floor at least (its scale: the eye's distance to look_at), or no lower than
  // it was when it was already that low.
  const double margin = 1e-3 * glm::length(camera.position - camera.look_at);
  if (before > 0 && height(moved) < std::min(margin, before)) {
    moved = camera;
    orbit(moved, yaw_rad, 0);
  }
  camera = moved;
}

void orbit_in(const Scene& scene, Camera& camera, double yaw_rad, double pitch_rad) {
  if (const std::optional<Floor> floor = find_floor(scene, camera)) {
    orbit_above(camera, yaw_rad, pitch_rad, floor->point, floor->normal);
  } else {
    orbit(camera, yaw_rad, pitch_rad);
  }
}

void dolly(Camera& camera, double factor, double max_distance) {
  if (!(factor > 0) || !std::isfinite(factor)) return;
  const Vec3 offset = camera.position - camera.look_at;
  const double distance = glm::length(offset);
  // A camera already beyond the limit may come closer but not go further.
  const double far = std::max(max_distance, distance);
  const double new_distance = std::clamp(distance * factor, 2 * min_distance(camera), far);
  Camera moved = camera;
  moved.position = camera.look_at + offset * (new_distance / distance);
  if (camera_is_valid(moved)) camera = moved;
}

void dolly_in(const PreparedScene& prepared, Camera& camera, double factor, double max_distance) {
  Camera moved = camera;
  dolly(moved, factor, max_distance);
  const double before = glm::length(camera.position - camera.look_at);
  const double step = before - glm::length(moved.position - camera.look_at);
  if (step > 0) {
    const Ray towards = make_ray(camera.position, glm::normalize(camera.look_at - camera.position));
    if (const std::optional<Hit> hit = intersect(prepared, towards, step + 0.01 * before)) {
      const double allowed = std::max(hit->t - 0.01 * before, 0.0);  // a hundredth short of the surface
      if (allowed < step) {
        moved = camera;
        moved.position = camera.position + towards.dir * allowed;
      }
    }
  }
  camera = moved;
}

void pan(Camera& camera, double dx_px, double dy_px, double viewport_height_px) {
  if (!(viewport_height_px > 0)) return;
  const Vec3 forward = glm::normalize(camera.look_at - camera.position);
  const Vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const Vec3 up = glm::cross(right, forward);
  const double distance = glm::length(camera.look_at - camera.position);
  // World units per pixel at the look-at point: the view is 2 tan(fov/2) distance tall.
  const double units_per_px = 2 * std::tan(glm::radians(camera.fov_y_deg) / 2) * distance / viewport_height_px;
  const Vec3 shift = (-dx_px * right + dy_px * up) * units_per_px;
  camera.position += shift;
  camera.look_at += shift;
}

bool frame_scene(Camera& camera, const Scene& scene, double aspect) {
  const Aabb bounds = scene_bounds(scene);
  if (bounds.empty()) return false;  // no finite objects (planes are infinite)
  const Vec3 center = 0.5 * (bounds.lo + bounds.hi);
  const Vec3 f = glm::normalize(camera.look_at - camera.position);
  const Vec3 right = glm::normalize(glm::cross(f, camera.up));
  const Vec3 up = glm::cross(right, f);
  // The view's half angles less a margin: the objects keep kFrameMargin of the image free
  // on each side.
  const double tan_y = std::tan(glm::radians(camera.fov_y_deg) / 2) * (1 - 2 * kFrameMargin);
  const double tan_x = tan_y * (aspect > 0 ? aspect : 1);
  const double hy = std::atan(tan_y), hx = std::atan(tan_x);
  // The eye at center + s R + t U - d F, looking along F. A ball of radius r at (x, y, z) in the
  // view's axes about the centre is inside the right side of half angle h when
  // d sin h + s cos h >= r + x cos h - z sin h, and inside the left side when
  // d sin h - s cos h >= r - x cos h - z sin h (likewise up and down with t). With A and B the
  // largest right sides of the two, d = (A + B) / (2 sin h) and s = (A - B) / (2 cos h) is the
  // nearest eye that keeps every object in: the objects then touch both sides.
  double right_need = -1e300, left_need = -1e300, top_need = -1e300, bottom_need = -1e300;
  const auto keep = [&](const Vec3& p, double r) {
    const Vec3 q = p - center;
    const double x = glm::dot(q, right), y = glm::dot(q, up), z = glm::dot(q, f);
    right_need = std::max(right_need, r + x * std::cos(hx) - z * std::sin(hx));
    left_need = std::max(left_need, r - x * std::cos(hx) - z * std::sin(hx));
    top_need = std::max(top_need, r + y * std::cos(hy) - z * std::sin(hy));
    bottom_need = std::max(bottom_need, r - y * std::cos(hy) - z * std::sin(hy));
  };
  for (const Sphere& s : scene.spheres) keep(s.center, s.radius);
  for (const Triangle& t : scene.triangles) {
    for (const Vec3& v : {t.v0, t.v1, t.v2}) keep(v, 0);
  }
  for (const Mesh& m : scene.meshes) {
    const Aabb& b = m.geometry->bounds;
    for (int corner = 0; corner < 8; ++corner) {
      keep(Vec3(corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y, corner & 4 ? b.hi.z : b.lo.z), 0);
    }
  }
  const double d = std::max({(right_need + left_need) / (2 * std::sin(hx)), (top_need + bottom_need) / (2 * std::sin(hy)),
                             1e-12 * std::max(1.0, glm::length(bounds.hi - bounds.lo))});
  const Vec3 eye = center + (right_need - left_need) / (2 * std::cos(hx)) * right +
                   (top_need - bottom_need) / (2 * std::cos(hy)) * up - d * f;
  Camera framed = camera;
  framed.position = eye;
  framed.look_at = eye + d * f;
  if (!camera_is_valid(framed)) return false;
  camera = framed;
  return true;
}

Camera fit_to_view(const Camera& camera, double framed_aspect, double view_aspect) {
  if (!(framed_aspect > 0) || !(view_aspect > 0) || view_aspect >= framed_aspect) return camera;
  Camera fitted = camera;
  const double half = std::tan(glm::radians(camera.fov_y_deg) / 2) * framed_aspect / view_aspect;
  fitted.fov_y_deg = std::min(glm::degrees(2 * std::atan(half)), kMaxFittedFovDeg);
  return fitted;
}

double dolly_limit(const Scene& scene, const Camera& loaded) {
  const Aabb bounds = scene_bounds(scene);
  const double radius = bounds.empty() ? 0 : 0.5 * glm::length(bounds.hi - bounds.lo);
  const double start = glm::length(loaded.position - loaded.look_at);
  return kDollyLimitFactor * std::max({radius, start, 1e-300});
}

double view_depth(const Camera& camera, const Vec3& p) {
  return glm::dot(p - camera.position, glm::normalize(camera.look_at - camera.position));
}

std::optional<ViewportPoint> project(const Camera& camera, const Vec3& p, int width, int height) {
  if (width <= 0 || height <= 0) return std::nullopt;
  // The ray tree's projection: the inverse of the renderer's camera formula, one definition.
  const auto at = project_point(make_camera_frame(camera, width, height), p);
  if (!at) return std::nullopt;
  return ViewportPoint{at->x, at->y};
}

Vec3 unproject(const Camera& camera, ViewportPoint pixel, double depth, int width, int height) {
  const CameraFrame frame = make_camera_frame(camera, std::max(width, 1), std::max(height, 1));
  const double sx = 2 * pixel.x / std::max(width, 1) - 1;
  const double sy = 1 - 2 * pixel.y / std::max(height, 1);
  return frame.origin + depth * (frame.forward + sx * frame.right + sy * frame.up);
}

}  // namespace phonglab::ui
