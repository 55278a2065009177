#include "io/handout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/scene/camera.h"
#include "core/teaching/ray_tree_view.h"
#include "io/figure.h"
#include "io/scene/scene_io.h"

namespace phonglab {

namespace {

constexpr int kTitleScale = 3;        // font units to pixels of a page at least kLargePage wide
constexpr int kCaptionScale = 2;
constexpr int kLargePage = 640;       // narrower pages use one unit less (the text stays a third of the page)
constexpr int kLineHeight = 12;  // stb_easy_font's line height in font units
constexpr int kMargin = 12;
const glm::vec3 kPageBackground{0.02f};
const glm::vec3 kTitleColor{1.0f};
const glm::vec3 kCaptionColor{0.8f};
const glm::vec3 kQuestionColor{1.0f, 0.75f, 0.2f};
const glm::vec3 kProbeColor{1.0f, 0.9f, 0.1f};

glm::vec3 segment_color(TreeSegmentKind kind) {
  switch (kind) {
    case TreeSegmentKind::kPrimary: return {1.0f, 1.0f, 1.0f};
    case TreeSegmentKind::kShadowVisible: return {1.0f, 0.85f, 0.2f};
    case TreeSegmentKind::kShadowBlocked: return {0.9f, 0.15f, 0.1f};
    case TreeSegmentKind::kReflection: return {0.2f, 0.8f, 1.0f};
    case TreeSegmentKind::kRefraction: return {0.3f, 1.0f, 0.4f};
    case TreeSegmentKind::kArrowN: return {0.3f, 0.4f, 1.0f};
    case TreeSegmentKind::kArrowL: return {1.0f, 0.85f, 0.2f};
    case TreeSegmentKind::kArrowR: return {1.0f, 0.3f, 0.8f};
    case TreeSegmentKind::kArrowV: return {0.9f, 0.9f, 0.9f};
  }
  return {1.0f, 1.0f, 1.0f};
}

void plot(Image& image, int x, int y, glm::vec3 color) {
  if (x >= 0 && y >= 0 && x < image.width && y < image.height) image.at(x, y) = color;
}

// A line two pixels wide, stepped along its longer axis.
void draw_line(Image& image, ImagePoint a, ImagePoint b, glm::vec3 color) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const int steps = std::max(1, static_cast<int>(std::ceil(std::max(std::abs(dx), std::abs(dy)))));
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const int x = static_cast<int>(std::floor(a.x + t * dx)), y = static_cast<int>(std::floor(a.y + t * dy));
    plot(image, x, y, color);
    plot(image, x + 1, y, color);
    plot(image, x, y + 1, color);
  }
}

void draw_ring(Image& image, double cx, double cy, double radius, glm::vec3 color) {
  const int n = std::max(16, static_cast<int>(radius * 8));
  for (int i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979323846 * i / n;
    const double b = 2 * 3.14159265358979323846 * (i + 1) / n;
    draw_line(image, {cx + radius * std::cos(a), cy + radius * std::sin(a)}, {cx + radius * std::cos(b), cy + radius * std::sin(b)},
              color);
  }
}

// The view's image; `eye` is its shading eye (view_shading_eye), found once per view.
Image render_plain(const PreparedScene& prepared, const StepView& view, const std::optional<Vec3>& eye, int width, int height,
                   const HandoutOptions& options) {
  if (view.small_multiples) {
    FigureOptions figure;
    figure.cell_width = std::max(1, width / 3);
    figure.cell_height = std::max(1, (height - 2 * figure_label_height()) / 2);
    figure.spp = options.spp;
    figure.threads = options.threads;
    figure.shading_eye = eye;
    return make_figure(prepared, figure);
  }
  RenderOptions render;
  render.term = view.term;
  render.threads = options.threads;
  render.shading_eye = eye;
  Accumulator accum;
  accum.reset(width, height);
  render_passes(prepared, render, accum, std::max(1, options.spp));
  return mean_image(accum);
}

void draw_probe(Image& image, const PreparedScene& prepared, const StepView& view, const std::optional<Vec3>& eye) {
  const auto pixel = probe_in(prepared.scene(), prepared.scene().camera, view, image.width, image.height);
  if (!pixel) return;
  const int px = (*pixel)[0], py = (*pixel)[1];
  if (view.ray_tree) {
    const PixelProbe probe = probe_pixel(prepared, image.width, image.height, px, py,
                                         eye);
    const CameraFrame frame = make_camera_frame(prepared.scene().camera, image.width, image.height);
    const auto segments = ray_tree_segments(prepared.scene(), probe.root);
    for (const ScreenSegment& s : project_ray_tree(frame, segments, ray_tree_near(prepared.scene(), probe.root))) {
      draw_line(image, s.from, s.to, segment_color(s.kind));
    }
  }
  draw_ring(image, px + 0.5, py + 0.5, std::max(6.0, image.height / 60.0), kProbeColor);
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
  if (!view.small_multiples) draw_probe(image, prepared, view, eye);
  return image;
}

