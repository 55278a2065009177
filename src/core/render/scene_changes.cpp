#include "core/render/scene_changes.h"

#include <algorithm>
#include <cstddef>

namespace phonglab {

namespace {

// The number of fields of an aggregate: the most initialisers T{...} accepts. A field added to
// Material, Light or Scene changes it, and the checks below fail until changes_between (and the
// scene writer) know what the field is.
struct AnyField {
  template <class U>
  operator U() const;  // never defined: only asked whether it converts
};
template <class T, class... Fields>
constexpr std::size_t field_count() {
  if constexpr (requires { T{Fields{}..., AnyField{}}; }) return field_count<T, Fields..., AnyField>();
  else return sizeof...(Fields);
}
static_assert(field_count<Material>() == 10, "a field added to Material: classify it in changes_between");
static_assert(field_count<Light>() == 5, "a field added to Light: classify it in changes_between");
static_assert(field_count<Scene>() == 20, "a field added to Scene: classify it in changes_between");

}  // namespace

Changes::Linear Changes::linear() const {
  if (retrace || limits_changed || depth_grew || eye_moved || model_changed || background_changed ||
      any(n_changed) || any(bounce_changed)) {
    return Linear::kNone;
  }
  if (any(light_moved)) {
    if (std::count(light_moved.begin(), light_moved.end(), true) > 1 || any(coefficients) || ambient_changed) {
      return Linear::kNone;
    }
    for (std::size_t l = 0; l < light_shading.size(); ++l) {
      if (light_shading[l] && !light_moved[l]) return Linear::kNone;  // another light's intensity with it
    }
    return Linear::kMovedLight;
  }
  const bool materials = any(coefficients), lights = any(light_shading);
  const int families = (materials ? 1 : 0) + (lights ? 1 : 0) + (ambient_changed ? 1 : 0);
  if (families > 1) return Linear::kNone;  // a product of two edited coefficients
  if (families == 0) return Linear::kMaterials;  // nothing changed: the trees' own image
  return materials ? Linear::kMaterials : lights ? Linear::kLights : Linear::kAmbient;
}

Changes changes_between(const Scene& a, const Scene& b) {
  Changes c;
  // Names, sources, object indices and the file's image size (a render is given its own) change
  // no pixel; everything else is compared.
  c.retrace = !(a.camera == b.camera) || a.spheres != b.spheres || a.planes != b.planes ||
              a.triangles != b.triangles || a.meshes != b.meshes || a.materials.size() != b.materials.size() ||
              a.lights.size() != b.lights.size();
  if (c.retrace) return c;
  for (std::size_t i = 0; i < b.lights.size(); ++i) {
    const Light& x = a.lights[i];
    const Light& y = b.lights[i];
    c.retrace = c.retrace || x.type != y.type;
    c.light_moved.push_back(x.position != y.position || x.direction != y.direction);
    c.light_shading.push_back(x.intensity != y.intensity || x.enabled != y.enabled);
  }
  for (std::size_t i = 0; i < b.materials.size(); ++i) {
    const Material& x = a.materials[i];
    const Material& y = b.materials[i];
    c.coefficients.push_back(x.ka != y.ka || x.kd != y.kd || x.ks != y.ks);
    c.material_shading.push_back(c.coefficients.back() || x.n != y.n);
    c.n_changed.push_back(x.n != y.n);
    c.bounce_changed.push_back(x.kr != y.kr || x.kt != y.kt || x.ior != y.ior || x.fresnel != y.fresnel);
    c.ior_changed.push_back(x.ior != y.ior);
  }
  c.limits_changed = a.max_depth != b.max_depth || a.min_weight != b.min_weight;
  c.depth_grew = b.max_depth > a.max_depth;
  c.model_changed = a.specular_model != b.specular_model;
  c.indirect_bounces_changed = a.indirect_bounces != b.indirect_bounces;
  c.ambient_changed = a.ambient != b.ambient;
  c.background_changed = a.background != b.background;
  return c;
}

bool indirect_unchanged(const Scene& a, const Scene& b) {
  const Changes c = changes_between(a, b);
  if (c.retrace || c.limits_changed || c.model_changed || c.background_changed || c.indirect_bounces_changed ||
      any(c.light_moved) || any(c.light_shading) || any(c.n_changed) || any(c.bounce_changed)) {
    return false;
  }
  for (std::size_t i = 0; i < b.materials.size(); ++i) {
    if (a.materials[i].kd != b.materials[i].kd || a.materials[i].ks != b.materials[i].ks) return false;
  }
  return true;
}

}  // namespace phonglab
