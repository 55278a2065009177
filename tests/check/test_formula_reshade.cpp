// A formula edit re-shaded from stored ray trees (RayTrees::reshade with the rules' experiment,
// docs/formulas.md "Speed"): the image equals the traced image with the same formulas
// (render_pass through the experiment hook) bit for bit, on every embedded scene and on seeded
// random scenes with mirrors, glass and triangles, for the full image and the term images, for
// formulas that light what the reference leaves dark and formulas that give NaN; with a light
// moved and a coefficient edited at the same time; and the trees then serve the production
// scene again. Rules that change rays (no shadows, eta inverted) are refused.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>

#include "check/rules.h"
#include "core/render/ray_trees.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"
#include "io/embedded_scenes.h"
#include "tests/support/formula_rules.h"
#include "tests/support/random_scenes.h"

namespace phonglab {
namespace {

constexpr int kW = 40, kH = 27;

using test::rules_of;

// The rule sets every scene is re-shaded with: the reference formulas, a student's wrong ones
// (unclamped, a diffuse term without kd that lights mirrors and glass, NaN where R.V < 0 and n is
// not whole), and the ambient-per-light mistake.
std::vector<LocalRules> rule_sets() {
  std::vector<LocalRules> sets;
  sets.push_back(rules_of({{FormulaSlot::kAmbient, "ka * Ia"},
                           {FormulaSlot::kDiffuse, "kd * dot(N, L)"},
                           {FormulaSlot::kSpecular, "R = reflect(-L, N); ks * pow(max(0, dot(R, V)), n)"}}));
  sets.push_back(rules_of({{FormulaSlot::kSpecular, "R = reflect(-L, N); ks * pow(dot(R, V), n)"}}));
  sets.push_back(rules_of({{FormulaSlot::kDiffuse, "vec3(dot(N, L)) * 0.5"},
                           {FormulaSlot::kAmbient, "0.1 * Ia + P * 0.001"}}));
  sets.push_back(rules_of({{FormulaSlot::kSpecular, "ks * pow(dot(reflect(L, N), V) * 1.5, n + 0.5)"}}));
  LocalRules per_light;
  per_light.ambient_per_light = true;
  sets.push_back(per_light);
  return sets;
}

Accumulator traced(const PreparedScene& scene, bool terms) {
  Accumulator a;
  a.reset(kW, kH, terms);
  RenderOptions options;
  options.threads = 2;
  render_pass(scene, options, a);
  return a;
}

Accumulator reshaded(RayTrees& trees, std::shared_ptr<const PreparedScene> scene, bool terms) {
  Accumulator a;
  a.reset(kW, kH, terms);
  EXPECT_NE(trees.scope_for(*scene, kW, kH, std::nullopt), EditScope::kRetrace);
  EXPECT_TRUE(trees.reshade(std::move(scene), Term::kFull, std::nullopt, 2, a).completed);
  return a;
}

::testing::AssertionResult same_bits(const Accumulator& a, const Accumulator& b) {
  if (a.sum.size() != b.sum.size() || a.terms.size() != b.terms.size()) return ::testing::AssertionFailure() << "sizes";
  for (std::size_t i = 0; i < a.sum.size(); ++i) {
    if (std::memcmp(&a.sum[i], &b.sum[i], sizeof(Color)) != 0) {
      return ::testing::AssertionFailure() << "pixel " << i % kW << "," << i / kW << ": re-shaded (" << a.sum[i].x
                                           << ", " << a.sum[i].y << ", " << a.sum[i].z << ") traced (" << b.sum[i].x
                                           << ", " << b.sum[i].y << ", " << b.sum[i].z << ")";
    }
  }
  for (std::size_t i = 0; i < a.terms.size(); ++i) {
    if (std::memcmp(&a.terms[i], &b.terms[i], sizeof(Terms)) != 0) {
      return ::testing::AssertionFailure() << "the terms of pixel " << i % kW << "," << i / kW << " differ";
    }
  }
  return ::testing::AssertionSuccess();
}

// Every rule set re-shaded from one recording of `scene`, in a chain (each from the last), then
// the production scene again: each image the traced one.
void check_scene(const Scene& scene, const std::string& name) {
  auto production = std::make_shared<const PreparedScene>(scene);
  for (const bool terms : {false, true}) {
    std::unique_ptr<RayTrees> trees = RayTrees::record(production, kW, kH, std::nullopt, 2, std::size_t{1} << 30);
    ASSERT_NE(trees, nullptr) << name;
    for (const LocalRules& rules : rule_sets()) {
      auto with_rules = std::make_shared<const PreparedScene>(prepare_with_rules(scene, *production, rules));
      EXPECT_TRUE(same_bits(reshaded(*trees, with_rules, terms), traced(*with_rules, terms)))
          << name << (terms ? " (term images)" : "") << ", rules " << &rules - rule_sets().data();
    }
    EXPECT_FALSE(trees->recombines(*production, kW, kH, Term::kFull, std::nullopt, false))
        << "the stored values are a formula's: no live path from them";
    EXPECT_TRUE(same_bits(reshaded(*trees, production, terms), traced(*production, terms))) << name << ", production again";
  }
}

TEST(FormulaReshade, EqualsTheTracedFormulaImageOnEveryEmbeddedScene) {
  for (const EmbeddedScene& e : embedded_scenes()) {
    LoadResult loaded = load_scene_arg(std::string(e.name));
    ASSERT_TRUE(loaded.ok()) << e.name;
    check_scene(*loaded.scene, std::string(e.name));
  }
}

TEST(FormulaReshade, EqualsTheTracedFormulaImageOnSeededRandomScenes) {
  for (std::uint32_t seed = 1; seed <= 12; ++seed) check_scene(random_scene_data(seed), "seed " + std::to_string(seed));
}

// A light moved and a coefficient edited with the formulas in place: the shadow rays towards the
// light are cast again, the formulas read the new L and kd.
TEST(FormulaReshade, AMovedLightAndAnEditedCoefficientWithFormulas) {
  for (std::uint32_t seed = 1; seed <= 8; ++seed) {
    Scene scene = random_scene_data(seed);
    if (scene.lights.empty() || scene.materials.empty()) continue;
    auto production = std::make_shared<const PreparedScene>(scene);
    const LocalRules rules = rule_sets()[0];
    // Recorded from the scene with the formulas: the trees are its production twin's.
    auto first = std::make_shared<const PreparedScene>(prepare_with_rules(scene, *production, rules));
    std::unique_ptr<RayTrees> trees = RayTrees::record(first, kW, kH, std::nullopt, 2, std::size_t{1} << 30);
    ASSERT_NE(trees, nullptr);
    scene.lights[0].position += Vec3(0.3, -0.2, 0.1);
    scene.lights[0].direction = glm::normalize(scene.lights[0].direction + Vec3(0.1, 0, 0));
    scene.materials[0].kd *= 0.5;
    auto edited = std::make_shared<const PreparedScene>(prepare_with_rules(scene, *production, rules));
    EXPECT_TRUE(same_bits(reshaded(*trees, edited, false), traced(*edited, false))) << "seed " << seed;
  }
}

// Rules that change rays are traced, never re-shaded.
TEST(FormulaReshade, RulesThatChangeRaysAreRefused) {
  const Scene scene = random_scene_data(3);
  auto production = std::make_shared<const PreparedScene>(scene);
  std::unique_ptr<RayTrees> trees = RayTrees::record(production, kW, kH, std::nullopt, 2, std::size_t{1} << 30);
  ASSERT_NE(trees, nullptr);
  for (const int which : {0, 1}) {
    LocalRules rules;
    (which == 0 ? rules.no_shadows : rules.eta_inverted) = true;
    auto with_rules = std::make_shared<const PreparedScene>(prepare_with_rules(scene, *production, rules));
    EXPECT_EQ(trees->scope_for(*with_rules, kW, kH, std::nullopt), EditScope::kRetrace) << which;
    EXPECT_EQ(RayTrees::record(with_rules, kW, kH, std::nullopt, 2, std::size_t{1} << 30), nullptr) << which;
  }
  // A formula alone is a shading edit, even of the same scene.
  auto with_formula = std::make_shared<const PreparedScene>(prepare_with_rules(scene, *production, rule_sets()[1]));
  EXPECT_EQ(trees->scope_for(*with_formula, kW, kH, std::nullopt), EditScope::kShading);
}

}  // namespace
}  // namespace phonglab
