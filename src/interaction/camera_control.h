// Camera manipulation for the viewport: orbit, dolly, pan, framing, and the projection of
// world points to viewport pixels (light markers) and back (dragging a light). Pure math on
// the scene's Camera; no ImGui, no GL.
#pragma once

#include "core/accel/prepared_scene.h"

#include <limits>
#include <optional>
#include <string>

#include "core/scene/scene.h"

namespace phonglab::ui {

// Whether the renderer can use the camera: position apart from look_at, up not parallel to
// the view direction, fov_y in (0, 180). Edits that would break it are refused.
bool camera_is_valid(const Camera& camera);
// Why the renderer cannot use the camera ("fov y must be between 0 and 180 degrees (got 0)"), or
// empty when it can: one rule with camera_is_valid.
std::string camera_problem(const Camera& camera);

// Turns the camera about look_at: `yaw_rad` about the up vector, `pitch_rad` towards up
// (positive looks more from above); stops short of the poles so up never aligns with the view.
void orbit(Camera& camera, double yaw_rad, double pitch_rad);
// orbit, but an eye above the floor (the plane through `floor_point` with normal
// `floor_normal`) is never taken under it: a pitch that would is dropped, the yaw kept. A student's
// drag must not leave the room through its floor (an eye under it sees the floor's back: nothing).
void orbit_above(Camera& camera, double yaw_rad, double pitch_rad, const Vec3& floor_point, const Vec3& floor_normal);
// The hand's orbit in a scene: orbit_above its floor (find_floor), plain orbit without one. The
// desktop's drag and the page's.
void orbit_in(const Scene& scene, Camera& camera, double yaw_rad, double pitch_rad);

// Scales the distance from look_at by `factor` (< 1 moves closer), never reaching look_at and
// never beyond `max_distance` (a camera already beyond it may only come closer).
void dolly(Camera& camera, double factor, double max_distance = std::numeric_limits<double>::infinity());
// The hand's dolly in a scene: dolly, but coming closer the eye stops short of the first surface
// between it and look_at (by a hundredth of its distance to it), so the wheel never takes the eye
// inside an object (where a sphere's inside is all one sees).
void dolly_in(const PreparedScene& prepared, Camera& camera, double factor,
              double max_distance = std::numeric_limits<double>::infinity());

// The dolly's far limit for a scene: 20 times the larger of its finite objects' bounding radius and
// the distance of the camera it was loaded with.
double dolly_limit(const Scene& scene, const Camera& loaded);

// The camera a view of `view_aspect` (width / height) renders with: `camera` itself when the view
// is at least as wide as `framed_aspect` (the scene file's image), else with its vertical field of
// view widened so that the horizontal extent of the framed image stays in view.
Camera fit_to_view(const Camera& camera, double framed_aspect, double view_aspect);

// Slides position and look_at in the view plane so the point under the cursor follows a
// drag of (dx_px, dy_px) in a viewport `viewport_height_px` pixels tall.
void pan(Camera& camera, double dx_px, double dy_px, double viewport_height_px);

// Aims at the centre of the finite objects' bounds (spheres, triangles, meshes) along the view
// direction, from the nearest distance that keeps every object inside a view of this aspect
// (width / height) with a small margin. False, camera unchanged, when there are none.
bool frame_scene(Camera& camera, const Scene& scene, double aspect);

// A viewport position in pixels, x right and y down from the top-left.
struct ViewportPoint {
  double x = 0;
  double y = 0;
};

// Where world point `p` appears in a width x height viewport; nothing when it is behind
// the camera.
std::optional<ViewportPoint> project(const Camera& camera, const Vec3& p, int width, int height);

// Distance of `p` in front of the camera along the view direction.
double view_depth(const Camera& camera, const Vec3& p);

// The world point `depth` in front of the camera (along the view direction) that appears at
// `pixel`: moving a light there keeps it in the camera's view plane.
Vec3 unproject(const Camera& camera, ViewportPoint pixel, double depth, int width, int height);

}  // namespace phonglab::ui
