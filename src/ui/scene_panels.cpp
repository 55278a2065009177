// The panels that edit the scene: camera, materials, lights, shading settings.
#include "ui/panels.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "interaction/camera_control.h"
#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

// One row of the coefficient list: the widget takes the width left of the term text, which
// names the coefficient's place in the equation.
void widget_before_term(float term_width) {
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  ImGui::SetNextItemWidth(std::max(ImGui::GetContentRegionAvail().x - term_width - spacing, 1.0f));
}

void term_text(const char* text) {
  ImGui::SameLine();
  ImGui::TextUnformatted(text);
}

ImVec4 display_color(const Color& c) {
  const double m = max_channel(c);
  const Color n = m > 1 ? c / m : c;  // keep the hue of intensities above 1
  return ImVec4(static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z), 1.0f);
}

}  // namespace

bool camera_panel(Camera& camera, CameraActions& actions, std::string& notice) {
  bool edited = false;
  // Edit a copy and keep it only if the renderer can use it (no zero view vector, no up
  // along the view); say why when it is refused.
  Camera edit = camera;
  bool changed = false;
  std::string typed[4];  // what each field refused to take as typed text
  changed |= drag_vec3("position", edit.position, 0.02f, "%.3f", &typed[0]);
  locate("camera.position");
  changed |= drag_vec3("look at", edit.look_at, 0.02f, "%.3f", &typed[1]);
  changed |= drag_vec3("up", edit.up, 0.01f, "%.3f", &typed[2]);
  changed |= slider_double("fov y (deg)", edit.fov_y_deg, 5.0, 150.0, "%.1f", false, &typed[3]);
  locate("camera.fov");
  static constexpr std::array<const char*, 4> kFields = {"position", "look at", "up", "fov y"};
  for (std::size_t i = 0; i < kFields.size(); ++i) {
    if (!typed[i].empty()) notice = std::string(kFields[i]) + ": " + typed[i];
  }
  if (changed) {
    notice = camera_problem(edit);
    if (notice.empty()) {
      camera = edit;
      edited = true;
    }
  }
  if (!notice.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kWarningColor);
    ImGui::TextWrapped("Refused: %s. The camera keeps its last good value.", notice.c_str());
    ImGui::PopStyleColor();
  }
  if (ImGui::Button("Frame (F)")) actions.frame_scene = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset (R)")) actions.reset = true;
  ImGui::TextDisabled("Left-drag orbit, right-drag/wheel dolly, middle- or Shift+left-drag pan, click selects.");
  return edited;
}

