// The lecture's illumination equation (docs/model.md): local Phong/Blinn-Phong shading with hard
// shadows, and Whitted recursion for mirrors and glass, pruned by path weight.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/geometry/geometry.h"
#include "core/scene/math.h"
#include "core/scene/scene.h"
#include "core/shading/indirect.h"

namespace phonglab {

// The five terms of the equation at one hit; their sum is the radiance.
struct Terms {
  Color ambient{0};     // ka * Ia
  Color diffuse{0};     // sum over lights of vis * I * kd * max(0, N.L)
  Color specular{0};    // sum over lights of vis * I * ks * spec
  Color reflection{0};  // kr' * trace(reflected ray)
  Color refraction{0};  // kt' * trace(refracted or totally reflected ray)
  Color sum() const { return ambient + diffuse + specular + reflection + refraction; }
};

// Rays cast, by kind.
struct RayCounts {
  std::uint64_t primary = 0;
  std::uint64_t shadow = 0;
  std::uint64_t reflection = 0;
  std::uint64_t refraction = 0;  // includes rays sent along the mirror direction under TIR
  std::uint64_t indirect = 0;    // gather rays of the indirect light's estimate
  std::uint64_t total() const { return primary + shadow + reflection + refraction + indirect; }
  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary;
    shadow += o.shadow;
    reflection += o.reflection;
    refraction += o.refraction;
    indirect += o.indirect;
    return *this;
  }
};

// Exact unpolarised Fresnel reflectance for a ray arriving with cos_i = -D.N >= 0, where
// eta = n_incident / n_transmitted. 1 under total internal reflection.
double fresnel_exact(double cos_i, double eta);

// How a hit faces the incoming ray (direction d).
struct HitSide {
  bool entering = false;  // d arrives on the outward side of the geometric normal
  Vec3 ng{0};             // geometric normal on d's side
  Vec3 n{0};              // shading normal N, facing d
};
inline HitSide hit_side(const Hit& hit, const Vec3& d) {
  const bool entering = glm::dot(hit.ng, d) < 0;
  return HitSide{entering, entering ? hit.ng : -hit.ng, glm::dot(hit.ns, d) < 0 ? hit.ns : -hit.ns};
}

// The specular factor max(0, cos)^n. The base is clamped before pow, so a fractional n never
// sees a negative base (docs/accuracy.md N4, N5); pow(0, n) is exactly 0 for n > 0, which spares the
// call for most lit points.
inline double specular_factor(double cos_spec, double n) {
  const double base = clamp_positive(clamp_unit(cos_spec));
  return (base == 0 && n > 0) ? 0.0 : std::pow(base, n);
}

// The specular cosine under the scene's model: R.V (Phong; `r` = R) or N.H (Blinn; `r` = H).
inline double specular_cosine(SpecularModel model, const Vec3& n, const Vec3& l, const Vec3& v, double n_dot_l, Vec3& r) {
  if (model == SpecularModel::kPhong) {
    r = 2.0 * n_dot_l * n - l;
    return glm::dot(r, v);
  }
  const Vec3 h = l + v;
  const double len = glm::length(h);
  r = len > 0 ? h / len : n;  // L = -V only at grazing: any H then gives N.H <= 0
  return len > 0 ? glm::dot(n, r) : 0;
}

// The unit vector L from P towards a light and the distance to it (infinity for directional
// lights). False for a point light exactly at P: no direction, no light.
inline bool light_direction(const Light& light, const Vec3& p, Vec3& l, double& dist) {
  if (light.type == LightType::kPoint) {
    const Vec3 to_light = light.position - p;
    dist = glm::length(to_light);
    if (!(dist > 0)) return false;
    l = to_light / dist;
    return true;
  }
  dist = std::numeric_limits<double>::infinity();
  l = -light.direction;
  return true;
}

// The shadow ray from P (offset along the facing geometric normal ng towards L) to a light: the
// open segment to a point light, pulled in at the light's end by the same relative amount as the
// origin is pushed off the surface (a light lying on a surface does not shadow itself), or the
// half-line along L. False when the light is within rounding distance of the surface: visible,
// no ray.
inline bool shadow_ray(const Light& light, const Vec3& p, const Vec3& ng, const Vec3& l, double offset, Ray& ray,
                       double& t_max) {
  const Vec3 origin = offset_origin(p, ng, l, offset);
  if (light.type == LightType::kDirectional) {
    ray = make_ray(origin, l);
    t_max = std::numeric_limits<double>::infinity();
    return true;
  }
  const Vec3 to_light = light.position - origin;
  const double dist = glm::length(to_light);
  t_max = dist - surface_offset(light.position, 0);
  if (!(t_max > 0)) return false;
  ray = make_ray(origin, to_light / dist);
  return true;
}

