#include "core/shading/shading.h"

#include "core/accel/accel.h"
#include "experiments/numerics_variants.h"

namespace phonglab {

void prepare_scene(Scene& scene) {
  for (Plane& pl : scene.planes) pl.normal = glm::normalize(pl.normal);
  for (Light& l : scene.lights) {
    if (l.type == LightType::kDirectional) l.direction = glm::normalize(l.direction);
  }
  scene.accel = build_scene_accel(scene);
}

double fresnel_exact(double cos_i, double eta) {
  cos_i = clamp_unit(cos_i);
  const double sin2_t = eta * eta * (1 - cos_i * cos_i);
  if (sin2_t >= 1) return 1;  // total internal reflection
  const double cos_t = std::sqrt(1 - sin2_t);
  // Amplitude ratios for s and p polarisation, divided through by n_transmitted.
  const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double f = 0.5 * (rs * rs + rp * rp);
  return f > 1 ? 1 : (f < 0 ? 0 : f);
}

Bounce bounce(const Scene& scene, const Material& m, const Vec3& d, const Vec3& n, bool entering,
              bool force_refraction) {
  Bounce b;
  const double cos_i = clamp_unit(-glm::dot(d, n));
  b.eta = entering ? 1.0 / m.ior : m.ior;
  const double k = 1 - b.eta * b.eta * (1 - cos_i * cos_i);
  b.tir = k < 0;
  if (uses_fresnel(m)) {
    b.fresnel = b.tir ? 1.0
                      : (scene.numerics.schlick_fresnel ? fresnel_schlick(cos_i, b.eta) : fresnel_exact(cos_i, b.eta));
  }
  set_bounce_weights(m, b);
  b.mirror = reflect_dir(d, n);
  if (!is_zero(b.kt) || force_refraction) {
    b.refracted = b.tir ? b.mirror : glm::normalize(b.eta * d + (b.eta * cos_i - std::sqrt(k)) * n);
  }
  return b;
}

namespace {

// What blocks a shadow ray, for the probe only.
struct Occluder {
  ObjectRef object;     // nearest blocker, none when the light is visible
  double distance = 0;  // from the shaded point P to the blocker's hit
};

// The nearest object strictly between the ends of a shadow ray from P (for the probe only).
Occluder find_occluder(const Scene& scene, const Ray& ray, double t_max, const Vec3& p) {
  if (auto hit = intersect(scene, ray, t_max)) return Occluder{hit->object, glm::length(hit->p - p)};
  return {};
}

// Shadow ray for one light from a surface point. Returns vis_l. Always inlined: shade's light
// loop is the hot path, and the bench ablation's second call site must not move it out of line.
[[gnu::always_inline]] inline bool light_visible(const Scene& scene, const Light& light, const Hit& hit, const Vec3& ng_facing,
                   const Vec3& l, double offset, RayCounts& counts, Occluder* occluder) {
  ++counts.shadow;
  const Vec3 origin = offset_origin(hit.p, ng_facing, l, offset);
  if (light.type == LightType::kDirectional) {
    const Ray ray = make_ray(origin, l);
    const double t_max = std::numeric_limits<double>::infinity();
    if (occluder) *occluder = find_occluder(scene, ray, t_max, hit.p);
    return !occluded(scene, ray, t_max);
  }
  // The open segment to the light, pulled in at the light's end by the same relative amount
  // as the origin is pushed off the surface: a light lying on a surface does not shadow itself.
  const Vec3 to_light = light.position - origin;
  const double dist = glm::length(to_light);
  const double t_max = dist - surface_offset(light.position, 0);
  if (!(t_max > 0)) return true;  // the light is within rounding distance of the surface
  const Ray ray = make_ray(origin, to_light / dist);
  if (occluder) *occluder = find_occluder(scene, ray, t_max, hit.p);
  return !occluded(scene, ray, t_max);
}

}  // namespace

Terms shade(const Scene& scene, const TraceLimits& limits, const Ray& ray, const Hit& hit, int depth,
            double weight, RayCounts& counts, ProbeNode* probe, const Vec3* shading_eye,
            const TermsWanted& wanted) {
  const Material& m = scene.materials[hit.material];
  const Vec3& d = ray.dir;
  const HitSide side = hit_side(hit, d);
  const bool entering = side.entering;
  const Vec3& ng_facing = side.ng;
  const Vec3& n = side.n;
  // V: towards the real eye (-D), or towards a moved eye ("move your head"); an eye exactly at
  // P has no direction and falls back to -D.
  Vec3 v = -d;
  if (shading_eye) {
    const Vec3 to_eye = *shading_eye - hit.p;
    const double len = glm::length(to_eye);
    if (len > 0) v = to_eye / len;
  }
  const double offset =
      scene.numerics.fixed_offset > 0 ? scene.numerics.fixed_offset : surface_offset(scene, hit);

  Terms terms;
  terms.ambient = m.ka * scene.ambient;
  if (probe) {
    probe->hit = true;
    probe->t = hit.t;
    probe->p = hit.p;
    probe->ng = hit.ng;
    probe->n = n;
    probe->v = v;
    probe->entering = entering;
    probe->material = hit.material;
    probe->object = hit.object;
  }

  // Local term: lights are skipped where no term can come back (kd = ks = 0, N.L <= 0).
  const bool has_diffuse = !is_zero(m.kd);
  const bool has_specular = !is_zero(m.ks);
  if (wanted.lights && (has_diffuse || has_specular || probe)) {
    for (std::size_t li = 0; li < scene.lights.size(); ++li) {
      const Light& light = scene.lights[li];
      if (!light.enabled) continue;
      Vec3 l;
      double dist = std::numeric_limits<double>::infinity();
      if (light.type == LightType::kPoint) {
        const Vec3 to_light = light.position - hit.p;
        dist = glm::length(to_light);
        if (!(dist > 0)) continue;  // light exactly at the point: no direction, no light
        l = to_light / dist;
      } else {
        l = -light.direction;
      }
      const double n_dot_l = glm::dot(n, l);
      ProbeLight* pl = nullptr;
      if (probe) {
        pl = &probe->lights.emplace_back();
        pl->index = static_cast<int>(li);
        pl->l = l;
        pl->n_dot_l = n_dot_l;
        pl->distance = dist;
      }
      if (!(n_dot_l > 0)) {  // light behind the surface: neither diffuse nor specular
        if (scene.numerics.shadow_rays_behind) [[unlikely]]  // bench ablation: a ray for nothing
          light_visible(scene, light, hit, ng_facing, l, offset, counts, nullptr);
        continue;
      }
      if (!has_diffuse && !has_specular && !probe) continue;

      double spec = 0;
      if (has_specular || probe) {
        double cos_spec;
        Vec3 r;
        if (scene.specular_model == SpecularModel::kPhong) {
          r = 2.0 * n_dot_l * n - l;
          cos_spec = glm::dot(r, v);
        } else {
          const Vec3 h = l + v;
          const double len = glm::length(h);
          r = len > 0 ? h / len : n;  // L = -V only at grazing: any H then gives N.H <= 0
          cos_spec = len > 0 ? glm::dot(n, r) : 0;
        }
        spec = specular_factor(cos_spec, m.n);
        if (pl) {
          pl->r = r;
          pl->r_dot_v = cos_spec;
          pl->spec_factor = spec;
        }
      }
      Occluder occluder;
      const bool visible =
          light_visible(scene, light, hit, ng_facing, l, offset, counts, probe ? &occluder : nullptr);
      if (pl) {
        pl->lit_side = true;
        pl->visible = visible;
        pl->occluder = occluder.object;
        pl->occluder_distance = occluder.distance;
      }
      if (!visible) continue;
      const Color diffuse = light.intensity * m.kd * n_dot_l;
      const Color specular = light.intensity * m.ks * spec;
      terms.diffuse += diffuse;
      terms.specular += specular;
      if (pl) {
        pl->diffuse = diffuse;
        pl->specular = specular;
      }
    }
  }

  // Recursion for mirrors and glass.
  // Bench ablation: also a refraction ray for opaque materials (kt = 0), as a naive tracer casts.
  const bool force_refraction = scene.numerics.refraction_for_opaque && is_zero(m.kt);
  if (depth < limits.max_depth && (!is_zero(m.kr) || !is_zero(m.kt) || force_refraction)) {
    const Bounce bn = bounce(scene, m, d, n, entering, force_refraction);
    const Color& kr = bn.kr;
    const Color& kt = bn.kt;
    if (probe) {
      probe->kr_eff = kr;
      probe->kt_eff = kt;
      probe->fresnel = bn.fresnel;
      probe->tir = bn.tir;
      probe->eta = bn.eta;
    }
    // One child ray with weight k along dir; nothing when k = 0 or the path weight is too low.
    auto child = [&](const Color& kw, const Vec3& dir, std::uint64_t& count,
                     std::unique_ptr<ProbeNode>& probe_child) -> Color {
      if (is_zero(kw)) return Color(0);
      const double w = weight * max_channel(kw);
      if (w < limits.min_weight) return Color(0);
      ++count;
      if (probe) probe_child = std::make_unique<ProbeNode>();
      const Ray ray_out = make_ray(offset_origin(hit.p, ng_facing, dir, offset), dir);
      return kw * trace(scene, limits, ray_out, depth + 1, w, counts, probe_child.get());
    };
    std::unique_ptr<ProbeNode> no_probe;
    if (wanted.reflection) terms.reflection = child(kr, bn.mirror, counts.reflection, probe ? probe->reflection : no_probe);
    if (wanted.refraction && (!is_zero(kt) || force_refraction)) {
      const Vec3& dir = bn.refracted;
      if (!is_zero(kt)) {
        terms.refraction = child(kt, dir, counts.refraction, probe ? probe->refraction : no_probe);
      } else {  // the ablation: traced at the parent's path weight, and multiplied by kt' = 0
        ++counts.refraction;
        const Ray ray_out = make_ray(offset_origin(hit.p, ng_facing, dir, offset), dir);
        terms.refraction = kt * trace(scene, limits, ray_out, depth + 1, weight, counts);
      }
    }
  }
  if (probe) {
    probe->terms = terms;
    probe->total = terms.sum();
  }
  return terms;
}

Color trace(const Scene& scene, const TraceLimits& limits, const Ray& ray, int depth, double weight,
            RayCounts& counts, ProbeNode* probe, const Vec3* shading_eye) {
  if (probe) {
    probe->depth = depth;
    probe->weight = weight;
    probe->origin = ray.origin;
    probe->dir = ray.dir;
  }
  const std::optional<Hit> hit = intersect(scene, ray);
  if (!hit) {
    if (probe) probe->total = scene.background;
    return scene.background;
  }
  return shade(scene, limits, ray, *hit, depth, weight, counts, probe, shading_eye).sum();
}

}  // namespace phonglab