std::string ascii_text(const std::string& text) {
  static const std::pair<std::string_view, std::string_view> kSpelled[] = {
      {"\xC2\xB7", "*"},   {"\xCE\xA3", "sum "}, {"\xC3\x97", "x"},     {"\xE2\x88\x92", "-"}, {"\xE2\x80\x94", " - "},
      {"\xE2\x80\x93", "-"}, {"\xE2\x80\x99", "'"}, {"\xE2\x80\x9C", "\""}, {"\xE2\x80\x9D", "\""}, {"\xE2\x89\xA5", ">="},
      {"\xE2\x89\xA4", "<="}, {"\xE2\x86\x92", "->"}, {"\xCE\xB7", "eta"}, {"\xC2\xB0", " deg"}, {"\xE2\x80\xA6", "..."}};
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    bool matched = false;
    for (const auto& [from, to] : kSpelled) {
      if (text.compare(i, from.size(), from) == 0) {
        out += to;
        i += from.size();
        matched = true;
        break;
      }
    }
    if (matched) continue;
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      out += c == '\n' ? ' ' : text[i];
      ++i;
    } else {
      out += '?';  // any other character: one mark for its bytes
      ++i;
      while (i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) ++i;
    }
  }
  return out;
}

std::vector<std::string> wrap_text(const std::string& text, int scale, int max_width) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
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

Image step_page(const Lesson& lesson, LessonPlace place, const HandoutOptions& options) {
  const LessonStep& step = lesson.steps.at(static_cast<std::size_t>(place.step));
  const Image image = render_step_view(lesson, place, options);
  const int text_width = std::max(1, image.width - 2 * kMargin);
  const int smaller = image.width >= kLargePage ? 0 : 1;
  const int title_scale = kTitleScale - smaller, caption_scale = kCaptionScale - smaller;
  char number[32];
  std::snprintf(number, sizeof number, "%d/%zu  ", place.step + 1, lesson.steps.size());
  const auto title = wrap_text(number + ascii_text(step.title), title_scale, text_width);
  auto caption = wrap_text(ascii_text(step.caption), caption_scale, text_width);
  std::vector<std::string> question;
  if (step.has_question()) question = wrap_text("Q: " + ascii_text(step.question), caption_scale, text_width);
  std::vector<std::string> answer;
  if (place.revealed && step.has_question()) answer = wrap_text("A: " + ascii_text(step.answer), caption_scale, text_width);
  const int title_h = static_cast<int>(title.size()) * kLineHeight * title_scale;
  const int line_h = kLineHeight * caption_scale;
  const int text_h = title_h + static_cast<int>(caption.size() + question.size() + answer.size()) * line_h + 3 * kMargin;
  Image page;
  page.width = image.width;
  page.height = image.height + text_h;
  page.pixels.assign(static_cast<std::size_t>(page.width) * static_cast<std::size_t>(page.height), kPageBackground);
  std::copy(image.pixels.begin(), image.pixels.end(), page.pixels.begin());
  int y = image.height + kMargin;
  for (const std::string& l : title) {
    draw_label(page, kMargin, y, l, title_scale, kTitleColor, text_width);
    y += kLineHeight * title_scale;
  }
  y += kMargin;
  const auto lines = [&](const std::vector<std::string>& list, glm::vec3 color) {
    for (const std::string& l : list) {
      draw_label(page, kMargin, y, l, caption_scale, color, text_width);
      y += line_h;
    }
  };
  lines(caption, kCaptionColor);
  lines(question, kQuestionColor);
  lines(answer, kTitleColor);
  return page;
}

std::string write_handout(const Lesson& lesson, const std::string& dir, const HandoutOptions& options,
                          std::vector<std::string>* written) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return dir + ": cannot create the folder: " + ec.message();
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << html_escape(lesson.title)
       << "</title>\n<style>\nbody{font-family:sans-serif;max-width:70em;margin:2em auto;padding:0 1em;color:#222}\n"
          "img{max-width:100%;display:block;margin:.5em 0}\n.step{margin-bottom:3em}\n.question{color:#a60}\n"
          "</style>\n</head>\n<body>\n<h1>"
       << html_escape(lesson.title) << "</h1>\n<p>" << html_escape(lesson.description) << "</p>\n";
  for (int i = 0; i < static_cast<int>(lesson.steps.size()); ++i) {
    const LessonStep& step = lesson.steps[static_cast<std::size_t>(i)];
    html << "<section class=\"step\" id=\"step-" << i + 1 << "\">\n<h2>" << i + 1 << ". " << html_escape(step.title)
         << "</h2>\n<p>" << html_escape(step.caption) << "</p>\n";
    for (const bool revealed : {false, true}) {
      if (revealed && !step.has_question()) break;
      const std::string name = step_file(i, revealed);
      const std::string path = (std::filesystem::path(dir) / name).string();
      const std::string png = encode_png_srgb(step_page(lesson, {i, revealed}, options));
      if (std::string err = write_file_atomically(path, png); !err.empty()) return path + ": " + err;
      if (written != nullptr) written->push_back(path);
      if (revealed) html << "<p><b>Answer:</b> " << html_escape(step.answer) << "</p>\n";
      else if (step.has_question()) html << "<p class=\"question\"><b>Question:</b> " << html_escape(step.question) << "</p>\n";
      html << "<img alt=\"" << html_escape(step.title) << "\" src=\"data:image/png;base64," << base64(png) << "\">\n";
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
