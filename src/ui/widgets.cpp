#include "ui/widgets.h"

#include "interaction/numbers.h"

#include <imgui_internal.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

namespace phonglab::ui {

void locate(const std::string& name) {
  auto* locations = static_cast<ItemLocations*>(ImGui::GetIO().UserData);
  if (locations == nullptr) return;
  locations->rects[name] = ScreenRect{ImGui::GetItemRectMin(), ImGui::GetItemRectMax()};
  if (locations->scroll_to == name) {
    // Only a widget not wholly in view is scrolled to: one in view stays where the user sees it.
    const float top = ImGui::GetWindowPos().y;
    const float bottom = top + ImGui::GetWindowSize().y;
    if (ImGui::GetItemRectMin().y < top || ImGui::GetItemRectMax().y > bottom) ImGui::SetScrollHereY(0.5f);
    locations->scroll_to.clear();
  }
}


namespace {

// Ctrl+click turns a slider or drag field into a text field, and ImGui's filter then drops every
// character that cannot be part of a number without a word. The widget `key` was such a field
// last frame (remember_typing): name the dropped characters in `refused` before the widget
// consumes this frame's typing.
void name_dropped_letters(ImGuiID key, std::string* refused) {
  if (refused == nullptr || !ImGui::GetStateStorage()->GetBool(key + 1)) return;
  std::string dropped;
  for (const ImWchar c : ImGui::GetIO().InputQueueCharacters) {
    if (c < 0x80 && std::strchr("0123456789.eE+-*/ ", static_cast<int>(c)) == nullptr) dropped += static_cast<char>(c);
  }
  if (!dropped.empty()) *refused = "'" + dropped + "' is not a number (only digits, '.', 'e' and signs)";
}

// After the widget: whether it (or, for a row of fields, one of them) is a text field now. Kept in
// ImGui's per-window storage under key + 1.
void remember_typing(ImGuiID key) {
  const ImGuiContext& g = *ImGui::GetCurrentContext();
  const bool typing = ImGui::IsItemActive() && g.TempInputId != 0 && g.TempInputId == g.ActiveId;
  ImGui::GetStateStorage()->SetBool(key + 1, typing);
}


}  // namespace

bool input_text(const char* label, std::string& text, ImGuiInputTextFlags flags) {
  // ImGui edits a fixed char buffer; give it generous room beyond the current text and copy
  // back only on an edit (paths longer than this grow by this much per frame of typing).
  constexpr std::size_t kSlack = 1024;
  std::vector<char> buffer(text.size() + kSlack, '\0');
  std::memcpy(buffer.data(), text.data(), text.size());
  const bool edited = ImGui::InputText(label, buffer.data(), buffer.size(), flags);
  if (edited) text.assign(buffer.data());
  return edited;
}

bool color_edit(const char* label, Color& color) {
  float rgb[3] = {static_cast<float>(color.x), static_cast<float>(color.y), static_cast<float>(color.z)};
  // Written back only when edited: a float round trip must not change untouched values.
  if (!ImGui::ColorEdit3(label, rgb, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)) return false;
  color = Color(tidy_float(std::max(rgb[0], 0.0f)), tidy_float(std::max(rgb[1], 0.0f)), tidy_float(std::max(rgb[2], 0.0f)));
  return true;
}

bool color_strength_edit(const char* label, Color& color, float max_strength) {
  constexpr const char* kStrengthFormat = "%.3f";
  ImGui::PushID(label);
  // Swatch and slider share the width the caller set for one item.
  const float width = ImGui::CalcItemWidth();
  const double strength = max_channel(color);
  const Color hue = strength > 0 ? color / strength : Color(1);
  bool edited = false;

  float hue_rgb[3] = {static_cast<float>(hue.x), static_cast<float>(hue.y), static_cast<float>(hue.z)};
  if (ImGui::ColorEdit3("##hue", hue_rgb, ImGuiColorEditFlags_NoInputs | ImGuiColorEditFlags_NoLabel |
                                               ImGuiColorEditFlags_Float)) {
    color = tidy_color(Color(hue_rgb[0], hue_rgb[1], hue_rgb[2]) * strength);
    edited = true;
  }
  if (ImGui::IsItemHovered()) {
    const char* name = label[0] == '#' && label[1] == '#' ? label + 2 : label;  // hidden labels
    ImGui::SetTooltip("%s = (%.3f, %.3f, %.3f)", name, color.x, color.y, color.z);
  }
  ImGui::SameLine(0, ImGui::GetStyle().ItemInnerSpacing.x);
  ImGui::SetNextItemWidth(std::max(width - ImGui::GetFrameHeight() - ImGui::GetStyle().ItemInnerSpacing.x, 1.0f));
  float new_strength = static_cast<float>(strength);
  if (ImGui::SliderFloat(label, &new_strength, 0.0f, max_strength, kStrengthFormat)) {
    // The largest channel becomes exactly what the slider shows; the others keep their ratio to it.
    const double target = shown_value(std::max(static_cast<double>(new_strength), 0.0), kStrengthFormat);
    color = strength > 0 ? tidy_color(color * (target / strength)) : Color(target);
    for (int c = 0; c < 3; ++c) {
      if (strength > 0 && color[c] != 0 && hue[c] == 1) color[c] = target;
    }
    edited = true;
  }
  ImGui::PopID();
  return edited;
}

bool drag_vec3(const char* label, Vec3& v, float speed, const char* format, std::string* refused) {
  const ImGuiID key = ImGui::GetID(label);
  name_dropped_letters(key, refused);
  const bool changed = ImGui::DragScalarN(label, ImGuiDataType_Double, &v.x, 3, speed, nullptr, nullptr, format);
  remember_typing(key);
  return changed;
}

bool slider_double(const char* label, double& value, double min, double max, const char* format,
                   bool logarithmic, std::string* refused) {
  const ImGuiSliderFlags flags = logarithmic ? ImGuiSliderFlags_Logarithmic : ImGuiSliderFlags_None;
  const ImGuiID key = ImGui::GetID(label);
  name_dropped_letters(key, refused);
  const bool changed = ImGui::SliderScalar(label, ImGuiDataType_Double, &value, &min, &max, format, flags);
  remember_typing(key);
  if (!changed) return false;
  value = shown_value(value, format);
  return true;
}

bool font_has(ImWchar c) { return ImGui::GetFont()->FindGlyphNoFallback(c) != nullptr; }

std::string i_a() { return font_has(0x2090) ? "I\xE2\x82\x90" : "I_a"; }

std::string i_l() { return font_has(0x2097) ? "I\xE2\x82\x97" : "I_l"; }

std::string with_font_subscripts(std::string text) {
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"I\xE2\x82\x90", i_a()}, {"I\xE2\x82\x97", i_l()}}) {
    if (from == to) continue;
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
      text.replace(at, from.size(), to);
    }
  }
  return text;
}

void help_marker(const char* text) {
  // Whole or on the next line, never broken as "(?" and ")".
  const float width = ImGui::CalcTextSize("(?)").x;
  ImGui::SameLine();
  if (ImGui::GetContentRegionAvail().x < width) ImGui::NewLine();
  ImGui::PushTextWrapPos(-1.0f);
  ImGui::TextDisabled("(?)");
  ImGui::PopTextWrapPos();
  if (ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

}  // namespace phonglab::ui
