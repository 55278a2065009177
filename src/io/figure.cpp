#include "io/figure.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace phonglab {

namespace {

constexpr int kLabelScale = 2;        // font units to pixels: readable on a projected slide
constexpr int kFontUnitsHigh = 12;    // stb_easy_font's line height in font units
constexpr int kLabelPadding = 4;      // pixels above and below the text
constexpr int kGutter = 4;            // pixels of background between two cells (across and down)
constexpr std::size_t kQuadBytes = 64;  // stb_easy_font: 4 vertices of 16 bytes per quad
const glm::vec3 kLabelBackground{0.02f};  // dark grey (sRGB 39): the gutters show between two black cells
const glm::vec3 kLabelColor{1.0f};

Image render_term(const PreparedScene& scene, Term term, const FigureOptions& options) {
  RenderOptions render;
  render.term = term;
  render.threads = options.threads;
  render.shading_eye = options.shading_eye;
  Accumulator accum;
  accum.reset(options.cell_width, options.cell_height);
  for (int s = 0; s < std::max(options.spp, 1); ++s) render_pass(scene, render, accum);
  return mean_image(accum);
}

}  // namespace

std::string_view figure_label(Term term) {
  switch (term) {
    case Term::kAmbient: return "ambient ka*I_a";
    case Term::kDiffuse: return "diffuse sum_l vis*I_l*kd*max(0,N.L)";
    case Term::kSpecular: return "specular sum_l vis*I_l*ks*max(0,R.V)^n";
    case Term::kReflection: return "reflection kr'*trace(R)";
    case Term::kRefraction: return "refraction kt'*trace(T)";
    case Term::kFull: return "sum = the image";
    default: return term_name(term);
  }
}

int figure_label_height() { return kFontUnitsHigh * kLabelScale + 2 * kLabelPadding; }

int figure_gutter() { return kGutter; }

std::vector<std::string> wrap_text(std::string_view text, int scale, int max_width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t begin = text.find_first_not_of(' ', at);
    if (begin == std::string_view::npos) break;
    const std::size_t end = std::min(text.find(' ', begin), text.size());
    const std::string word(text.substr(begin, end - begin));
    at = end;
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && label_width(longer, scale) > max_width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

int figure_label_scale(int cell_width) {
  const int room = cell_width - 2 * kLabelPadding;
  for (const Term term : kFigureTerms) {
    if (label_width(figure_label(term), kLabelScale) > room) return 1;
  }
  return kLabelScale;
}

int label_width(std::string_view text, int scale) {
  std::string buffer_text(text);  // stb_easy_font takes a mutable char*
  return stb_easy_font_width(buffer_text.data()) * scale;
}

void draw_label(Image& image, int x, int y, std::string_view text, int scale, glm::vec3 color, int max_width) {
  std::string buffer_text(text);  // stb_easy_font takes a mutable char*
  std::vector<char> vertices(kQuadBytes * (buffer_text.size() * 32 + 1));  // generous: <= ~30 quads a glyph
  const int quads = stb_easy_font_print(0, 0, buffer_text.data(), nullptr, vertices.data(),
                                        static_cast<int>(vertices.size()));
  for (int q = 0; q < quads; ++q) {
    // Each quad is an axis-aligned rectangle: corners 0 and 2 are opposite.
    float corner[4][2];
    for (int v = 0; v < 4; ++v) {
      const char* vertex = vertices.data() + static_cast<std::size_t>(q) * kQuadBytes + static_cast<std::size_t>(v) * 16;
      std::copy_n(reinterpret_cast<const float*>(vertex), 2, corner[v]);
    }
    const float x0 = std::min({corner[0][0], corner[1][0], corner[2][0], corner[3][0]});
    const float x1 = std::max({corner[0][0], corner[1][0], corner[2][0], corner[3][0]});
    const float y0 = std::min({corner[0][1], corner[1][1], corner[2][1], corner[3][1]});
    const float y1 = std::max({corner[0][1], corner[1][1], corner[2][1], corner[3][1]});
    const int px0 = std::max(x + static_cast<int>(std::lround(x0 * static_cast<float>(scale))), 0);
    const int px1 = std::min({x + static_cast<int>(std::lround(x1 * static_cast<float>(scale))), image.width, x + max_width});
    const int py0 = std::max(y + static_cast<int>(std::lround(y0 * static_cast<float>(scale))), 0);
    const int py1 = std::min(y + static_cast<int>(std::lround(y1 * static_cast<float>(scale))), image.height);
    for (int py = py0; py < py1; ++py) {
      for (int px = px0; px < px1; ++px) image.at(px, py) = color;
    }
  }
}

Image make_figure(const PreparedScene& scene, const FigureOptions& options) {
  const int cell_w = std::max(options.cell_width, 1);
  const int cell_h = std::max(options.cell_height, 1);
  const int label_h = figure_label_height();
  Image figure;
  figure.width = 3 * cell_w + 2 * kGutter;
  figure.height = 2 * (cell_h + label_h) + kGutter;
  figure.pixels.assign(static_cast<std::size_t>(figure.width) * static_cast<std::size_t>(figure.height),
                       kLabelBackground);
  const int scale = figure_label_scale(cell_w);
  FigureOptions cell = options;
  cell.cell_width = cell_w;
  cell.cell_height = cell_h;
  for (std::size_t i = 0; i < kFigureTerms.size(); ++i) {
    const int column = static_cast<int>(i % 3);
    const int row = static_cast<int>(i / 3);
    const int x0 = column * (cell_w + kGutter);
    const int y0 = row * (cell_h + label_h + kGutter);
    const Image term = render_term(scene, kFigureTerms[i], cell);
    for (int y = 0; y < cell_h; ++y) {
      for (int x = 0; x < cell_w; ++x) figure.at(x0 + x, y0 + y) = term.at(x, y);
    }
    // One size for every label: the large font where all six fit a cell, else the small one,
    // broken into the strip's two lines; what still does not fit is clipped at the cell's edge.
    const int room = cell_w - 2 * kLabelPadding;
    const std::string_view text = figure_label(kFigureTerms[i]);
    std::vector<std::string> lines = scale == kLabelScale ? std::vector<std::string>{std::string(text)} : wrap_text(text, scale, room);
    if (lines.size() == 2) {
      // Two lines: the term's name, then its place in the equation (when that fits a line).
      const std::size_t space = text.find(' ');
      const std::string_view rest = text.substr(space + 1);
      if (space != std::string_view::npos && label_width(rest, scale) <= room) lines = {std::string(text.substr(0, space)), std::string(rest)};
    }
    int y = y0 + cell_h + kLabelPadding;
    if (lines.size() == 1) y += (kLabelScale - scale) * kFontUnitsHigh / 2;  // one small line: centred in the strip
    for (std::size_t l = 0; l < lines.size() && l < static_cast<std::size_t>(kLabelScale / scale); ++l) {
      draw_label(figure, x0 + kLabelPadding, y, lines[l], scale, kLabelColor, room);
      y += kFontUnitsHigh * scale;
    }
  }
  return figure;
}

std::string write_figure(const std::string& path, const PreparedScene& scene, const FigureOptions& options) {
  return write_image(path, make_figure(scene, options));
}

}  // namespace phonglab
