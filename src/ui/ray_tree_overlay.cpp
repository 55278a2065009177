#include "ui/ray_tree_overlay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/teaching/heat_map.h"
#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

// Bounce colours by depth 1, 2, 3, 4+: reflections cool (cyan to violet), refractions green.
constexpr ImU32 kTreeOutline = IM_COL32(0, 0, 0, 170);  // under every line, so it reads on any image

// The tree's make-up, walked from the probe (not from the segments, which may be filtered).
struct TreeTally {
  int shadow_visible = 0;
  int shadow_blocked = 0;
  int reflections = 0;
  int refractions = 0;
  int deepest = 0;
};
void tally(const ProbeNode& node, TreeTally& t) {
  t.deepest = std::max(t.deepest, node.depth);
  for (const ProbeLight& l : node.lights) {
    if (!l.lit_side) continue;
    if (l.visible) ++t.shadow_visible;
    else ++t.shadow_blocked;
  }
  if (node.reflection) {
    ++t.reflections;
    tally(*node.reflection, t);
  }
  if (node.refraction) {
    ++t.refractions;
    tally(*node.refraction, t);
  }
}

ImVec2 to_screen(const ImageRect& rect, const ImagePoint& p) {
  return ImVec2(rect.origin.x + static_cast<float>(p.x) * rect.scale.x,
                rect.origin.y + static_cast<float>(p.y) * rect.scale.y);
}


// A colour swatch line in the legend, then its text on the same row.
void legend_row(ImU32 color, const char* text, bool cross_at_end = false) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float h = ImGui::GetTextLineHeight();
  const float w = 2.2f * h;
  const ImVec2 a(at.x, at.y + h / 2), b(at.x + w, at.y + h / 2);
  draw->AddLine(a, b, kTreeOutline, 4.5f);
  draw->AddLine(a, b, color, 2.5f);
  if (cross_at_end) {
    const float r = h * 0.3f;
    draw->AddLine(ImVec2(b.x - r, b.y - r), ImVec2(b.x + r, b.y + r), color, 2.5f);
    draw->AddLine(ImVec2(b.x - r, b.y + r), ImVec2(b.x + r, b.y - r), color, 2.5f);
  }
  ImGui::Dummy(ImVec2(w + h * 0.5f, h));
  ImGui::SameLine();
  ImGui::TextUnformatted(text);
}

// One legend row for a bounce kind: its name, then a numbered swatch per depth present
// (depth 4 and deeper share a colour).
void depth_row(TreeSegmentKind kind, const char* text, int deepest) {
  const float h = ImGui::GetTextLineHeight();
  ImGui::Dummy(ImVec2(2.7f * h, h));  // the swatch column of the other rows
  ImGui::SameLine();
  ImGui::TextUnformatted(text);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  for (int d = 1; d <= std::min(deepest, 4); ++d) {
    ImGui::SameLine();
    const ImVec2 at = ImGui::GetCursorScreenPos();
    char label[8];
    std::snprintf(label, sizeof label, d < 4 || deepest == 4 ? "%d" : "%d+", d);
    const ImU32 color = segment_color(kind, d);
    const float seg = 1.1f * h;
    draw->AddLine(ImVec2(at.x, at.y + h / 2), ImVec2(at.x + seg, at.y + h / 2), kTreeOutline, 4.5f);
    draw->AddLine(ImVec2(at.x, at.y + h / 2), ImVec2(at.x + seg, at.y + h / 2), color, 2.5f);
    draw->AddText(ImVec2(at.x + seg + 2, at.y), color, label);
    ImGui::Dummy(ImVec2(seg + 2 + ImGui::CalcTextSize(label).x, h));
  }
}

}  // namespace

ImU32 segment_color(TreeSegmentKind kind, int depth, bool blocked) {
  const std::array<std::uint8_t, 3> c = segment_srgb8(kind, depth, blocked);  // the one palette (core)
  return IM_COL32(c[0], c[1], c[2], 255);
}

std::string depth_cut_format(int scene_max_depth) {
  if (scene_max_depth <= 0) return "%d: the scene's max depth is 0";
  return "%d of " + std::to_string(scene_max_depth);
}

