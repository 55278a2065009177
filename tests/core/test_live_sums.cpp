// The live path of a slider (RayTrees::recombine, src/core/render/ray_trees_live.cpp): for every
// edit the image is linear in, the trees' last image plus the edited coefficients' changes times
// their per-pixel sums equals the exact re-shade (render_pass of the edited scene) to 1e-12
// relative, over seeded random scenes, chains of edits of one family and every term; the trees
// are left as they were (the exact re-shade after it is bit for bit a fresh render); and edits
// that are not linear are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <algorithm>
#include <array>
#include <memory>
#include <random>
#include <string>

#include "core/render/ray_trees.h"
#include "core/render/render.h"
#include "tests/support/random_scenes.h"
#include "tests/support/simd_targets.h"

using namespace phonglab;

namespace {

constexpr int kW = 21, kH = 13;

std::shared_ptr<const PreparedScene> prepared(const Scene& s) { return std::make_shared<const PreparedScene>(s); }

Accumulator fresh_image(const PreparedScene& scene, Term term) {
  Accumulator accum;
  accum.reset(kW, kH);
  RenderOptions options;
  options.term = term;
  options.threads = 2;
  render_pass(scene, options, accum);
  return accum;
}

Accumulator sized() {
  Accumulator accum;
  accum.reset(kW, kH);
  return accum;
}

// Sized, as the renderer hands the live path its accumulator (reset_for_first_pass: not
// cleared), and full of NaN: a pixel the live path does not write stays NaN.
Accumulator uncleared() {
  Accumulator accum = sized();
  std::fill(accum.sum.begin(), accum.sum.end(), Color(std::numeric_limits<double>::quiet_NaN()));
  return accum;
}

// One edit of a live family: 0 some material's ka, kd or ks (also from or to 0), 1 Ia, 2 a
// light's intensity or mute, 3 light `moved` dragged (a point light's position or a directional
// light's direction; sometimes its intensity or mute too).
void linear_edit(Scene& s, std::mt19937& rng, int family, std::size_t moved = 0) {
  const auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  if (family == 0) {
    Material& m = s.materials[pick(s.materials.size())];
    switch (pick(3)) {
      case 0: m.ka = random_color(rng, 0.2, 0.4); break;
      case 1: m.kd = random_color(rng, 0.2, 0.9); break;
      default: m.ks = random_color(rng, 0.2, 0.9); break;
    }
  } else if (family == 1) {
    s.ambient = random_color(rng, 0.1, 1.5);
  } else if (family == 3 && !s.lights.empty()) {
    Light& l = s.lights[moved % s.lights.size()];
    std::uniform_real_distribution<double> step(-1.5, 1.5);
    if (l.type == LightType::kPoint) l.position += Vec3(step(rng), step(rng), step(rng));
    else l.direction += Vec3(step(rng), step(rng), step(rng)) * 0.3;
    if (pick(5) == 0) l.enabled ^= true;
    if (pick(3) == 0) l.intensity = random_color(rng, 0.1, 2);
  } else if (!s.lights.empty()) {
    Light& l = s.lights[pick(s.lights.size())];
    if (pick(4) == 0) l.enabled ^= true;
    else l.intensity = random_color(rng, 0.1, 2);
  }
}

// |live - exact| within 1e-12 of the larger of the pixel's values before and after the edit.
::testing::AssertionResult close(const Accumulator& live, const Accumulator& exact, const Accumulator& before) {
  for (std::size_t i = 0; i < exact.sum.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double scale = std::max({std::abs(exact.sum[i][c]), std::abs(before.sum[i][c]), 1e-300});
      if (!(std::abs(live.sum[i][c] - exact.sum[i][c]) <= 1e-12 * scale)) {
        return ::testing::AssertionFailure() << "pixel " << i % kW << "," << i / kW << " channel " << c << ": live "
                                             << live.sum[i][c] << " exact " << exact.sum[i][c];
      }
    }
  }
  return ::testing::AssertionSuccess();
}

bool same_bits(const Accumulator& a, const Accumulator& b) {
  return a.sum.size() == b.sum.size() && std::memcmp(a.sum.data(), b.sum.data(), a.sum.size() * sizeof(Color)) == 0;
}

}  // namespace

