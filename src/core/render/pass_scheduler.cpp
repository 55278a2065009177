#include "core/render/pass_scheduler.h"

#include <algorithm>
#include <utility>

#include "core/render/quad_shading.h"
#include "core/render/ray_trees.h"
#include "core/render/scene_changes.h"

namespace phonglab {

namespace {

int ceil_div(int a, int b) { return (a + b - 1) / b; }

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

std::vector<ProgressiveLevel> progressive_levels(int width, int height, const ProgressiveSettings& settings) {
  return quad_rung_draws(settings.term, settings.ambient, settings.term_images) ? make_live_levels(width, height)
                                                                               : make_levels(width, height);
}

PassScheduler::PassScheduler() = default;
PassScheduler::~PassScheduler() = default;

std::size_t PassScheduler::tree_bytes() const { return trees_ ? trees_->memory_bytes() : 0; }

void PassScheduler::begin(std::shared_ptr<const PreparedScene> scene, int width, int height,
                          const ProgressiveSettings& settings, bool interacting) {
  scene_ = std::move(scene);
  settings_ = settings;
  interacting_ = interacting;
  // An edit that changes no ray (or only shadow rays) is re-shaded at full resolution at once.
  // While the hand is on, a linear edit is recombined from the trees' sums (its exact re-shade
  // follows when the hand stops).
  const RayTrees::Route route =
      scene_ && trees_ && trees_apply(settings)
          ? trees_->route(*scene_, width, height, settings.term, settings.shading_eye, settings.term_images, interacting)
          : RayTrees::Route::kTrace;
  trees_serve_ = route != RayTrees::Route::kTrace;
  reshade_ = reshaded_ = trees_serve_;
  live_ = route == RayTrees::Route::kLive;
  live_shown_ = false;
  ladder_.begin(progressive_levels(width, height, settings), interacting, live_budget_ms(settings), reshade_);
  nan_count_ = 0;
  shown_any_ = false;
  accum_stale_ = true;  // reset before the next pass (22 MB to clear at 1280x720: outside any lock)
}

bool PassScheduler::carry_over(std::shared_ptr<const PreparedScene> scene, int width, int height,
                               const ProgressiveSettings& settings) {
  const bool same_size = !ladder_.empty() && ladder_.levels().back().width == width && ladder_.levels().back().height == height;
  if (!(shown_any_ && !accum_stale_ && accum_.samples > 0 &&
        carries_over(settings_, settings, scene_.get(), scene.get(), same_size))) {
    return false;
  }
  scene_ = std::move(scene);
  return true;
}

void PassScheduler::update(const ProgressiveSettings& settings, bool interacting) {
  settings_ = settings;
  interacting_ = interacting;
}

bool PassScheduler::wants_pass() const {
  if (!scene_ || ladder_.empty()) return false;
  const int cap = std::min(std::max(settings_.interactive_divisor, 1), ladder_.start().divisor);
  const bool capped = interacting_ && shown_any_ &&
                      (!settings_.refine_while_interacting || reshaded_ || ladder_.level().divisor < cap);
  const auto target = static_cast<std::uint32_t>(std::max(settings_.target_spp, 1));
  const std::uint32_t samples = accum_stale_ ? 0 : accum_.samples;
  return !capped && (!ladder_.at_full() || samples < target || live_shown_);
}

PassScheduler::Step PassScheduler::step(const std::atomic<bool>* cancel, std::vector<glm::vec3>* first_image) {
  const auto cancelled = [&] { return cancel != nullptr && cancel->load(); };
  if (live_shown_ && !interacting_) {
    // The hand stopped: the live image is replaced by the exact re-shade, bit for bit render_pass's.
    live_shown_ = live_ = false;
    reshade_ = accum_stale_ = true;
  }
  if (accum_stale_) {
    // A live recombination, a re-shade or a traced first pass writes every pixel: no need to
    // clear them first.
    accum_.reset_for_first_pass(level().width, level().height, settings_.term_images);
    accum_stale_ = false;
  }
  Step out;
  PassStats& pass = out.pass;
  if (live_ && interacting_) {
    pass = trees_->recombine(*scene_, settings_.term, settings_.threads, accum_, cancel, accum_live_);
    if (pass.completed) live_ms_ = pass.seconds * 1e3;
    live_ = false;
    accum_live_ = pass.completed;
    if (!pass.completed && !cancelled()) {
      accum_stale_ = true;  // a sum the trees cannot give: the exact re-shade instead
      return step(cancel, first_image);
    }
    reshade_ = false;
    live_shown_ = pass.completed;
  } else if (reshade_) {
    accum_live_ = false;
    pass = trees_->reshade(scene_, settings_.term, settings_.shading_eye, settings_.threads, accum_, cancel);
    reshade_ = false;
    // Half updated, or full of holes that every later re-shade would trace again: the next
    // traced generation records anew. (A cancelled re-shade of shading alone keeps them.)
    if ((!pass.completed && !trees_->usable()) || trees_->worn()) {
      trees_.reset();
      trees_serve_ = false;
    }
  } else {
    accum_live_ = false;
    RenderOptions options;
    options.term = settings_.term;
    options.threads = settings_.threads;
    options.shading_eye = settings_.shading_eye;
    options.ambient = settings_.ambient;
    // A first pass converts its image for the screen tile by tile, as it goes.
    if (accum_.samples == 0 && first_image != nullptr) {
      first_image->resize(accum_.sum.size());
      options.first_sample_image = first_image->data();
    }
    out.converted = options.first_sample_image != nullptr;
    pass = level().quads ? render_quad_shaded(*scene_, options, accum_, cancel) : render_pass(*scene_, options, accum_, cancel);
  }
  if (!pass.completed) {
    // A first pass overtaken by the next restart took at least this long: while interacting
    // the next restart starts below it, or nothing would ever show.
    if (!shown_any_) ladder_.overtaken(pass.seconds * 1e3);
    // Cancelled midway: the accumulator is partly updated; the next pass is a first one again.
    accum_stale_ = true;
    accum_live_ = false;
    out.converted = false;
    return out;
  }
  nan_count_ += pass.nan_count;
  return out;
}

void PassScheduler::shown(double ms, const std::atomic<bool>* cancel) {
  shown_any_ = true;
  // A re-shade says nothing of a traced pass's time.
  ladder_.passed(ms, !reshaded_);
  if (ladder_.advance()) {
    accum_stale_ = true;  // the next level's first pass (the image stays in accum_ until then)
    accum_live_ = false;
  } else if (!interacting_) {
    record_trees(cancel);  // once per scene: at once if it has none that serve
  }
}

// After a full-resolution pass while the hand is off (the first, or the first after a drag): the
// trees of the generation's scene, unless the kept ones still serve or the budget refused this
// size before. A restart cancels the recording.
void PassScheduler::record_trees(const std::atomic<bool>* cancel) {
  const ProgressiveLevel& full = ladder_.levels().back();
  if (settings_.tree_budget_bytes == 0 || !trees_apply(settings_) || trees_serve_) return;
  const Refusal here{full.width, full.height, settings_.tree_budget_bytes};
  if (refused_.width == here.width && refused_.height == here.height && refused_.budget == here.budget) return;
  accum_live_ = false;
  // The new trees take over the old ones' memory (no page faults for a few hundred MiB).
  trees_ = RayTrees::record(scene_, full.width, full.height, settings_.shading_eye, settings_.threads,
                            settings_.tree_budget_bytes, cancel, true, std::move(trees_));
  if (!trees_ && !(cancel != nullptr && cancel->load())) refused_ = here;
  trees_serve_ = trees_ != nullptr;
}

}  // namespace phonglab
