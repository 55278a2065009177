// The progressive image's passes, decided and run synchronously: what a generation is (its
// ladder of levels, coarse to fine, with the quad-shaded live rung), whether its first image is
// traced, re-shaded from the stored ray trees or recombined from their sums while the hand is on,
// when the live image hands over to the exact one, and when the trees are recorded. One scheduler
// for the previewer's render thread (ProgressiveRenderer, progressive.h, which adds the thread,
// the restarts' locking and cancellation and the publication of images) and the page's frame loop
// (apps/web's WebView), each calling step() a pass at a time.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/accel/prepared_scene.h"
#include "core/render/render.h"
#include "core/scene/scene.h"

namespace phonglab {

class RayTrees;

// What the renderer should produce; changing anything but `term` never restarts it.
struct ProgressiveSettings {
  int target_spp = 64;              // samples per pixel at full resolution, then idle
  int threads = 0;                  // threads per pass; 0 = all hardware threads
  Term term = Term::kFull;          // what the pixels show (a change restarts)
  // Also the five term images, from the same samples (the small multiples: one trace, five
  // sums; a change restarts).
  bool term_images = false;
  int interactive_divisor = 4;      // while interacting, refine no further than 1/this resolution
  // While interacting, refine at all after the first image (the page's frame loop, whose pass no
  // restart can cancel, shows one image per edit while the hand is on).
  bool refine_while_interacting = true;
  // While interacting, each restart starts at the finest level whose last measured pass fits
  // 1/this of a second (the previewer holds a drag's next edit until the image is out, so a
  // pass that long gives this many images a second); 0: always at the coarsest level.
  double live_images_per_s = 24;
  // Memory for the ray trees of the first sample (core/render/ray_trees.h), with which an edit
  // that changes no ray is re-shaded instead of traced; 0: none kept. The default holds a
  // 1920x1080 image of a scene like `lecture`.
  std::size_t tree_budget_bytes = std::size_t{512} << 20;
  bool lower_thread_priority = false;  // Linux: render at a higher nice value so the UI stays smooth
  std::optional<Vec3> shading_eye;  // "move your head": RenderOptions::shading_eye (a change restarts)
  // RenderOptions::ambient (a change restarts). The indirect light is traced every time (no ray
  // trees); an edit of ka or Ia alone keeps what has converged, any other edit restarts (a kd,
  // ks, light or geometry edit changes the light every surface gathers from every other).
  Ambient ambient = Ambient::kConstant;
};
// Whether the settings show the indirect light (its full image or its term).
inline bool shows_indirect(const ProgressiveSettings& s) { return ambient_for(s.term, s.ambient) == Ambient::kIndirect; }

// One step of the coarse-to-fine ladder.
struct ProgressiveLevel {
  int divisor = 1;  // the image is 1/divisor of the full resolution along each axis
  int width = 0;    // pixels
  int height = 0;   // pixels
  // The quad-shaded live rung (core/render/quad_shading.h): full resolution, every primary ray
  // traced, the shading a quarter where it is smooth. Only a live start, never a refinement step.
  bool quads = false;
  friend bool operator==(const ProgressiveLevel&, const ProgressiveLevel&) = default;
};
// 1/8, 1/4, 1/2 and full resolution, leaving out coarse levels that would not be smaller than
// the next one (a tiny window renders at full resolution at once).
std::vector<ProgressiveLevel> make_levels(int width, int height);
// The live ladder: make_levels with the quad-shaded rung before full resolution, so ordered by
// the error of each image as shown against the exact one, the largest first (measured by
// `phonglab-bench SCENE --live`: 1/8, 1/4, 1/2, the quad-shaded rung at a few hundredths of the
// half level's, the exact image). A window too small for coarse levels has no rung either.
std::vector<ProgressiveLevel> make_live_levels(int width, int height);
// `levels` (coarse to fine) with the rung inserted before the last, exact one; unchanged when
// there is only that.
std::vector<ProgressiveLevel> with_quad_rung(std::vector<ProgressiveLevel> levels);

// The last pass times measured at each level, by divisor. A level's expected time is the median
// of its last three (the mean of two, or the one): one pass slowed by the machine does not move
// a drag to a coarser level.
struct LevelTimes {
  static constexpr std::size_t kKept = 3;
  // At 1/8, 1/4, 1/2, the quad-shaded rung and full resolution; newest first, 0: none.
  std::array<std::array<double, kKept>, 5> recent{};
  static std::size_t slot(int divisor, bool quads) {
    return divisor >= 8 ? 0 : divisor >= 4 ? 1 : divisor >= 2 ? 2 : quads ? 3 : 4;
  }
  // The expected time of a pass at `divisor` (the quad-shaded rung with `quads`); 0 when none
  // was measured.
  double at(int divisor, bool quads = false) const;
  // A pass at `divisor` took `ms`.
  void note(int divisor, double ms, bool quads = false);
  void forget(int divisor, bool quads = false);  // no pass at `divisor` measured yet
};
// The index into `levels` of the finest level whose pass is expected to take at most
// `budget_ms`: its expected time, or, not measured yet, the next coarser measured level's
// time scaled by the ratio of their pixel counts. 0 (the coarsest) when none fits or nothing is
// known. With `probe`, one level finer than that when it is expected within 1.5 budgets: its
// time was measured a while ago, perhaps on a busier machine (ProgressiveRenderer probes so
// twice a second while the hand is on).
// The time a pass may take while interacting: 1 / live_images_per_s (0: none).
double live_budget_ms(const ProgressiveSettings& settings);
std::size_t live_start_level(const std::vector<ProgressiveLevel>& levels, const LevelTimes& times, double budget_ms,
                             bool probe = false);

// Where a generation stands on the ladder and where a restart starts: the one policy the
// previewer's render thread and the page's frame loop both follow, each with a ladder of its own.
class LevelLadder {
 public:
  static constexpr std::chrono::milliseconds kProbePeriod{500};
  // A new generation over `levels` (the live ladder; the times measured so far are forgotten
  // when its full resolution differs from the last one's). While `interacting` it starts at the
  // least error whose expected time fits `budget_ms` (live_start_level), and at most twice a
  // second one finer when that is expected within 1.5 budgets (a probe: its time may have been
  // measured on a busier moment); else at the coarsest. `at_full`: at the exact image at once.
  void begin(std::vector<ProgressiveLevel> levels, bool interacting, double budget_ms, bool at_full = false);
  const std::vector<ProgressiveLevel>& levels() const { return levels_; }
  bool empty() const { return levels_.empty(); }
  const ProgressiveLevel& level() const { return levels_[index_]; }  // the current one
  const ProgressiveLevel& start() const { return levels_[start_]; }  // where the generation started
  bool at_full() const { return index_ + 1 == levels_.size(); }
  // A completed pass at the current level took `ms` (`traced`: a re-shade says nothing of a
  // traced pass's time). A probe's pass is the level's time now: the older ones were why it was not run.
  void passed(double ms, bool traced = true);
  // The generation's first pass, overtaken by the next restart after `ms`: the level takes at
  // least that long, or a drag would never show anything.
  void overtaken(double ms);
  // On towards the exact image, past the quad-shaded rung (a live start only); false at it.
  bool advance();
  // To the exact image (a generation re-shaded from stored trees).
  void to_full() { index_ = levels_.empty() ? 0 : levels_.size() - 1; }

