// The door through which an experiment changes the equation: the bench's numerics and ablations
// (src/experiments/), and a student's work checked against the reference (src/check/: a typed
// formula in place of a local term, a known mistake). The production renderer has none
// (PreparedScene::experiment() is null) and its code never asks for one: trace and shade pick,
// once per call from outside, an instantiation of the equation compiled with or without these
// hooks. Geometry experiments come in through the accelerator instead (PreparedScene's factory).
#pragma once

#include <cstddef>

#include "core/geometry/geometry.h"
#include "core/scene/scene.h"
#include "core/shading/shading.h"

namespace phonglab {

// What the local terms read at one hit and light (the names of a student's formula).
struct LocalHit {
  const Scene* scene = nullptr;
  const Material* material = nullptr;
  const Light* light = nullptr;  // null for the ambient term
  Vec3 p{0}, n{0}, l{0}, v{0};   // P, the facing shading normal N, L (0 for ambient), V
  double n_dot_l = 0;            // N.L (> 0 where the light terms are evaluated)
  double spec = 0;               // the production specular factor under the scene's model
};

class Experiment {
 public:
  virtual ~Experiment() = default;
  // F of a dielectric for cos_i = -D.N, eta = n_incident / n_transmitted (fresnel_exact in production).
  virtual double fresnel(double cos_i, double eta) const { return fresnel_exact(cos_i, eta); }
  // How far a secondary ray leaving `hit` starts off the surface (surface_offset in production).
  virtual double offset(const Scene& scene, const Hit& hit) const { return surface_offset(scene, hit); }
  // Cast shadow rays to lights behind the surface too (N.L <= 0), for nothing.
  virtual bool shadow_rays_behind() const { return false; }
  // Trace a refraction ray for opaque materials (kt = 0) too, multiplied by kt' = 0.
  virtual bool refraction_for_opaque() const { return false; }

  // The local terms. The ambient term at a hit (production: ka·Ia).
  virtual Color ambient(const LocalHit& h) const { return h.material->ka * h.scene->ambient; }
  // One visible light's diffuse and specular shares, I_l included (production: light_share).
  virtual LightShare light_share(const LocalHit& h) const {
    return phonglab::light_share(*h.light, *h.material, h.n_dot_l, h.spec);
  }
  // Whether the light terms are evaluated at a hit of m (production: kd or ks non-zero; a typed
  // formula may light what the reference leaves dark).
  virtual bool lit(const Material& m) const { return is_lit(m); }
  // Whether shadow rays are cast (false: every light is visible).
  virtual bool shadows() const { return true; }
  // Whether a refracting hit takes eta the wrong way round: ior entering, 1 / ior leaving.
  virtual bool eta_inverted() const { return false; }

  // Whether the experiment changes the local terms alone (ambient, light_share, lit): every ray,
  // hit and shadow ray is production's, so an image is re-shaded from ray trees recorded without
  // it (RayTrees::reshade), which asks for the terms many hits at a time below.
  virtual bool local_terms_only() const { return false; }
  // ambient() and light_share() of `count` hits at once (a formula evaluates them lane by lane).
  virtual void ambient_batch(const LocalHit* hits, std::size_t count, Color* out) const {
    for (std::size_t i = 0; i < count; ++i) out[i] = ambient(hits[i]);
  }
  virtual void light_share_batch(const LocalHit* hits, std::size_t count, LightShare* out) const {
    for (std::size_t i = 0; i < count; ++i) out[i] = light_share(hits[i]);
  }
};

}  // namespace phonglab
