#include "core/render/progressive.h"

#include <algorithm>
#include <utility>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace phonglab {

namespace {

// One step of the coarse-to-fine ladder.
struct Level {
  int divisor = 1;  // the image is 1/divisor of the full resolution along each axis
  int width = 0;    // pixels
  int height = 0;   // pixels
};

int ceil_div(int a, int b) { return (a + b - 1) / b; }

// 1/8, 1/4, 1/2 and full resolution, leaving out coarse levels that would not be smaller than
// the next one (a tiny window renders at full resolution at once).
std::vector<Level> make_levels(int width, int height) {
  std::vector<Level> levels;
  if (width <= 0 || height <= 0) return levels;
  for (const int divisor : {8, 4, 2}) {
    const Level level{divisor, ceil_div(width, divisor), ceil_div(height, divisor)};
    const bool smaller_than_full = level.width < width || level.height < height;
    const bool smaller_than_previous =
        levels.empty() || level.width > levels.back().width || level.height > levels.back().height;
    if (smaller_than_full && smaller_than_previous) levels.push_back(level);
  }
  levels.push_back(Level{1, width, height});
  return levels;
}

// Render workers are created by the thread that runs the pass and inherit its nice value on
// Linux, so lowering it here keeps every worker below the UI thread.
void lower_this_thread_priority() {
#if defined(__linux__)
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  // 5: the UI thread (and a software GL driver working for it) wins about 3:1 when both want
  // the CPU; higher values let any other busy program starve the preview.
  setpriority(PRIO_PROCESS, tid, 5);
#endif
}

double ms_between(std::chrono::steady_clock::time_point a, std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

}  // namespace

ProgressiveRenderer::ProgressiveRenderer(ProgressiveSettings settings, std::function<void()> on_frame)
    : settings_(settings), on_frame_(std::move(on_frame)) {
  thread_ = std::thread(&ProgressiveRenderer::run, this);
}

ProgressiveRenderer::~ProgressiveRenderer() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
    cancel_.store(true);
  }
  wake_.notify_all();
  thread_.join();
}

std::uint64_t ProgressiveRenderer::restart_locked() {
  ++generation_;
  restart_time_ = std::chrono::steady_clock::now();
  published_fresh_ = false;  // an image not yet taken belongs to the old generation: drop it
  cancel_.store(true);
  wake_.notify_one();
  return generation_;
}

std::uint64_t ProgressiveRenderer::set_scene(std::shared_ptr<const PreparedScene> scene) {
  const std::lock_guard lock(mutex_);
  scene_ = std::move(scene);
  return restart_locked();
}

std::uint64_t ProgressiveRenderer::set_scene(std::shared_ptr<const PreparedScene> scene, int width, int height) {
  const std::lock_guard lock(mutex_);
  scene_ = std::move(scene);
  width_ = std::max(width, 0);
  height_ = std::max(height, 0);
  return restart_locked();
}

std::uint64_t ProgressiveRenderer::set_resolution(int width, int height) {
  const std::lock_guard lock(mutex_);
  width = std::max(width, 0);
  height = std::max(height, 0);
  if (width == width_ && height == height_) return generation_;
  width_ = width;
  height_ = height;
  return restart_locked();
}

std::uint64_t ProgressiveRenderer::set_settings(const ProgressiveSettings& settings) {
  const std::lock_guard lock(mutex_);
  const bool restart = settings.term != settings_.term || settings.shading_eye != settings_.shading_eye;
  const bool keep_priority = settings_.lower_thread_priority;  // fixed at construction
  settings_ = settings;
  settings_.lower_thread_priority = keep_priority;
  if (restart) return restart_locked();
  // A higher target may mean more work: not idle until the thread has looked again.
  idle_ = false;
  wake_.notify_one();
  return generation_;
}

void ProgressiveRenderer::set_interacting(bool interacting) {
  const std::lock_guard lock(mutex_);
  if (interacting_ == interacting) return;
  interacting_ = interacting;
  idle_ = false;  // refinement may resume: not idle until the thread has looked again
  wake_.notify_one();
}

bool ProgressiveRenderer::take_frame(ProgressiveFrame& frame) {
  const std::lock_guard lock(mutex_);
  if (!published_fresh_) return false;
  std::swap(frame, published_);
  published_fresh_ = false;
  return true;
}

