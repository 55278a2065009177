// Re-shading from stored ray trees (src/core/render/ray_trees.h): for every edit it accepts, the
// re-shaded image equals a fresh render_pass of the edited scene bit for bit, over seeded random
// scenes and seeded random edits of each kind, in chains of edits, for the full image and each
// term; and the edits it must refuse are classified as such.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <memory>
#include <random>
#include <string>

#include "core/packet/packet.h"
#include "core/render/ray_trees.h"
#include "core/render/render.h"
#include "tests/support/random_scenes.h"
#include "tests/support/test_support.h"
#include "tests/support/simd_targets.h"

using namespace phonglab;

namespace {

constexpr int kW = 23, kH = 15;

Accumulator fresh_image(const PreparedScene& scene, Term term, bool packets) {
  Accumulator accum;
  accum.reset(kW, kH);
  RenderOptions options;
  options.term = term;
  options.threads = 2;
  options.packets = packets;
  render_pass(scene, options, accum);
  return accum;
}

Accumulator reshaded_image(RayTrees& trees, std::shared_ptr<const PreparedScene> scene, Term term,
                           const std::optional<Vec3>& eye = std::nullopt) {
  Accumulator accum;
  accum.reset(kW, kH);
  const PassStats stats = trees.reshade(std::move(scene), term, eye, 2, accum);
  EXPECT_TRUE(stats.completed);
  EXPECT_EQ(accum.samples, 1u);
  return accum;
}

::testing::AssertionResult same_bits(const Accumulator& a, const Accumulator& b) {
  if (a.sum.size() != b.sum.size()) return ::testing::AssertionFailure() << "sizes differ";
  for (std::size_t i = 0; i < a.sum.size(); ++i) {
    if (std::memcmp(&a.sum[i], &b.sum[i], sizeof(Color)) != 0) {
      return ::testing::AssertionFailure() << "pixel " << i % kW << "," << i / kW << ": re-shaded (" << a.sum[i].x
                                           << ", " << a.sum[i].y << ", " << a.sum[i].z << ") fresh (" << b.sum[i].x
                                           << ", " << b.sum[i].y << ", " << b.sum[i].z << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

// A random edit that changes no ray: ka, kd, ks or n of a material, Ia, the background, a light's
// intensity or mute, the specular model.
void shading_edit(Scene& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  switch (std::uniform_int_distribution<int>(0, 8)(rng)) {
    case 0: s.materials[pick(s.materials.size())].ka = random_color(rng, 0.3, 0.3); break;
    case 1: s.materials[pick(s.materials.size())].kd = random_color(rng, 0.3, 0.9); break;  // also from or to 0
    case 2: s.materials[pick(s.materials.size())].ks = random_color(rng, 0.3, 0.9); break;
    case 3: s.materials[pick(s.materials.size())].n = u(rng) < 0.1 ? 0.0 : std::pow(10.0, 3 * u(rng)); break;
    case 4: s.ambient = random_color(rng, 0.2, 1); break;
    case 5: s.background = random_color(rng, 0.3, 0.5); break;
    case 6:
      if (!s.lights.empty()) s.lights[pick(s.lights.size())].intensity = random_color(rng, 0.2, 2);
      break;
    case 7:
      if (!s.lights.empty()) s.lights[pick(s.lights.size())].enabled ^= true;
      break;
    default:
      s.specular_model = s.specular_model == SpecularModel::kPhong ? SpecularModel::kBlinn : SpecularModel::kPhong;
      break;
  }
}

// A light moved or turned.
void light_edit(Scene& s, std::mt19937& rng) {
  if (s.lights.empty()) return;
  std::uniform_real_distribution<double> c(-3, 3);
  Light& l = s.lights[std::uniform_int_distribution<std::size_t>(0, s.lights.size() - 1)(rng)];
  const double scale = std::max(1e-3, glm::length(s.camera.position) / 6);
  l.position += Vec3(c(rng), c(rng), c(rng)) * scale;
  l.direction = glm::normalize(Vec3(c(rng), -1, c(rng)));
}

// A random edit of what children a hit has: kr, kt, ior or Fresnel of a material, the depth
// limit or the pruning weight (children appear, vanish or change direction).
void bounce_edit(Scene& s, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  Material& m = s.materials[std::uniform_int_distribution<std::size_t>(0, s.materials.size() - 1)(rng)];
  switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
    case 0: m.kr = random_color(rng, 0.4, 0.9); break;
    case 1: m.kt = random_color(rng, 0.4, 0.9); break;
    case 2: m.ior = 1 + u(rng); break;
    case 3: m.fresnel ^= true; break;
    case 4: s.max_depth = std::uniform_int_distribution<int>(0, 7)(rng); break;
    default: s.min_weight = u(rng) < 0.3 ? 0.0 : std::pow(10.0, -4 + 3 * u(rng)); break;
  }
}

std::shared_ptr<const PreparedScene> prepared(const Scene& s) { return std::make_shared<const PreparedScene>(s); }

}  // namespace

TEST(EditScope, SaysWhatAnEditInvalidates) {
  const Scene a = load_scene_or_fail("lecture");
  Scene b = a;
  EXPECT_EQ(edit_scope(a, b), EditScope::kNothing);
  b.materials[0].kd.x += 0.1;
  b.lights[0].enabled = false;
  b.specular_model = SpecularModel::kBlinn;
  EXPECT_EQ(edit_scope(a, b), EditScope::kShading);
  b.lights[1].position.y += 1;
  EXPECT_EQ(edit_scope(a, b), EditScope::kLights);
  for (int k = 0; k < 5; ++k) {
    Scene c = b;
    if (k == 0) c.materials[0].kr = Color(0.5);
    if (k == 1) c.materials[5].ior = 1.33;
    if (k == 2) c.materials[5].fresnel ^= true;
    if (k == 3) c.max_depth += 1;
    if (k == 4) c.min_weight *= 2;
    EXPECT_EQ(edit_scope(a, c), EditScope::kBounces) << k;
  }
  for (int k = 0; k < 4; ++k) {
    Scene c = b;
    if (k == 0) c.camera.position.x += 1e-9;
    if (k == 1) c.spheres[0].radius *= 1.01;
    if (k == 2) c.lights.pop_back();
    if (k == 3) c.materials.push_back(Material{});
    EXPECT_EQ(edit_scope(a, c), EditScope::kRetrace) << k;
  }
}

// Re-shading the recorded scene itself, then chains of random edits of the kinds it accepts
// (shading, moved lights, and children that appear, vanish or turn):
// every image equals a fresh render of the edited scene, traced ray by ray and in packets.
// Trees recorded in packets (where the packet tracer serves the scene) and ray by ray, on
// alternate seeds: every re-shade from either is bit for bit a fresh render.
TEST(RayTrees, ReshadedImagesAreBitIdenticalToFreshRenders) {
  test::for_each_simd_target([&] {
    int edits = 0;
    for (std::uint32_t seed = 1; seed <= 120; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      Scene s = random_scene_data(seed, seed % 4 == 0);
      std::shared_ptr<const PreparedScene> scene = prepared(s);
      const bool packets = seed % 2 == 0;
      std::unique_ptr<RayTrees> trees =
          RayTrees::record(scene, kW, kH, std::nullopt, 2, std::size_t{1} << 30, nullptr, packets);
      ASSERT_NE(trees, nullptr);
      ASSERT_TRUE(same_bits(reshaded_image(*trees, scene, Term::kFull), fresh_image(*scene, Term::kFull, false)));
      std::mt19937 rng(seed);
      for (int e = 0; e < 9; ++e) {
        if (e % 3 == 2) {
          light_edit(s, rng);
        } else if (e % 3 == 1) {
          bounce_edit(s, rng);
        } else {
          shading_edit(s, rng);
        }
        scene = prepared(s);
        ASSERT_NE(trees->scope_for(*scene, kW, kH, std::nullopt), EditScope::kRetrace);
        const Accumulator fresh = fresh_image(*scene, Term::kFull, false);
        ASSERT_TRUE(same_bits(reshaded_image(*trees, scene, Term::kFull), fresh)) << "after edit " << e;
        if (packet_cpu_supported()) {
          ASSERT_TRUE(same_bits(fresh, fresh_image(*scene, Term::kFull, true)));
        }
        ++edits;
      }
    }
    EXPECT_GT(edits, 1000);
  });
}

// Each term image from the same trees, after an edit: what render_pass gives for that term.
TEST(RayTrees, TermImagesComeFromTheSameTrees) {
  for (std::uint32_t seed = 200; seed <= 240; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Scene s = random_scene_data(seed);
    std::unique_ptr<RayTrees> trees = RayTrees::record(prepared(s), kW, kH, std::nullopt, 1, std::size_t{1} << 30);
    ASSERT_NE(trees, nullptr);
    std::mt19937 rng(seed);
    shading_edit(s, rng);
    const std::shared_ptr<const PreparedScene> scene = prepared(s);
    for (const Term term : {Term::kAmbient, Term::kDiffuse, Term::kSpecular, Term::kReflection, Term::kRefraction}) {
      SCOPED_TRACE(std::string(term_name(term)));
      ASSERT_TRUE(same_bits(reshaded_image(*trees, scene, term), fresh_image(*scene, term, false)));
    }
  }
}

// The small multiples from the same trees: one re-shade with term images gives the main image
// and each term image bit for bit what render_pass gives them, after chains of random edits.
TEST(RayTrees, OneReshadeGivesEveryTermImage) {
  const std::array<Term, 5>& terms = kFiveTerms;
  const auto& members = kFiveTermMembers;
  for (std::uint32_t seed = 400; seed <= 430; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    Scene s = random_scene_data(seed, seed % 4 == 0);
    std::unique_ptr<RayTrees> trees = RayTrees::record(prepared(s), kW, kH, std::nullopt, 2, std::size_t{1} << 30);
    ASSERT_NE(trees, nullptr);
    std::mt19937 rng(seed);
    for (int e = 0; e < 4; ++e) {
      if (e == 1) light_edit(s, rng);
      else if (e == 2) bounce_edit(s, rng);
      else shading_edit(s, rng);
      const std::shared_ptr<const PreparedScene> scene = prepared(s);
      // Between term-image re-shades, a plain one: the values it keeps must stay right.
      if (e == 3) {
        ASSERT_TRUE(same_bits(reshaded_image(*trees, scene, Term::kDiffuse), fresh_image(*scene, Term::kDiffuse, false)));
      }
      Accumulator together;
      together.reset(kW, kH, true);
      ASSERT_TRUE(trees->reshade(scene, Term::kFull, std::nullopt, 2, together).completed);
      ASSERT_TRUE(same_bits(together, fresh_image(*scene, Term::kFull, false))) << "after edit " << e;
      for (std::size_t k = 0; k < terms.size(); ++k) {
        Accumulator term;
        term.reset(kW, kH);
        for (std::size_t i = 0; i < term.sum.size(); ++i) term.sum[i] = together.terms[i].*members[k];
        ASSERT_TRUE(same_bits(term, fresh_image(*scene, terms[k], false))) << term_name(terms[k]) << " after edit " << e;
      }
    }
  }
}

// "Move your head": trees recorded with one eye re-shade to the image render_pass gives with
// another (V changes at the primary hits only), with other edits between, and back to no eye.
TEST(RayTrees, AnotherEyeIsAReshade) {
  test::for_each_simd_target([&] {
    for (std::uint32_t seed = 300; seed <= 340; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      Scene s = random_scene_data(seed);
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> c(-2, 2);
      const double scale = std::max(1e-3, glm::length(s.camera.position) / 6);
      const auto random_eye = [&] { return std::optional<Vec3>(s.camera.position + Vec3(c(rng), c(rng), c(rng)) * scale); };
      std::optional<Vec3> eye = seed % 2 ? random_eye() : std::nullopt;
      std::unique_ptr<RayTrees> trees = RayTrees::record(prepared(s), kW, kH, eye, 2, std::size_t{1} << 30);
      ASSERT_NE(trees, nullptr);
      for (int e = 0; e < 4; ++e) {
        eye = e == 3 ? std::nullopt : random_eye();
        if (e == 1) light_edit(s, rng);
        if (e == 2) shading_edit(s, rng);
        const std::shared_ptr<const PreparedScene> scene = prepared(s);
        ASSERT_GE(trees->scope_for(*scene, kW, kH, eye), EditScope::kShading);
        Accumulator fresh;
        fresh.reset(kW, kH);
        RenderOptions options;
        options.shading_eye = eye;
        options.packets = false;
        render_pass(*scene, options, fresh);
        ASSERT_TRUE(same_bits(reshaded_image(*trees, scene, Term::kFull, eye), fresh)) << "after edit " << e;
      }
    }
  });
}

TEST(RayTrees, RecordingStopsAtTheMemoryBudget) {
  const auto scene = std::make_shared<const PreparedScene>(load_prepared("lecture"));
  EXPECT_EQ(RayTrees::record(scene, 64, 36, std::nullopt, 2, 10000), nullptr);
  const std::unique_ptr<RayTrees> trees = RayTrees::record(scene, 64, 36, std::nullopt, 2, std::size_t{1} << 30);
  ASSERT_NE(trees, nullptr);
  EXPECT_GE(trees->node_count(), 64u * 36u / 2);  // most centre rays meet something
  EXPECT_GE(trees->memory_bytes(), trees->node_count() * sizeof(RayTrees::Node));
  EXPECT_EQ(trees->scope_for(*scene, 64, 35, std::nullopt), EditScope::kRetrace);  // another size
}
