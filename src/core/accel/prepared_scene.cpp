#include "core/accel/prepared_scene.h"

#include <atomic>
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

std::uint64_t next_id() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

}  // namespace

PreparedScene::PreparedScene(Scene scene)
    : scene_(normalised(std::move(scene))), accel_(build_scene_accel(scene_)), id_(next_id()) {}

PreparedScene::PreparedScene(Scene scene, const AccelFactory& make_accel, std::shared_ptr<const Experiment> experiment)
    : scene_(normalised(std::move(scene))),
      accel_(make_accel ? make_accel(scene_) : build_scene_accel(scene_)),
      experiment_(std::move(experiment)),
      id_(next_id()) {}

PreparedScene::PreparedScene(const PreparedScene& other)
    : scene_(other.scene_), accel_(other.accel_), experiment_(other.experiment_), id_(next_id()) {}

PreparedScene::PreparedScene(PreparedScene&& other) noexcept
    : scene_(std::move(other.scene_)),
      accel_(std::move(other.accel_)),
      experiment_(std::move(other.experiment_)),
      id_(next_id()) {
  other.id_ = next_id();  // what is left of it is another (empty) scene
}

PreparedScene& PreparedScene::operator=(const PreparedScene& other) {
  if (this != &other) {
    scene_ = other.scene_;
    accel_ = other.accel_;
    experiment_ = other.experiment_;
    id_ = next_id();
  }
  return *this;
}

PreparedScene& PreparedScene::operator=(PreparedScene&& other) noexcept {
  scene_ = std::move(other.scene_);
  accel_ = std::move(other.accel_);
  experiment_ = std::move(other.experiment_);
  id_ = next_id();
  other.id_ = next_id();
  return *this;
}

std::optional<Hit> intersect(const PreparedScene& prepared, const Ray& ray, double t_max) {
  if (const Accelerator* accel = prepared.accel()) return accel->intersect(prepared.scene(), ray, t_max);
  return intersect_all(prepared.scene(), ray, t_max);
}

bool occluded(const PreparedScene& prepared, const Ray& ray, double t_max) {
  if (const Accelerator* accel = prepared.accel()) return accel->occluded(prepared.scene(), ray, t_max);
  return occluded_all(prepared.scene(), ray, t_max);
}

}  // namespace phonglab
