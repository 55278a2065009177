// Figures for slides: the five term images of docs/model.md and their sum in a labelled 3x2 grid.
// Deterministic: the same scene and options give the same pixels (and PNG bytes).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

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

// The label under a cell: the term's name and its place in the equation, in ASCII for the
// bitmap font (the Unicode equation's symbols spelled out: sum_l for the sum over the lights
// l, I_a and I_l for the subscripts, * for the middle dot, N.L for N·L).
std::string_view figure_label(Term term);

// Height in pixels of the label strip under every cell.
int figure_label_height();

// Pixels of background between two cells, across and down.
int figure_gutter();

// The font scale of every label of a figure with cells `cell_width` wide: 2 when all six
// labels fit on one line, else 1 (a label then takes up to the strip's two lines).
int figure_label_scale(int cell_width);

// Renders the six term images of a prepared scene and lays them out as
// 3 columns x 2 rows, each cell with its label strip below, figure_gutter() pixels of
// background between the cells: the montage is 3*cell_width + 2*gutter x
// 2*(cell_height + figure_label_height()) + gutter pixels, linear RGB.
Image make_figure(const PreparedScene& scene, const FigureOptions& options);

// Draws `text` in a built-in bitmap font (stb_easy_font) into `image`, top-left at (x, y),
// each font unit `scale` pixels, in linear colour `color`. Clipped to the image and to
// `max_width` pixels across.
void draw_label(Image& image, int x, int y, std::string_view text, int scale, glm::vec3 color, int max_width);

// Width in pixels of `text` in draw_label's font at `scale`.
int label_width(std::string_view text, int scale);

// `text` broken at its spaces into lines of at most `max_width` pixels in draw_label's font at
// `scale` (a word wider than that gets a line of its own).
std::vector<std::string> wrap_text(std::string_view text, int scale, int max_width);

// make_figure written as an 8-bit sRGB PNG (or a PFM by extension). Empty string or the error.
std::string write_figure(const std::string& path, const PreparedScene& scene, const FigureOptions& options);

}  // namespace phonglab
