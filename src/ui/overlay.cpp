#include "ui/overlay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace phonglab::ui {

namespace {

constexpr ImU32 kLabelText = IM_COL32(255, 255, 255, 240);
constexpr ImU32 kOutline = IM_COL32(0, 0, 0, 200);
constexpr ImU32 kProbeYellow = IM_COL32(255, 230, 0, 255);

bool free_of(const ScreenRect& r, const std::vector<ScreenRect>& taken) {
  return std::none_of(taken.begin(), taken.end(), [&](const ScreenRect& t) { return overlaps(r, t); });
}

bool inside(const ScreenRect& r, ImVec2 lo, ImVec2 hi) {
  return r.min.x >= lo.x && r.min.y >= lo.y && r.max.x <= hi.x && r.max.y <= hi.y;
}


}  // namespace

bool overlaps(const ScreenRect& a, const ScreenRect& b) {
  return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y;
}

ScreenRect rect_at(ImVec2 anchor, ImVec2 pivot, ImVec2 size) {
  const ImVec2 min(anchor.x - pivot.x * size.x, anchor.y - pivot.y * size.y);
  return ScreenRect{min, ImVec2(min.x + size.x, min.y + size.y)};
}

void text_on_plate(ImDrawList* draw, ImVec2 at, const char* text, float ui_scale, float alpha, float wrap_width) {
  const ImVec2 size = ImGui::CalcTextSize(text, nullptr, false, wrap_width > 0 ? wrap_width : -1.0f);
  const float pad = 4 * ui_scale;
  draw->AddRectFilled(ImVec2(at.x - pad, at.y - pad * 0.6f), ImVec2(at.x + size.x + pad, at.y + size.y + pad * 0.6f),
                      IM_COL32(0, 0, 0, static_cast<int>(255 * alpha)), 3 * ui_scale);
  draw->AddText(ImGui::GetFont(), ImGui::GetFontSize(), at, kLabelText, text, nullptr, wrap_width > 0 ? wrap_width : 0.0f);
}

void draw_probe_ring(ImDrawList* draw, ImVec2 c, float ui_scale) {
  const float r = 6 * ui_scale;
  const float w = 1.5f * ui_scale;
  draw->AddCircle(c, r, IM_COL32(0, 0, 0, 255), 20, 2 * w);
  draw->AddCircle(c, r, kProbeYellow, 20, w);
  draw->AddLine(ImVec2(c.x - 2.2f * r, c.y), ImVec2(c.x - r, c.y), kProbeYellow, w);
  draw->AddLine(ImVec2(c.x + r, c.y), ImVec2(c.x + 2.2f * r, c.y), kProbeYellow, w);
  draw->AddLine(ImVec2(c.x, c.y - 2.2f * r), ImVec2(c.x, c.y - r), kProbeYellow, w);
  draw->AddLine(ImVec2(c.x, c.y + r), ImVec2(c.x, c.y + 2.2f * r), kProbeYellow, w);
}

ImVec2 slide_clear(ImVec2 pos, float half, const std::vector<ScreenRect>& taken, ImVec2 lo, ImVec2 hi) {
  const auto box = [&](ImVec2 p) { return ScreenRect{ImVec2(p.x - half, p.y - half), ImVec2(p.x + half, p.y + half)}; };
  if (free_of(box(pos), taken)) return pos;
  // On a left or right edge the marker slides vertically, on the top or bottom edge horizontally;
  // the nearest free place wins, searched outwards in steps of a marker.
  const bool vertical_edge = pos.x <= lo.x + half * 1.01f || pos.x >= hi.x - half * 1.01f;
  const float step = half;
  for (int k = 1; k < 400; ++k) {
    for (const float sign : {1.0f, -1.0f}) {
      ImVec2 p = pos;
      (vertical_edge ? p.y : p.x) += sign * step * static_cast<float>(k);
      if (p.x < lo.x + half || p.x > hi.x - half || p.y < lo.y + half || p.y > hi.y - half) continue;
      if (free_of(box(p), taken)) return p;
    }
  }
  return pos;
}

ImVec2 place_label(const LightMarker& marker, float radius, const std::vector<ScreenRect>& taken, ImVec2 lo, ImVec2 hi) {
  char label[16];
  std::snprintf(label, sizeof label, "L%d", marker.index);
  const ImVec2 size = ImGui::CalcTextSize(label);
  const float gap = 2.2f * radius;
  const ImVec2 p = marker.pos;
  const std::array<ImVec2, 8> candidates = {
      ImVec2(p.x + gap, p.y - gap - size.y * 0.5f), ImVec2(p.x + gap, p.y + gap - size.y * 0.5f),
      ImVec2(p.x - gap - size.x, p.y - gap - size.y * 0.5f), ImVec2(p.x - gap - size.x, p.y + gap - size.y * 0.5f),
      ImVec2(p.x - size.x * 0.5f, p.y + gap), ImVec2(p.x - size.x * 0.5f, p.y - gap - size.y),
      ImVec2(p.x + gap, p.y - size.y * 0.5f), ImVec2(p.x - gap - size.x, p.y - size.y * 0.5f)};
  for (const ImVec2& c : candidates) {
    const ScreenRect r{c, ImVec2(c.x + size.x, c.y + size.y)};
    if (inside(r, lo, hi) && free_of(r, taken)) return c;
  }
  for (const ImVec2& c : candidates) {
    if (inside(ScreenRect{c, ImVec2(c.x + size.x, c.y + size.y)}, lo, hi)) return c;
  }
  return candidates[0];
}

