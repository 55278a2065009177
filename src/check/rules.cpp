#include "check/rules.h"

namespace phonglab {

FormulaInputs formula_inputs(const LocalHit& h, FormulaSlot slot) {
  const Material& m = *h.material;
  FormulaInputs in;
  in.N = h.n;
  in.V = h.v;
  in.P = h.p;
  in.ka = m.ka;
  in.kd = m.kd;
  in.ks = m.ks;
  in.kr = m.kr;
  in.kt = m.kt;
  in.n = m.n;
  in.ior = m.ior;
  in.Ia = h.scene->ambient;
  if (slot != FormulaSlot::kAmbient && h.light) {
    in.L = h.l;
    in.I = h.light->intensity;
  }
  return in;
}

namespace {

class RulesExperiment final : public Experiment {
 public:
  explicit RulesExperiment(LocalRules rules) : rules_(std::move(rules)) {}

  Color ambient(const LocalHit& h) const override {
    const Formula* f = rules_.formulas[static_cast<int>(FormulaSlot::kAmbient)].get();
    const Color once = f ? f->evaluate(formula_inputs(h, FormulaSlot::kAmbient)) : Experiment::ambient(h);
    if (!rules_.ambient_per_light) return once;
    Color sum(0);
    for (const Light& light : h.scene->lights) {
      if (light.enabled) sum += once;
    }
    return sum;
  }

  LightShare light_share(const LocalHit& h) const override {
    const Formula* diffuse = rules_.formulas[static_cast<int>(FormulaSlot::kDiffuse)].get();
    const Formula* specular = rules_.formulas[static_cast<int>(FormulaSlot::kSpecular)].get();
    LightShare share = Experiment::light_share(h);
    if (diffuse) share.diffuse = h.light->intensity * diffuse->evaluate(formula_inputs(h, FormulaSlot::kDiffuse));
    if (specular) share.specular = h.light->intensity * specular->evaluate(formula_inputs(h, FormulaSlot::kSpecular));
    return share;
  }

  // A formula may light a material the reference leaves dark (a diffuse term without kd).
  bool lit(const Material& m) const override {
    return rules_.formulas[static_cast<int>(FormulaSlot::kDiffuse)] ||
           rules_.formulas[static_cast<int>(FormulaSlot::kSpecular)] || is_lit(m);
  }
  bool shadows() const override { return !rules_.no_shadows; }
  bool eta_inverted() const override { return rules_.eta_inverted; }

 private:
  LocalRules rules_;
};

}  // namespace

std::shared_ptr<const Experiment> make_rules_experiment(const LocalRules& rules) {
  return std::make_shared<RulesExperiment>(rules);
}

PreparedScene prepare_with_rules(Scene scene, const PreparedScene& geometry, const LocalRules& rules) {
  std::shared_ptr<const Accelerator> accel = geometry.shared_accel();
  const auto same_accel = [accel](const Scene&) { return accel; };
  return PreparedScene(std::move(scene), same_accel, rules.any() ? make_rules_experiment(rules) : nullptr);
}

}  // namespace phonglab
