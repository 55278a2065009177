// Pinhole camera rays and per-pixel sample positions (docs/model.md, camera and samples).
#pragma once

#include <cstdint>

#include "core/scene/math.h"
#include "core/scene/scene.h"

namespace phonglab {

// The camera's frame for one image size, computed once per pass.
struct CameraFrame {
  Vec3 origin;
  Vec3 forward;   // F
  Vec3 right;     // R, scaled by h * W / H
  Vec3 up;        // U, scaled by h
  int width = 1;  // W, pixels
  int height = 1; // H, pixels
};

// Up must not be parallel to the view direction: |normalize(F) x normalize(up)| must exceed this
// (one rule for the scene loader and the previewer's camera edits).
inline constexpr double kMinViewUpSine = 1e-9;

// |normalize(look_at - position) x normalize(up)|, computed on the normalised vectors so nothing
// under- or overflows; for a camera whose view vector and up are non-zero and finite.
double view_up_sine(const Camera& camera);

// F = normalize(look_at - position), R = normalize(F x up), U = R x F, h = tan(fov_y / 2).
CameraFrame make_camera_frame(const Camera& camera, int width, int height);

// "Move your head": the camera position turned by `angle_deg` about the camera's up axis
// (orthogonal to the view) around `pivot` (the probed point): the eye used for V in shading,
// at the same distance from the pivot. Positive turns to the viewer's right.
Vec3 head_eye(const Camera& camera, const Vec3& pivot, double angle_deg);

// The primary ray through image point (x + u, y + v); pixel (0, 0) is the top-left.
Ray camera_ray(const CameraFrame& frame, int x, int y, double u, double v);

// Offset (u, v) in [0, 1)^2 of sample `index` of pixel (x, y). Sample 0 is the centre
// (0.5, 0.5); later samples follow the R2 low-discrepancy sequence, rotated per pixel by a
// hash of (x, y, seed) so neighbouring pixels do not share a pattern. Depends on nothing
// else. Other seeds give independent sample sets (for error statistics); 0 is the default.
void sample_offset_r2(int x, int y, std::uint32_t index, double& u, double& v, std::uint32_t seed);  // index > 0
inline void sample_offset(int x, int y, std::uint32_t index, double& u, double& v, std::uint32_t seed = 0) {
  if (index == 0) {
    u = v = 0.5;
    return;
  }
  sample_offset_r2(x, y, index, u, v, seed);
}

}  // namespace phonglab
