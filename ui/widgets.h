// Small ImGui widgets over the renderer's double-precision types. Each returns "edited".
#pragma once

#include <string>

#include <imgui.h>

#include "renderer/math.h"

namespace phonglab::ui {

// A text field editing a std::string in place (grows the string as the user types).
bool input_text(const char* label, std::string& text, ImGuiInputTextFlags flags = 0);

// A linear RGB colour: swatch and picker, values may exceed 1.
bool color_edit(const char* label, Color& color);

// A reflectance as colour and strength: a swatch for the hue and a slider for the largest
// channel, so "twice as shiny" is one drag. Setting a strength on black gives grey.
bool color_strength_edit(const char* label, Color& color, float max_strength);

// Three doubles dragged together.
bool drag_vec3(const char* label, Vec3& v, float speed, const char* format = "%.3f");

// A double on a slider; `logarithmic` spreads decades evenly (shininess, weights).
bool slider_double(const char* label, double& value, double min, double max, const char* format,
                   bool logarithmic = false);

// A one-line help marker: "(?)" that shows `text` when hovered.
void help_marker(const char* text);

}  // namespace phonglab::ui