bool rays_panel(RayTreeSettings& s, const RayTreeSummary& summary) {
  bool edited = false;
  edited |= ImGui::Checkbox("ray tree of the probed pixel", &s.overlay);
  help_marker("Draws the probed pixel's rays over the view: the primary ray's hit, shadow rays (yellow: the light is "
              "seen, red: blocked, ending at the occluder), reflected and refracted rays coloured by depth, and N, L, "
              "R, V at the hit. Ctrl+click a pixel to probe it.");
  if (s.overlay) {
    ImGui::Indent();
    edited |= ImGui::Checkbox("shadow rays", &s.shadow_rays);
    ImGui::SameLine();
    edited |= ImGui::Checkbox("reflected, refracted", &s.secondary_rays);
    edited |= ImGui::Checkbox("N L R V arrows", &s.arrows);
    ImGui::SameLine();
    edited |= ImGui::Checkbox("legend", &s.legend);
    ImGui::Unindent();
  }
  if (summary.probe == nullptr) {
    ImGui::TextDisabled("No pixel probed: Ctrl+click one in the view.");
  } else {
    TreeTally t;
    tally(summary.probe->root, t);
    const RayCounts& rays = summary.probe->rays;
    ImGui::Text("pixel (%d, %d): %llu rays", summary.probe->x, summary.probe->y,
                static_cast<unsigned long long>(rays.total()));
    ImGui::Text("shadow %d (%d blocked), reflected %d, refracted %d", t.shadow_visible + t.shadow_blocked,
                t.shadow_blocked, t.reflections, t.refractions);
    if (!summary.probe->root.hit) ImGui::TextDisabled("the primary ray misses: background");
    else ImGui::Text("deepest ray: depth %d", t.deepest);
  }
  ImGui::Separator();
  edited |= ImGui::Checkbox("cut recursion at depth", &s.depth_cut);
  locate("rays.depth_cut");
  help_marker("Shows the image with max depth = min(the scene's, this): 0 is local shading only, 1 adds one "
              "bounce, ... A way of looking, not an edit: no undo step, nothing to save.");
  // The cut goes from 0 (local shading) to the scene's own depth; a scene of depth 0 has nothing to cut.
  const int top = std::max(summary.scene_max_depth, 0);
  ImGui::BeginDisabled(!s.depth_cut || top == 0);
  if (s.depth_cut) s.cut_depth = std::clamp(s.cut_depth, 0, top);
  const std::string format = depth_cut_format(top);
  edited |= ImGui::SliderInt("depth", &s.cut_depth, 0, top, format.c_str(), ImGuiSliderFlags_AlwaysClamp);
  ImGui::EndDisabled();
  ImGui::Separator();
  edited |= ImGui::Checkbox("heat map: rays per pixel", &s.heat_map);
  help_marker("Shows how many rays each pixel cost (primary, shadow, reflected, refracted; the mean over its "
              "samples) on a black-to-yellow ramp, scaled to the image's maximum. The same as the Render panel's "
              "'rays' view.");
  if (s.heat_map && summary.heat_max > 0) ImGui::Text("scale: 0 .. %.4g rays per pixel", summary.heat_max);
  return edited;
}

