#include "core/render/progressive.h"

#include "core/packet/packet.h"
#include "core/render/quad_shading.h"
#include "core/render/ray_trees.h"
#include "core/render/scene_changes.h"

#include <algorithm>
#include <utility>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace phonglab {

namespace {

int ceil_div(int a, int b) { return (a + b - 1) / b; }

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

// Whether the generation starting carries on the job's accumulation: the indirect light's image
// of a scene that differs only in ka or Ia, at the same size and settings.
bool carries_over(const ProgressiveSettings& was, const ProgressiveSettings& now, const PreparedScene* old_scene,
                  const PreparedScene* new_scene, bool same_size) {
  return same_size && old_scene && new_scene && shows_indirect(now) && !now.term_images && !was.term_images &&
         was.term == now.term && was.ambient == now.ambient && was.shading_eye == now.shading_eye &&
         indirect_unchanged(old_scene->scene(), new_scene->scene());
}

// Whether the first sample's ray trees can stand for what the settings show: one of the lecture's
// images (the indirect light is traced every time).
bool trees_apply(const ProgressiveSettings& s) { return reshades(s.term) && !shows_indirect(s); }


}  // namespace


double live_budget_ms(const ProgressiveSettings& settings) {
  return settings.live_images_per_s > 0 ? 1000 / settings.live_images_per_s : 0;
}

std::vector<ProgressiveLevel> make_levels(int width, int height) {
  std::vector<ProgressiveLevel> levels;
  if (width <= 0 || height <= 0) return levels;
  for (const int divisor : {8, 4, 2}) {
    const ProgressiveLevel level{divisor, ceil_div(width, divisor), ceil_div(height, divisor)};
    const bool smaller_than_full = level.width < width || level.height < height;
    const bool smaller_than_previous =
        levels.empty() || level.width > levels.back().width || level.height > levels.back().height;
    if (smaller_than_full && smaller_than_previous) levels.push_back(level);
  }
  levels.push_back(ProgressiveLevel{1, width, height});
  return levels;
}

std::vector<ProgressiveLevel> make_live_levels(int width, int height) { return with_quad_rung(make_levels(width, height)); }

std::vector<ProgressiveLevel> with_quad_rung(std::vector<ProgressiveLevel> levels) {
  if (levels.size() > 1) {
    ProgressiveLevel rung = levels.back();
    rung.quads = true;
    levels.insert(levels.end() - 1, rung);
  }
  return levels;
}

double LevelTimes::at(int divisor, bool quads) const {
  static_assert(kKept == 3);
  const std::array<double, kKept>& t = recent[slot(divisor, quads)];  // newest first: zeros only at the end
  if (!(t[1] > 0)) return t[0];
  if (!(t[2] > 0)) return 0.5 * (t[0] + t[1]);
  return std::max(std::min(t[0], t[1]), std::min(std::max(t[0], t[1]), t[2]));  // the median
}

void LevelTimes::forget(int divisor, bool quads) { recent[slot(divisor, quads)] = {}; }

void LevelTimes::note(int divisor, double ms, bool quads) {
  std::array<double, kKept>& t = recent[slot(divisor, quads)];
  std::rotate(t.begin(), t.end() - 1, t.end());  // newest first: the oldest drops off
  t[0] = ms;
}

std::size_t live_start_level(const std::vector<ProgressiveLevel>& levels, const LevelTimes& times, double budget_ms,
                             bool probe) {
  std::size_t start = 0;
  double known_ms = 0;   // the last measured level's time on the way up
  double known_px = 0;   // and its pixel count
  std::vector<double> expected(levels.size(), 0.0);  // 0: nothing known at or below the level
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const double px = static_cast<double>(levels[i].width) * levels[i].height;
    double ms = times.at(levels[i].divisor, levels[i].quads);
    if (ms > 0) {
      known_ms = ms;
      known_px = px;
    } else if (known_ms > 0) {
      ms = known_ms * px / known_px;
    } else {
      continue;
    }
    expected[i] = ms;
    if (ms <= budget_ms) start = i;
  }
  if (probe && start + 1 < levels.size() && expected[start + 1] > 0 && expected[start + 1] <= 1.5 * budget_ms) {
    ++start;
  }
  return start;
}

