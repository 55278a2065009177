// A scene made ready for rendering, once per snapshot: the file's data with its directions
// normalised, the accelerator built over its primitives and, for the bench only, an experiment.
// Immutable: an edit makes a new one, so no copy can carry a stale accelerator.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>

#include "core/geometry/geometry.h"
#include "core/scene/scene.h"

namespace phonglab {

class Experiment;  // core/shading/experiment.h

class PreparedScene {
 public:
  using AccelFactory = std::function<std::shared_ptr<const Accelerator>(const Scene&)>;

  // The production renderer's: the default accelerator (build_scene_accel), no experiment.
  explicit PreparedScene(Scene scene);
  // With the accelerator `make_accel` builds over the normalised scene (benchmarks, tests: a
  // forced BVH, Embree, the experiments' geometry), and optionally an experiment.
  PreparedScene(Scene scene, const AccelFactory& make_accel, std::shared_ptr<const Experiment> experiment = nullptr);

  // Copies and moves are new snapshots: each gets an id of its own.
  PreparedScene(const PreparedScene& other);
  PreparedScene(PreparedScene&& other) noexcept;
  PreparedScene& operator=(const PreparedScene& other);
  PreparedScene& operator=(PreparedScene&& other) noexcept;
  ~PreparedScene() = default;

  const Scene& scene() const { return scene_; }
  const Accelerator* accel() const { return accel_.get(); }  // null: queries test every primitive
  // The same accelerator, shared: a snapshot of the same geometry with another experiment (a
  // checked mistake) is prepared over it without building it again.
  const std::shared_ptr<const Accelerator>& shared_accel() const { return accel_; }
  const Experiment* experiment() const { return experiment_.get(); }  // null: the production renderer
  // The same scene and accelerator without the experiment (the production renderer's).
  PreparedScene without_experiment() const {
    PreparedScene twin(*this);
    twin.experiment_.reset();
    return twin;
  }
  // Unique to this object for the life of the program (what a tracer built for it, kept between
  // passes, is checked against, with its address).
  std::uint64_t id() const { return id_; }

 private:
  Scene scene_;
  std::shared_ptr<const Accelerator> accel_;
  std::shared_ptr<const Experiment> experiment_;
  std::uint64_t id_;
};

// Nearest hit with t in (0, t_max), through the accelerator when there is one.
std::optional<Hit> intersect(const PreparedScene& prepared, const Ray& ray,
                             double t_max = std::numeric_limits<double>::infinity());

// Whether anything lies on the ray with t in (0, t_max). Stops at the first hit found.
bool occluded(const PreparedScene& prepared, const Ray& ray, double t_max);

}  // namespace phonglab
