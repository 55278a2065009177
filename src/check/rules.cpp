#include "check/rules.h"

#include <vector>

namespace phonglab {

namespace {

// The given names at `count` hits, as the formulas of `slot` read them: L and I are 0 in the
// ambient slot. The one definition of what a name is at a hit (formula_inputs reads it too).
class HitsSource final : public FormulaSource {
 public:
  HitsSource(const LocalHit* hits, FormulaSlot slot) : hits_(hits), light_slot_(slot != FormulaSlot::kAmbient) {}
  void fill(int name, std::size_t first, std::size_t n, double* x, double* y, double* z) const override {
    const LocalHit* h = hits_ + first;
    const auto triple = [&](auto&& get) {
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3& v = get(h[i]);
        x[i] = v.x, y[i] = v.y, z[i] = v.z;
      }
    };
    const auto number = [&](auto&& get) {
      for (std::size_t i = 0; i < n; ++i) x[i] = get(h[i]);
    };
    static const Vec3 zero(0);
    switch (name) {  // formula_given_names() order
      case 0: return triple([](const LocalHit& a) -> const Vec3& { return a.n; });
      case 1: return triple([&](const LocalHit& a) -> const Vec3& { return light_slot_ && a.light ? a.l : zero; });
      case 2: return triple([](const LocalHit& a) -> const Vec3& { return a.v; });
      case 3: return triple([](const LocalHit& a) -> const Vec3& { return a.p; });
      case 4: return triple([](const LocalHit& a) -> const Vec3& { return a.material->ka; });
      case 5: return triple([](const LocalHit& a) -> const Vec3& { return a.material->kd; });
      case 6: return triple([](const LocalHit& a) -> const Vec3& { return a.material->ks; });
      case 7: return number([](const LocalHit& a) { return a.material->n; });
      case 8: return triple([](const LocalHit& a) -> const Vec3& { return a.material->kr; });
      case 9: return triple([](const LocalHit& a) -> const Vec3& { return a.material->kt; });
      case 10: return number([](const LocalHit& a) { return a.material->ior; });
      case 11: return triple([](const LocalHit& a) -> const Vec3& { return a.scene->ambient; });
      default: return triple([&](const LocalHit& a) -> const Vec3& { return light_slot_ && a.light ? a.light->intensity : zero; });
    }
  }

 private:
  const LocalHit* hits_;
  bool light_slot_;
};

class RulesExperiment final : public Experiment {
 public:
  explicit RulesExperiment(LocalRules rules) : rules_(std::move(rules)) {}

  // One hit is a batch of one: the rules have one definition.
  Color ambient(const LocalHit& h) const override {
    Color out;
    ambient_batch(&h, 1, &out);
    return out;
  }
  void ambient_batch(const LocalHit* hits, std::size_t count, Color* out) const override {
    if (const Formula* f = formula(FormulaSlot::kAmbient)) {
      f->evaluate(HitsSource(hits, FormulaSlot::kAmbient), count, out);
    } else {
      for (std::size_t i = 0; i < count; ++i) out[i] = Experiment::ambient(hits[i]);
    }
    if (rules_.ambient_per_light) {
      for (std::size_t i = 0; i < count; ++i) out[i] = per_light(hits[i], out[i]);
    }
  }

  LightShare light_share(const LocalHit& h) const override {
    LightShare out;
    light_share_batch(&h, 1, &out);
    return out;
  }
  void light_share_batch(const LocalHit* hits, std::size_t count, LightShare* out) const override {
    for (std::size_t i = 0; i < count; ++i) out[i] = Experiment::light_share(hits[i]);
    thread_local std::vector<Color> values;
    if (values.size() < count) values.resize(count);
    if (const Formula* f = formula(FormulaSlot::kDiffuse)) {
      f->evaluate(HitsSource(hits, FormulaSlot::kDiffuse), count, values.data());
      for (std::size_t i = 0; i < count; ++i) out[i].diffuse = hits[i].light->intensity * values[i];
    }
    if (const Formula* f = formula(FormulaSlot::kSpecular)) {
      f->evaluate(HitsSource(hits, FormulaSlot::kSpecular), count, values.data());
      for (std::size_t i = 0; i < count; ++i) out[i].specular = hits[i].light->intensity * values[i];
    }
  }

  // A formula may light a material the reference leaves dark (a diffuse term without kd).
  bool lit(const Material& m) const override {
    return formula(FormulaSlot::kDiffuse) || formula(FormulaSlot::kSpecular) || is_lit(m);
  }
  bool shadows() const override { return !rules_.no_shadows; }
  bool eta_inverted() const override { return rules_.eta_inverted; }
  bool local_terms_only() const override { return !rules_.no_shadows && !rules_.eta_inverted; }

 private:
  const Formula* formula(FormulaSlot slot) const { return rules_.formulas[static_cast<int>(slot)].get(); }
  // The ambient term once, or once for every enabled light (the ambient-per-light mistake).
  Color per_light(const LocalHit& h, const Color& once) const {
    if (!rules_.ambient_per_light) return once;
    Color sum(0);
    for (const Light& light : h.scene->lights) {
      if (light.enabled) sum += once;
    }
    return sum;
  }
  LocalRules rules_;
};

}  // namespace

FormulaInputs formula_inputs(const LocalHit& hit, FormulaSlot slot) { return HitsSource(&hit, slot).at(0); }

std::shared_ptr<const Experiment> make_rules_experiment(const LocalRules& rules) {
  return std::make_shared<RulesExperiment>(rules);
}

PreparedScene prepare_with_rules(Scene scene, const PreparedScene& geometry, const LocalRules& rules) {
  std::shared_ptr<const Accelerator> accel = geometry.shared_accel();
  const auto same_accel = [accel](const Scene&) { return accel; };
  return PreparedScene(std::move(scene), same_accel, rules.any() ? make_rules_experiment(rules) : nullptr);
}

}  // namespace phonglab
