#include "core/accel/prepared_scene.h"

#include <utility>

#include "core/accel/accel.h"

namespace phonglab {

namespace {

// Unit plane normals and directional-light directions, as the equation takes them.
Scene normalised(Scene scene) {
  for (Plane& pl : scene.planes) pl.normal = glm::normalize(pl.normal);
  for (Light& l : scene.lights) {
    if (l.type == LightType::kDirectional) l.direction = glm::normalize(l.direction);
  }
  return scene;
}

}  // namespace

PreparedScene::PreparedScene(Scene scene) : scene_(normalised(std::move(scene))), accel_(build_scene_accel(scene_)) {}

PreparedScene::PreparedScene(Scene scene, const AccelFactory& make_accel, std::shared_ptr<const Experiment> experiment)
    : scene_(normalised(std::move(scene))),
      accel_(make_accel ? make_accel(scene_) : build_scene_accel(scene_)),
      experiment_(std::move(experiment)) {}

std::optional<Hit> intersect(const PreparedScene& prepared, const Ray& ray, double t_max) {
  if (const Accelerator* accel = prepared.accel()) return accel->intersect(prepared.scene(), ray, t_max);
  return intersect_all(prepared.scene(), ray, t_max);
}

bool occluded(const PreparedScene& prepared, const Ray& ray, double t_max) {
  if (const Accelerator* accel = prepared.accel()) return accel->occluded(prepared.scene(), ray, t_max);
  return occluded_all(prepared.scene(), ray, t_max);
}

}  // namespace phonglab
