// Numbers as the panels show them: what a float widget or a slider's text meant, so an edited
// value is the one the user saw and a saved file carries no float noise. No ImGui.
#pragma once

namespace phonglab::ui {

// The double nearest to the shortest decimal that reads back as `value` in float: what a float
// slider or colour picker meant (0.366, not 0.3659999966621399).
double tidy_float(double value);

// The number a slider's text shows for `value` with its printf `format` ("%.3f", "x%.1f"): the
// first number in the formatted text, or `value` itself when the text holds none.
double shown_value(double value, const char* format);

}  // namespace phonglab::ui
