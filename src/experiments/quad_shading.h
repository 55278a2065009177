// A live rung under study for the camera drag (docs/speed.md, "The camera drag"): exact
// visibility and less shading. Sample 0 at every pixel centre, every pixel's primary ray traced
// (exact silhouettes, exactly which surface each pixel shows); in a 2x2 quad whose four primary
// hits are on one surface, of a material that neither reflects nor refracts, only the top-left
// pixel is shaded (its lights, shadow rays and terms) at first. Each other pixel of such a quad
// is interpolated between the shaded pixels of its surface at the corners of the cell around it
// (never across an edge), unless those corners differ by more than two display codes (a shadow's
// edge, a highlight, a terminator): then it is shaded itself. Quads on an edge, mirrors and glass
// are shaded whole. Measured by `phonglab-bench SCENE --live` against the exact image and the
// coarse levels; written with the scalar tracer to learn its error before its packet version
// exists, so its time here is not the rung's.
#pragma once

#include <atomic>

#include "core/render/render.h"

namespace phonglab {

// Writes the rung's image of `prepared` into `accum` (its size; samples becomes 1). Equation
// terms only (the full image or one of its five terms); the shading is the scalar tracer's.
// Same image for any thread count.
PassStats render_quad_shaded(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                             const std::atomic<bool>* cancel = nullptr);

}  // namespace phonglab
