#include "core/shading/shading.h"

#include "core/shading/experiment.h"

#include <array>

namespace phonglab {

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

namespace {

// What blocks a shadow ray, for the probe only.
struct Occluder {
  ObjectRef object;     // nearest blocker, none when the light is visible
  double distance = 0;  // from the shaded point P to the blocker's hit
};

// The probe's record of a hit: where, which normals, which V.
void record_hit(ProbeNode& probe, const Hit& hit, const HitSide& side, const Vec3& v) {
  probe.hit = true;
  probe.t = hit.t;
  probe.p = hit.p;
  probe.ng = hit.ng;
  probe.n = side.n;
  probe.v = v;
  probe.entering = side.entering;
  probe.material = hit.material;
  probe.object = hit.object;
}

// The equation, compiled twice. Equation<false> is the production renderer: it never asks for
// an experiment, and the hooks below fold to the production rules. Equation<true> routes them
// through prepared.experiment() (the bench's ablations and numerics, core/shading/experiment.h).
template <bool kExperiment>
class Equation {
 public:
  Equation(const PreparedScene& prepared, const TraceLimits& limits, RayCounts& counts,
           TraceRecorder* recorder = nullptr, IndirectSampler* indirect = nullptr)
      : prepared_(prepared),
        scene_(prepared.scene()),
        limits_(limits),
        counts_(counts),
        recorder_(recorder),
        indirect_(indirect) {}

  Color trace(const Ray& ray, int depth, double weight, ProbeNode* probe, const Vec3* shading_eye) {
    if (probe) {
      probe->depth = depth;
      probe->weight = weight;
      probe->origin = ray.origin;
      probe->dir = ray.dir;
    }
    const std::optional<Hit> hit = intersect(prepared_, ray);
    if (!hit) {
      if (probe) probe->total = scene_.background;
      if (recorder_) recorder_->ray_missed();
      return scene_.background;
    }
    return shade(ray, *hit, depth, weight, probe, shading_eye, TermsWanted{}).sum();
  }

  Terms shade(const Ray& ray, const Hit& hit, int depth, double weight, ProbeNode* probe, const Vec3* shading_eye,
              const TermsWanted& wanted) {
    const Material& m = scene_.materials[hit.material];
    const HitSide side = hit_side(hit, ray.dir);
    const Vec3 v = view_direction(hit.p, ray.dir, shading_eye);
    const double offset = offset_of(hit);
    Terms terms;
    terms.ambient = indirect_ ? tree_gather(m, hit.p, side, offset) : ambient(m, hit, side, v);
    if (probe) record_hit(*probe, hit, side, v);
    if (recorder_) recorder_->begin_hit(ray, hit, side, offset, depth);
    // Lights are skipped where no term can come back (kd = ks = 0, N.L <= 0); a recorder of ray
    // trees is told of every light, so that a later edit of kd, ks or a mute needs no new rays.
    if (wanted.lights && (lit(m) || probe || recorder_)) {
      light_terms(m, hit, side, v, offset, probe, terms);
    }
    mirror_and_glass_terms(m, ray, hit, side, depth, weight, offset, probe, wanted, terms);
    if (recorder_) recorder_->end_hit();
    if (probe) {
      probe->terms = terms;
      probe->total = terms.sum();
    }
    return terms;
  }

  // The indirect term's estimate at P (indirect_estimate in shading.h): one gather ray.
  Color gather(const Material& m, const Vec3& p, const HitSide& side, double offset) {
    if (indirect_->bounces_left() <= 0 || is_zero(m.kd)) return Color(0);
    double u1 = 0, u2 = 0;
    indirect_->next_point(u1, u2);
    const Vec3 dir = cosine_direction(side.n, u1, u2);
    ++counts_.indirect;
    // What a camera at P looking along the direction sees: a primary ray's radiance, one bounce
    // fewer, estimated along one path (trace_path).
    indirect_->descend();
    const Color in = trace_path(make_ray(offset_origin(p, side.ng, dir, offset), dir), 0, 1.0);
    indirect_->ascend();
    return m.kd * in;
  }