ProgressiveStatus ProgressiveRenderer::status() const {
  const std::lock_guard lock(mutex_);
  return ProgressiveStatus{generation_, idle_ && idle_generation_ == generation_, passes_, serial_,
                           published_generation_};
}

bool ProgressiveRenderer::wait_idle(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  return idle_cv_.wait_for(lock, timeout,
                           [&] { return stop_ || (idle_ && idle_generation_ == generation_); });
}

void ProgressiveRenderer::run() {
  {
    const std::lock_guard lock(mutex_);
    if (settings_.lower_thread_priority) lower_this_thread_priority();
  }
  // The state of the generation being rendered; only this thread touches it.
  std::uint64_t generation = 0;
  std::shared_ptr<const PreparedScene> scene;
  std::vector<Level> levels;
  std::size_t level = 0;
  Accumulator accum;
  std::uint64_t nan_count = 0;
  bool published_any = false;
  std::chrono::steady_clock::time_point restart_time;
  ProgressiveSettings settings;

  for (;;) {
    {
      std::unique_lock lock(mutex_);
      for (;;) {
        if (stop_) return;
        if (generation_ != generation) {
          generation = generation_;
          scene = scene_;
          levels = make_levels(width_, height_);
          level = 0;
          nan_count = 0;
          published_any = false;
          restart_time = restart_time_;
          // Cleared only together with picking up the newest generation, so a raised flag
          // always means "the job you hold is stale".
          cancel_.store(false);
          if (!levels.empty()) accum.reset(levels[0].width, levels[0].height);
        }
        settings = settings_;
        bool work = scene != nullptr && !levels.empty();
        if (work) {
          // The first image of a generation is always rendered, even while interacting.
          const bool capped = interacting_ && published_any &&
                              levels[level].divisor < std::max(settings.interactive_divisor, 1);
          const bool coarse = level + 1 < levels.size();
          const auto target = static_cast<std::uint32_t>(std::max(settings.target_spp, 1));
          work = !capped && (coarse || accum.samples < target);
        }
        if (work) break;
        idle_ = true;
        idle_generation_ = generation;
        idle_cv_.notify_all();
        wake_.wait(lock);
      }
      idle_ = false;
    }

    RenderOptions options;
    options.term = settings.term;
    options.threads = settings.threads;
    options.shading_eye = settings.shading_eye;
    const PassStats pass = render_pass(*scene, options, accum, &cancel_);
    if (!pass.completed) {
      // Cancelled midway: a restart is pending and the accumulator is partly updated.
      accum.reset(levels[level].width, levels[level].height);
      continue;
    }
    nan_count += pass.nan_count;

    // Build the image outside the lock; publishing is then a swap.
    back_.generation = generation;
    back_.width = accum.width;
    back_.height = accum.height;
    back_.divisor = levels[level].divisor;
    back_.spp = accum.samples;
    back_.pixels.resize(accum.sum.size());
    const double inv_samples = 1.0 / static_cast<double>(accum.samples);
    for (std::size_t i = 0; i < accum.sum.size(); ++i) back_.pixels[i] = glm::vec3(accum.sum[i] * inv_samples);
    back_.stats.pass_ms = pass.seconds * 1e3;
    back_.stats.pass_rays = pass.rays;
    back_.stats.mrays_per_s = pass.seconds > 0 ? static_cast<double>(pass.rays.total()) / pass.seconds * 1e-6 : 0;
    back_.stats.nan_count = nan_count;
    back_.stats.packets = pass.packets;

    bool published = false;
    {
      const std::lock_guard lock(mutex_);
      ++passes_;
      if (generation_ == generation) {
        back_.stats.serial = ++serial_;
        published_generation_ = generation;
        back_.stats.ms_since_restart = ms_between(restart_time, std::chrono::steady_clock::now());
        std::swap(back_, published_);
        published_fresh_ = true;
        published = true;
      }
    }
    if (published && on_frame_) on_frame_();
    published_any = true;
    if (level + 1 < levels.size()) {
      ++level;
      accum.reset(levels[level].width, levels[level].height);
    }
  }
}

}  // namespace phonglab
