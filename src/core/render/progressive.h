// Progressive rendering for the previewer: a render thread that runs the passes of an image
// coarse to fine (1/8, 1/4, 1/2, full resolution, then more samples per pixel up to a target) as
// the PassScheduler decides them (pass_scheduler.h, the page's scheduler too), restarting
// whenever it is handed a new scene snapshot, and publishes each image.
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

#include "core/render/pass_scheduler.h"
#include "core/render/render.h"
#include "core/scene/scene.h"

namespace phonglab {

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
