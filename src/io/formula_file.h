// A student's formulas saved in a file of their own, beside the scene and never in it
// (docs/formulas.md, "Saving your formulas"): a JSON object with a text per slot,
//   {"diffuse": "kd * dot(N, L)", "specular": "R = reflect(-L, N)\nks * pow(max(0, dot(R, V)), n)"}
// A slot left out is the equation's own term. A text is kept as typed, even one that does not
// compile (the panel shows its error again); only the file's shape is checked here.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "check/formula.h"
#include "io/diagnostic.h"

namespace phonglab {

using FormulaTexts = std::array<std::string, kFormulaSlots>;  // FormulaSlot order; "": none

struct FormulaFileLoad {
  std::optional<FormulaTexts> texts;
  std::vector<Diagnostic> errors;  // file:line:col: path: message
  bool ok() const { return texts.has_value(); }
  std::string error_text() const { return diagnostics_text(errors); }
};

// The file's text: the non-empty slots, in slot order, with a trailing newline.
std::string formula_file_text(const FormulaTexts& texts);
FormulaFileLoad load_formula_text(const std::string& text, const std::string& file_name);
FormulaFileLoad load_formula_file(const std::string& path);
// Written through a temporary file and a rename (a crash never leaves half a file); "" on
// success, else the error.
std::string save_formula_file(const std::string& path, const FormulaTexts& texts);

}  // namespace phonglab
