#include "io/handout.h"

#include "check/formula.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <utility>

#include "core/scene/camera.h"
#include "io/embedded_scenes.h"
#include "core/scene/math.h"
#include "core/teaching/ray_tree_view.h"
#include "io/figure.h"
#include "io/scene/scene_io.h"

namespace phonglab {

namespace {

constexpr int kIndirectSpp = 32;  // samples a pixel of a step that shows the indirect light, at least

const glm::vec3 kOutline{0.0f};  // under every line and marker, so it reads on any image

// An sRGB colour given as the previewer's 8-bit one, in the image's linear RGB.
glm::vec3 srgb(int r, int g, int b) {
  const auto lin = [](int c) { return static_cast<float>(srgb_to_linear(c / 255.0)); };
  return {lin(r), lin(g), lin(b)};
}

// The ray tree's one palette (core/teaching/ray_tree_view.h), as the image's linear values.
glm::vec3 segment_color(TreeSegmentKind kind, int depth, bool blocked = false) {
  const std::array<std::uint8_t, 3> c = segment_srgb8(kind, depth, blocked);
  return srgb(c[0], c[1], c[2]);
}

void plot(Image& image, int x, int y, glm::vec3 color) {
  if (x >= 0 && y >= 0 && x < image.width && y < image.height) image.at(x, y) = color;
}

// A line `width` pixels wide, stepped along its longer axis.
void draw_line(Image& image, ImagePoint a, ImagePoint b, glm::vec3 color, int width = 2) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy)))));
  const int lo = -(width - 1) / 2, hi = width / 2;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::floor(a.x + t * dx)), y = static_cast<int>(std::floor(a.y + t * dy));
    for (int oy = lo; oy <= hi; ++oy) {
      for (int ox = lo; ox <= hi; ++ox) plot(image, x + ox, y + oy, color);
    }
  }
}

// A line with a dark outline under it.
void draw_outlined(Image& image, ImagePoint a, ImagePoint b, glm::vec3 color) {
  draw_line(image, a, b, kOutline, 4);
  draw_line(image, a, b, color, 2);
}

void draw_disc(Image& image, double cx, double cy, double radius, glm::vec3 color) {
  const int x0 = static_cast<int>(std::floor(cx - radius)), x1 = static_cast<int>(std::ceil(cx + radius));
  const int y0 = static_cast<int>(std::floor(cy - radius)), y1 = static_cast<int>(std::ceil(cy + radius));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double ex = x + 0.5 - cx, ey = y + 0.5 - cy;
      if (ex * ex + ey * ey <= radius * radius) plot(image, x, y, color);
    }
  }
}

void draw_ring(Image& image, double cx, double cy, double radius, glm::vec3 color, int width = 2) {
  const int n = std::max(16, static_cast<int>(radius * 8));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / n;
    const double b = 2 * 3.14159265358979323846 * (i + 1) / n;
    draw_line(image, {cx + radius * std::cos(a), cy + radius * std::sin(a)}, {cx + radius * std::cos(b), cy + radius * std::sin(b)},
              color, width);
  }
}

void draw_triangle(Image& image, ImagePoint a, ImagePoint b, ImagePoint c, glm::vec3 color) {
  const auto edge = [](ImagePoint p, ImagePoint q, double x, double y) { return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x); };
  const double area = edge(a, b, c.x, c.y);
  if (area == 0) return;
  const int x0 = static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))), x1 = static_cast<int>(std::ceil(std::max({a.x, b.x, c.x})));
  const int y0 = static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))), y1 = static_cast<int>(std::ceil(std::max({a.y, b.y, c.y})));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double w0 = edge(b, c, px, py) / area, w1 = edge(c, a, px, py) / area, w2 = edge(a, b, px, py) / area;
      if (w0 >= 0 && w1 >= 0 && w2 >= 0) plot(image, x, y, color);
    }
  }
}

// Text on a dark plate, top-left at (x, y), kept inside the image.
void draw_tag(Image& image, int x, int y, const std::string& text, int scale, glm::vec3 color) {
  const int w = label_width(text, scale), h = 10 * scale, pad = 2 * scale;
  x = std::clamp(x, pad, std::max(pad, image.width - w - pad));
  y = std::clamp(y, pad, std::max(pad, image.height - h - pad));
  for (int py = y - pad; py < y + h + pad; ++py) {
    for (int px = x - pad; px < x + w + pad; ++px) plot(image, px, py, kOutline);
  }
  draw_label(image, x, y + scale, text, scale, color, w + 1);
}

