// The Formula panel (docs/formulas.md): a text box per slot with the names it may use, its
// error under it as it is typed, which image the view shows, and the check's verdict.
#include <imgui.h>
#include <imgui_stdlib.h>

#include "ui/panels.h"
#include "ui/widgets.h"

namespace phonglab::ui {

std::string_view formula_view_name(FormulaView view) {
  switch (view) {
    case FormulaView::kYours: return "yours";
    case FormulaView::kReference: return "reference";
    case FormulaView::kDifference: return "difference";
  }
  return "yours";
}

std::optional<FormulaView> formula_view_from_name(std::string_view name) {
  for (const FormulaView v : {FormulaView::kYours, FormulaView::kReference, FormulaView::kDifference}) {
    if (formula_view_name(v) == name) return v;
  }
  return std::nullopt;
}

FormulaPanelEdits formula_panel(FormulaPanelState& state) {
  FormulaPanelEdits edits;
  ImGui::TextWrapped("Type your own term; it renders in place of the equation's at every hit. Names: %s",
                     state.names.c_str());
  static constexpr const char* kLabels[kFormulaSlots] = {"ambient (once per hit)", "diffuse (per light, N\xC2\xB7L > 0)",
                                                         "specular (per light, N\xC2\xB7L > 0)"};
  static constexpr const char* kIds[kFormulaSlots] = {"##formula_ambient", "##formula_diffuse", "##formula_specular"};
  static constexpr const char* kLocations[kFormulaSlots] = {"formula.ambient", "formula.diffuse", "formula.specular"};
  for (int s = 0; s < kFormulaSlots; ++s) {
    const auto i = static_cast<std::size_t>(s);
    ImGui::TextUnformatted(kLabels[s]);
    const float lines = state.texts[i].empty() ? 1.6f : 3.2f;
    if (ImGui::InputTextMultiline(kIds[s], &state.texts[i], ImVec2(-1.0f, ImGui::GetTextLineHeight() * lines))) {
      edits.slot = s;
      edits.held = ImGui::IsItemActive();
    }
    if (ImGui::IsItemDeactivatedAfterEdit()) {
      edits.slot = s;
      edits.held = false;
    }
    locate(kLocations[s]);
    if (!state.errors[i].empty()) ImGui::TextColored(kErrorColor, "%s", state.errors[i].c_str());
    if (state.texts[i].empty()) {
      ImGui::SameLine();
      if (ImGui::SmallButton((std::string("starter##") + kLocations[s]).c_str())) edits.starter = s;
    }
  }
  ImGui::TextUnformatted("view:");
  for (const FormulaView v : {FormulaView::kYours, FormulaView::kReference, FormulaView::kDifference}) {
    ImGui::SameLine();
    if (ImGui::RadioButton(std::string(formula_view_name(v)).c_str(), state.view == v)) {
      state.view = v;
      edits.view = true;
    }
  }
  if (state.view == FormulaView::kDifference) {
    ImGui::TextDisabled("orange: yours brighter, blue: darker, magenta: NaN; the reference dimmed");
  }
  if (state.hints_left >= 0) {
    ImGui::BeginDisabled(state.hints_left == 0);
    if (ImGui::Button(state.hints_left > 0 ? ("a hint (" + std::to_string(state.hints_left) + " left)").c_str()
                                           : "no hint left")) {
      edits.hint = true;
    }
    ImGui::EndDisabled();
    locate("formula.hint");
  }
  if (!state.verdict.empty()) {
    ImGui::TextColored(state.matches ? ImVec4(0.55f, 0.9f, 0.55f, 1.0f) : kErrorColor, "%s", state.verdict.c_str());
    locate("formula.verdict");
  }
  ImGui::TextUnformatted("Your formulas' file (not the scene's):");
  ImGui::InputText("##formulas_path", &state.formulas_path);
  locate("formula.file_path");
  ImGui::SameLine();
  if (ImGui::Button("save")) edits.save_formulas = true;
  locate("formula.file_save");
  ImGui::SameLine();
  if (ImGui::Button("open")) edits.open_formulas = true;
  locate("formula.file_open");
  if (!state.formulas_status.empty()) {
    ImGui::TextColored(state.formulas_failed ? kErrorColor : ImVec4(0.7f, 0.7f, 0.7f, 1.0f), "%s",
                       state.formulas_status.c_str());
    locate("formula.file_status");
  }
  ImGui::Separator();
  ImGui::TextUnformatted("Your own ray tracer's image of this view (PNG, PPM, PFM at the view's size):");
  ImGui::InputText("##image_path", &state.image_path);
  locate("formula.image_path");
  ImGui::SameLine();
  if (ImGui::Button("check it")) edits.open_image = true;
  locate("formula.image_check");
  if (!state.image_error.empty()) ImGui::TextColored(kErrorColor, "%s", state.image_error.c_str());
  if (!state.image_name.empty()) {
    ImGui::Text("%s: A of the compare; the views show yours, the reference, the difference", state.image_name.c_str());
    ImGui::SameLine();
    if (ImGui::SmallButton("close")) edits.close_image = true;
    ImGui::TextColored(state.image_matches ? ImVec4(0.55f, 0.9f, 0.55f, 1.0f) : kErrorColor, "%s",
                       state.image_verdict.c_str());
    locate("formula.image_verdict");
    if (!state.image_probe.empty()) ImGui::TextUnformatted(state.image_probe.c_str());
  }
  if (!state.probe.empty()) {
    ImGui::TextDisabled("the probed pixel (Ctrl+click), yours against the reference:");
    ImGui::TextUnformatted(state.probe.c_str());
    locate("formula.probe");
  }
  return edits;
}

}  // namespace phonglab::ui
