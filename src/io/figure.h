// Figures for slides: the five term images of docs/model.md and their sum in a labelled 3x2 grid.
// Deterministic: the same scene and options give the same pixels (and PNG bytes).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "io/image_io.h"
#include "core/render/render.h"
#include "core/scene/scene.h"

namespace phonglab {

// How a figure is made.
struct FigureOptions {
  int cell_width = 320;   // pixels across one term image
  int cell_height = 180;  // pixels down one term image
  int spp = 1;            // samples per pixel of every term image
  int threads = 0;        // 0: all hardware threads (the pixels do not depend on it)
  std::optional<Vec3> shading_eye;  // "move your head": RenderOptions::shading_eye
};

// The six cells in reading order: ambient, diffuse, specular / reflection, refraction, sum.
inline constexpr std::array<Term, 6> kFigureTerms = {Term::kAmbient,    Term::kDiffuse,    Term::kSpecular,
                                                     Term::kReflection, Term::kRefraction, Term::kFull};

// The label under a cell: the term's name and its place in the equation (ASCII only).
std::string_view figure_label(Term term);

// Height in pixels of the label strip under every cell.
int figure_label_height();

// Renders the six term images of a prepared scene and lays them out as
// 3 columns x 2 rows, each cell with its label strip below: the montage is
// 3*cell_width x 2*(cell_height + figure_label_height()) pixels, linear RGB.
Image make_figure(const PreparedScene& scene, const FigureOptions& options);

// Draws `text` in a built-in bitmap font (stb_easy_font) into `image`, top-left at (x, y),
// each font unit `scale` pixels, in linear colour `color`. Clipped to the image and to
// `max_width` pixels across.
void draw_label(Image& image, int x, int y, std::string_view text, int scale, glm::vec3 color, int max_width);

// Width in pixels of `text` in draw_label's font at `scale`.
int label_width(std::string_view text, int scale);

// make_figure written as an 8-bit sRGB PNG (or a PFM by extension). Empty string or the error.
std::string write_figure(const std::string& path, const PreparedScene& scene, const FigureOptions& options);

}  // namespace phonglab