// Pixels of the marks: a bit larger on larger images, as the previewer's scale with its UI.
double mark_size(const Image& image) { return std::max(5.0, image.height / 77.0); }
int text_scale(const Image& image) { return image.height >= 500 ? 2 : 1; }


// The ray tree as the previewer's overlay draws it (src/ui/ray_tree_overlay.cpp, draw_ray_tree),
// in three layers: the arrows' shafts, the rays over them (a shadow ray runs along its L arrow,
// and its red end at the occluder must show), then the arrowheads and their letters. A ray's
// end: the primary hit a dot, a blocked shadow ray a cross at the occluder, a seen one a ring.
void draw_ray_tree(Image& image, const std::vector<ScreenSegment>& segments, bool blinn, int lit_lights) {
  const double mark = mark_size(image) * 0.8;
  const int scale = text_scale(image);
  for (int pass = 0; pass < 3; ++pass) {
    for (const ScreenSegment& s : segments) {
      if (is_arrow(s.kind) != (pass != 1)) continue;
      const glm::vec3 color = segment_color(s.kind, s.depth, s.blocked);
      const ImagePoint a = s.from, b = s.to;
      if (pass < 2) draw_outlined(image, a, b, color);
      if (pass == 0 || !s.to_visible) continue;
      if (pass == 2) {
        const double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
        std::string letter = arrow_letter(s.kind, blinn);
        if ((s.kind == TreeSegmentKind::kArrowL || s.kind == TreeSegmentKind::kArrowR) && lit_lights > 1) {
          letter += std::to_string(s.light);
        }
        if (len < 3) {  // seen end-on (V, unless the head moves): a ring with a dot
          draw_ring(image, b.x, b.y, mark, color);
          draw_disc(image, b.x, b.y, 1.5, color);
          draw_tag(image, static_cast<int>(b.x - mark) - label_width(letter, scale) - 3, static_cast<int>(b.y - mark) - 10 * scale,
                   letter, scale, color);
          continue;
        }
        const double ux = dx / len, uy = dy / len, head = std::min(1.6 * mark, 0.5 * len);
        const ImagePoint base{b.x - ux * head, b.y - uy * head};
        draw_triangle(image, b, {base.x - uy * head * 0.5, base.y + ux * head * 0.5}, {base.x + uy * head * 0.5, base.y - ux * head * 0.5},
                      color);
        const int w = label_width(letter, scale), h = 10 * scale;
        draw_tag(image, static_cast<int>(b.x + ux * (h * 0.8 + 2) - w / 2.0), static_cast<int>(b.y + uy * (h * 0.8 + 2) - h / 2.0),
                 letter, scale, color);
        continue;
      }
      switch (s.kind) {
        case TreeSegmentKind::kPrimary:
          draw_disc(image, b.x, b.y, mark * 0.8 * 1.3, kOutline);
          draw_disc(image, b.x, b.y, mark * 0.8, color);
          break;
        case TreeSegmentKind::kShadowBlocked:
          draw_line(image, {b.x - mark, b.y - mark}, {b.x + mark, b.y + mark}, color);
          draw_line(image, {b.x - mark, b.y + mark}, {b.x + mark, b.y - mark}, color);
          break;
        case TreeSegmentKind::kShadowVisible: draw_ring(image, b.x, b.y, mark * 0.7, color); break;
        case TreeSegmentKind::kReflection:
        case TreeSegmentKind::kRefraction:
          draw_disc(image, b.x, b.y, mark * 0.7, color);
          draw_tag(image, static_cast<int>(b.x + mark + 2), static_cast<int>(b.y) - 10 * scale - 2, std::to_string(s.depth), scale,
                   color);
          break;
        default: break;
      }
    }
  }
}

// The probed pixel's mark: the previewer's ring with its four ticks (src/ui/overlay.cpp, draw_probe_ring).
void draw_probe_ring(Image& image, double cx, double cy) {
  const double r = std::max(6.0, image.height / 60.0);
  const glm::vec3 yellow = srgb(255, 230, 0);
  draw_ring(image, cx, cy, r, kOutline, 4);
  draw_ring(image, cx, cy, r, yellow);
  for (const auto& [ux, uy] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}}) {
    draw_line(image, {cx + ux * r, cy + uy * r}, {cx + ux * 2.2 * r, cy + uy * 2.2 * r}, yellow);
  }
}

}  // namespace