void LevelLadder::begin(std::vector<ProgressiveLevel> levels, bool interacting, double budget_ms, bool at_full) {
  if (levels_.empty() || levels.empty() || levels_.back().width != levels.back().width ||
      levels_.back().height != levels.back().height) {
    times_ = {};
  }
  levels_ = std::move(levels);
  probing_ = false;
  index_ = 0;
  if (at_full) {
    to_full();
  } else if (interacting && !levels_.empty()) {
    const std::size_t fits = live_start_level(levels_, times_, budget_ms);
    index_ = fits;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_probe_ >= kProbePeriod) {
      index_ = live_start_level(levels_, times_, budget_ms, true);
      probing_ = index_ != fits;
      if (probing_) last_probe_ = now;
    }
  }
  start_ = index_;
}

void LevelLadder::passed(double ms, bool traced) {
  if (traced && probing_) times_.forget(level().divisor, level().quads);
  if (traced) times_.note(level().divisor, ms, level().quads);
  probing_ = false;
}

void LevelLadder::overtaken(double ms) {
  if (ms > times_.at(level().divisor, level().quads)) times_.note(level().divisor, ms, level().quads);
}

bool LevelLadder::advance() {
  if (at_full()) return false;
  ++index_;
  if (levels_[index_].quads && !at_full()) ++index_;
  return true;
}

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
  std::shared_ptr<const PreparedScene> scene;
  LevelLadder ladder;           // the levels, where this generation started and stands, their times
  bool reshade = false;         // the next pass re-shades the stored trees instead of tracing
  bool reshaded = false;        // this generation's first image was re-shaded
  bool live = false;            // the next pass recombines the stored trees' sums (a linear edit, hand on)
  bool live_shown = false;      // the image is the live one: the exact re-shade is owed
  bool accum_live = false;      // accum holds the image the trees last recombined, nothing since
  bool image_converted = false; // the last pass wrote its image for the screen (back_.pixels) too
  double live_ms = 1e9;         // the last live pass (wait_for_live_image); none yet: not quick
  Accumulator accum;
  std::uint64_t nan_count = 0;
  bool published_any = false;
  bool republish = false;       // the accumulation carries over to this generation: publish it as its own
  bool accum_stale = false;     // accum still holds the previous generation's sums
  bool interacting = false;     // interacting_ when the pass began
  std::chrono::steady_clock::time_point restart_time;
  ProgressiveSettings settings;
  std::unique_ptr<RayTrees> trees;  // the first sample's trees of a recent scene, or null
  bool trees_serve = false;         // they can re-shade this generation (scene, size, eye and what is shown)
  struct Refusal {
    int width = 0, height = 0;
    std::size_t budget = 0;
  } refused;  // the last recording over budget: not tried again at this size and budget
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
    if (job.live_shown && !job.interacting) {
      // The hand stopped: the live image is replaced by the exact re-shade, bit for bit render_pass's.
      job.live_shown = job.live = false;
      job.reshade = job.accum_stale = true;
    }
    if (job.accum_stale) {
      // A live recombination, a re-shade or a traced first pass writes every pixel: no need to
      // clear them first (22 MB at 1280x720).
      const ProgressiveLevel& lv = job.ladder.level();
      job.accum.reset_for_first_pass(lv.width, lv.height, job.settings.term_images);
      job.accum_stale = false;
    }
    PassStats pass;
    job.image_converted = false;
    if (job.live && job.interacting) {
      pass = job.trees->recombine(*job.scene, job.settings.term, job.settings.threads, job.accum, &cancel_,
                                  job.accum_live);
      if (pass.completed) job.live_ms = pass.seconds * 1e3;
      job.live = false;
      job.accum_live = pass.completed;
      if (!pass.completed && !cancel_.load()) {
        job.accum_stale = true;  // a sum the trees cannot give: the exact re-shade instead
        continue;
      }
      job.reshade = false;
      job.live_shown = pass.completed;
    } else if (job.reshade) {
      job.accum_live = false;
      pass = job.trees->reshade(job.scene, job.settings.term, job.settings.shading_eye, job.settings.threads,
                                job.accum, &cancel_);
      job.reshade = false;
      // Half updated, or full of holes that every later re-shade would trace again: the next
      // traced generation records anew. (A cancelled re-shade of shading alone keeps them.)
      if ((!pass.completed && !job.trees->usable()) || job.trees->worn()) {
        job.trees.reset();
        job.trees_serve = false;
      }
    } else {
      job.accum_live = false;
      RenderOptions options;
      options.term = job.settings.term;
      options.threads = job.settings.threads;
      options.shading_eye = job.settings.shading_eye;
      options.ambient = job.settings.ambient;
      // A first pass converts its image for the screen tile by tile, as it goes (publish's work).
      if (job.accum.samples == 0) {
        back_.pixels.resize(job.accum.sum.size());
        options.first_sample_image = back_.pixels.data();
      }
      job.image_converted = options.first_sample_image != nullptr;
      pass = job.ladder.level().quads ? render_quad_shaded(*job.scene, options, job.accum, &cancel_)
                                         : render_pass(*job.scene, options, job.accum, &cancel_);
    }
    const double pass_ms = pass.seconds * 1e3;
    if (!pass.completed) {
      // A first pass overtaken by the next restart took at least this long: while interacting
      // the next restart starts below it, or nothing would ever show.
      if (!job.published_any) job.ladder.overtaken(pass_ms);
      // Cancelled midway: a restart is pending and the accumulator is partly updated; the next
      // pass is a first one again, which writes every pixel.
      job.accum.reset_for_first_pass(job.ladder.level().width, job.ladder.level().height, job.settings.term_images);
      job.accum_live = false;
      continue;
    }
    job.nan_count += pass.nan_count;
    const auto publishing = std::chrono::steady_clock::now();
    publish(job, pass);
    // A level's time is what the hall waits for its image: the pass and the image's conversion
    // for the screen (which grows with the pixels too, and is the render thread's while the next
    // pass waits). A re-shade says nothing of a traced pass's time. A probe's pass is the
    // level's time now: the older ones were why it was not run.
    job.ladder.passed(pass_ms + ms_between(publishing, std::chrono::steady_clock::now()), !job.reshaded);
    if (job.ladder.advance()) {
      job.accum.reset_for_first_pass(job.ladder.level().width, job.ladder.level().height, job.settings.term_images);
      job.accum_live = false;
    } else if (!job.interacting) {
      record_trees(job);  // once per scene: at once if it has none that serve
    }
  }
}