bool materials_panel(std::vector<Material>& materials, int& selected, SpecularModel model) {
  if (materials.empty()) {
    ImGui::TextDisabled("The scene has no materials.");
    return false;
  }
  selected = std::clamp(selected, 0, static_cast<int>(materials.size()) - 1);
  bool edited = false;

  const auto rows = static_cast<float>(std::min<std::size_t>(materials.size(), 6));
  const float list_height = ImGui::GetTextLineHeightWithSpacing() * (rows + 0.4f);
  if (ImGui::BeginListBox("##materials", ImVec2(-FLT_MIN, list_height))) {
    for (int i = 0; i < static_cast<int>(materials.size()); ++i) {
      ImGui::PushID(i);
      const Material& m = materials[static_cast<std::size_t>(i)];
      ImGui::ColorButton("##swatch", display_color(m.kd + m.ks * 0.25 + m.kr * 0.5),
                         ImGuiColorEditFlags_NoTooltip | ImGuiColorEditFlags_NoDragDrop,
                         ImVec2(ImGui::GetTextLineHeight(), ImGui::GetTextLineHeight()));
      ImGui::SameLine();
      if (ImGui::Selectable(m.name.empty() ? "(unnamed)" : m.name.c_str(), selected == i)) selected = i;
      ImGui::PopID();
    }
    ImGui::EndListBox();
  }

  // The lecture's equation, each coefficient then repeated beside its slider.
  const bool greek = font_has(0x03A3);
  const char* sum = greek ? "\xCE\xA3" : "sum";  // capital sigma
  const char* spec = model == SpecularModel::kBlinn ? "max(0,N\xC2\xB7H)^n" : "max(0,R\xC2\xB7V)^n";
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("I = ka\xC2\xB7%s + %s vis\xC2\xB7%s\xC2\xB7(kd\xC2\xB7max(0,N\xC2\xB7L) + ks\xC2\xB7%s)"
                      " + kr\xC2\xB7trace(R) + kt\xC2\xB7trace(T)",
                      i_a().c_str(), sum, i_l().c_str(), spec);
  ImGui::PopTextWrapPos();

  Material& m = materials[static_cast<std::size_t>(selected)];
  ImGui::PushID(selected);  // widget state must not carry over from one material to another
  const float term_width = ImGui::GetFontSize() * 9.0f;
  widget_before_term(term_width);
  edited |= color_strength_edit("##ka", m.ka, 1.0f);
  locate("material.ka");
  term_text(("ka\xC2\xB7" + i_a()).c_str());
  widget_before_term(term_width);
  edited |= color_strength_edit("##kd", m.kd, 1.0f);
  locate("material.kd");
  term_text("kd\xC2\xB7max(0,N\xC2\xB7L)");
  widget_before_term(term_width);
  edited |= color_strength_edit("##ks", m.ks, 1.0f);
  locate("material.ks");
  term_text(model == SpecularModel::kBlinn ? "ks\xC2\xB7(N\xC2\xB7H)^n" : "ks\xC2\xB7(R\xC2\xB7V)^n");
  widget_before_term(term_width);
  if (slider_double("##n", m.n, 0.0, 2000.0, "%.1f", true)) {
    m.n = std::max(m.n, 0.0);
    edited = true;
  }
  locate("material.n");
  term_text("n: shininess");
  widget_before_term(term_width);
  edited |= color_strength_edit("##kr", m.kr, 1.0f);
  term_text("kr\xC2\xB7trace(R)");
  widget_before_term(term_width);
  edited |= color_strength_edit("##kt", m.kt, 1.0f);
  term_text("kt\xC2\xB7trace(T)");
  widget_before_term(term_width);
  if (slider_double("##ior", m.ior, 1.0, 3.0, "%.3f")) {
    m.ior = std::max(m.ior, 0.01);  // must stay > 0 (docs/scene-format.md)
    edited = true;
  }
  term_text(greek ? "ior: \xCE\xB7 = 1/ior" : "ior: eta = 1/ior");
  edited |= ImGui::Checkbox("Fresnel", &m.fresnel);
  ImGui::SameLine();
  ImGui::TextDisabled(m.fresnel ? "kr' = kr + kt\xC2\xB7" "F, kt' = kt\xC2\xB7(1-F)" : "kr' = kr, kt' = kt");
  ImGui::PopID();
  return edited;
}

