// The previewer's progressive renderer: the restart protocol (no image of an old scene after
// set_scene), coarse-to-fine order, idling at the target, thread-count independence.
// Written to run under ThreadSanitizer: small images, no sleeps longer than needed.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <ctime>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

#include "core/render/progressive.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"
#include "tests/support/test_support.h"

using namespace phonglab;
using namespace std::chrono_literals;

namespace {

constexpr auto kLongWait = 60s;  // generous: TSan slows rendering by an order of magnitude

// Only the background shows; `decoys` spheres behind the camera make passes slow without
// changing a pixel, so restarts land in the middle of passes.
std::shared_ptr<const PreparedScene> background_scene(const Color& background, int decoys) {
  Scene s;
  s.background = background;
  s.materials.push_back(Material{});
  for (int i = 0; i < decoys; ++i) s.spheres.push_back(Sphere{Vec3(i % 10, i / 10, 40), 0.25, 0});
  return std::make_shared<const PreparedScene>(std::move(s));
}

std::shared_ptr<const PreparedScene> lecture_scene() {
  return std::make_shared<const PreparedScene>(load_prepared("lecture"));
}

bool all_pixels_are(const ProgressiveFrame& frame, const glm::vec3& color) {
  for (const glm::vec3& p : frame.pixels) {
    if (p != color) return false;
  }
  return !frame.pixels.empty();
}

// Records every published frame's level and spp by taking it from the on_frame hook.
struct FrameLog {
  std::mutex mutex;
  std::vector<int> divisors;
  std::vector<std::uint32_t> spps;
  ProgressiveRenderer* renderer = nullptr;
  void on_frame() {
    ProgressiveFrame frame;
    const std::lock_guard lock(mutex);
    if (renderer && renderer->take_frame(frame)) {
      divisors.push_back(frame.divisor);
      spps.push_back(frame.spp);
    }
  }
};

double process_cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

TEST(ProgressiveRenderer, NoFrameAfterSetSceneShowsTheOldScene) {
  const glm::vec3 red(1, 0, 0), blue(0, 0, 1);
  const auto scene_a = background_scene(Color(1, 0, 0), 200);
  const auto scene_b = background_scene(Color(0, 0, 1), 200);
  ProgressiveSettings settings;
  settings.target_spp = 3;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(96, 64);
  int frames_checked = 0;
  for (int round = 0; round < 40; ++round) {
    renderer.set_scene(scene_a);
    // Vary the moment of the switch: before, during and after A's first passes.
    std::this_thread::sleep_for(std::chrono::microseconds(250 * (round % 8)));
    ProgressiveFrame frame;
    if (renderer.take_frame(frame)) {
      EXPECT_TRUE(all_pixels_are(frame, red)) << "round " << round;
    }
    const std::uint64_t generation_b = renderer.set_scene(scene_b);
    const auto deadline = std::chrono::steady_clock::now() + kLongWait;
    bool finished = false;
    while (!finished && std::chrono::steady_clock::now() < deadline) {
      if (renderer.take_frame(frame)) {
        ++frames_checked;
        ASSERT_EQ(frame.generation, generation_b) << "round " << round;
        ASSERT_TRUE(all_pixels_are(frame, blue)) << "round " << round << ": a pixel of scene A";
        finished = frame.divisor == 1;
      } else {
        std::this_thread::sleep_for(100us);
      }
    }
    EXPECT_TRUE(finished) << "round " << round;
  }
  EXPECT_GE(frames_checked, 40);
}

TEST(ProgressiveRenderer, LevelsGoCoarseToFineThenAccumulateToTheTarget) {
  FrameLog log;
  ProgressiveSettings settings;
  settings.target_spp = 3;
  ProgressiveRenderer renderer(settings, [&] { log.on_frame(); });
  {
    const std::lock_guard lock(log.mutex);
    log.renderer = &renderer;
  }
  renderer.set_resolution(64, 48);
  renderer.set_scene(background_scene(Color(0.5), 0));
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  const std::lock_guard lock(log.mutex);
  EXPECT_EQ(log.divisors, (std::vector<int>{8, 4, 2, 1, 1, 1}));
  EXPECT_EQ(log.spps, (std::vector<std::uint32_t>{1, 1, 1, 1, 2, 3}));
  log.renderer = nullptr;
}

TEST(ProgressiveRenderer, CoarseLevelImagesHaveTheirReducedSize) {
  ProgressiveSettings settings;
  settings.target_spp = 1;
  settings.interactive_divisor = 8;
  ProgressiveRenderer renderer(settings);
  renderer.set_interacting(true);
  renderer.set_resolution(160, 90);
  renderer.set_scene(background_scene(Color(0.25), 0));
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_EQ(frame.divisor, 8);
  EXPECT_EQ(frame.width, 20);
  EXPECT_EQ(frame.height, 12);  // ceil(90 / 8)
  EXPECT_EQ(frame.pixels.size(), 20u * 12u);
}

TEST(ProgressiveRenderer, InteractingStaysAtCoarseLevelsUntilReleased) {
  FrameLog log;
  ProgressiveSettings settings;
  settings.target_spp = 2;
  settings.interactive_divisor = 4;
  ProgressiveRenderer renderer(settings, [&] { log.on_frame(); });
  {
    const std::lock_guard lock(log.mutex);
    log.renderer = &renderer;
  }
  renderer.set_interacting(true);
  renderer.set_resolution(64, 48);
  renderer.set_scene(background_scene(Color(0.5), 0));
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  {
    const std::lock_guard lock(log.mutex);
    EXPECT_EQ(log.divisors, (std::vector<int>{8, 4}));
  }
  renderer.set_interacting(false);
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  const std::lock_guard lock(log.mutex);
  EXPECT_EQ(log.divisors, (std::vector<int>{8, 4, 2, 1, 1}));
  log.renderer = nullptr;
}

// The finest level whose pass fits the budget: measured times where known, else the next
// coarser measured time times the ratio of pixel counts.
TEST(ProgressiveLevels, LiveStartIsTheFinestLevelThatFitsTheBudget) {
  const std::vector<ProgressiveLevel> levels = make_levels(1280, 720);
  ASSERT_EQ(levels.size(), 4u);
  LevelTimes times;
  EXPECT_EQ(live_start_level(levels, times, 33), 0u);  // nothing measured: the coarsest
  times.note(8, 0.5);  // 160x90; 1/4 and 1/2 then expected at 2 and 8 ms, full at 32
  EXPECT_EQ(levels[live_start_level(levels, times, 33)].divisor, 1);
  EXPECT_EQ(levels[live_start_level(levels, times, 31.9)].divisor, 2);
  EXPECT_EQ(levels[live_start_level(levels, times, 7.9)].divisor, 4);
  EXPECT_EQ(levels[live_start_level(levels, times, 0.4)].divisor, 8);  // none fits: the coarsest
  times.note(2, 20);  // measured slower than expected: the full level is now expected at 80 ms
  EXPECT_EQ(levels[live_start_level(levels, times, 33)].divisor, 2);
  EXPECT_EQ(levels[live_start_level(levels, times, 19)].divisor, 4);
  times.note(1, 30);  // measured: that wins over the estimate
  EXPECT_EQ(levels[live_start_level(levels, times, 33)].divisor, 1);
}

// The live ladder holds the quad-shaded rung between 1/2 and the exact image (the order of their
// measured errors), at full resolution; a window too small for coarse levels has no rung.
TEST(ProgressiveLevels, TheLiveLadderHoldsTheQuadRungBeforeTheExactImage) {
  const std::vector<ProgressiveLevel> live = make_live_levels(1280, 720);
  ASSERT_EQ(live.size(), 5u);
  const std::vector<int> divisors = {live[0].divisor, live[1].divisor, live[2].divisor, live[3].divisor, live[4].divisor};
  EXPECT_EQ(divisors, (std::vector<int>{8, 4, 2, 1, 1}));
  EXPECT_TRUE(live[3].quads);
  EXPECT_FALSE(live[4].quads);
  EXPECT_EQ(live[3].width, 1280);
  EXPECT_EQ(live[3].height, 720);
  for (const ProgressiveLevel& level : make_levels(1280, 720)) EXPECT_FALSE(level.quads);
  EXPECT_EQ(make_live_levels(1, 1).size(), 1u);  // no coarse level, no rung
  EXPECT_FALSE(make_live_levels(1, 1)[0].quads);
}

// The least error that fits: the exact image when it fits, else the rung when its measured time
// fits, else 1/2. The rung's time is its own, not the exact image's.
TEST(ProgressiveLevels, TheRungIsChosenWhenTheExactImageDoesNotFitButItDoes) {
  const std::vector<ProgressiveLevel> live = make_live_levels(1280, 720);
  LevelTimes times;
  times.note(8, 0.7);
  times.note(4, 2.5);
  times.note(2, 10);
  times.note(1, 45);  // the exact image: beyond a 24th of a second
  // Not measured yet: expected as the 1/2 level's time times four (40 ms), which fits.
  EXPECT_TRUE(live[live_start_level(live, times, 41.7)].quads);
  times.note(1, 33, true);
  EXPECT_DOUBLE_EQ(times.at(1, true), 33);
  EXPECT_DOUBLE_EQ(times.at(1), 45);
  EXPECT_TRUE(live[live_start_level(live, times, 41.7)].quads);
  EXPECT_EQ(live[live_start_level(live, times, 30)].divisor, 2) << "neither fits 30 ms";
  times.note(1, 30);
  times.note(1, 31);  // the exact image fits now (median 31 ms): it wins over the rung
  const ProgressiveLevel& best = live[live_start_level(live, times, 41.7)];
  EXPECT_EQ(best.divisor, 1);
  EXPECT_FALSE(best.quads);
  times.forget(1, true);
  EXPECT_DOUBLE_EQ(times.at(1, true), 0);
  EXPECT_DOUBLE_EQ(times.at(1), 31);
}

// The ladder both the render thread and the page follow: coarse to fine past the rung while the
// hand is off; while it is on, the least error that fits, a probe one finer at most twice a
// second, the probe's pass standing alone as its level's time.
TEST(ProgressiveLevels, TheLadderStartsWhereTheTimesSayAndRefinesPastTheRung) {
  LevelLadder ladder;
  ladder.begin(make_live_levels(1280, 720), false, 41.7);
  std::vector<int> walked = {ladder.level().divisor};
  for (const double ms : {1.0, 3.0, 10.0}) {
    ladder.passed(ms);
    ASSERT_TRUE(ladder.advance());
    EXPECT_FALSE(ladder.level().quads) << "the rung is a live start only";
    walked.push_back(ladder.level().divisor);
  }
  EXPECT_EQ(walked, (std::vector<int>{8, 4, 2, 1}));
  EXPECT_TRUE(ladder.at_full());
  ladder.passed(50);  // the exact image: beyond the budget, within 1.5 budgets
  EXPECT_FALSE(ladder.advance());
  // The hand on: the rung is expected at four times the half level's 10 ms and fits; the first
  // restart probes the exact image.
  ladder.begin(make_live_levels(1280, 720), true, 41.7);
  EXPECT_TRUE(ladder.at_full()) << "a probe one finer than fits";
  ladder.passed(60);  // the probe's time stands alone: the exact image is now expected at 60 ms
  ladder.begin(make_live_levels(1280, 720), true, 41.7);
  EXPECT_TRUE(ladder.level().quads) << "no second probe within half a second";
  EXPECT_TRUE(ladder.start().quads);
  ladder.overtaken(45);  // overtaken after 45 ms: the rung takes at least that
  ladder.begin(make_live_levels(1280, 720), true, 41.7);
  EXPECT_EQ(ladder.level().divisor, 2);
  EXPECT_FALSE(ladder.level().quads);
  ladder.begin(make_live_levels(1280, 720), true, 41.7, true);
  EXPECT_TRUE(ladder.at_full()) << "a re-shade starts at the exact image";
  ladder.begin(make_live_levels(640, 360), true, 41.7);
  EXPECT_EQ(ladder.level().divisor, 8) << "another size: nothing measured, the coarsest";
}

// A level's expected time is the median of its last three passes: one slow pass does not move a
// drag to a coarser level; a probe tries one level finer when it is expected within 1.5 budgets.
TEST(ProgressiveLevels, OneSlowPassDoesNotDemoteAndAProbeTriesOneFiner) {
  const std::vector<ProgressiveLevel> levels = make_levels(1280, 720);
  LevelTimes times;
  times.note(8, 0.5);
  times.note(4, 2);
  times.note(2, 9);
  times.note(1, 35);
  times.note(1, 36);
  EXPECT_DOUBLE_EQ(times.at(1), 35.5);  // the mean of two
  times.note(1, 60);                    // one pass on a busy moment
  EXPECT_DOUBLE_EQ(times.at(1), 36);    // the median of three
  EXPECT_EQ(levels[live_start_level(levels, times, 41.7)].divisor, 1);
  times.note(1, 61);
  EXPECT_DOUBLE_EQ(times.at(1), 60);  // two slow ones: it is slow now
  EXPECT_EQ(levels[live_start_level(levels, times, 41.7)].divisor, 2);
  EXPECT_EQ(levels[live_start_level(levels, times, 41.7, true)].divisor, 1) << "60 ms is within 1.5 budgets";
  EXPECT_EQ(levels[live_start_level(levels, times, 33, true)].divisor, 2) << "60 ms is beyond 1.5 budgets";
  times.note(1, 34);
  times.note(1, 33);
  EXPECT_EQ(levels[live_start_level(levels, times, 41.7)].divisor, 1) << "the probe measured it fast again";
}

// Once its levels have been timed, a restart while interacting starts at the finest level that
// fits, and stays there until the interaction ends; a budget of 0 keeps the coarse start.
TEST(ProgressiveRenderer, LiveRestartsStartAtTheFinestLevelThatFits) {
  for (const double images_per_s : {1.0, 0.0}) {
    SCOPED_TRACE(images_per_s);
    FrameLog log;
    ProgressiveSettings settings;
    settings.target_spp = 1;
    settings.live_images_per_s = images_per_s;  // 1 s: any pass of a 64x48 image fits
    ProgressiveRenderer renderer(settings, [&] { log.on_frame(); });
    {
      const std::lock_guard lock(log.mutex);
      log.renderer = &renderer;
    }
    renderer.set_resolution(64, 48);
    renderer.set_scene(background_scene(Color(0.5), 0));
    ASSERT_TRUE(renderer.wait_idle(kLongWait));  // every level timed once
    std::this_thread::sleep_for(100ms);           // restarts far apart: the budget decides
    renderer.set_interacting(true);
    renderer.set_scene(background_scene(Color(0.25), 1));  // new geometry: traced, not re-shaded
    ASSERT_TRUE(renderer.wait_idle(kLongWait));
    renderer.set_interacting(false);
    ASSERT_TRUE(renderer.wait_idle(kLongWait));
    const std::lock_guard lock(log.mutex);
    const std::vector<int> live = images_per_s > 0 ? std::vector<int>{8, 4, 2, 1, 1} : std::vector<int>{8, 4, 2, 1, 8, 4, 2, 1};
    EXPECT_EQ(log.divisors, live);
    log.renderer = nullptr;
  }
}

// After an image has reached full resolution its first sample's trees are kept: an edit that
// changes no ray (kd), or only shadow rays (a light moved), then shows the full-resolution image
// at once, re-shaded, bit for bit what render_pass gives; more samples follow as before. With no
// memory for trees, the same edit starts again at 1/8.
TEST(ProgressiveRenderer, EditsThatChangeNoRayAreReshadedAtFullResolution) {
  for (const std::size_t budget : {std::size_t{64} << 20, std::size_t{0}}) {
    SCOPED_TRACE(budget);
    FrameLog log;
    ProgressiveSettings settings;
    settings.target_spp = 2;
    settings.tree_budget_bytes = budget;
    settings.live_images_per_s = 0;  // a traced restart starts at 1/8
    ProgressiveRenderer renderer(settings, [&] { log.on_frame(); });
    {
      const std::lock_guard lock(log.mutex);
      log.renderer = &renderer;
    }
    renderer.set_resolution(40, 30);
    Scene scene = load_scene_or_fail("lecture");
    renderer.set_scene(std::make_shared<const PreparedScene>(scene));
    ASSERT_TRUE(renderer.wait_idle(kLongWait));
    for (int edit = 0; edit < 2; ++edit) {
      if (edit == 0) scene.materials[0].kd = Color(0.1, 0.5, 0.2);
      else scene.lights[0].position += Vec3(0.5, 0.2, 0);
      const auto edited = std::make_shared<const PreparedScene>(scene);
      {
        const std::lock_guard lock(log.mutex);
        log.renderer = nullptr;  // the first image of the edit is taken here
      }
      renderer.set_interacting(true);  // as while a slider is held: the first image only
      renderer.set_scene(edited);
      ASSERT_TRUE(renderer.wait_idle(kLongWait));
      ProgressiveFrame frame;
      ASSERT_TRUE(renderer.take_frame(frame));
      EXPECT_EQ(frame.divisor, budget > 0 ? 1 : 4);  // re-shaded, or the coarse levels up to the cap
      EXPECT_EQ(frame.stats.reshaded, budget > 0);
      if (budget > 0) {
        EXPECT_GT(frame.stats.tree_bytes, 0u);
        Accumulator fresh;
        fresh.reset(40, 30);
        render_pass(*edited, RenderOptions{}, fresh);
        ASSERT_EQ(frame.pixels.size(), fresh.sum.size());
        for (std::size_t i = 0; i < frame.pixels.size(); ++i) ASSERT_EQ(frame.pixels[i], glm::vec3(fresh.sum[i])) << i;
      }
      renderer.set_interacting(false);
      ASSERT_TRUE(renderer.wait_idle(kLongWait));
      ASSERT_TRUE(renderer.take_frame(frame));
      EXPECT_EQ(frame.spp, 2u);
    }
  }
}

// A UI frame may wait for its own edit's live image: wait_for_live_image returns with it when the
// render thread makes it on the live path and the last live image was quick, and without waiting
// for the timeout when it is not live (a camera edit) or not known to be quick (the first). (Those
// two may still find their image published already: a pass of 40x30 pixels is that quick.)
TEST(ProgressiveRenderer, ALiveImageIsWaitedForOnlyWhenItIsQuick) {
  ProgressiveSettings settings;
  settings.target_spp = 1;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(40, 30);
  Scene scene = load_scene_or_fail("lecture");
  renderer.set_scene(std::make_shared<const PreparedScene>(scene));
  ASSERT_TRUE(renderer.wait_idle(kLongWait));  // the image, then its trees
  renderer.set_interacting(true);
  const auto edit = [&](bool camera) {
    if (camera) scene.camera.position.x += 0.1;
    else scene.materials[0].kd.x = scene.materials[0].kd.x > 0.5 ? 0.3 : 0.7;
    return renderer.set_scene(std::make_shared<const PreparedScene>(scene));
  };
  const auto returns_promptly = [&](std::uint64_t generation) {
    const auto start = std::chrono::steady_clock::now();
    const bool shown = renderer.wait_for_live_image(generation, 50ms, kLongWait);
    EXPECT_LT(std::chrono::steady_clock::now() - start, kLongWait / 2);
    return shown;
  };
  returns_promptly(edit(false));  // the first live image: its time not known yet
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_TRUE(frame.stats.live);
  const std::uint64_t second = edit(false);
  EXPECT_TRUE(returns_promptly(second));  // quick now: waited for, and there
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_EQ(frame.generation, second);
  EXPECT_TRUE(frame.stats.live);
  returns_promptly(edit(true));  // a camera edit traces: not waited for
  renderer.set_interacting(false);
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
}

// The small multiples: with term_images, every image brings the five term images of the same
// samples, traced or re-shaded from the trees; each is what render_pass gives that term.
TEST(ProgressiveRenderer, TermImagesComeWithEveryImage) {
  ProgressiveSettings settings;
  settings.target_spp = 1;
  settings.term_images = true;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(40, 30);
  Scene scene = load_scene_or_fail("lecture");
  const std::array<Term, 5>& terms = kFiveTerms;
  for (int edit = 0; edit < 2; ++edit) {
    if (edit == 1) scene.materials[0].ks = Color(0.9, 0.1, 0.2);  // re-shaded from the trees
    const auto prepared_scene = std::make_shared<const PreparedScene>(scene);
    renderer.set_scene(prepared_scene);
    ASSERT_TRUE(renderer.wait_idle(kLongWait));
    ProgressiveFrame frame;
    ASSERT_TRUE(renderer.take_frame(frame));
    ASSERT_EQ(frame.divisor, 1);
    EXPECT_EQ(frame.stats.reshaded, edit == 1);
    for (std::size_t k = 0; k < terms.size(); ++k) {
      Accumulator alone;
      alone.reset(40, 30);
      RenderOptions options;
      options.term = terms[k];
      render_pass(*prepared_scene, options, alone);
      ASSERT_EQ(frame.terms[k].size(), alone.sum.size());
      for (std::size_t i = 0; i < alone.sum.size(); ++i) {
        ASSERT_EQ(frame.terms[k][i], glm::vec3(alone.sum[i])) << term_name(terms[k]) << " pixel " << i;
      }
    }
  }
  settings.term_images = false;
  renderer.set_settings(settings);
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_TRUE(frame.terms[0].empty());
}

TEST(ProgressiveRenderer, IdlesWithoutUsingTheCpuAfterTheTarget) {
  ProgressiveSettings settings;
  settings.target_spp = 4;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(48, 32);
  renderer.set_scene(lecture_scene());
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_EQ(frame.divisor, 1);
  EXPECT_EQ(frame.spp, 4u);

  const std::uint64_t passes = renderer.status().passes;
  const double cpu_before = process_cpu_seconds();
  std::this_thread::sleep_for(300ms);
  const double cpu_used = process_cpu_seconds() - cpu_before;
  EXPECT_EQ(renderer.status().passes, passes);
  EXPECT_TRUE(renderer.status().idle);
  EXPECT_LT(cpu_used, 0.05) << "the idle render thread should sleep, not spin";
  EXPECT_FALSE(renderer.take_frame(frame)) << "no new image while idle";
}

TEST(ProgressiveRenderer, RaisingTheTargetContinuesWithoutRestart) {
  ProgressiveSettings settings;
  settings.target_spp = 2;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(32, 24);
  const std::uint64_t generation = renderer.set_scene(lecture_scene());
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  settings.target_spp = 5;
  settings.threads = 1;  // neither a new target nor a thread count changes the image: no restart
  EXPECT_EQ(renderer.set_settings(settings), generation);
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_EQ(frame.generation, generation);
  EXPECT_EQ(frame.spp, 5u);
}

TEST(ProgressiveRenderer, TermChangeRestarts) {
  ProgressiveSettings settings;
  settings.target_spp = 1;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(32, 24);
  const std::uint64_t generation = renderer.set_scene(lecture_scene());
  settings.term = Term::kNormal;
  EXPECT_GT(renderer.set_settings(settings), generation);
}

TEST(ProgressiveRenderer, ResultIsIndependentOfThreadCountAndMatchesRenderPass) {
  const auto scene = lecture_scene();
  constexpr int kWidth = 40, kHeight = 30, kSpp = 3;
  std::vector<ProgressiveFrame> finals;
  for (const int threads : {1, 2, 3}) {
    ProgressiveSettings settings;
    settings.target_spp = kSpp;
    settings.threads = threads;
    ProgressiveRenderer renderer(settings);
    renderer.set_resolution(kWidth, kHeight);
    renderer.set_scene(scene);
    ASSERT_TRUE(renderer.wait_idle(kLongWait));
    ProgressiveFrame frame;
    ASSERT_TRUE(renderer.take_frame(frame));
    ASSERT_EQ(frame.spp, static_cast<std::uint32_t>(kSpp));
    finals.push_back(std::move(frame));
  }
  EXPECT_EQ(finals[0].pixels, finals[1].pixels);
  EXPECT_EQ(finals[0].pixels, finals[2].pixels);

  // The full-resolution accumulation starts again at sample 0: the same as plain passes.
  Accumulator accum;
  accum.reset(kWidth, kHeight);
  for (int i = 0; i < kSpp; ++i) render_pass(*scene, RenderOptions{}, accum);
  std::vector<glm::vec3> expected;
  for (const Color& sum : accum.sum) expected.emplace_back(sum * (1.0 / kSpp));
  EXPECT_EQ(finals[0].pixels, expected);
}

TEST(ProgressiveRenderer, SetSceneDoesNotWaitForTheRunningPass) {
  ProgressiveSettings settings;
  settings.target_spp = 1000;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(256, 256);
  renderer.set_scene(background_scene(Color(1, 0, 0), 400));
  std::this_thread::sleep_for(20ms);  // a pass is now running
  double slowest_ms = 0;
  for (int i = 0; i < 20; ++i) {
    const auto start = std::chrono::steady_clock::now();
    renderer.set_scene(background_scene(Color(0, i % 2, 1), 400));
    slowest_ms = std::max(slowest_ms, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    std::this_thread::sleep_for(2ms);
  }
  // Building the snapshot dominates; the call itself only takes the lock briefly.
  EXPECT_LT(slowest_ms, 50.0);
}

TEST(ProgressiveRenderer, DestructionDuringAPassStopsPromptly) {
  const auto start = std::chrono::steady_clock::now();
  {
    ProgressiveSettings settings;
    settings.target_spp = 1000;
    ProgressiveRenderer renderer(settings);
    renderer.set_resolution(512, 512);
    renderer.set_scene(background_scene(Color(1, 0, 0), 400));
    std::this_thread::sleep_for(20ms);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0);
}

TEST(ProgressiveRenderer, TinyImagesRenderAtFullResolutionAtOnce) {
  FrameLog log;
  ProgressiveSettings settings;
  settings.target_spp = 2;
  ProgressiveRenderer renderer(settings, [&] { log.on_frame(); });
  {
    const std::lock_guard lock(log.mutex);
    log.renderer = &renderer;
  }
  renderer.set_resolution(1, 1);
  renderer.set_scene(background_scene(Color(0.5), 0));
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  const std::lock_guard lock(log.mutex);
  EXPECT_EQ(log.divisors, (std::vector<int>{1, 1}));
  log.renderer = nullptr;
}

TEST(ProgressiveRenderer, NoSceneOrEmptyImageMeansIdleWithoutFrames) {
  ProgressiveRenderer renderer;
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  renderer.set_resolution(0, 0);
  renderer.set_scene(background_scene(Color(0.5), 0));
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ProgressiveFrame frame;
  EXPECT_FALSE(renderer.take_frame(frame));
}

// The indirect light's view: an edit of ka (which it never reads) keeps the samples it has and
// shows them as the new generation's image; an edit of kd starts again. The image after the ka
// edit is the one a fresh render of the edited scene gives, bit for bit.
TEST(ProgressiveRenderer, IndirectViewKeepsItsSamplesThroughAKaEditButNotAKdEdit) {
  ProgressiveSettings settings;
  settings.target_spp = 4;
  settings.ambient = Ambient::kIndirect;
  settings.tree_budget_bytes = 0;
  ProgressiveRenderer renderer(settings);
  renderer.set_resolution(48, 27);
  const auto scene = lecture_scene();
  renderer.set_scene(scene);
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ProgressiveFrame frame;
  ASSERT_TRUE(renderer.take_frame(frame));
  ASSERT_EQ(frame.spp, 4u);

  Scene ka_edit = scene->scene();
  ka_edit.materials[0].ka = Color(0.9, 0.1, 0.1);
  ka_edit.ambient = Color(0.3);
  const std::uint64_t kept = renderer.set_scene(std::make_shared<const PreparedScene>(ka_edit));
  ASSERT_TRUE(renderer.wait_idle(kLongWait));
  ASSERT_TRUE(renderer.take_frame(frame));
  EXPECT_EQ(frame.generation, kept);
  EXPECT_EQ(frame.spp, 4u);  // no sample was traced again
  EXPECT_EQ(frame.divisor, 1);
  RenderOptions options;
  options.ambient = Ambient::kIndirect;
  Accumulator fresh;
  fresh.reset(48, 27);
  render_passes(PreparedScene(ka_edit), options, fresh, 4);
  for (std::size_t i = 0; i < fresh.sum.size(); ++i) ASSERT_EQ(frame.pixels[i], glm::vec3(fresh.sum[i] / 4.0));

  Scene kd_edit = ka_edit;
  kd_edit.materials[0].kd = Color(0.2);
  const std::uint64_t restarted = renderer.set_scene(std::make_shared<const PreparedScene>(kd_edit));
  std::vector<std::uint32_t> spps;
  const auto deadline = std::chrono::steady_clock::now() + kLongWait;
  while (!renderer.status().idle || renderer.status().generation != restarted) {
    if (renderer.take_frame(frame)) spps.push_back(frame.spp);
    ASSERT_LT(std::chrono::steady_clock::now(), deadline);
    std::this_thread::sleep_for(1ms);
  }
  if (renderer.take_frame(frame)) spps.push_back(frame.spp);
  EXPECT_EQ(frame.generation, restarted);
  EXPECT_EQ(frame.divisor, 1);
  ASSERT_FALSE(spps.empty());
  EXPECT_EQ(frame.spp, 4u);
  fresh.reset(48, 27);
  render_passes(PreparedScene(kd_edit), options, fresh, 4);  // traced again: the kd edit's own image
  for (std::size_t i = 0; i < fresh.sum.size(); ++i) ASSERT_EQ(frame.pixels[i], glm::vec3(fresh.sum[i] / 4.0));
}