bool ProgressiveRenderer::wait_for_work(Job& job) {
  std::unique_lock lock(mutex_);
  for (;;) {
    if (stop_) return false;
    if (generation_ != job.generation) start_generation_locked(job);
    job.settings = settings_;
    job.interacting = interacting_;
    bool work = job.scene != nullptr && !job.ladder.empty();
    if (work) {
      // The first image of a generation is always rendered, even while interacting. While
      // interacting, no finer than the interactive divisor or the level it started at, and
      // nothing after a re-shaded image (the next edit comes soon).
      const int cap = std::min(std::max(job.settings.interactive_divisor, 1), job.ladder.start().divisor);
      const bool capped = interacting_ && job.published_any && (job.reshaded || job.ladder.level().divisor < cap);
      const bool coarse = !job.ladder.at_full();
      const auto target = static_cast<std::uint32_t>(std::max(job.settings.target_spp, 1));
      const std::uint32_t samples = job.accum_stale ? 0 : job.accum.samples;
      work = job.republish || (!capped && (coarse || samples < target || job.live_shown));
    }
    if (work) {
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
  const bool same_size = !job.ladder.empty() && job.ladder.levels().back().width == width_ &&
                         job.ladder.levels().back().height == height_;
  if (job.published_any && !job.accum_stale && job.accum.samples > 0 &&
      carries_over(job.settings, settings_, job.scene.get(), scene_.get(), same_size)) {
    job.generation = generation_;
    job.scene = scene_;
    job.restart_time = restart_time_;
    job.republish = true;
    decided_generation_ = job.generation;
    decided_live_ms_ = -1;
    idle_cv_.notify_all();
    cancel_.store(false);
    return;
  }
  job.republish = false;
  job.generation = generation_;
  job.scene = scene_;
  // An edit that changes no ray (or only shadow rays) is re-shaded at full resolution at once.
  // While the hand is on, a linear edit is recombined from the trees' sums (its exact re-shade
  // follows when the hand stops).
  const RayTrees::Route route = job.scene && job.trees && trees_apply(settings_)
                                    ? job.trees->route(*job.scene, width_, height_, settings_.term, settings_.shading_eye,
                                                       settings_.term_images, interacting_)
                                    : RayTrees::Route::kTrace;
  job.trees_serve = route != RayTrees::Route::kTrace;
  job.reshade = job.trees_serve;
  job.reshaded = job.reshade;
  job.live = route == RayTrees::Route::kLive;
  job.live_shown = false;
  decided_generation_ = job.generation;  // wait_for_live_image
  decided_live_ms_ = job.live ? job.live_ms : -1.0;
  idle_cv_.notify_all();
  const bool rung = quad_rung_draws(settings_.term, settings_.ambient, settings_.term_images);
  job.ladder.begin(rung ? make_live_levels(width_, height_) : make_levels(width_, height_),
                   interacting_, live_budget_ms(settings_), job.reshade);
  job.nan_count = 0;
  job.published_any = false;
  job.restart_time = restart_time_;
  // Cleared only together with picking up the newest generation, so a raised flag always means
  // "the job you hold is stale".
  cancel_.store(false);
  job.accum_stale = true;  // made ready outside the lock (22 MB to clear at 1280x720)
}

// Builds the image outside the lock; publishing is then a swap.
void ProgressiveRenderer::publish(Job& job, const PassStats& pass) {
  back_.generation = job.generation;
  back_.width = job.accum.width;
  back_.height = job.accum.height;
  back_.divisor = job.ladder.level().divisor;
  back_.quads = job.ladder.level().quads;
  back_.spp = job.accum.samples;
  back_.pixels.resize(job.accum.sum.size());
  const double inv_samples = 1.0 / static_cast<double>(job.accum.samples);
  if (!job.image_converted) {
    for (std::size_t i = 0; i < job.accum.sum.size(); ++i) back_.pixels[i] = glm::vec3(job.accum.sum[i] * inv_samples);
  }
  job.image_converted = false;
  for (std::size_t k = 0; k < kFiveTermMembers.size(); ++k) {
    std::vector<glm::vec3>& image = back_.terms[k];
    image.resize(job.accum.terms.size());
    for (std::size_t i = 0; i < image.size(); ++i) image[i] = glm::vec3(job.accum.terms[i].*kFiveTermMembers[k] * inv_samples);
  }
  back_.stats.pass_ms = pass.seconds * 1e3;
  back_.stats.pass_rays = pass.rays;
  back_.stats.mrays_per_s = pass.seconds > 0 ? static_cast<double>(pass.rays.total()) / pass.seconds * 1e-6 : 0;
  back_.stats.nan_count = job.nan_count;
  back_.stats.packets = pass.packets;
  back_.stats.packet_kernels = pass.packets ? packet_simd_target() : "";
  back_.stats.packet_lanes = pass.packets ? packet_simd_lanes() : 0;
  back_.stats.reshaded = job.reshaded && job.accum.samples == 1;
  back_.stats.live = job.live_shown;
  back_.stats.tree_bytes = job.trees ? job.trees->memory_bytes() : 0;
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
  job.published_any = true;
}

// After a full-resolution pass while the hand is off (the first, or the first after a drag): the
// trees of the generation's scene, unless the kept ones still serve or the budget refused this
// size before. A restart cancels the recording.
void ProgressiveRenderer::record_trees(Job& job) {
  const ProgressiveSettings& s = job.settings;
  const ProgressiveLevel& full = job.ladder.levels().back();
  if (s.tree_budget_bytes == 0 || !trees_apply(s)) return;
  if (job.trees_serve) return;
  const Job::Refusal here{full.width, full.height, s.tree_budget_bytes};
  if (job.refused.width == here.width && job.refused.height == here.height && job.refused.budget == here.budget) return;
  job.accum_live = false;
  // The new trees take over the old ones' memory (no page faults for a few hundred MiB).
  job.trees = RayTrees::record(job.scene, full.width, full.height, s.shading_eye, s.threads, s.tree_budget_bytes, &cancel_,
                               true, std::move(job.trees));
  if (!job.trees && !cancel_.load()) job.refused = here;
  job.trees_serve = job.trees != nullptr;
}

}  // namespace phonglab