  // An unbiased estimate of trace()'s radiance with the indirect term in ka·Ia's place, along one
  // path: at each hit the direct light (the lights' diffuse and specular terms, every shadow ray)
  // and at most one of the ways on: a gather (kd ⊙ E, while bounces are left), the reflected or
  // the refracted child (kr', kt', where trace() would trace them: the same depth and path-weight
  // limits), chosen by pick_way and divided by its chance. The full tree would follow every way
  // at every hit, and gathers at its hits again: work growing as (ways at a hit)^(bounces x
  // depth) on a scene with a mirror and glass; one way a hit keeps a gather's cost its path's.
  Color trace_path(const Ray& ray, int depth, double weight) {
    const std::optional<Hit> hit = intersect(prepared_, ray);
    if (!hit) return scene_.background;
    const Material& m = scene_.materials[hit->material];
    const HitSide side = hit_side(*hit, ray.dir);
    const double offset = offset_of(*hit);
    Terms terms;
    if (lit(m)) light_terms(m, *hit, side, view_direction(hit->p, ray.dir, nullptr), offset, nullptr, terms);
    Color result = terms.diffuse + terms.specular;

    std::array<Way, 3> ways{};
    std::size_t count = 0;
    if (indirect_->bounces_left() > 0 && !is_zero(m.kd)) ways[count++] = Way{WayKind::kGather, m.kd, 1.0};
    Bounce bn;
    if (depth < limits_.max_depth && has_children(m)) {
      bn = bounce(m, ray.dir, side.n, eta_side(side), false,
                  [this](double cos_i, double eta) { return fresnel(cos_i, eta); });
      if (const std::optional<double> w = child_weight(bn.kr, weight, limits_.min_weight)) {
        ways[count++] = Way{WayKind::kReflection, bn.kr, *w};
      }
      if (const std::optional<double> w = child_weight(bn.kt, weight, limits_.min_weight)) {
        ways[count++] = Way{WayKind::kRefraction, bn.kt, *w};
      }
    }
    double chance = 0;
    const Way* way = pick_way(ways.data(), count, chance);
    if (way == nullptr) return result;
    switch (way->kind) {
      case WayKind::kGather:
        result += gather(m, hit->p, side, offset) / chance;
        break;
      case WayKind::kReflection:
        ++counts_.reflection;
        result += bn.kr * trace_path(make_ray(offset_origin(hit->p, side.ng, bn.mirror, offset), bn.mirror),
                                     depth + 1, way->weight) / chance;
        break;
      case WayKind::kRefraction:
        ++counts_.refraction;
        result += bn.kt * trace_path(make_ray(offset_origin(hit->p, side.ng, bn.refracted, offset), bn.refracted),
                                     depth + 1, way->weight) / chance;
        break;
    }
    return result;
  }

  // The indirect term at a hit of the Whitted tree: a gather, taken with chance q (pick_way's
  // rule for one way) and divided by q; a dim kd (a mirror's or glass's few per cent) rarely
  // pays for a whole path.
  Color tree_gather(const Material& m, const Vec3& p, const HitSide& side, double offset) {
    if (indirect_->bounces_left() <= 0 || is_zero(m.kd)) return Color(0);
    const Way way{WayKind::kGather, m.kd, 1.0};
    double chance = 0;
    if (pick_way(&way, 1, chance) == nullptr) return Color(0);
    return gather(m, p, side, offset) / chance;
  }

 private:
  enum class WayKind : std::uint8_t { kGather, kReflection, kRefraction };
  struct Way {
    WayKind kind;
    Color k;        // its coefficient: kd, kr' or kt'
    double weight;  // a child's path weight
  };

