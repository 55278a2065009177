// The one scheduler of the previewer's render thread and the page's frame loop, driven
// synchronously as the page drives it: the ladder walked to the target, every image the one
// render_pass gives; an edit that changes no ray re-shaded, a linear one recombined while the hand
// is on and handed over to the exact image when it stops; one image per edit while the hand is on
// when the caller cannot cancel a pass.
#include <gtest/gtest.h>

#include <memory>
#include <utility>
#include <vector>

#include "core/render/pass_scheduler.h"
#include "core/render/render.h"
#include "tests/support/test_support.h"

using namespace phonglab;

namespace {

constexpr int kW = 40, kH = 30;

ProgressiveSettings settings_for(int target, std::size_t tree_budget) {
  ProgressiveSettings s;
  s.target_spp = target;
  s.threads = 2;
  s.tree_budget_bytes = tree_budget;
  s.live_images_per_s = 0;  // a traced start is at the coarsest level
  return s;
}

// `samples` passes of render_pass at full resolution.
Accumulator rendered(const PreparedScene& scene, std::uint32_t samples) {
  Accumulator a;
  a.reset(kW, kH);
  for (std::uint32_t i = 0; i < samples; ++i) render_pass(scene, RenderOptions{}, a);
  return a;
}

void expect_same_sums(const Accumulator& got, const Accumulator& want) {
  ASSERT_EQ(got.width, want.width);
  ASSERT_EQ(got.height, want.height);
  ASSERT_EQ(got.samples, want.samples);
  for (std::size_t i = 0; i < want.sum.size(); ++i) ASSERT_EQ(got.sum[i], want.sum[i]) << i;
}

// Steps until no pass is owed; the levels' divisors of the images, 0 for the quad-shaded rung.
std::vector<int> run_to_rest(PassScheduler& passes) {
  std::vector<int> divisors;
  while (passes.wants_pass()) {
    const PassScheduler::Step step = passes.step();
    EXPECT_TRUE(step.pass.completed);
    divisors.push_back(passes.level().quads ? 0 : passes.level().divisor);
    passes.shown(step.pass.seconds * 1e3);
    if (divisors.size() > 20) break;
  }
  return divisors;
}

}  // namespace

TEST(PassScheduler, AGenerationWalksTheLadderToItsTargetAndEndsOnRenderPasssImage) {
  Scene scene = load_scene_or_fail("lecture");
  const auto prepared = std::make_shared<const PreparedScene>(scene);
  PassScheduler passes;
  passes.begin(prepared, kW, kH, settings_for(2, 0), false);
  EXPECT_EQ(run_to_rest(passes), (std::vector<int>{8, 4, 2, 1, 1}));
  expect_same_sums(passes.accum(), rendered(*prepared, 2));
  EXPECT_FALSE(passes.reshaded());
}

TEST(PassScheduler, AKdDragIsRecombinedLiveAndTheExactReshadeFollowsWhenTheHandStops) {
  Scene scene = load_scene_or_fail("lecture");
  PassScheduler passes;
  const ProgressiveSettings settings = settings_for(1, std::size_t{64} << 20);
  passes.begin(std::make_shared<const PreparedScene>(scene), kW, kH, settings, false);
  run_to_rest(passes);
  ASSERT_GT(passes.tree_bytes(), 0u);  // recorded at the exact image, the hand off

  scene.materials[0].kd = Color(0.1, 0.5, 0.2);
  const auto edited = std::make_shared<const PreparedScene>(scene);
  passes.begin(edited, kW, kH, settings, true);
  EXPECT_TRUE(passes.reshaded());
  EXPECT_GT(passes.live_expected_ms(), 0);  // recombined: the wait for a live image may apply
  ASSERT_TRUE(passes.wants_pass());
  const PassScheduler::Step live = passes.step();
  ASSERT_TRUE(live.pass.completed);
  EXPECT_TRUE(passes.live_shown());
  EXPECT_EQ(passes.level().divisor, 1);
  const Accumulator exact = rendered(*edited, 1);
  for (std::size_t i = 0; i < exact.sum.size(); ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(passes.accum().sum[i][c], exact.sum[i][c], 1e-12) << i;
  }
  passes.shown(1);
  EXPECT_FALSE(passes.wants_pass());  // the hand is on: the next edit comes soon

  passes.update(settings, false);  // the hand stops
  ASSERT_TRUE(passes.wants_pass());
  passes.step();
  EXPECT_FALSE(passes.live_shown());
  expect_same_sums(passes.accum(), exact);  // the exact re-shade, bit for bit render_pass's
  passes.shown(1);
  EXPECT_FALSE(passes.wants_pass());
}

TEST(PassScheduler, OneImagePerEditWhileTheHandIsOnWhenNoRestartCanCancelAPass) {
  const auto prepared = std::make_shared<const PreparedScene>(load_scene_or_fail("lecture"));
  for (const bool refine : {true, false}) {
    SCOPED_TRACE(refine);
    ProgressiveSettings settings = settings_for(1, 0);
    settings.refine_while_interacting = refine;
    PassScheduler passes;
    passes.begin(prepared, kW, kH, settings, true);
    // Refining while the hand is on stops at the interactive divisor (1/4); the page's one image
    // per edit stays at the first.
    EXPECT_EQ(run_to_rest(passes), refine ? (std::vector<int>{8, 4}) : (std::vector<int>{8}));
    passes.update(settings, false);  // the hand stops: on to the exact image
    const std::vector<int> rest = run_to_rest(passes);
    ASSERT_FALSE(rest.empty());
    EXPECT_EQ(rest.back(), 1);
    expect_same_sums(passes.accum(), rendered(*prepared, 1));
  }
}