// A light's intensity times a material's kd and ks: what N.L and the specular factor multiply
// (the packet tracer forms them once per light and material, the scalar one per hit).
struct LightProducts {
  Color kd{0}, ks{0};
};
inline LightProducts light_products(const Light& light, const Material& m) {
  return {light.intensity * m.kd, light.intensity * m.ks};
}
// One visible light's share of the diffuse and specular terms (spec: the specular factor).
struct LightShare {
  Color diffuse{0}, specular{0};
};
inline LightShare light_share(const Light& light, const Material& m, double n_dot_l, double spec) {
  const LightProducts p = light_products(light, m);
  return {p.kd * n_dot_l, p.ks * spec};
}
inline void add_light(const Light& light, const Material& m, double n_dot_l, double spec, Color& diffuse,
                      Color& specular) {
  const LightShare share = light_share(light, m, n_dot_l, spec);
  diffuse += share.diffuse;
  specular += share.specular;
}

// The rules both tracers share, one definition each.
// Lights are evaluated at a hit only where a term can come back: kd or ks non-zero.
inline bool is_lit(const Material& m) { return !is_zero(m.kd) || !is_zero(m.ks); }
// Children (reflected, refracted rays) may follow only from mirrors and glass: kr or kt non-zero.
inline bool has_children(const Material& m) { return !is_zero(m.kr) || !is_zero(m.kt); }
// Pruning: the path weight of a child ray with weight k from a ray of path weight `weight`, or
// nothing when the child is not traced (k = 0, or the weight falls below min_weight).
inline std::optional<double> child_weight(const Color& k, double weight, double min_weight) {
  if (is_zero(k)) return std::nullopt;
  const double w = weight * max_channel(k);
  if (w < min_weight) return std::nullopt;
  return w;
}
// "Move your head": V at P towards a moved eye; nothing when the eye is exactly at P (V stays -D).
inline std::optional<Vec3> towards_eye(const Vec3& p, const Vec3& eye) {
  const Vec3 to_eye = eye - p;
  const double len = glm::length(to_eye);
  if (len > 0) return to_eye / len;
  return std::nullopt;
}

// V at a hit point P of a ray along d: towards the real eye (-D), or towards a moved eye ("move
// your head"); an eye exactly at P has no direction and falls back to -D.
inline Vec3 view_direction(const Vec3& p, const Vec3& d, const Vec3* shading_eye) {
  if (shading_eye) {
    if (const std::optional<Vec3> v = towards_eye(p, *shading_eye)) return *v;
  }
  return -d;
}

// What a mirror or glass hit passes on to its children.
struct Bounce {
  Color kr{0}, kt{0};    // kr', kt': with Fresnel, kr + kt F and kt (1 - F)
  double eta = 1;        // n_incident / n_transmitted
  bool tir = false;      // total internal reflection
  double fresnel = 0;    // F, when the material uses Fresnel
  Vec3 mirror{0};        // reflected direction
  Vec3 refracted{0};     // transmitted direction (the mirror one under TIR); set when kt' != 0
                         // or `force_refraction`
};
// Whether m's kr and kt are weighted by the Fresnel reflectance.
inline bool uses_fresnel(const Material& m) { return m.fresnel && !is_zero(m.kt); }
// kr' and kt' of b from m and b.fresnel.
inline void set_bounce_weights(const Material& m, Bounce& b) {
  if (uses_fresnel(m)) {
    b.kr = m.kr + m.kt * b.fresnel;
    b.kt = m.kt * (1 - b.fresnel);
  } else {
    b.kr = m.kr;
    b.kt = m.kt;
  }
}
// For a ray with direction d meeting material m with facing normal n. `fresnel(cos_i, eta)`
// gives F: fresnel_exact, except in the bench's experiments.
template <class Fresnel = double (*)(double, double)>
Bounce bounce(const Material& m, const Vec3& d, const Vec3& n, bool entering, bool force_refraction = false,
              Fresnel fresnel = fresnel_exact) {
  Bounce b;
  const double cos_i = clamp_unit(-glm::dot(d, n));
  b.eta = entering ? 1.0 / m.ior : m.ior;
  const double k = 1 - b.eta * b.eta * (1 - cos_i * cos_i);
  b.tir = k < 0;
  if (uses_fresnel(m)) b.fresnel = b.tir ? 1.0 : fresnel(cos_i, b.eta);
  set_bounce_weights(m, b);
  b.mirror = reflect_dir(d, n);
  if (!is_zero(b.kt) || force_refraction) {
    b.refracted = b.tir ? b.mirror : glm::normalize(b.eta * d + (b.eta * cos_i - std::sqrt(k)) * n);
  }
  return b;
}

// One light's part in a probed hit.
struct ProbeLight {
  int index = 0;          // into Scene::lights
  Vec3 l{0};              // unit vector towards the light
  Vec3 r{0};              // Phong: mirror of L about N; Blinn: half vector H
  double n_dot_l = 0;
  double r_dot_v = 0;     // Phong: R.V; Blinn: N.H
  double spec_factor = 0; // max(0, R.V)^n (or N.H), 0 when N.L <= 0
  double distance = 0;    // to a point light; infinity for directional lights
  bool lit_side = false;  // N.L > 0, so a shadow ray was cast
  bool visible = false;   // vis_l
  ObjectRef occluder;     // nearest blocker when not visible
  double occluder_distance = 0;  // from P to where the shadow ray meets it (when not visible)
  Color diffuse{0};       // vis * I * kd * max(0, N.L)
  Color specular{0};      // vis * I * ks * spec
};