  // Which way on a path takes (Russian roulette over its ways): way i with chance
  // max_channel(k_i) / max(S, kRoulette), S the sum over the ways, and none with what is left
  // (1 - S / kRoulette when S < kRoulette). Every k_i / chance stays at most max(S, kRoulette)
  // per channel, so no sample is wild; ways as bright as a Cornell box's walls (S >= 0.25)
  // always go on, and alone they take no random number at all.
  static constexpr double kRoulette = 0.25;
  const Way* pick_way(const Way* ways, std::size_t count, double& chance) {
    if (count == 0) return nullptr;
    double sum = 0;
    for (std::size_t i = 0; i < count; ++i) sum += max_channel(ways[i].k);
    const double scale = std::max(sum, kRoulette);
    if (count == 1 && sum >= kRoulette) {
      chance = 1;
      return ways;
    }
    const double u = indirect_->next_choice() * scale;
    double below = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const double share = max_channel(ways[i].k);
      below += share;
      if (u < below) {
        chance = share / scale;
        return ways + i;
      }
    }
    return nullptr;  // u in [S, scale): the path ends here
  }

  // The hooks: production rules, or the experiment's.
  double fresnel(double cos_i, double eta) const {
    if constexpr (kExperiment) return prepared_.experiment()->fresnel(cos_i, eta);
    return fresnel_exact(cos_i, eta);
  }
  double offset_of(const Hit& hit) const {
    if constexpr (kExperiment) return prepared_.experiment()->offset(scene_, hit);
    return surface_offset(scene_, hit);
  }
  bool shadow_rays_behind() const {
    if constexpr (kExperiment) return prepared_.experiment()->shadow_rays_behind();
    return false;
  }
  bool refraction_for_opaque() const {
    if constexpr (kExperiment) return prepared_.experiment()->refraction_for_opaque();
    return false;
  }
  // The local terms' hooks (a student's formula, a known mistake: core/shading/experiment.h).
  Color ambient(const Material& m, const Hit& hit, const HitSide& side, const Vec3& v) const {
    if constexpr (kExperiment) {
      return prepared_.experiment()->ambient(LocalHit{&scene_, &m, nullptr, hit.p, side.n, Vec3(0), v, 0, 0});
    }
    return m.ka * scene_.ambient;
  }
  bool lit(const Material& m) const {
    if constexpr (kExperiment) return prepared_.experiment()->lit(m);
    return is_lit(m);
  }
  bool shadows() const {
    if constexpr (kExperiment) return prepared_.experiment()->shadows();
    return true;
  }
  // The side bounce() takes eta for: the hit's own, or the other (the eta-inverted mistake).
  bool eta_side(const HitSide& side) const {
    if constexpr (kExperiment) return prepared_.experiment()->eta_inverted() ? !side.entering : side.entering;
    return side.entering;
  }

  // The nearest object strictly between the ends of a shadow ray from P (for the probe only).
  Occluder find_occluder(const Ray& ray, double t_max, const Vec3& p) const {
    if (auto hit = intersect(prepared_, ray, t_max)) return Occluder{hit->object, glm::length(hit->p - p)};
    return {};
  }

  // Shadow ray for one light from a surface point. Returns vis_l. Always inlined: the light
  // loop is the hot path.
  [[gnu::always_inline]] inline bool light_visible(const Light& light, const Hit& hit, const Vec3& ng_facing,
                                                   const Vec3& l, double offset, Occluder* occluder) {
    if (!shadows()) return true;
    ++counts_.shadow;
    Ray ray;
    double t_max = 0;
    if (!shadow_ray(light, hit.p, ng_facing, l, offset, ray, t_max)) return true;
    if (occluder) *occluder = find_occluder(ray, t_max, hit.p);
    return !occluded(prepared_, ray, t_max);
  }