void draw_light_markers(std::span<const LightMarker> markers, float radius, float ui_scale) {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  for (const LightMarker& m : markers) {
    const ImU32 fill = ImGui::ColorConvertFloat4ToU32(m.enabled ? m.color : ImVec4(0.4f, 0.4f, 0.4f, 0.8f));
    if (m.offscreen) {
      // An arrowhead at the edge of the view pointing at the light.
      const ImVec2 d = m.toward;
      const ImVec2 n(-d.y, d.x);
      const ImVec2 tip(m.pos.x + d.x * radius * 1.5f, m.pos.y + d.y * radius * 1.5f);
      const ImVec2 left(m.pos.x + n.x * radius, m.pos.y + n.y * radius);
      const ImVec2 right(m.pos.x - n.x * radius, m.pos.y - n.y * radius);
      draw->AddTriangleFilled(tip, left, right, fill);
      draw->AddTriangle(tip, left, right, kOutline, 1.5f);
    } else {
      // Short rays around the disc read as "a light", not as a scene object.
      for (int k = 0; k < 8; ++k) {
        const float a = static_cast<float>(k) * 0.785398f;  // 45 degrees apart
        const ImVec2 dir(std::cos(a), std::sin(a));
        const ImVec2 from(m.pos.x + dir.x * radius * 1.3f, m.pos.y + dir.y * radius * 1.3f);
        const ImVec2 to(m.pos.x + dir.x * radius * 1.9f, m.pos.y + dir.y * radius * 1.9f);
        draw->AddLine(from, to, kOutline, 4.0f);
        draw->AddLine(from, to, fill, 2.0f);
      }
      if (m.enabled) draw->AddCircleFilled(m.pos, radius, fill);
      draw->AddCircle(m.pos, radius, m.enabled ? kOutline : fill, 0, 2.0f);
    }
    if (m.selected || m.hovered) {
      draw->AddCircle(m.pos, radius * 2.3f, m.selected ? IM_COL32(255, 210, 60, 255) : IM_COL32(255, 255, 255, 160), 0,
                      2.0f);
    }
    char label[16];
    std::snprintf(label, sizeof label, "L%d", m.index);
    text_on_plate(draw, m.label_pos, label, ui_scale, 0.6f);
  }
}

std::string term_caption(Term term, bool blinn) {
  const bool greek = font_has(0x03A3) && font_has(0x00B7);
  const std::string sum = greek ? "\xCE\xA3 " : "sum ";
  const std::string dot = greek ? "\xC2\xB7" : "*";
  const std::string ia = i_a();
  const std::string il = i_l();
  const std::string spec = blinn ? "max(0, N" + dot + "H)^n" : "max(0, R" + dot + "V)^n";
  switch (term) {
    case Term::kFull: return "the full image: I = the sum of the five terms";
    case Term::kAmbient: return "ambient only: ka" + dot + ia;
    case Term::kDiffuse: return "diffuse only: " + sum + "vis" + dot + il + dot + "kd" + dot + "max(0, N" + dot + "L)";
    case Term::kSpecular: return "specular only: " + sum + "vis" + dot + il + dot + "ks" + dot + spec;
    case Term::kReflection: return "reflection only: kr'" + dot + "I_reflected";
    case Term::kRefraction: return "refraction only: kt'" + dot + "I_refracted";
    case Term::kNormal: return "debug view: the shading normal N as a colour";
    case Term::kDepth: return "debug view: distance to the primary hit";
    case Term::kRays: return "debug view: rays cast per pixel";
    case Term::kIndirect: return "indirect only: kd" + dot + "E, the light from other surfaces that ka" + dot + ia + " stands in for";
  }
  return "";
}

void keys_help() {
  static constexpr std::array<std::array<const char*, 2>, 27> kRows = {{
      {"left-drag", "orbit: the scene follows the hand"},
      {"right-drag, wheel", "dolly"},
      {"middle-drag, Shift+left-drag", "pan"},
      {"click", "select the clicked object and its material"},
      {"drag the selected object's handle", "slide it on the floor (Alt: by its surface; V: up, down; X, Y, Z: one axis)"},
      {"Ctrl+click", "probe the pixel (its equation, its ray tree)"},
      {"drag a light marker or arrow", "move that light"},
      {"1", "the full image"},
      {"2 3 4 5 6", "ambient, diffuse, specular, reflection, refraction alone"},
      {"M", "the five terms and their sum side by side"},
      {"I, Shift+I", "what ambient stands in for: ka*Ia, indirect light, the two side by side, their difference"},
      {"Shift+1..9", "solo light L0..L8 (again: every light back)"},
      {"F", "frame the scene"},
      {"R", "reset the camera to the file's"},
      {"H", "hide or show the panels"},
      {"L", "hide or show the lights' markers"},
      {"Ctrl+Z", "undo"},
      {"Ctrl+Shift+Z, Ctrl+Y", "redo"},
      {"Ctrl+O", "open a scene or a mesh (the file browser)"},
      {"Ctrl+S, Ctrl+Shift+S", "save, save as"},
      {"Ctrl+Q", "quit (unsaved edits are asked about)"},
      {"drop a .json / .obj", "open it / add it as a mesh object"},
      {"Right, Page Down, Space", "lesson: the answer, then the next step"},
      {"Left, Page Up", "lesson: back"},
      {"F11", "lesson: presenter mode (Esc leaves it)"},
      {"F1, ?", "this help"},
      {"Esc", "close it"},
  }};
  ImGui::TextUnformatted("Keys and mouse");
  ImGui::Separator();
  if (ImGui::BeginTable("##keys", 2, ImGuiTableFlags_SizingFixedFit)) {
    for (const auto& row : kRows) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(row[0]);
      ImGui::TableSetColumnIndex(1);
      ImGui::TextDisabled("%s", row[1]);
    }
    ImGui::EndTable();
  }
}

}  // namespace phonglab::ui