 private:
  std::vector<ProgressiveLevel> levels_;
  std::size_t index_ = 0, start_ = 0;
  LevelTimes times_;
  std::chrono::steady_clock::time_point last_probe_{};
  bool probing_ = false;  // this generation started finer than fits: its first pass's time stands alone
};


// The levels a generation of `settings` at `width` x `height` goes through: the live ladder
// (make_live_levels) where the quad-shaded rung draws what is shown (quad_rung_draws), else
// make_levels.
std::vector<ProgressiveLevel> progressive_levels(int width, int height, const ProgressiveSettings& settings);

class PassScheduler {
 public:
  PassScheduler();
  ~PassScheduler();
  PassScheduler(const PassScheduler&) = delete;
  PassScheduler& operator=(const PassScheduler&) = delete;

  // A new generation: `scene` at `width` x `height` (full resolution of one image) under
  // `settings`, the hand on or off. Its first image is re-shaded from the stored ray trees where
  // they serve (RayTrees::route), recombined from their sums while the hand is on and the edit is
  // linear, else traced from where the ladder starts (LevelLadder::begin: by the hand's budget).
  void begin(std::shared_ptr<const PreparedScene> scene, int width, int height, const ProgressiveSettings& settings,
             bool interacting);
  // Whether the image accumulated so far stands for `scene` under `settings` too (the indirect
  // light's image, and an edit of ka or Ia alone: scene_changes' indirect_unchanged); then it
  // carries over, only the scene changing.
  bool carry_over(std::shared_ptr<const PreparedScene> scene, int width, int height, const ProgressiveSettings& settings);
  // Between passes: the settings that change no image (threads, target, budgets) and the hand.
  void update(const ProgressiveSettings& settings, bool interacting);

