// The door through which the bench's experiments (src/experiments/) change the equation's
// numerics or add the work the production renderer spares. The production renderer has none
// (PreparedScene::experiment() is null) and its code never asks for one: trace and shade pick,
// once per call from outside, an instantiation of the equation compiled with or without these
// hooks. Geometry experiments come in through the accelerator instead (PreparedScene's factory).
#pragma once

#include "core/geometry/geometry.h"
#include "core/scene/scene.h"

namespace phonglab {

class Experiment {
 public:
  virtual ~Experiment() = default;
  // F of a dielectric for cos_i = -D.N, eta = n_incident / n_transmitted (fresnel_exact in production).
  virtual double fresnel(double cos_i, double eta) const = 0;
  // How far a secondary ray leaving `hit` starts off the surface (surface_offset in production).
  virtual double offset(const Scene& scene, const Hit& hit) const = 0;
  // Cast shadow rays to lights behind the surface too (N.L <= 0), for nothing.
  virtual bool shadow_rays_behind() const = 0;
  // Trace a refraction ray for opaque materials (kt = 0) too, multiplied by kt' = 0.
  virtual bool refraction_for_opaque() const = 0;
};

}  // namespace phonglab
