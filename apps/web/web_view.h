// The web page's view of one session (bound to JavaScript in web_main.cpp): the document, its
// edits and undo are the session's (src/session); the image is made a pass per step() by the
// core's PassScheduler (core/render/pass_scheduler.h), the desktop render thread's own: coarse to
// fine (1/8, 1/4, 1/2, the quad-shaded live rung, full resolution, then more samples), on the
// page's thread and, in the threaded module, its helpers (the image the same bits for any count);
// an edit that changes no ray re-shaded from the first sample's ray trees, a linear one
// recombined from their sums while the hand is on, the exact re-shade when it stops. WebView
// renders and encodes the image; the binding's other parts are its components over the shared
// PageState: the document (WebScene), the instruments (WebInstruments), the formulas and checks
// (WebFormulas) and a lesson (WebLesson).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <emscripten/val.h>

#include "apps/web/page_state.h"
#include "apps/web/web_formulas.h"
#include "apps/web/web_instruments.h"
#include "apps/web/web_lesson.h"
#include "apps/web/web_scene.h"
#include "core/render/pass_scheduler.h"

namespace phonglab {

class WebView final : public PageImage {
 public:
  WebView() = default;
  WebView(const WebView&) = delete;
  WebView& operator=(const WebView&) = delete;

  WebScene& scene() { return scene_; }
  WebInstruments& instruments() { return instruments_; }
  WebFormulas& formulas() { return formulas_; }
  WebLesson& lesson() { return lesson_; }

  void set_size(int width, int height);
  int width() const { return s_.width; }
  int height() const { return s_.height; }
  // The samples the image goes to; fewer than it has already: the image starts again (the 1 spp
  // switch shows the pixel centres, what a student's own tracer computes first).
  void set_target(int spp);
  int target() const { return s_.target; }
  // While the hand is on, each edit's image is one pass at the desktop's live level (the least
  // error whose measured pass fits a 24th of a second); when it lets go, finer levels follow.
  void set_interacting(bool on);
  // Threads a pass runs on: 1 in the page's one-thread module; in the threaded one, at most the
  // workers started with it (the page passes navigator.hardwareConcurrency).
  void set_threads(int threads) { s_.threads = std::clamp(threads, 1, 64); }
  int threads() const { return s_.threads; }

  // One pass: true when it made a new image (false: the target is reached, or the hand is on
  // and this edit's image is shown).
  bool step();
  // The image on screen (PageState::shown): its size, samples and level.
  int image_width() const { return s_.shown.width; }
  int image_height() const { return s_.shown.height; }
  int spp() const { return static_cast<int>(s_.shown.spp); }
  int divisor() const { return s_.shown.divisor; }
  bool quads() const { return s_.shown.quads; }               // the image is the quad-shaded live rung (divisor 1)
  bool live() const { return passes_.live_shown(); }         // the image is a linear edit's recombination
  bool reshaded() const { return passes_.reshaded(); }       // this generation's first sample was re-shaded
  int generation() const { return s_.generation; }           // restarts so far
  int shown_generation() const { return shown_generation_; }  // the one the image belongs to
  emscripten::val pixels() const;  // RGBA, image_width() x image_height()
  int images() const { return images_; }  // images encoded so far: a new one to draw when it moves
  double heat_max() const { return heat_max_; }  // the heat map's scale's top

  // The speed: `frames` passes of the document at the page's size, 1 spp each on threads(),
  // the full image as the desktop's scalar renderer traces it; JSON: the passes' times (ms) and
  // the rays of one.
  std::string bench(int frames) const;

  // PageImage, for the components.
  void restart() override;
  void reshow() override;
  bool finished() const override;
  int target_spp() const override;
  bool constant_ambient() const override { return ambient_for(pass_term(), s_.view.ambient) != Ambient::kIndirect; }

 private:
  ProgressiveSettings settings() const;  // the generation's, from the view
  int trace_width() const;   // the traced image's size at full resolution: one cell in the small multiples
  int trace_height() const;
  void begin_generation();   // the view's scene prepared, and how its first sample is made
  // The indirect light beside ka·Ia, or their gap: the indirect term traced with the term images.
  bool ambient_pair() const {
    return !s_.view.small_multiples && s_.view.ambient == Ambient::kIndirect && s_.view.ambient_shown != AmbientShown::kImage;
  }
  Term pass_term() const { return s_.view.small_multiples ? Term::kFull : ambient_pair() ? Term::kIndirect : s_.view.term; }
  void encode();
  std::vector<glm::vec3> live_pixels() const;

  PageState s_;
  WebLesson lesson_{s_, *this};
  WebScene scene_{s_, *this, lesson_};
  WebInstruments instruments_{s_, *this, lesson_};
  WebFormulas formulas_{s_, *this};
  PassScheduler passes_;  // the generation's passes, as the desktop's render thread has them
  std::vector<unsigned char> rgba_;
  int shown_generation_ = -1;  // the generation of the image on screen (-1: none yet)
  int images_ = 0;
  double heat_max_ = 0;
};

}  // namespace phonglab
