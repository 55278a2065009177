// Lesson handouts: every step rendered as it is presented (its term or small multiples, the
// head moved, the depth cut, the compare against A, the probed pixel and its ray tree), its
// caption set below the image, and an HTML page holding them all. Deterministic: the same
// lesson and options give the same bytes for any thread count.
#pragma once

#include <string>
#include <vector>

#include "core/teaching/lesson.h"
#include "io/image_io.h"

namespace phonglab {

struct HandoutOptions {
  int width = 0;    // pixels across each step's image; 0: its scene's own width
  int height = 0;   // pixels down; 0: its scene's own height
  int spp = 4;      // samples per pixel
  int threads = 0;  // 0: all hardware threads (the bytes do not depend on it)
};

// The image a step shows at `place` (linear RGB), without its caption.
Image render_step_view(const Lesson& lesson, LessonPlace place, const HandoutOptions& options);

// The step's page: its image with the title and caption below (and the question, or the
// answer once revealed), in the PNG font (ASCII: the equation's symbols are spelled out).
Image step_page(const Lesson& lesson, LessonPlace place, const HandoutOptions& options);

// Text as the PNG font can draw it: the equation's symbols (middle dot, sigma, ...) spelled in ASCII.
std::string ascii_text(const std::string& text);

// `text` broken into lines of at most `max_width` pixels in draw_label's font at `scale`.
std::vector<std::string> wrap_text(const std::string& text, int scale, int max_width);

// Writes DIR/step-NN.png for every step (NN from 01; a question's answer as answer-NN.png)
// and DIR/index.html, a page holding every image (inline, so it is one file to send) and the
// captions. Creates DIR. `written` receives the paths. Empty string or the error.
std::string write_handout(const Lesson& lesson, const std::string& dir, const HandoutOptions& options,
                          std::vector<std::string>* written = nullptr);

}  // namespace phonglab
