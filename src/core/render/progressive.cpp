#include "core/render/progressive.h"

#include "core/packet/packet.h"

#include <algorithm>
#include <utility>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace phonglab {

namespace {

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
  const bool restart = settings.term != settings_.term || settings.term_images != settings_.term_images ||
                       settings.shading_eye != settings_.shading_eye || settings.ambient != settings_.ambient;
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

bool ProgressiveRenderer::wait_for_live_image(std::uint64_t generation, std::chrono::milliseconds quick,
                                              std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  const auto settled = [&] {
    const bool quick_live = decided_live_ms_ >= 0 && decided_live_ms_ <= static_cast<double>(quick.count());
    return stop_ || generation_ != generation || published_generation_ >= generation ||
           (decided_generation_ == generation && !quick_live);
  };
  idle_cv_.wait_for(lock, timeout, settled);
  return published_generation_ >= generation && generation_ == generation;
}

bool ProgressiveRenderer::wait_idle(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  return idle_cv_.wait_for(lock, timeout,
                           [&] { return stop_ || (idle_ && idle_generation_ == generation_); });
}

// The generation being rendered; only the render thread touches it.
struct ProgressiveRenderer::Job {
  std::uint64_t generation = 0;
  PassScheduler passes;          // the generation's passes: levels, trees, the live image (pass_scheduler.h)
  bool republish = false;        // the accumulation carries over to this generation: publish it as its own
  bool image_converted = false;  // the last pass wrote its image for the screen (back_.pixels) too
  std::chrono::steady_clock::time_point restart_time;
};

void ProgressiveRenderer::run() {
  {
    const std::lock_guard lock(mutex_);
    if (settings_.lower_thread_priority) lower_this_thread_priority();
  }
  Job job;
  while (wait_for_work(job)) {
    if (job.republish) {  // the new generation's image is the one accumulated so far
      job.republish = false;
      publish(job, PassStats{});
      continue;
    }
    const PassScheduler::Step step = job.passes.step(&cancel_, &back_.pixels);
    if (!step.pass.completed) continue;
    job.image_converted = step.converted;
    const auto publishing = std::chrono::steady_clock::now();
    publish(job, step.pass);
    // A level's time is what the hall waits for its image: the pass and the image's conversion
    // for the screen (which grows with the pixels too, and is the render thread's while the next
    // pass waits).
    job.passes.shown(step.pass.seconds * 1e3 + ms_between(publishing, std::chrono::steady_clock::now()), &cancel_);
  }
}

bool ProgressiveRenderer::wait_for_work(Job& job) {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (stop_) return false;
    if (generation_ != job.generation) start_generation_locked(job);
    job.passes.update(settings_, interacting_);
    if (job.republish || job.passes.wants_pass()) {
      idle_ = false;
      return true;
    }
    idle_ = true;
    idle_generation_ = job.generation;
    idle_cv_.notify_all();
    wake_.wait(lock);
  }
}

void ProgressiveRenderer::start_generation_locked(Job& job) {
  job.generation = generation_;
  job.restart_time = restart_time_;
  job.republish = job.passes.carry_over(scene_, width_, height_, settings_);
  if (!job.republish) job.passes.begin(scene_, width_, height_, settings_, interacting_);
  decided_generation_ = job.generation;  // wait_for_live_image
  decided_live_ms_ = job.republish ? -1.0 : job.passes.live_expected_ms();
  idle_cv_.notify_all();
  // Cleared only together with picking up the newest generation, so a raised flag always means
  // "the job you hold is stale".
  cancel_.store(false);
}

// Builds the image outside the lock; publishing is then a swap.
void ProgressiveRenderer::publish(Job& job, const PassStats& pass) {
  const PassScheduler& passes = job.passes;
  const Accumulator& accum = passes.accum();
  back_.generation = job.generation;
  back_.width = accum.width;
  back_.height = accum.height;
  back_.divisor = passes.level().divisor;
  back_.quads = passes.level().quads;
  back_.spp = accum.samples;
  back_.pixels.resize(accum.sum.size());
  const double inv_samples = 1.0 / static_cast<double>(accum.samples);
  if (!job.image_converted) {
    for (std::size_t i = 0; i < accum.sum.size(); ++i) back_.pixels[i] = glm::vec3(accum.sum[i] * inv_samples);
  }
  job.image_converted = false;
  for (std::size_t k = 0; k < kFiveTermMembers.size(); ++k) {
    std::vector<glm::vec3>& image = back_.terms[k];
    image.resize(accum.terms.size());
    for (std::size_t i = 0; i < image.size(); ++i) image[i] = glm::vec3(accum.terms[i].*kFiveTermMembers[k] * inv_samples);
  }
  back_.stats.pass_ms = pass.seconds * 1e3;
  back_.stats.pass_rays = pass.rays;
  back_.stats.mrays_per_s = pass.seconds > 0 ? static_cast<double>(pass.rays.total()) / pass.seconds * 1e-6 : 0;
  back_.stats.nan_count = passes.nan_count();
  back_.stats.packets = pass.packets;
  back_.stats.packet_kernels = pass.packets ? packet_simd_target() : "";
  back_.stats.packet_lanes = pass.packets ? packet_simd_lanes() : 0;
  back_.stats.reshaded = passes.reshaded() && accum.samples == 1;
  back_.stats.live = passes.live_shown();
  back_.stats.tree_bytes = passes.tree_bytes();
  bool published = false;
  {
    const std::lock_guard lock(mutex_);
    ++passes_;
    if (generation_ == job.generation) {
      back_.stats.serial = ++serial_;
      published_generation_ = job.generation;
      back_.stats.ms_since_restart = ms_between(job.restart_time, std::chrono::steady_clock::now());
      std::swap(back_, published_);
      published_fresh_ = true;
      published = true;
    }
  }
  if (published) idle_cv_.notify_all();  // wait_for_live_image
  if (published && on_frame_) on_frame_();
}

}  // namespace phonglab
