#include "apps/web/web_view.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "core/scene/display8.h"
#include "core/teaching/compare.h"
#include "core/teaching/heat_map.h"

namespace phonglab {
namespace {

constexpr int kColumns = 3, kRows = 2;  // the small multiples: the five terms, then the full image

}  // namespace

void WebView::set_target(int spp) {
  const int before = s_.target;
  s_.target = std::max(spp, 1);
  if (s_.target < before && s_.shown.spp > static_cast<std::uint32_t>(s_.target)) restart();
}

void WebView::set_size(int width, int height) {
  s_.width = std::max(width, 1);
  s_.height = std::max(height, 1);
  restart();
}

void WebView::set_interacting(bool on) {
  s_.interacting = on;
  // The hand stopped: the gesture is one undo step; the scheduler replaces a live image by the
  // exact re-shade, or goes on to finer levels from the live one.
  if (!on) s_.session.settle(false);
}

bool WebView::step() {
  // A view changed without a restart (a lesson closed) may change the ladder: it starts again.
  if (!s_.prepared || passes_.ladder().levels() != progressive_levels(trace_width(), trace_height(), settings())) {
    begin_generation();
  }
  passes_.update(settings(), s_.interacting);
  if (!passes_.wants_pass()) return false;
  const auto start = std::chrono::steady_clock::now();
  passes_.step();
  s_.shown.divisor = passes_.level().divisor;
  s_.shown.quads = passes_.level().quads;
  encode();
  const bool a_taken = s_.a.requested() && !s_.a.first_full() &&
                       s_.a.take_when_ready(static_cast<std::uint64_t>(s_.generation), s_.shown, finished());
  if (a_taken) encode();  // shown against the new A
  // The level's time is what the student waits for: the pass and its image encoded.
  passes_.shown(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  lesson_.update_lesson();
  return true;
}

int WebView::trace_width() const { return s_.view.small_multiples ? std::max(1, s_.width / kColumns) : s_.width; }

int WebView::trace_height() const { return s_.view.small_multiples ? std::max(1, s_.height / kRows) : s_.height; }

// The page's generation, as the desktop's render thread has it (core/render/pass_scheduler.h): the
// image of one cell of the small multiples' grid, the view's term and "move your head"'s eye.
ProgressiveSettings WebView::settings() const {
  ProgressiveSettings s;
  s.term = pass_term();
  s.ambient = s_.view.ambient;
  s.term_images = s_.view.small_multiples || ambient_pair();
  s.shading_eye = s_.eye;
  s.threads = s_.threads;
  // A difference against a first-full A compares like with like: the live image stays at A's sample.
  s.target_spp = target_spp();
  s.tree_budget_bytes = std::size_t{256} << 20;
  s.refine_while_interacting = false;  // no restart cancels a pass here: one image per edit while the hand is on
  return s;
}

void WebView::begin_generation() {
  // With formulas, the equation traced with its hooks (src/check/rules.h): no trees to re-shade.
  const FormulaBook& formulas = s_.session.formulas();
  s_.prepared = formulas.any() && s_.formula_view == 0
                  ? std::make_shared<const PreparedScene>(view_scene(s_.session.scene(), s_.view), PreparedScene::AccelFactory{},
                                                          make_rules_experiment(formulas.rules()))
                  : std::make_shared<const PreparedScene>(view_scene(s_.session.scene(), s_.view));
  s_.eye = view_shading_eye(*s_.prepared, s_.view, s_.width, s_.height);
  // The trees are of the traced image's size: one cell of the grid in the small multiples, so a
  // switch between the grid and one image traces anew.
  passes_.begin(s_.prepared, trace_width(), trace_height(), settings(), s_.interacting);
}

emscripten::val WebView::pixels() const {
  return emscripten::val(emscripten::typed_memory_view(rgba_.size(), rgba_.data()));
}

bool WebView::finished() const {
  return shown_generation_ == s_.generation && s_.shown.divisor == 1 && !s_.shown.quads && !passes_.live_shown() &&
         s_.shown.spp >= static_cast<std::uint32_t>(target_spp()) && !s_.view.small_multiples;
}

int WebView::target_spp() const {
  return s_.a.target_spp(s_.target, s_.session.lessons().lesson() != nullptr, s_.view.compare, constant_ambient());
}

void WebView::reshow() {
  if (shown_generation_ == s_.generation) encode();
}

void WebView::restart() {
  ++s_.generation;
  s_.prepared.reset();  // the next step begins the generation (the scheduler's ladder: the hand's budget)
}

// The image as the desktop shows it: the accumulator's means, or the small multiples' grid (the
// five terms in the equation's order, then the full image).
std::vector<glm::vec3> WebView::live_pixels() const {
  const Accumulator& accum = passes_.accum();
  const int w = accum.width, h = accum.height;
  if (!s_.view.small_multiples) {
    std::vector<glm::vec3> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) out[static_cast<std::size_t>(y * w + x)] = glm::vec3(accum.mean(x, y));
    return out;
  }
  const int gw = w * kColumns;
  std::vector<glm::vec3> out(static_cast<std::size_t>(gw) * static_cast<std::size_t>(h * kRows));
  const double inv = 1.0 / static_cast<double>(std::max(accum.samples, 1u));
  for (int cell = 0; cell < kColumns * kRows; ++cell) {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * w + x);
        const Color c = cell < 5 ? accum.terms[i].*kFiveTermMembers[static_cast<std::size_t>(cell)] * inv
                                 : accum.mean(x, y);
        out[static_cast<std::size_t>((cell / kColumns * h + y) * gw + cell % kColumns * w + x)] = glm::vec3(c);
      }
    }
  }
  return out;
}