void draw_ray_tree(ImDrawList* draw, std::span<const ScreenSegment> segments, const ImageRect& rect, float ui_scale,
                   bool blinn, int light_count) {
  const float thick = 2.0f * ui_scale;
  const float dot = 3.5f * ui_scale;
  // Three layers: the arrows' shafts, then the rays over them (a shadow ray runs along its L
  // arrow, and its red end at the occluder must show), then the arrowheads and letters.
  for (int pass = 0; pass < 3; ++pass) {
    for (const ScreenSegment& s : segments) {
      if (is_arrow(s.kind) != (pass != 1)) continue;
      const ImVec2 a = to_screen(rect, s.from);
      const ImVec2 b = to_screen(rect, s.to);
      const ImU32 color = segment_color(s.kind, s.depth, s.blocked);
      if (pass < 2) {
        draw->AddLine(a, b, kTreeOutline, thick + 2.5f * ui_scale);
        draw->AddLine(a, b, color, thick);
      }
      if (pass == 0) continue;
      if (pass == 2) {
        // An arrowhead and the vector's letter at the tip (only when the tip is on screen).
        if (!s.to_visible) continue;
        const float dx = b.x - a.x, dy = b.y - a.y;
        const float len = std::sqrt(dx * dx + dy * dy);
        if (len < 3 * ui_scale) {
          // Seen end-on (V always is, unless the head moves): the "arrow towards you" symbol,
          // a ring with a dot, labelled beside it.
          const float r = 6 * ui_scale;
          draw->AddCircle(b, r, kTreeOutline, 0, thick + 2 * ui_scale);
          draw->AddCircle(b, r, color, 0, thick);
          draw->AddCircleFilled(b, 1.5f * ui_scale, color);
          const char* letter = arrow_letter(s.kind, blinn);
          const ImVec2 text_at(b.x - r - ImGui::CalcTextSize(letter).x - 2 * ui_scale, b.y - ImGui::GetFontSize());
          draw->AddText(ImVec2(text_at.x + 1, text_at.y + 1), IM_COL32(0, 0, 0, 220), letter);
          draw->AddText(text_at, color, letter);
          continue;
        }
        const ImVec2 d(dx / len, dy / len), n(-d.y, d.x);
        const float head = std::min(9.0f * ui_scale, 0.5f * len);
        const ImVec2 base(b.x - d.x * head, b.y - d.y * head);
        draw->AddTriangleFilled(b, ImVec2(base.x + n.x * head * 0.5f, base.y + n.y * head * 0.5f),
                                ImVec2(base.x - n.x * head * 0.5f, base.y - n.y * head * 0.5f), color);
        char label[16];
        if ((s.kind == TreeSegmentKind::kArrowL || s.kind == TreeSegmentKind::kArrowR) && light_count > 1) {
          std::snprintf(label, sizeof label, "%s%d", arrow_letter(s.kind, blinn), s.light);
        } else {
          std::snprintf(label, sizeof label, "%s", arrow_letter(s.kind, blinn));
        }
        const ImVec2 text_at(b.x + d.x * 4 * ui_scale - ImGui::CalcTextSize(label).x / 2 + d.x * ImGui::GetFontSize() * 0.4f,
                             b.y + d.y * 4 * ui_scale - ImGui::GetFontSize() / 2 + d.y * ImGui::GetFontSize() * 0.4f);
        draw->AddText(ImVec2(text_at.x + 1, text_at.y + 1), IM_COL32(0, 0, 0, 220), label);
        draw->AddText(text_at, color, label);
        continue;
      }
      if (!s.to_visible) continue;  // leaves the image or the ray escaped: no end point to mark
      switch (s.kind) {
        case TreeSegmentKind::kPrimary:
          draw->AddCircleFilled(b, dot * 1.3f, kTreeOutline);
          draw->AddCircleFilled(b, dot, color);
          break;
        case TreeSegmentKind::kShadowBlocked: {
          const float r = 5 * ui_scale;
          draw->AddLine(ImVec2(b.x - r, b.y - r), ImVec2(b.x + r, b.y + r), color, thick);
          draw->AddLine(ImVec2(b.x - r, b.y + r), ImVec2(b.x + r, b.y - r), color, thick);
          break;
        }
        case TreeSegmentKind::kShadowVisible:
          draw->AddCircle(b, dot, color, 0, thick * 0.75f);
          break;
        case TreeSegmentKind::kReflection:
        case TreeSegmentKind::kRefraction: {
          draw->AddCircleFilled(b, dot, color);
          char depth[8];
          std::snprintf(depth, sizeof depth, "%d", s.depth);
          const ImVec2 at(b.x + dot + 2 * ui_scale, b.y - ImGui::GetFontSize());
          draw->AddText(ImVec2(at.x + 1, at.y + 1), IM_COL32(0, 0, 0, 220), depth);
          draw->AddText(at, color, depth);
          break;
        }
        default:
          break;
      }
    }
  }
}