TEST(LiveSums, RecombinedImagesEqualTheExactReshade) {
  test::for_each_simd_target([&] {
    int checked = 0;
    for (std::uint32_t seed = 1; seed <= 90; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      const Term term = std::array<Term, 6>{Term::kFull, Term::kAmbient, Term::kDiffuse, Term::kSpecular,
                                            Term::kReflection, Term::kRefraction}[seed % 6];
      Scene s = random_scene_data(seed, seed % 4 == 0);
      std::shared_ptr<const PreparedScene> base = prepared(s);
      // Two copies of the same trees (in packets and ray by ray): one writes a new image each
      // time, the other each image over the last (as the previewer's renderer).
      std::unique_ptr<RayTrees> trees = RayTrees::record(base, kW, kH, std::nullopt, 2, std::size_t{1} << 30, nullptr, true);
      std::unique_ptr<RayTrees> over_trees =
          RayTrees::record(base, kW, kH, std::nullopt, 2, std::size_t{1} << 30, nullptr, false);
      ASSERT_NE(trees, nullptr);
      ASSERT_NE(over_trees, nullptr);
      Accumulator before = sized();
      ASSERT_TRUE(trees->reshade(base, term, std::nullopt, 2, before).completed);  // the trees' image of `term`
      Accumulator unused = sized();
      ASSERT_TRUE(over_trees->reshade(base, term, std::nullopt, 2, unused).completed);
      std::mt19937 rng(seed);
      const int family = static_cast<int>(seed % 4);
      Accumulator over = sized();  // each image written over the last, as the previewer's
      for (int e = 0; e < 6; ++e) {  // a drag: every edit against the same trees
        linear_edit(s, rng, family, seed / 4);
        const std::shared_ptr<const PreparedScene> edited = prepared(s);
        if (edited->scene().lights.empty() && family >= 2) break;
        ASSERT_TRUE(trees->recombines(*edited, kW, kH, term, std::nullopt, false)) << "edit " << e;
        Accumulator live = uncleared();  // every pixel is written: no clearing needed
        const PassStats stats = trees->recombine(*edited, term, 1 + e % 2, live);
        ASSERT_TRUE(stats.completed);
        EXPECT_EQ(live.samples, 1u);
        const Accumulator exact = fresh_image(*edited, term);
        ASSERT_TRUE(close(live, exact, before)) << "edit " << e << ", term " << term_name(term);
        over.samples = 0;
        ASSERT_TRUE(over_trees->recombine(*edited, term, 2, over, nullptr, e > 0).completed);
        ASSERT_TRUE(close(over, exact, before)) << "written over the last, edit " << e << ", term " << term_name(term);
        ++checked;
      }
      // The hand stops: the exact re-shade from the same trees, bit for bit a fresh render.
      const std::shared_ptr<const PreparedScene> rest = prepared(s);
      Accumulator exact = sized();
      ASSERT_TRUE(trees->reshade(rest, term, std::nullopt, 2, exact).completed);
      EXPECT_TRUE(same_bits(exact, fresh_image(*rest, term)));
    }
    EXPECT_GT(checked, 400);
  });
}

// The moved light's live path on the lecture's kind of scene at a larger size, with the light
// dragged across the image (lit and shadowed sides swap), through the packet kernels and ray by
// ray, in every term; and a muted light moved gives the image without it.
TEST(LiveSums, AMovedLightsShareIsCastAgainAtTheStoredHits) {
  test::for_each_simd_target([&] {
    for (std::uint32_t seed = 200; seed < 230; ++seed) {
      SCOPED_TRACE("seed " + std::to_string(seed));
      Scene s = random_scene_data(seed, seed % 3 == 0);
      if (s.lights.empty()) continue;
      const Term term = std::array<Term, 4>{Term::kFull, Term::kDiffuse, Term::kSpecular, Term::kReflection}[seed % 4];
      const std::shared_ptr<const PreparedScene> base = prepared(s);
      std::unique_ptr<RayTrees> trees = RayTrees::record(base, kW, kH, std::nullopt, 2, std::size_t{1} << 30, nullptr, seed % 2 == 0);
      ASSERT_NE(trees, nullptr);
      Accumulator before = sized();
      ASSERT_TRUE(trees->reshade(base, term, std::nullopt, 2, before).completed);
      Light& light = s.lights[seed % s.lights.size()];
      for (int e = 0; e < 4; ++e) {
        if (light.type == LightType::kPoint) light.position = Vec3(light.position.x * -0.7 + e, light.position.y, -light.position.z);
        else light.direction = Vec3(-light.direction.x + 0.2 * e, light.direction.y, light.direction.z * 0.5);
        if (e == 3) light.enabled = !light.enabled;
        const std::shared_ptr<const PreparedScene> edited = prepared(s);
        ASSERT_TRUE(trees->recombines(*edited, kW, kH, term, std::nullopt, false));
        Accumulator live = uncleared();
        ASSERT_TRUE(trees->recombine(*edited, term, 2, live, nullptr, e > 0).completed);
        ASSERT_TRUE(close(live, fresh_image(*edited, term), before)) << "edit " << e << ", term " << term_name(term);
      }
    }
  });
}

