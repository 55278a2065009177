// Progressive rendering for the previewer: a render thread that owns the accumulator and
// refines an image coarse to fine (1/8, 1/4, 1/2, full resolution, then more samples per
// pixel up to a target), restarting whenever it is handed a new scene snapshot.
//
// Restart protocol: set_scene / set_resolution / a term change bump a generation counter under
// the lock, drop any published frame not yet taken and raise the cancel flag of the running
// pass. The thread publishes a finished pass only if its generation is still current (checked
// under the same lock), so once set_scene(B) has returned, take_frame never yields a pixel of an
// older scene. No call here waits for the render thread except the destructor.
//
// Pure: no GL, no window system. The previewer and the tests drive it alike.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "core/render/render.h"
#include "core/scene/scene.h"

namespace phonglab {

// What the renderer should produce; changing anything but `term` never restarts it.
struct ProgressiveSettings {
  int target_spp = 64;              // samples per pixel at full resolution, then idle
  int threads = 0;                  // threads per pass; 0 = all hardware threads
  Term term = Term::kFull;          // what the pixels show (a change restarts)
  // Also the five term images, from the same samples (the small multiples: one trace, five
  // sums; a change restarts).
  bool term_images = false;
  int interactive_divisor = 4;      // while interacting, refine no further than 1/this resolution
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

// Statistics of one published image.
struct FrameStats {
  double pass_ms = 0;                 // wall time of the pass that completed the image
  RayCounts pass_rays;                // rays that pass cast, by kind
  double mrays_per_s = 0;             // pass_rays.total() / pass time, millions per second
  std::uint64_t nan_count = 0;        // NaN/Inf samples since the restart (replaced by 0)
  double ms_since_restart = 0;        // from the restart to this image's publication
  std::uint64_t serial = 0;           // counts every image ever published (1, 2, ...)
  bool packets = false;               // PassStats::packets of that pass
  const char* packet_kernels = "";    // then the packet kernels' instance ("AVX2": packet_simd_target)
  int packet_lanes = 0;               // and its lanes
  bool reshaded = false;              // re-shaded from the stored ray trees, not traced
  bool live = false;                  // the live path's image of a linear edit (RayTrees::recombine):
                                      // equal to rounding; the exact re-shade follows when the hand stops
  std::size_t tree_bytes = 0;         // memory the stored ray trees take (0: none kept)
};

// One finished image: the mean of the samples so far at one level of resolution.
struct ProgressiveFrame {
  std::uint64_t generation = 0;   // restart count the pixels belong to
  int width = 0;                  // pixels across at this level
  int height = 0;                 // pixels down at this level
  int divisor = 1;                // 8, 4 or 2 for the coarse levels, 1 at full resolution
  bool quads = false;             // the quad-shaded live rung (divisor 1), not the exact image
  std::uint32_t spp = 0;          // samples per pixel in `pixels`
  std::vector<glm::vec3> pixels;  // linear RGB mean, row-major from the top-left
  // With ProgressiveSettings::term_images: ambient, diffuse, specular, reflection and refraction
  // at the primary hits, each like `pixels`; else empty.
  std::array<std::vector<glm::vec3>, 5> terms;
  FrameStats stats;
};

// What the render thread is doing, for overlays and tests.
struct ProgressiveStatus {
  std::uint64_t generation = 0;  // current generation (the newest restart)
  bool idle = false;             // waiting: target reached, interacting cap hit or no scene
  std::uint64_t passes = 0;      // completed passes since construction
  std::uint64_t serial = 0;      // FrameStats::serial of the newest published image (0: none)
  std::uint64_t published_generation = 0;  // generation of the newest published image
};

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

class ProgressiveRenderer {
 public:
  // `on_frame` (optional) runs on the render thread after each publication, outside the lock:
  // a GUI wakes its event loop from it.
  explicit ProgressiveRenderer(ProgressiveSettings settings = {}, std::function<void()> on_frame = {});
  // Cancels the running pass and joins the render thread.
  ~ProgressiveRenderer();
  ProgressiveRenderer(const ProgressiveRenderer&) = delete;
  ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

  // Hands over an immutable, prepared snapshot (PreparedScene) and restarts. Returns the new
  // generation. A null scene stops rendering.
  std::uint64_t set_scene(std::shared_ptr<const PreparedScene> scene);
  // The same with a new full-resolution size: one restart for both (a UI frame that both
  // edits the scene and resizes the window restarts once).
  std::uint64_t set_scene(std::shared_ptr<const PreparedScene> scene, int width, int height);
  // Full-resolution image size in pixels; restarts when it changes. Returns the generation.
  std::uint64_t set_resolution(int width, int height);
  // Applies settings; only a term change restarts (samples do not depend on threads, and a
  // new target continues or stops the accumulation). Returns the generation.
  std::uint64_t set_settings(const ProgressiveSettings& settings);
  // While interacting, refinement stops at the interactive divisor; clearing it resumes.
  void set_interacting(bool interacting);

  // Swaps the newest not-yet-taken image into `frame` (O(1) under the lock: the buffers trade
  // places). Returns false, leaving `frame` untouched, when there is nothing new.
  bool take_frame(ProgressiveFrame& frame);
  ProgressiveStatus status() const;
  // Blocks until the render thread idles on the current generation, or the timeout passes.
  // For tests and scripts; a UI never calls it.
  bool wait_idle(std::chrono::milliseconds timeout);
  // While a hand is on: blocks until `generation`'s image is published, when the render thread
  // makes it on the live path and its last live image took at most `quick` (so the edit shows in
  // the UI frame that made it, not the next); returns at once otherwise, or after `timeout`.
  // True when that image is published.
  bool wait_for_live_image(std::uint64_t generation, std::chrono::milliseconds quick, std::chrono::milliseconds timeout);

 private:
  struct Job;
  void run();
  bool wait_for_work(Job& job);  // false: stop
  void start_generation_locked(Job& job);
  void publish(Job& job, const PassStats& pass);
  void record_trees(Job& job);
  std::uint64_t restart_locked();

  mutable std::mutex mutex_;
  std::condition_variable wake_;       // the render thread sleeps on it when idle
  std::condition_variable idle_cv_;    // wait_idle sleeps on it
  std::atomic<bool> cancel_{false};    // raised by a restart; the running pass stops between tiles
  // Guarded by mutex_:
  std::shared_ptr<const PreparedScene> scene_;
  int width_ = 0;
  int height_ = 0;
  ProgressiveSettings settings_;
  bool interacting_ = false;
  bool stop_ = false;
  bool idle_ = false;
  std::uint64_t generation_ = 0;
  std::uint64_t idle_generation_ = 0;  // generation the thread last idled on
  std::uint64_t passes_ = 0;
  std::uint64_t serial_ = 0;
  std::uint64_t published_generation_ = 0;
  std::uint64_t decided_generation_ = 0;  // the newest generation the render thread has picked up
  double decided_live_ms_ = -1;           // its live pass's expected time (the last one's), -1: not live
  std::chrono::steady_clock::time_point restart_time_;
  ProgressiveFrame published_;
  bool published_fresh_ = false;       // published_ holds an image nobody has taken yet
  // Owned by the render thread only:
  ProgressiveFrame back_;
  std::function<void()> on_frame_;     // set once at construction
  std::thread thread_;                 // started last, after every member above exists
};

}  // namespace phonglab