void ray_tree_legend(std::span<const ScreenSegment> segments, bool blinn) {
  bool present[9] = {};
  bool unlit_arrow = false;
  int reflection_depth = 0, refraction_depth = 0;
  for (const ScreenSegment& s : segments) {
    present[static_cast<int>(s.kind)] = true;
    unlit_arrow = unlit_arrow || (is_arrow(s.kind) && s.blocked);
    if (s.kind == TreeSegmentKind::kReflection) reflection_depth = std::max(reflection_depth, s.depth);
    if (s.kind == TreeSegmentKind::kRefraction) refraction_depth = std::max(refraction_depth, s.depth);
  }
  ImGui::TextUnformatted("ray tree of the probed pixel");
  legend_row(segment_color(TreeSegmentKind::kPrimary, 0), "primary ray, its hit");
  if (present[static_cast<int>(TreeSegmentKind::kShadowVisible)]) {
    legend_row(segment_color(TreeSegmentKind::kShadowVisible, 0), "shadow ray: light seen");
  }
  if (present[static_cast<int>(TreeSegmentKind::kShadowBlocked)]) {
    legend_row(segment_color(TreeSegmentKind::kShadowBlocked, 0), "shadow ray: blocked", true);
  }
  if (reflection_depth > 0) depth_row(TreeSegmentKind::kReflection, "reflected, depth", reflection_depth);
  if (refraction_depth > 0) depth_row(TreeSegmentKind::kRefraction, "refracted, depth", refraction_depth);
  if (present[static_cast<int>(TreeSegmentKind::kArrowN)]) {
    const auto letter = [](TreeSegmentKind kind, const char* what) {
      ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(segment_color(kind, 0)), "%s", what);
    };
    letter(TreeSegmentKind::kArrowN, "N normal");
    ImGui::SameLine();
    letter(TreeSegmentKind::kArrowL, " L to light");
    letter(TreeSegmentKind::kArrowR, blinn ? "H half vector" : "R mirrored L");
    ImGui::SameLine();
    letter(TreeSegmentKind::kArrowV, " V to eye");
    if (unlit_arrow) {
      ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(segment_color(TreeSegmentKind::kArrowL, 0, true)),
                         "grey L, R: towards a light that is blocked");
    }
  }
}

namespace {

// A colour ramp as a bar `width` wide, `color(t)` for t in [lo, hi], ticks at `ticks` (their
// labels already formatted), under `title`.
template <typename Ramp>
void ramp_bar(const char* title, float width, double lo, double hi, Ramp color,
              const std::vector<std::pair<double, std::string>>& ticks) {
  ImGui::TextUnformatted(title);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 at = ImGui::GetCursorScreenPos();
  const float h = ImGui::GetTextLineHeight();
  constexpr int kSteps = 64;  // enough that a piecewise-linear ramp looks continuous
  const auto code = [&](double t) {
    const Color c = color(t);
    return IM_COL32(static_cast<int>(std::lround(c.x * 255)), static_cast<int>(std::lround(c.y * 255)),
                    static_cast<int>(std::lround(c.z * 255)), 255);
  };
  for (int i = 0; i < kSteps; ++i) {
    const float x0 = at.x + width * static_cast<float>(i) / kSteps;
    const float x1 = at.x + width * static_cast<float>(i + 1) / kSteps;
    const ImU32 left = code(lo + (hi - lo) * i / kSteps), right = code(lo + (hi - lo) * (i + 1) / kSteps);
    draw->AddRectFilledMultiColor(ImVec2(x0, at.y), ImVec2(x1, at.y + h), left, right, right, left);
  }
  draw->AddRect(at, ImVec2(at.x + width, at.y + h), IM_COL32(255, 255, 255, 120));
  ImGui::Dummy(ImVec2(width, h));
  const ImVec2 labels = ImGui::GetCursorScreenPos();
  for (const auto& [t, text] : ticks) {
    const float x = labels.x + width * static_cast<float>((t - lo) / (hi - lo));
    const float w = ImGui::CalcTextSize(text.c_str()).x;
    const float left = std::clamp(x - w / 2, labels.x, labels.x + width - w);
    draw->AddLine(ImVec2(x, labels.y - 3), ImVec2(x, labels.y), IM_COL32(255, 255, 255, 200));
    draw->AddText(ImVec2(left, labels.y), IM_COL32(255, 255, 255, 230), text.c_str());
  }
  ImGui::Dummy(ImVec2(width, h));
}

std::string tick_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.3g", v);
  return v == 0 ? std::string("0") : std::string(text);
}

}  // namespace

void heat_legend(double max, float width) {
  // Ticks at 0, half and the maximum.
  std::vector<std::pair<double, std::string>> ticks;
  for (int k = 0; k <= 2; ++k) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", max * k / 2);
    ticks.emplace_back(k / 2.0, text);
  }
  ramp_bar("rays per pixel", width, 0, 1, [](double t) { return heat_ramp_srgb(t); }, ticks);
}

void ambient_gap_legend(double scale, float width) {
  ramp_bar("indirect - ka\xC2\xB7I\xE2\x82\x90 (mean of R, G, B)", width, -1, 1, [](double t) { return ambient_gap_srgb(t); },
           {{-1, tick_text(-scale)}, {0, "0"}, {1, tick_text(scale)}});
  ImGui::TextUnformatted("orange: more light arrives than ka\xC2\xB7I\xE2\x82\x90 says");
  ImGui::TextUnformatted("blue: less; black: ka\xC2\xB7I\xE2\x82\x90 is right");
}

}  // namespace phonglab::ui