// A moved light's arrays count against the trees' budget: over it, no live path for the light
// (the exact re-shade serves), and the coefficients' live path goes on.
TEST(LiveSums, AMovedLightsArraysStayWithinTheTreesBudget) {
  Scene s = random_scene_data(7);
  ASSERT_GE(s.lights.size(), 1u);
  s.lights[0].type = LightType::kPoint;
  const std::shared_ptr<const PreparedScene> base = prepared(s);
  const std::size_t trees_alone = RayTrees::record(base, kW, kH, std::nullopt, 2, std::size_t{1} << 30)->memory_bytes();
  for (const bool roomy : {true, false}) {
    SCOPED_TRACE(roomy ? "room for the arrays" : "no room for them");
    const std::size_t budget = roomy ? std::size_t{1} << 30 : trees_alone + trees_alone / 20;
    std::unique_ptr<RayTrees> trees = RayTrees::record(base, kW, kH, std::nullopt, 2, budget);
    ASSERT_NE(trees, nullptr);
    Accumulator image = sized();
    ASSERT_TRUE(trees->reshade(base, Term::kFull, std::nullopt, 2, image).completed);
    Scene moved = s;
    moved.lights[0].position += Vec3(0.5, 0.1, -0.2);
    const std::shared_ptr<const PreparedScene> edited = prepared(moved);
    ASSERT_TRUE(trees->recombines(*edited, kW, kH, Term::kFull, std::nullopt, false));
    Accumulator live = uncleared();
    EXPECT_EQ(trees->recombine(*edited, Term::kFull, 2, live).completed, roomy);
    EXPECT_EQ(trees->recombines(*edited, kW, kH, Term::kFull, std::nullopt, false), roomy);
    if (!roomy) {
      EXPECT_LE(trees->memory_bytes(), budget);
    }
    Scene shaded = s;
    shaded.materials[0].kd *= 0.5;
    Accumulator kd = sized();
    EXPECT_TRUE(trees->recombine(*prepared(shaded), Term::kFull, 2, kd).completed);
  }
}

// After a re-shade that traced children the trees do not store (another ior turns refracted
// rays), a sum that needs them cannot be taken: recombine says so (not completed, nothing
// shown) and recombines() refuses from then on, so the exact re-shade serves.
TEST(LiveSums, ASumTheTreesCannotGiveIsNotShown) {
  int refused = 0;
  for (std::uint32_t seed = 1; seed <= 60 && refused < 3; ++seed) {
    Scene s = random_scene_data(seed);
    const auto glass = std::find_if(s.materials.begin(), s.materials.end(), [](const Material& m) { return !is_zero(m.kt); });
    if (glass == s.materials.end()) continue;
    const std::shared_ptr<const PreparedScene> base = prepared(s);
    std::unique_ptr<RayTrees> trees = RayTrees::record(base, kW, kH, std::nullopt, 2, std::size_t{1} << 30);
    ASSERT_NE(trees, nullptr);
    glass->ior += 0.3;
    const std::shared_ptr<const PreparedScene> turned = prepared(s);
    Accumulator image = sized();
    ASSERT_TRUE(trees->reshade(turned, Term::kFull, std::nullopt, 2, image).completed);
    s.ambient *= 0.5;
    const std::shared_ptr<const PreparedScene> edited = prepared(s);
    if (!trees->recombines(*edited, kW, kH, Term::kFull, std::nullopt, false)) continue;
    Accumulator live = uncleared();
    const PassStats stats = trees->recombine(*edited, Term::kFull, 2, live);
    if (stats.completed) {
      ASSERT_TRUE(close(live, fresh_image(*edited, Term::kFull), image));
      continue;
    }
    EXPECT_EQ(live.samples, 0u);
    EXPECT_FALSE(trees->recombines(*edited, kW, kH, Term::kFull, std::nullopt, false));
    ++refused;
  }
  EXPECT_GE(refused, 1);
}