bool lights_panel(std::vector<Light>& lights, int& selected, LightSolo& solo) {
  bool edited = false;
  // Lights added or removed elsewhere (undo, reload) make the saved flags meaningless.
  if (solo.soloed >= static_cast<int>(lights.size()) || (solo.soloed >= 0 && solo.saved.size() != lights.size())) {
    solo = LightSolo{};
  }
  for (int i = 0; i < static_cast<int>(lights.size()); ++i) {
    ImGui::PushID(i);
    Light& light = lights[static_cast<std::size_t>(i)];
    edited |= ImGui::Checkbox("##enabled", &light.enabled);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("on (unticked: muted)");
    ImGui::SameLine();
    const bool soloed = solo.soloed == i;
    if (soloed) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    if (ImGui::SmallButton("S")) {
      toggle_solo(lights, solo, i);
      edited = true;
    }
    if (soloed) ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip(soloed ? "end solo: restore the other lights" : "solo: this light alone");
    ImGui::SameLine();
    char label[96];
    if (light.type == LightType::kPoint) {
      std::snprintf(label, sizeof label, "L%d point at (%.2f, %.2f, %.2f)", i, light.position.x,
                    light.position.y, light.position.z);
    } else {
      std::snprintf(label, sizeof label, "L%d directional (%.2f, %.2f, %.2f)", i, light.direction.x,
                    light.direction.y, light.direction.z);
    }
    if (ImGui::Selectable(label, selected == i)) selected = i;
    ImGui::PopID();
  }
  // A new light is appended, selected, and ends any solo.
  const auto add = [&](const Light& light) {
    lights.push_back(light);
    selected = static_cast<int>(lights.size()) - 1;
    solo = LightSolo{};
    edited = true;
  };
  const bool add_point = ImGui::Button("Add point");
  locate("lights.add_point");
  if (add_point) add(Light{.position = Vec3(2, 5, 3), .intensity = Color(0.5)});
  ImGui::SameLine();
  if (ImGui::Button("Add directional")) {
    add(Light{.type = LightType::kDirectional, .direction = glm::normalize(Vec3(-1, -1, -0.5)), .intensity = Color(0.2)});
  }
  ImGui::SameLine();
  const bool have_selection = selected >= 0 && selected < static_cast<int>(lights.size());
  ImGui::BeginDisabled(!have_selection);
  if (ImGui::Button("Remove") && have_selection) {
    lights.erase(lights.begin() + selected);
    selected = std::min(selected, static_cast<int>(lights.size()) - 1);
    solo = LightSolo{};
    edited = true;
  }
  ImGui::EndDisabled();
  if (selected < 0 || selected >= static_cast<int>(lights.size())) {
    ImGui::TextDisabled(lights.empty() ? "No lights: only the ambient term remains." : "Select a light to edit it.");
    return edited;
  }

  Light& light = lights[static_cast<std::size_t>(selected)];
  ImGui::PushID(selected);
  ImGui::Separator();
  int type = light.type == LightType::kPoint ? 0 : 1;
  if (ImGui::Combo("type", &type, "point\0directional\0")) {
    light.type = type == 0 ? LightType::kPoint : LightType::kDirectional;
    edited = true;
  }
  edited |= color_strength_edit("intensity", light.intensity, 2.0f);
  if (light.type == LightType::kPoint) {
    edited |= drag_vec3("position", light.position, 0.02f);
    ImGui::TextDisabled("Or drag its marker in the viewport.");
  } else {
    Vec3 direction = light.direction;
    // A zero direction is invalid (docs/scene-format.md): refuse it rather than hand it to the renderer.
    if (drag_vec3("direction", direction, 0.01f) && glm::length(direction) > 1e-9 && all_finite(direction)) {
      light.direction = direction;
      edited = true;
    }
  }
  edited |= ImGui::Checkbox("enabled", &light.enabled);
  ImGui::PopID();
  return edited;
}

bool shading_settings_panel(Scene& scene) {
  bool edited = false;
  edited |= color_edit(("ambient " + i_a()).c_str(), scene.ambient);
  edited |= color_edit("background", scene.background);
  edited |= ImGui::SliderInt("max depth", &scene.max_depth, 0, 16, "%d", ImGuiSliderFlags_AlwaysClamp);
  help_marker("Recursion depth for reflection and refraction rays. 0 = local shading only.");
  if (slider_double("min weight", scene.min_weight, 0.0, 1.0, "%.4g", true)) {
    scene.min_weight = std::clamp(scene.min_weight, 0.0, 1.0);
    edited = true;
  }
  help_marker("Child rays whose path weight falls below this are not traced.");
  int model = scene.specular_model == SpecularModel::kPhong ? 0 : 1;
  bool model_changed = ImGui::RadioButton("Phong", &model, 0);
  locate("render.phong");
  ImGui::SameLine();
  model_changed |= ImGui::RadioButton("Blinn-Phong", &model, 1);
  locate("render.blinn");
  if (model_changed) {
    scene.specular_model = model == 0 ? SpecularModel::kPhong : SpecularModel::kBlinn;
    edited = true;
  }
  // N.H is closer to 1 than R.V (the half-angle is half the angle): the same highlight needs an
  // exponent about four times larger. Offered, never done behind the user's back.
  const bool blinn = scene.specular_model == SpecularModel::kBlinn;
  ImGui::TextDisabled(blinn ? "Blinn-Phong: n about 4\xC3\x97 Phong's gives the same highlight."
                            : "Phong: n about \xC2\xBC of Blinn-Phong's gives the same highlight.");
  const bool convert = ImGui::SmallButton(blinn ? "every material's n \xC3\x97 4" : "every material's n \xC3\xB7 4");
  locate("render.convert_n");
  if (convert) {
    for (Material& m : scene.materials) m.n = blinn ? m.n * 4 : m.n / 4;
    edited = true;
  }
  return edited;
}

}  // namespace phonglab::ui