void draw_light_markers(Image& image, const Scene& scene) {
  const CameraFrame frame = make_camera_frame(scene.camera, image.width, image.height);
  const double r = mark_size(image);
  const int scale = text_scale(image);
  const double inset = 2.5 * r;
  for (int i = 0; i < static_cast<int>(scene.lights.size()); ++i) {
    const Light& light = scene.lights[static_cast<std::size_t>(i)];
    if (light.type != LightType::kPoint) continue;
    const std::optional<ImagePoint> at = project_point(frame, light.position);
    if (!at || !std::isfinite(at->x) || !std::isfinite(at->y)) continue;  // behind the eye: none, as in the previewer
    const double m = std::max(max_channel(light.intensity), 1e-9);
    const glm::vec3 fill = light.enabled ? glm::vec3(static_cast<float>(light.intensity.x / m), static_cast<float>(light.intensity.y / m),
                                                     static_cast<float>(light.intensity.z / m))
                                         : glm::vec3(0.13f);
    const ImagePoint p{std::clamp(at->x, inset, std::max(inset, image.width - inset)),
                       std::clamp(at->y, inset, std::max(inset, image.height - inset))};
    if (p.x != at->x || p.y != at->y) {
      // Outside the image: an arrowhead at its edge pointing at the light.
      const double dx = at->x - p.x, dy = at->y - p.y, len = std::hypot(dx, dy);
      const double ux = dx / len, uy = dy / len;
      const ImagePoint tip{p.x + ux * r * 1.5, p.y + uy * r * 1.5};
      const ImagePoint left{p.x - uy * r, p.y + ux * r}, right{p.x + uy * r, p.y - ux * r};
      draw_triangle(image, {tip.x + ux * 2, tip.y + uy * 2}, {left.x - uy * 1.5, left.y + ux * 1.5},
                    {right.x + uy * 1.5, right.y - ux * 1.5}, kOutline);
      draw_triangle(image, tip, left, right, fill);
    } else {
      // Short rays around the disc read as "a light", not as a scene object.
      for (int k = 0; k < 8; ++k) {
        const double a = k * 0.7853981633974483;
        const ImagePoint from{p.x + std::cos(a) * r * 1.3, p.y + std::sin(a) * r * 1.3};
        const ImagePoint to{p.x + std::cos(a) * r * 1.9, p.y + std::sin(a) * r * 1.9};
        draw_outlined(image, from, to, fill);
      }
      draw_disc(image, p.x, p.y, r + 1.5, kOutline);
      if (light.enabled) draw_disc(image, p.x, p.y, r, fill);
      else draw_ring(image, p.x, p.y, r - 1, fill);
    }
    // The label beside it, up and to the right (left of it near the right edge).
    char label_text[16];  // (snprintf: GCC 12 warns, -Wrestrict, a false positive, on "L" + std::to_string)
    std::snprintf(label_text, sizeof label_text, "L%d", i);
    const std::string label = label_text;
    const int w = label_width(label, scale);
    const int gap = static_cast<int>(std::lround(2.2 * r));
    const int x = p.x + gap + w + 4 < image.width ? static_cast<int>(p.x) + gap : static_cast<int>(p.x) - gap - w;
    const int y = p.y - gap - 10 * scale >= 0 ? static_cast<int>(p.y) - gap - 10 * scale : static_cast<int>(p.y) + gap;
    draw_tag(image, x, y, label, scale, glm::vec3(1.0f));
  }
}

