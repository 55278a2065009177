// Lesson handouts: every step rendered as it is presented (its term or small multiples, the
// head moved, the depth cut, the compare against A, the probed pixel and its ray tree, the
// light markers), and an HTML page holding them all with each step's number, title, caption,
// question and answer. Deterministic: the same lesson and options give the same bytes for any
// thread count.
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
  // The web page (tools/dev.sh web) each step links to, as URL#lesson=NAME&step=K; empty: no
  // links. Only an embedded lesson's steps link (the page has those inside).
  std::string live_page;
};

// The image a step shows at `place` (linear RGB), as the previewer's view shows it: its term
// or small multiples, the compare, and over the full view the probed pixel's ring and its ray
// tree (the overlay's colours and marks) and, unless the view hides them, the light markers.
// No text of the step: the title, caption, question and answer are the page's (index.html).
Image render_step_view(const Lesson& lesson, LessonPlace place, const HandoutOptions& options);

// The previewer's light markers drawn into `image` (seen through scene.camera at the image's
// size): each point light a filled disc in its colour (hollow when muted) with short rays
// around it and its label "L0", "L1", ...; one outside the image an arrowhead at the edge
// pointing at it; none for a light behind the eye or a directional one.
void draw_light_markers(Image& image, const Scene& scene);

// Writes DIR/step-NN.png for every step (NN from 01; a question's answer as answer-NN.png)
// and DIR/index.html, a page holding every image (inline, so it is one file to send) and the
// captions. Creates DIR. `written` receives the paths. Empty string or the error.
std::string write_handout(const Lesson& lesson, const std::string& dir, const HandoutOptions& options,
                          std::vector<std::string>* written = nullptr);

}  // namespace phonglab