std::string WebView::bench(int frames) const {
  const PreparedScene prepared(s_.session.scene());
  RenderOptions options;
  options.threads = s_.threads;
  std::string times;
  std::uint64_t rays = 0;
  for (int f = 0; f < frames; ++f) {
    Accumulator accum;
    accum.reset(s_.width, s_.height);
    const auto start = std::chrono::steady_clock::now();
    const PassStats pass = render_pass(prepared, options, accum);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    times += (times.empty() ? "" : ", ") + std::to_string(ms);
    rays = pass.rays.total();
  }
  return "{\"ms\": [" + times + "], \"rays\": " + std::to_string(rays) + "}";
}

// 8-bit sRGB of the image (what `phonglab-cli render -o x.png` writes), against A in a compare.
void WebView::encode() {
  const Accumulator& accum = passes_.accum();
  shown_generation_ = s_.generation;
  s_.shown.generation = static_cast<std::uint64_t>(s_.generation);
  s_.shown.width = accum.width * (s_.view.small_multiples ? kColumns : 1);
  s_.shown.height = accum.height * (s_.view.small_multiples ? kRows : 1);
  s_.shown.spp = accum.samples;
  s_.shown.pixels = live_pixels();
  std::vector<glm::vec3> live = s_.shown.pixels;
  heat_max_ = s_.view.term == Term::kRays ? phonglab::heat_max(live) : 0;
  if (s_.view.term == Term::kRays) live = heat_map_pixels(live, heat_max_);
  if (ambient_pair() && accum.has_terms()) {
    std::vector<glm::vec3> ambient(live.size());
    const double inv = 1.0 / static_cast<double>(std::max(accum.samples, 1u));
    for (std::size_t i = 0; i < ambient.size(); ++i) ambient[i] = glm::vec3(accum.terms[i].ambient * inv);
    live = ambient_shown_pixels(s_.view.ambient_shown, live, ambient, s_.shown.width, s_.view.wipe);
  }
  if (s_.view.compare != CompareView::kNone && s_.a.comparable(s_.shown, s_.view.compare, constant_ambient())) {
    live = compare_pixels(live, s_.a.image().pixels, s_.shown.width, s_.view.compare, s_.view.wipe, s_.view.difference_gain);
  }
  if (std::optional<std::vector<glm::vec3>> checked = formulas_.check_view_pixels()) live = std::move(*checked);
  const Display8Encoder& srgb = Display8Encoder::srgb();
  rgba_.resize(4 * live.size());
  for (std::size_t i = 0; i < live.size(); ++i) {
    rgba_[4 * i] = srgb(live[i].x), rgba_[4 * i + 1] = srgb(live[i].y), rgba_[4 * i + 2] = srgb(live[i].z);
    rgba_[4 * i + 3] = 255;
  }
  ++images_;
}

}  // namespace phonglab