namespace {

// The view's image; `eye` is its shading eye (view_shading_eye), found once per view.
Image render_plain(const PreparedScene& prepared, const StepView& view, const std::optional<Vec3>& eye, int width, int height,
                   const HandoutOptions& options) {
  if (view.small_multiples) {
    FigureOptions figure;
    figure.cell_width = std::max(1, (width - 2 * figure_gutter()) / 3);
    figure.cell_height = std::max(1, (height - 2 * figure_label_height() - figure_gutter()) / 2);
    figure.spp = options.spp;
    figure.threads = options.threads;
    figure.shading_eye = eye;
    return make_figure(prepared, figure);
  }
  // The indirect light beside ka·Ia, or their gap: one image of the indirect term with the term
  // images (the ambient one is ka·Ia), as the previewer shows it.
  const bool pair = view.ambient == Ambient::kIndirect && view.ambient_shown != AmbientShown::kImage;
  RenderOptions render;
  render.term = pair ? Term::kIndirect : view.term;
  render.ambient = view.ambient;
  render.threads = options.threads;
  render.shading_eye = eye;
  Accumulator accum;
  accum.reset(width, height, pair);
  // The indirect light is a Monte Carlo estimate: a printed page gets at least kIndirectSpp samples
  // a pixel, or its noise would hide what it shows.
  const int spp = view.ambient == Ambient::kIndirect ? std::max(options.spp, kIndirectSpp) : options.spp;
  render_passes(prepared, render, accum, std::max(1, spp));
  Image image = mean_image(accum);
  if (pair) {
    std::vector<glm::vec3> ambient(image.pixels.size());
    const double inv = 1.0 / static_cast<double>(std::max(accum.samples, 1u));
    for (std::size_t i = 0; i < ambient.size(); ++i) ambient[i] = glm::vec3(accum.terms[i].ambient * inv);
    image.pixels = ambient_shown_pixels(view.ambient_shown, image.pixels, ambient, width, view.wipe);
  }
  return image;
}

void draw_probe(Image& image, const PreparedScene& prepared, const StepView& view, const std::optional<Vec3>& eye) {
  const auto pixel = probe_in(prepared.scene(), prepared.scene().camera, view, image.width, image.height);
  if (!pixel) return;
  const int px = (*pixel)[0], py = (*pixel)[1];
  draw_probe_ring(image, px + 0.5, py + 0.5);
  if (!view.ray_tree) return;
  const PixelProbe probe = probe_pixel(prepared, image.width, image.height, px, py, eye);
  const CameraFrame frame = make_camera_frame(prepared.scene().camera, image.width, image.height);
  const auto segments = project_ray_tree(frame, ray_tree_segments(prepared.scene(), probe.root),
                                         ray_tree_near(prepared.scene(), probe.root));
  int lit_lights = 0;
  for (const ProbeLight& light : probe.root.lights) lit_lights += light.lit_side ? 1 : 0;
  draw_ray_tree(image, segments, prepared.scene().specular_model == SpecularModel::kBlinn, lit_lights);
  // Seen from the eye the primary ray is a point (it runs through the pixel into the picture):
  // say which ray that dot ends.
  for (const ScreenSegment& s : segments) {
    if (s.kind != TreeSegmentKind::kPrimary || !s.to_visible || std::hypot(s.to.x - s.from.x, s.to.y - s.from.y) >= 3) continue;
    const int scale = text_scale(image);
    const int r = static_cast<int>(std::lround(std::max(6.0, image.height / 60.0)));
    const char* const tag = "ray from the eye";  // centred below the ring's lower tick
    draw_tag(image, px - label_width(tag, scale) / 2, py + static_cast<int>(2.4 * r) + 3, tag, scale,
             segment_color(TreeSegmentKind::kPrimary, 0));
  }
}

std::string base64(const std::string& bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const auto byte = [&](std::size_t k) { return k < bytes.size() ? static_cast<unsigned char>(bytes[k]) : 0u; };
    const unsigned v = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += i + 1 < bytes.size() ? kDigits[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string step_file(int step, bool answer) {
  char name[40];
  std::snprintf(name, sizeof name, "%s-%02d.png", answer ? "answer" : "step", step + 1);
  return name;
}

}  // namespace

Image render_step_view(const Lesson& lesson, LessonPlace place, const HandoutOptions& options) {
  const LessonStep& step = lesson.steps.at(static_cast<std::size_t>(place.step));
  const StepView& view = view_at(step, place.revealed);
  const int width = options.width > 0 ? options.width : step.prepared_scene.width;
  const int height = options.height > 0 ? options.height : step.prepared_scene.height;
  const PreparedScene prepared(view_scene(step.prepared_scene, view));
  const std::optional<Vec3> eye = view_shading_eye(prepared, view, width, height);
  Image image = render_plain(prepared, view, eye, width, height, options);
  if (view.compare != CompareView::kNone && !view.small_multiples) {
    const CompareSource source = compare_source(lesson, place.step, view);
    const PreparedScene a_scene(view_scene(lesson.steps[static_cast<std::size_t>(source.step)].prepared_scene, source.view));
    const Image a = render_plain(a_scene, source.view, view_shading_eye(a_scene, source.view, width, height), width, height,
                                 options);
    image.pixels = compare_pixels(image.pixels, a.pixels, width, view.compare, view.wipe, view.difference_gain);
  }
  // The marks belong to the one full view, as in the previewer: none over the small multiples.
  if (view.small_multiples) return image;
  draw_probe(image, prepared, view, eye);
  if (view.light_markers) draw_light_markers(image, prepared.scene());
  return image;
}

std::string write_handout(const Lesson& lesson, const std::string& dir, const HandoutOptions& options,
                          std::vector<std::string>* written) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return dir + ": cannot create the folder: " + ec.message();
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << html_escape(lesson.title)
       << "</title>\n<style>\nbody{font-family:sans-serif;max-width:70em;margin:2em auto;padding:0 1em;color:#222}\n"
          "img{max-width:100%;display:block;margin:.5em 0}\n.step{margin-bottom:3em}\n.question{color:#a60}\n.of{font-size:60%;font-weight:normal;color:#777}\n"
          ".write{border:1px solid #999;min-height:7em;margin:.5em 0;background:repeating-linear-gradient(#fff 0 1.9em,#ccc 1.9em 2em)}\n"
          ".reference{break-before:page;page-break-before:always}\npre{font-size:110%;background:#f4f4f4;padding:.5em}\n"
          "</style>\n</head>\n<body>\n<h1>"
       << html_escape(lesson.title) << "</h1>\n<p>" << html_escape(lesson.description) << "</p>\n";
  const int steps = static_cast<int>(lesson.steps.size());
  const bool live = !options.live_page.empty() && find_embedded_lesson(lesson.name) != nullptr;
  for (int i = 0; i < steps; ++i) {
    const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
    html << "<section class=\"step\" id=\"step-" << i + 1 << "\">\n<h2>" << i + 1 << ". " << html_escape(step.title)
         << " <span class=\"of\">(step " << i + 1 << " of " << steps << ")</span></h2>\n<p>" << html_escape(step.caption)
         << "</p>\n";
    if (live) {
      html << "<p><a href=\"" << html_escape(options.live_page) << "#lesson=" << html_escape(lesson.name) << "&amp;step=" << i + 1
           << "\">Open this step live</a></p>\n";
    }
    for (const bool revealed : {false, true}) {
      if (revealed && !step.has_question()) break;
      const std::string name = step_file(i, revealed);
      const std::string path = (std::filesystem::path(dir) / name).string();
      const std::string png = encode_png_srgb(render_step_view(lesson, {i, revealed}, options));
      if (std::string err = write_file_atomically(path, png); !err.empty()) return path + ": " + err;
      if (written != nullptr) written->push_back(path);
      if (revealed) html << "<p><b>Answer:</b> " << html_escape(step.answer) << "</p>\n";
      else if (step.has_question()) html << "<p class=\"question\"><b>Question:</b> " << html_escape(step.question) << "</p>\n";
      html << "<img alt=\"" << html_escape(step.title) << "\" src=\"data:image/png;base64," << base64(png) << "\">\n";
    }
    if (step.exercise) {
      // The task with room to write the formula by hand; the reference is on the last page.
      html << "<p class=\"question\"><b>Your turn (the " << html_escape(step.exercise->slot) << " term):</b> "
           << html_escape(step.exercise->task) << "</p>\n<div class=\"write\"></div>\n";
    }
    html << "</section>\n";
  }
  bool exercises = false;
  for (const LessonStep& step : lesson.steps) exercises = exercises || step.exercise.has_value();
  if (exercises) {
    html << "<section class=\"reference\" id=\"reference-formulas\">\n<h2>The reference formulas</h2>\n"
            "<p>What phonglab renders for each term (docs/formulas.md); check yours with "
            "<code>phonglab-cli check SCENE --formula 'SLOT=...'</code>.</p>\n";
    for (int s = 0; s < kFormulaSlots; ++s) {
      const auto slot = static_cast<FormulaSlot>(s);
      html << "<h3>" << formula_slot_name(slot) << "</h3>\n<pre>" << html_escape(std::string(reference_formula(slot)))
           << "</pre>\n";
    }
    html << "</section>\n";
  }
  html << "</body>\n</html>\n";
  const std::string index = (std::filesystem::path(dir) / "index.html").string();
  if (std::string err = write_file_atomically(index, html.str()); !err.empty()) return index + ": " + err;
  if (written != nullptr) written->push_back(index);
  return "";
}

}  // namespace phonglab
