// The local rules a check renders with: a student's formulas in place of the equation's local
// terms, and the shading mistakes of the catalogue (src/check/mistakes.h). They reach the
// renderer through its experiment hook (core/shading/experiment.h), never a branch of the
// production path: a scene prepared with rules is traced by the equation compiled with hooks.
#pragma once

#include <array>
#include <memory>

#include "check/formula.h"
#include "core/accel/prepared_scene.h"
#include "core/shading/experiment.h"

namespace phonglab {

struct LocalRules {
  // Per slot (FormulaSlot order): the formula that replaces the term, or null for the equation's.
  std::array<std::shared_ptr<const Formula>, kFormulaSlots> formulas{};
  bool no_shadows = false;         // vis_l = 1 always
  bool eta_inverted = false;       // ior entering, 1 / ior leaving
  bool ambient_per_light = false;  // the ambient term added once for every (enabled) light
  bool any() const {
    return formulas[0] || formulas[1] || formulas[2] || no_shadows || eta_inverted || ambient_per_light;
  }
};

// The experiment that applies `rules`.
std::shared_ptr<const Experiment> make_rules_experiment(const LocalRules& rules);

// `scene` prepared with `rules` over `geometry`'s accelerator (the same geometry: only the
// camera, the recursion limits or the rules differ). Without rules, the production scene.
PreparedScene prepare_with_rules(Scene scene, const PreparedScene& geometry, const LocalRules& rules);

// What a formula reads at a hit (the given names), for the probe and the panel.
FormulaInputs formula_inputs(const LocalHit& hit, FormulaSlot slot);

}  // namespace phonglab