  // Diffuse and specular: the sum over the lights, each behind its shadow ray.
  void light_terms(const Material& m, const Hit& hit, const HitSide& side, const Vec3& v, double offset,
                   ProbeNode* probe, Terms& terms) {
    const bool has_specular = kExperiment || !is_zero(m.ks);  // a formula may not need ks
    const Vec3& n = side.n;
    for (std::size_t li = 0; li < scene_.lights.size(); ++li) {
      const Light& light = scene_.lights[li];
      if (!light.enabled && !recorder_) continue;
      Vec3 l;
      double dist = 0;
      if (!light_direction(light, hit.p, l, dist)) {
        if (recorder_) recorder_->light(static_cast<int>(li), LightSeen::kNoLight, 0, 0, 0);
        continue;
      }
      const double n_dot_l = glm::dot(n, l);
      ProbeLight* pl = nullptr;
      if (probe && light.enabled) {
        pl = &probe->lights.emplace_back();
        pl->index = static_cast<int>(li);
        pl->l = l;
        pl->n_dot_l = n_dot_l;
        pl->distance = dist;
      }
      if (!(n_dot_l > 0)) {  // light behind the surface: neither diffuse nor specular
        if (shadow_rays_behind() && light.enabled) light_visible(light, hit, side.ng, l, offset, nullptr);  // a ray for nothing
        if (recorder_) recorder_->light(static_cast<int>(li), LightSeen::kNoLight, n_dot_l, 0, 0);
        continue;
      }
      double spec = 0, cos_spec = 0;
      if (has_specular || probe || recorder_) {
        Vec3 r;
        cos_spec = specular_cosine(scene_.specular_model, n, l, v, n_dot_l, r);
        spec = specular_factor(cos_spec, m.n);
        if (pl) {
          pl->r = r;
          pl->r_dot_v = cos_spec;
          pl->spec_factor = spec;
        }
      }
      Occluder occluder;
      const bool visible = light_visible(light, hit, side.ng, l, offset, pl ? &occluder : nullptr);
      if (recorder_) {
        recorder_->light(static_cast<int>(li), visible ? LightSeen::kVisible : LightSeen::kBlocked, n_dot_l, cos_spec,
                         spec);
        if (!light.enabled) continue;
      }
      if (pl) {
        pl->lit_side = true;
        pl->visible = visible;
        pl->occluder = occluder.object;
        pl->occluder_distance = occluder.distance;
      }
      if (!visible) continue;
      LightShare share;
      if constexpr (kExperiment) {
        share = prepared_.experiment()->light_share(LocalHit{&scene_, &m, &light, hit.p, n, l, v, n_dot_l, spec});
      } else {
        share = light_share(light, m, n_dot_l, has_specular ? spec : 0.0);
      }
      terms.diffuse += share.diffuse;
      terms.specular += share.specular;
      if (pl) {
        pl->diffuse = share.diffuse;
        pl->specular = share.specular;
      }
    }
  }

  // One child ray with weight kw along dir; nothing when kw = 0 or the path weight is too low.
  Color child(TraceRecorder::Child kind, const Color& kw, const Hit& hit, const Vec3& ng_facing, const Vec3& dir,
              double offset, int depth, double weight, std::uint64_t& count, ProbeNode* probe,
              std::unique_ptr<ProbeNode>& probe_child) {
    const std::optional<double> w = child_weight(kw, weight, limits_.min_weight);
    if (!w) return Color(0);
    ++count;
    if (probe) probe_child = std::make_unique<ProbeNode>();
    if (recorder_) recorder_->begin_child(kind);
    const Ray ray_out = make_ray(offset_origin(hit.p, ng_facing, dir, offset), dir);
    return kw * trace(ray_out, depth + 1, *w, probe_child.get(), nullptr);
  }

