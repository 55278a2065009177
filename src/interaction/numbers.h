// Numbers as the panels show them: what a float widget or a slider's text meant, so an edited
// value is the one the user saw and a saved file carries no float noise. No ImGui.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include "core/scene/math.h"

namespace phonglab::ui {

// The double nearest to the shortest decimal that reads back as `value` in float: what a float
// slider or colour picker meant (0.366, not 0.3659999966621399).
double tidy_float(double value);
// tidy_float of each channel: a colour as a float panel shows it.
Color tidy_color(const Color& c);

// `v` (positive) to `digits` significant digits (at most 7), as the double nearest that decimal
// (0.6, not 0.60000000000000009); other values unchanged.
double significant(double v, int digits);

// The number a slider's text shows for `value` with its printf `format` ("%.3f", "x%.1f"): the
// first number in the formatted text, or `value` itself when the text holds none.
double shown_value(double value, const char* format);

// A probed number as the probe panel shows it: `digits` significant digits, and "≈ 0" for a
// value that is not zero but under 1e-12 in magnitude (9.039e-22 says nothing a student can use).
std::string probe_number(double value, int digits);
inline constexpr double kProbeZero = 1e-12;

// `text` wrapped to lines no wider than `width` by `measure`, breaking at spaces only (a number
// such as -0.1857 is never split at its point); a word wider than a line keeps a line of its own.
// The text's own line breaks stay; a wrapped line's continuation is indented by two spaces.
std::string wrap_at_spaces(std::string_view text, float width, const std::function<float(std::string_view)>& measure);

}  // namespace phonglab::ui
