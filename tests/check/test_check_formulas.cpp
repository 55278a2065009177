// check_formulas on seeded random scenes (spheres, planes and triangles, mirrors and glass, both
// specular models, scales from 1e-3 to 1e4): the reference formulas match at the 1e-9 of docs/checking.md, and a
// formula mistake is named; the check is the same for any thread count.
#include <gtest/gtest.h>

#include "check/check.h"
#include "tests/support/formula_rules.h"
#include "tests/support/random_scenes.h"

namespace phonglab {
namespace {

using test::rules_of;

Scene small(std::uint32_t seed) {
  Scene s = random_scene_data(seed);
  s.width = 48;
  s.height = 32;
  return s;
}

TEST(CheckFormulas, TheReferenceFormulasMatchOnSeededRandomScenes) {
  for (std::uint32_t seed = 1; seed <= 24; ++seed) {
    Scene scene = small(seed);
    // The Phong formula is the reference in a Phong scene; a Blinn scene's specular term is N.H.
    const char* specular = scene.specular_model == SpecularModel::kPhong
                               ? "R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)"
                               : "H = normalize(L + V); ks * pow(max(0, dot(N, H)), n)";
    const LocalRules rules = rules_of({{FormulaSlot::kAmbient, "ka * Ia"},
                                       {FormulaSlot::kDiffuse, "kd * dot(N, L)"},
                                       {FormulaSlot::kSpecular, specular}});
    const CheckResult r = check_formulas(scene, rules);
    EXPECT_TRUE(r.match) << "seed " << seed << ":\n" << check_report_text(r);
    EXPECT_EQ(r.nan, 0U) << "seed " << seed;
  }
}

TEST(CheckFormulas, AnUnclampedSpecularTermIsNamedOnSeededRandomScenes) {
  int named = 0, differing = 0;
  for (std::uint32_t seed = 1; seed <= 24; ++seed) {
    Scene scene = small(seed);
    scene.specular_model = SpecularModel::kPhong;
    const CheckResult r =
        check_formulas(scene, rules_of({{FormulaSlot::kSpecular, "R = reflect(-L, N); ks * pow(dot(R, V), n)"}}));
    if (r.match) continue;  // no lit point with R.V < 0 and an odd or fractional n in view
    ++differing;
    for (const Mistake m : r.mistakes) named += m == Mistake::kSpecularUnclamped ? 1 : 0;
    if (r.mistake.find("specular-unclamped") == std::string::npos) ADD_FAILURE() << "seed " << seed << ":\n" << check_report_text(r);
  }
  EXPECT_GT(differing, 4) << "the random scenes should show the mistake";
  EXPECT_EQ(named, differing) << "named first wherever it shows";
}

TEST(CheckFormulas, TheVerdictIsTheSameForAnyThreadCount) {
  Scene scene = small(7);
  const LocalRules rules = rules_of({{FormulaSlot::kSpecular, "R = reflect(L, N); ks * pow(max(0, dot(R, V)), n)"}});
  CheckOptions one, two;
  one.threads = 1;
  two.threads = 3;
  const CheckResult a = check_formulas(scene, rules, one), b = check_formulas(scene, rules, two);
  EXPECT_EQ(check_report_text(a), check_report_text(b));
  EXPECT_EQ(a.sign, b.sign);
}

}  // namespace
}  // namespace phonglab
