// The live rung with exact visibility and less shading (docs/speed.md, "The camera drag"): sample
// 0 at every pixel centre, every pixel's primary ray traced (exact silhouettes, exactly which
// surface each pixel shows); in a 2x2 quad whose four primary hits are on one surface (one
// object and one material, mirrors and glass alike) only the top-left pixel is shaded (its
// lights, shadow rays, terms and children) at first. Each other pixel of such a quad is interpolated between the
// shaded pixels of its surface at the corners of the cell around it (never across an edge),
// unless those corners differ by more than two display codes (a shadow's edge, a highlight, a
// terminator, a reflected edge): then it is shaded itself, from the hit already found. Quads on
// an edge are shaded whole. A shaded pixel's NaN or infinity is 0 (counted) before anything is
// interpolated from it. One pass, tile by tile: a tile also finds the hits of the next
// tiles' corner pixels it interpolates towards and shades them (their values are the same
// wherever they are shaded). Every shaded pixel is the exact image's bit for bit; the others are
// measured by `phonglab-bench SCENE --live`. The progressive renderer starts a restart there
// while the hand moves when the exact image does not fit the frame's budget and this does; the
// exact image replaces it when the hand stops.
#pragma once

#include <atomic>

#include "core/render/render.h"

namespace phonglab {

// Writes the rung's image of `prepared` into `accum` (its size, a first pass: samples becomes
// 1). The full image only (another term is rendered exactly, by render_pass). Traced in packets
// where the packet tracer serves the scene and options.packets allows; the same image either way
// and for any thread count.
// Whether the rung draws what is shown: the full image with ka·Ia (for `term` with `ambient`),
// without the five term images beside it. The one rule the live ladders ask.
inline bool quad_rung_draws(Term term, Ambient ambient, bool term_images) {
  return term == Term::kFull && ambient_for(term, ambient) == Ambient::kConstant && !term_images;
}

PassStats render_quad_shaded(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                             const std::atomic<bool>* cancel = nullptr);

}  // namespace phonglab