  // Whether a pass is owed: the first image always; while the hand is on, none finer than
  // settings.interactive_divisor or the level the generation started at, none after a re-shaded
  // or live image (the next edit comes soon); else on to the exact image and its target samples,
  // and the exact re-shade owed for a live image when the hand stops.
  bool wants_pass() const;
  struct Step {
    PassStats pass;          // completed: a new image in accum()
    bool converted = false;  // the pass wrote its image into `first_image` as it went
  };
  // One pass: the live recombination, the exact re-shade (also of a live image when the hand
  // stopped), or a traced pass at the ladder's level (the quad-shaded rung or render_pass). A
  // first traced pass writes its image for the screen into `first_image` (when given) tile by
  // tile. Cancelled midway, the accumulator is left to be reset and the ladder learns how long
  // the overtaken first pass took.
  Step step(const std::atomic<bool>* cancel = nullptr, std::vector<glm::vec3>* first_image = nullptr);
  // The completed pass's image is shown, `ms` after the pass began (what the hall waits for: the
  // pass and its conversion for the screen): the level's time noted, then on up the ladder; at
  // the exact image with the hand off, the trees recorded once for this scene (a restart's
  // `cancel` stops the recording).
  void shown(double ms, const std::atomic<bool>* cancel = nullptr);

  const Accumulator& accum() const { return accum_; }  // the last completed pass's image until the next pass
  const LevelLadder& ladder() const { return ladder_; }
  const ProgressiveLevel& level() const { return ladder_.level(); }
  const std::shared_ptr<const PreparedScene>& scene() const { return scene_; }
  const ProgressiveSettings& settings() const { return settings_; }
  bool reshaded() const { return reshaded_; }      // the generation's first image came from the trees
  bool live_shown() const { return live_shown_; }  // the image is a live recombination (its exact re-shade owed)
  bool shown_any() const { return shown_any_; }    // an image of this generation was shown
  // The generation's first image is recombined live: the last live pass's time (none yet: 1e9);
  // -1 when it is not.
  double live_expected_ms() const { return live_ ? live_ms_ : -1.0; }
  std::uint64_t nan_count() const { return nan_count_; }  // NaN samples since the generation began
  std::size_t tree_bytes() const;                          // the stored trees' memory (0: none)

 private:
  void record_trees(const std::atomic<bool>* cancel);

  std::shared_ptr<const PreparedScene> scene_;
  ProgressiveSettings settings_;
  bool interacting_ = false;
  LevelLadder ladder_;           // the levels, where this generation started and stands, their times
  Accumulator accum_;
  bool accum_stale_ = true;      // accum_ is to be reset before the next pass (another level or generation)
  bool reshade_ = false;         // the next pass re-shades the stored trees instead of tracing
  bool reshaded_ = false;
  bool live_ = false;            // the next pass recombines the stored trees' sums (a linear edit, hand on)
  bool live_shown_ = false;
  bool accum_live_ = false;      // accum_ holds the image the trees last recombined, nothing since
  double live_ms_ = 1e9;         // the last live pass; none yet: not quick
  bool shown_any_ = false;
  std::uint64_t nan_count_ = 0;
  std::unique_ptr<RayTrees> trees_;  // the first sample's trees of a recent scene, or null
  bool trees_serve_ = false;         // they can re-shade this generation (scene, size, eye and what is shown)
  struct Refusal {
    int width = 0, height = 0;
    std::size_t budget = 0;
  } refused_;  // the last recording over budget: not tried again at this size and budget
};
}  // namespace phonglab