  // Reflection and refraction: Whitted recursion for mirrors and glass.
  void mirror_and_glass_terms(const Material& m, const Ray& ray, const Hit& hit, const HitSide& side, int depth,
                              double weight, double offset, ProbeNode* probe, const TermsWanted& wanted,
                              Terms& terms) {
    // The ablation: also a refraction ray for opaque materials (kt = 0), as a naive tracer casts.
    const bool force_refraction = refraction_for_opaque() && is_zero(m.kt);
    if (!(depth < limits_.max_depth && (has_children(m) || force_refraction))) return;
    const Bounce bn = bounce(m, ray.dir, side.n, eta_side(side), force_refraction,
                             [this](double cos_i, double eta) { return fresnel(cos_i, eta); });
    if (recorder_) recorder_->bounced(bn);
    if (probe) {
      probe->kr_eff = bn.kr;
      probe->kt_eff = bn.kt;
      probe->fresnel = bn.fresnel;
      probe->tir = bn.tir;
      probe->eta = bn.eta;
    }
    std::unique_ptr<ProbeNode> no_probe;
    if (wanted.reflection) {
      terms.reflection = child(TraceRecorder::Child::kReflection, bn.kr, hit, side.ng, bn.mirror, offset, depth, weight, counts_.reflection, probe,
                               probe ? probe->reflection : no_probe);
    }
    if (!wanted.refraction) return;
    if (!is_zero(bn.kt)) {
      terms.refraction = child(TraceRecorder::Child::kRefraction, bn.kt, hit, side.ng, bn.refracted, offset, depth, weight, counts_.refraction, probe,
                               probe ? probe->refraction : no_probe);
    } else if (force_refraction) {  // the ablation: traced at the parent's path weight, times kt' = 0
      ++counts_.refraction;
      const Ray ray_out = make_ray(offset_origin(hit.p, side.ng, bn.refracted, offset), bn.refracted);
      terms.refraction = bn.kt * trace(ray_out, depth + 1, weight, nullptr, nullptr);
    }
  }

  const PreparedScene& prepared_;
  const Scene& scene_;
  const TraceLimits& limits_;
  RayCounts& counts_;
  TraceRecorder* recorder_;
  IndirectSampler* indirect_;  // null: ka·Ia at every hit
};

}  // namespace

Terms shade(const PreparedScene& prepared, const TraceLimits& limits, const Ray& ray, const Hit& hit, int depth,
            double weight, RayCounts& counts, ProbeNode* probe, const Vec3* shading_eye,
            const TermsWanted& wanted, IndirectSampler* indirect) {
  if (prepared.experiment()) [[unlikely]] {
    return Equation<true>(prepared, limits, counts, nullptr, indirect)
        .shade(ray, hit, depth, weight, probe, shading_eye, wanted);
  }
  return Equation<false>(prepared, limits, counts, nullptr, indirect)
      .shade(ray, hit, depth, weight, probe, shading_eye, wanted);
}

Color trace(const PreparedScene& prepared, const TraceLimits& limits, const Ray& ray, int depth, double weight,
            RayCounts& counts, ProbeNode* probe, const Vec3* shading_eye, IndirectSampler* indirect) {
  if (prepared.experiment()) [[unlikely]] {
    return Equation<true>(prepared, limits, counts, nullptr, indirect).trace(ray, depth, weight, probe, shading_eye);
  }
  return Equation<false>(prepared, limits, counts, nullptr, indirect).trace(ray, depth, weight, probe, shading_eye);
}

Color indirect_estimate(const PreparedScene& prepared, const TraceLimits& limits, const Material& m, const Vec3& p,
                        const HitSide& side, double offset, RayCounts& counts, IndirectSampler& indirect) {
  if (prepared.experiment()) [[unlikely]] {
    return Equation<true>(prepared, limits, counts, nullptr, &indirect).tree_gather(m, p, side, offset);
  }
  return Equation<false>(prepared, limits, counts, nullptr, &indirect).tree_gather(m, p, side, offset);
}

Color trace_recorded(const PreparedScene& prepared, const TraceLimits& limits, const Ray& ray, RayCounts& counts,
                     TraceRecorder& recorder, const Vec3* shading_eye) {
  return Equation<false>(prepared, limits, counts, &recorder).trace(ray, 0, 1.0, nullptr, shading_eye);
}

}  // namespace phonglab
