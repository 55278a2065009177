// Small ImGui widgets over the renderer's double-precision types. Each returns "edited".
#pragma once

#include <map>
#include <string>

#include <imgui.h>

#include "core/scene/math.h"
#include "interaction/numbers.h"

namespace phonglab::ui {

// Message colours (ImVec4 is not a literal type: these are plain constants).
inline const ImVec4 kErrorColor{1.0f, 0.45f, 0.4f, 1.0f};
inline const ImVec4 kWarningColor{1.0f, 0.8f, 0.3f, 1.0f};

// A screen rectangle, min inclusive, max exclusive.
struct ScreenRect {
  ImVec2 min;
  ImVec2 max;
};

// Where named widgets were drawn in the last frame, so test scripts can drive them by name with
// real (injected) mouse input. The app owns it and points ImGui's io.UserData at it; without
// one, locate() does nothing.
struct ItemLocations {
  std::map<std::string, ScreenRect> rects;
  std::string scroll_to;  // a widget to scroll into view when it is next drawn (then cleared)
};
// Records the last item's rectangle under `name`.
void locate(const std::string& name);


// A text field editing a std::string in place (grows the string as the user types).
bool input_text(const char* label, std::string& text, ImGuiInputTextFlags flags = 0);

// A linear RGB colour: swatch and picker, values may exceed 1.
bool color_edit(const char* label, Color& color);

// A reflectance as colour and strength: a swatch for the hue and a slider for the largest
// channel, so "twice as shiny" is one drag. Setting a strength on black gives grey.
bool color_strength_edit(const char* label, Color& color, float max_strength);

// Three doubles dragged together. With `refused`, text typed into them (Ctrl+click) that is not a
// number is reported there instead of being dropped without a word.
bool drag_vec3(const char* label, Vec3& v, float speed, const char* format = "%.3f", std::string* refused = nullptr);

// A double on a slider; `logarithmic` spreads decades evenly (shininess, weights). The value kept
// is the one the slider's text shows. With `refused`, text typed into it (Ctrl+click) that is not
// a number is reported there instead of being ignored without a word.
bool slider_double(const char* label, double& value, double min, double max, const char* format,
                   bool logarithmic = false, std::string* refused = nullptr);

// Whether the current font can draw `c` (the built-in fallback font lacks Greek and maths symbols).
bool font_has(ImWchar c);
// I with a subscript a, and with a subscript l ("Ia" in a sans-serif font reads as "la"); "I_a" and
// "I_l" when the font has no subscripts.
std::string i_a();
std::string i_l();
// `text` with its "Iₐ" and "Iₗ" as i_a() and i_l() give them.
std::string with_font_subscripts(std::string text);

// A one-line help marker: "(?)" that shows `text` when hovered.
void help_marker(const char* text);

}  // namespace phonglab::ui