TEST(LiveSums, EditsThatAreNotLinearAreRefused) {
  Scene s = random_scene_data(7);
  ASSERT_GE(s.lights.size(), 1u);
  ASSERT_GE(s.materials.size(), 1u);
  const std::shared_ptr<const PreparedScene> base = prepared(s);
  std::unique_ptr<RayTrees> trees = RayTrees::record(base, kW, kH, std::nullopt, 2, std::size_t{1} << 30);
  ASSERT_NE(trees, nullptr);
  const auto refused = [&](const std::function<void(Scene&)>& edit) {
    Scene t = s;
    edit(t);
    return !trees->recombines(*prepared(t), kW, kH, Term::kFull, std::nullopt, false);
  };
  EXPECT_TRUE(refused([](Scene& t) { t.materials[0].n += 1; }));
  EXPECT_TRUE(refused([](Scene& t) {
    t.specular_model = t.specular_model == SpecularModel::kBlinn ? SpecularModel::kPhong : SpecularModel::kBlinn;
  }));
  EXPECT_TRUE(refused([](Scene& t) { t.materials[0].kr += Color(0.3); }));
  // A moved light is shown live alone: not with a material's edit or another light's.
  EXPECT_FALSE(refused([](Scene& t) {
    t.lights[0].position += Vec3(0.1, 0, 0);
    t.lights[0].direction += Vec3(0, 0, 0.1);
    t.lights[0].intensity *= 2.0;
  }));
  EXPECT_TRUE(refused([](Scene& t) {
    t.lights[0].position += Vec3(0.1, 0, 0);
    t.materials[0].kd += Color(0.1);
  }));
  EXPECT_TRUE(refused([](Scene& t) {
    t.lights[0].position += Vec3(0.1, 0, 0);
    t.ambient *= 0.5;
  }));
  if (s.lights.size() > 1) {
    EXPECT_TRUE(refused([](Scene& t) {
      t.lights[0].position += Vec3(0.1, 0, 0);
      t.lights[1].position += Vec3(0.1, 0, 0);
    }));
    EXPECT_TRUE(refused([](Scene& t) {
      t.lights[0].position += Vec3(0.1, 0, 0);
      t.lights[1].intensity *= 2.0;
    }));
  }
  EXPECT_TRUE(refused([](Scene& t) { t.background += Color(0.2); }));
  EXPECT_TRUE(refused([](Scene& t) { t.camera.position += Vec3(0.1, 0, 0); }));
  // Two families at once: a product of two edited coefficients.
  EXPECT_TRUE(refused([](Scene& t) {
    t.materials[0].kd += Color(0.1);
    t.lights[0].intensity *= 2.0;
  }));
  EXPECT_TRUE(refused([](Scene& t) {
    t.materials[0].ka += Color(0.1);
    t.ambient *= 0.5;
  }));
  // Another size, eye, term, or term images.
  Scene t = s;
  t.materials[0].kd += Color(0.1);
  const std::shared_ptr<const PreparedScene> edited = prepared(t);
  EXPECT_TRUE(trees->recombines(*edited, kW, kH, Term::kFull, std::nullopt, false));
  EXPECT_FALSE(trees->recombines(*edited, kW + 1, kH, Term::kFull, std::nullopt, false));
  EXPECT_FALSE(trees->recombines(*edited, kW, kH, Term::kFull, Vec3(1, 2, 3), false));
  EXPECT_FALSE(trees->recombines(*edited, kW, kH, Term::kDiffuse, std::nullopt, false));
  EXPECT_FALSE(trees->recombines(*edited, kW, kH, Term::kFull, std::nullopt, true));
}