// Everything about one ray of a probed pixel's ray tree.
struct ProbeNode {
  int depth = 0;
  double weight = 1;        // product of max-channel weights from the camera
  Vec3 origin{0}, dir{0};
  bool hit = false;         // false: the ray returned the background
  double t = 0;
  Vec3 p{0}, ng{0}, n{0}, v{0};  // hit point, outward geometric normal, shading N (facing), V
  bool entering = false;
  int material = -1;
  ObjectRef object;
  std::vector<ProbeLight> lights;
  Terms terms;
  Color total{0};           // what this ray returns
  Color kr_eff{0}, kt_eff{0};  // kr', kt'
  double fresnel = 0;       // F when the material uses Fresnel
  bool tir = false;         // total internal reflection at this hit
  double eta = 1;           // n_incident / n_transmitted
  std::unique_ptr<ProbeNode> reflection, refraction;  // children actually traced
};

// Which terms of a hit its caller keeps: all of them for the full image, one for a term image.
// What feeds only terms nobody keeps is not computed: the light loop (diffuse and specular, with
// their shadow rays) and each child ray. The kept terms' values are the same either way.
struct TermsWanted {
  bool lights = true;
  bool reflection = true;
  bool refraction = true;
};

// Limits of the recursion.
struct TraceLimits {
  int max_depth = 5;
  double min_weight = 0.001;
};

// What a light is at a hit, as a recorder of ray trees keeps it.
enum class LightSeen : std::uint8_t {
  kNoLight,  // N.L <= 0 or the light exactly at P: neither term, no shadow ray
  kVisible,  // its shadow ray reached it
  kBlocked,  // its shadow ray met something
};

// Told of every ray of a traced tree, in the tracer's order (core/render/ray_trees.h keeps them
// for re-shading): a hit opens a node, its lights and children follow, end_hit closes it.
class TraceRecorder {
 public:
  enum class Child : std::uint8_t { kReflection, kRefraction };
  virtual ~TraceRecorder() = default;
  virtual void ray_missed() = 0;
  virtual void begin_hit(const Ray& ray, const Hit& hit, const HitSide& side, double offset, int depth) = 0;
  // Every light, enabled or not, whatever the material (the recorder casts the shadow rays an
  // edit might need later); spec for the material's n.
  virtual void light(int index, LightSeen seen, double n_dot_l, double cos_spec, double spec) = 0;
  // The open hit is a mirror or glass: what it passes on to its children.
  virtual void bounced(const Bounce& b) = 0;
  // The next ray_missed or begin_hit is this child of the open hit.
  virtual void begin_child(Child kind) = 0;
  virtual void end_hit() = 0;
};

// Radiance along a ray (docs/model.md, the equation: trace). `probe`, when given, receives the whole ray tree.
// `indirect`, when given, replaces ka·Ia at every hit by the estimate of the indirect term with the
// sampler's bounces left (docs/model.md, indirect light); without it, the lecture's ka·Ia.
// `shading_eye`, when given, is the eye used for V at this ray's hit only ("move your head":
// V = normalize(eye - P) instead of -D); the reflected and refracted children still follow the
// real ray and use their own -D. Without it the result is bit-identical to the plain equation.
Color trace(const PreparedScene& prepared, const TraceLimits& limits, const Ray& ray, int depth, double weight,
            RayCounts& counts, ProbeNode* probe = nullptr, const Vec3* shading_eye = nullptr,
            IndirectSampler* indirect = nullptr);

// trace() of a primary ray (depth 0, weight 1), telling `recorder` of the whole tree. The radiance
// is trace()'s, bit for bit; more shadow rays are cast (every light at every hit facing it).
// Not for scenes with an experiment.
Color trace_recorded(const PreparedScene& prepared, const TraceLimits& limits, const Ray& ray, RayCounts& counts,
                     TraceRecorder& recorder, const Vec3* shading_eye = nullptr);

// Shading of a known hit, term by term (`shading_eye` and `indirect` as for trace: V at this hit
// only; the ambient term is the indirect term's estimate). Terms that `wanted` leaves out are 0.
Terms shade(const PreparedScene& prepared, const TraceLimits& limits, const Ray& ray, const Hit& hit, int depth,
            double weight, RayCounts& counts, ProbeNode* probe = nullptr, const Vec3* shading_eye = nullptr,
            const TermsWanted& wanted = {}, IndirectSampler* indirect = nullptr);

// One estimate of the indirect term at a hit of material m (P, the facing normals, the ray
// offset as for its shadow rays): kd times the radiance a gather ray in a cosine-weighted
// direction about N brings back, its own hits with one bounce fewer. 0 with no bounce left or
// kd = 0 (no ray then). The rule both the scalar equation and the probe use.
Color indirect_estimate(const PreparedScene& prepared, const TraceLimits& limits, const Material& m, const Vec3& p,
                        const HitSide& side, double offset, RayCounts& counts, IndirectSampler& indirect);

}  // namespace phonglab
