#include "ui/panels.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "io/embedded_scenes.h"
#include "interaction/camera_control.h"
#include "ui/overlay.h"
#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

// ImVec4 is not a literal type: these are plain constants.
const ImVec4 kErrorColor{1.0f, 0.45f, 0.4f, 1.0f};
const ImVec4 kWarningColor{1.0f, 0.8f, 0.3f, 1.0f};


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

// "12.3k", "4.56M": ray counts that fit a narrow overlay.
void format_count(char* out, std::size_t size, std::uint64_t n) {
  const auto v = static_cast<double>(n);
  if (n >= 1000000) std::snprintf(out, size, "%.2fM", v / 1e6);
  else if (n >= 1000) std::snprintf(out, size, "%.1fk", v / 1e3);
  else std::snprintf(out, size, "%" PRIu64, n);
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
  const bool add_point = ImGui::Button("Add point");
  locate("lights.add_point");
  if (add_point) {
    Light light;
    light.position = Vec3(2, 5, 3);
    light.intensity = Color(0.5);
    lights.push_back(light);
    selected = static_cast<int>(lights.size()) - 1;
    solo = LightSolo{};
    edited = true;
  }
  ImGui::SameLine();
  if (ImGui::Button("Add directional")) {
    Light light;
    light.type = LightType::kDirectional;
    light.direction = glm::normalize(Vec3(-1, -1, -0.5));
    light.intensity = Color(0.2);
    lights.push_back(light);
    selected = static_cast<int>(lights.size()) - 1;
    solo = LightSolo{};
    edited = true;
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

void show_panel(Term& term, bool& small_multiples, bool blinn) {
  // The lecture's terms as buttons, in the order of the equation: one click, and the caption on
  // the image says what is shown.
  static constexpr std::array<Term, 6> kTerms = {Term::kFull, Term::kAmbient, Term::kDiffuse, Term::kSpecular,
                                                 Term::kReflection, Term::kRefraction};
  static constexpr std::array<const char*, 6> kLabels = {"1 image", "2 ambient", "3 diffuse", "4 specular",
                                                         "5 reflection", "6 refraction"};
  for (std::size_t i = 0; i < kTerms.size(); ++i) {
    if (i % 3 != 0) ImGui::SameLine();
    const bool on = term == kTerms[i] && !small_multiples;
    if (on) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
    if (ImGui::Button(kLabels[i], ImVec2(ImGui::GetContentRegionAvail().x / static_cast<float>(3 - i % 3) -
                                             (i % 3 == 2 ? 0 : ImGui::GetStyle().ItemSpacing.x * 0.67f),
                                         0))) {
      term = kTerms[i];
      small_multiples = false;
    }
    if (on) ImGui::PopStyleColor();
    locate(std::string("show.") + std::string(term_name(kTerms[i])));
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", term_caption(kTerms[i], blinn).c_str());
  }
  ImGui::Checkbox("all five and their sum side by side (M)", &small_multiples);
  int debug = term == Term::kNormal ? 1 : term == Term::kDepth ? 2 : term == Term::kRays ? 3 : 0;
  if (ImGui::Combo("debug view", &debug, "none\0normal\0depth\0rays per pixel\0")) {
    term = debug == 1 ? Term::kNormal : debug == 2 ? Term::kDepth : debug == 3 ? Term::kRays : Term::kFull;
  }
}

bool render_settings_panel(RenderSettings& settings, int hardware_threads) {
  bool edited = false;
  edited |= ImGui::SliderInt("target spp", &settings.target_spp, 1, 4096, "%d",
                             ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  edited |= ImGui::SliderFloat("resolution", &settings.resolution_scale, 0.125f, 1.0f, "%.3f x",
                               ImGuiSliderFlags_AlwaysClamp);
  char threads_format[32];
  if (settings.threads == 0) std::snprintf(threads_format, sizeof threads_format, "all (%d)", hardware_threads);
  else std::snprintf(threads_format, sizeof threads_format, "%%d");
  edited |= ImGui::SliderInt("threads", &settings.threads, 0, std::max(2 * hardware_threads, 4), threads_format,
                             ImGuiSliderFlags_AlwaysClamp);
  return edited;
}

bool display_panel(DisplaySettings& display) {
  bool edited = false;
  edited |= ImGui::SliderFloat("exposure", &display.exposure_ev, -8.0f, 8.0f, "%+.1f EV");
  ImGui::SameLine();
  if (ImGui::SmallButton("0")) {
    display.exposure_ev = 0;
    edited = true;
  }
  edited |= ImGui::Checkbox("sRGB display", &display.srgb);
  help_marker("Off shows the linear values unencoded (too dark): the reason images are sRGB-encoded.");
  edited |= ImGui::Checkbox("stats line", &display.show_stats);
  ImGui::SameLine();
  edited |= ImGui::Checkbox("details", &display.stats_details);
  // Applied on release: the panels would otherwise resize under the mouse while it drags. The
  // value being dragged is kept between frames, so the release applies what the slider showed.
  float size = display.ui_size_dragged > 0 ? display.ui_size_dragged : display.ui_size;
  ImGui::SliderFloat("UI size", &size, 0.75f, 2.5f, "%.2f x", ImGuiSliderFlags_AlwaysClamp);
  locate("display.ui_size");
  if (ImGui::IsItemActive()) display.ui_size_dragged = size;
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    display.ui_size = size;
    edited = true;
  }
  if (!ImGui::IsItemActive()) display.ui_size_dragged = -1;
  return edited;
}

bool instruments_panel(InstrumentSettings& settings, InstrumentActions& actions, bool have_a,
                       std::size_t undo_count, std::size_t redo_count, std::string& figure_path,
                       const std::string& figure_status) {
  bool edited = false;
  edited |= ImGui::Checkbox("probe mode", &settings.probe_mode);
  help_marker("On: a click in the view probes that pixel. Off: Ctrl+click probes, a click selects a material.");
  // Every row is always drawn (disabled when it does not apply), so nothing moves under the
  // pointer when A is taken or a mode is switched on.
  if (ImGui::Button("Snapshot A")) actions.snapshot_a = true;
  locate("instruments.snapshot_a");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("Keeps the finished image as A (taken when the image is done).");
  ImGui::SameLine();
  ImGui::BeginDisabled(!have_a);
  edited |= ImGui::RadioButton("live", &settings.compare, 0);
  ImGui::SameLine();
  edited |= ImGui::RadioButton("wipe", &settings.compare, 1);
  ImGui::SameLine();
  edited |= ImGui::RadioButton("|live - A|", &settings.compare, 2);
  ImGui::EndDisabled();
  ImGui::BeginDisabled(!have_a || settings.compare == 0);
  if (settings.compare == 2) {
    edited |= ImGui::SliderFloat("gain", &settings.difference_gain, 1.0f, 64.0f, "\xC3\x97%.0f", ImGuiSliderFlags_Logarithmic);
  } else {
    edited |= ImGui::SliderFloat("wipe", &settings.wipe, 0.0f, 1.0f, "A | live at %.2f");
  }
  locate("instruments.wipe");
  ImGui::EndDisabled();
  char label[48];
  std::snprintf(label, sizeof label, "Undo (%zu)", undo_count);
  ImGui::BeginDisabled(undo_count == 0);
  if (ImGui::Button(label)) actions.undo = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  std::snprintf(label, sizeof label, "Redo (%zu)", redo_count);
  ImGui::BeginDisabled(redo_count == 0);
  if (ImGui::Button(label)) actions.redo = true;
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::TextDisabled("Ctrl+Z, Ctrl+Shift+Z");
  ImGui::Separator();
  edited |= ImGui::Checkbox("move your head", &settings.move_head);
  help_marker("Shades with the eye turned about the probed point (or the look-at point): only V changes, "
              "the view stays. Diffuse and ambient stay the same; specular (and reflection) change.");
  ImGui::BeginDisabled(!settings.move_head);
  edited |= ImGui::SliderFloat("head angle", &settings.head_angle_deg, -90.0f, 90.0f, "%.0f deg");
  if (ImGui::Button("Eye A = this eye, then show |live - A|")) actions.head_reference = true;
  help_marker("Keeps the finished image as A; move the head: the difference has no diffuse term left.");
  ImGui::EndDisabled();
  ImGui::Separator();
  if (ImGui::Button("Figure for slides")) actions.save_figure = true;
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-FLT_MIN);
  input_text("##figure", figure_path);
  if (!figure_status.empty()) ImGui::TextWrapped("%s", figure_status.c_str());
  return edited;
}

void scene_file_panel(SceneFileState& state, SceneFileActions& actions) {
  ImGui::TextWrapped("%s%s", state.source.c_str(), state.dirty ? "  (modified)" : "");
  input_text("path", state.path_field);
  if (ImGui::Button("Open")) actions.open = true;
  ImGui::SameLine();
  // Save writes the document's own JSON file: not an embedded scene's, not over an OBJ.
  const bool can_save = !state.file_path.empty() && !state.opened_mesh;
  ImGui::BeginDisabled(!can_save);
  if (ImGui::Button("Save")) actions.save = true;
  ImGui::EndDisabled();
  if (!can_save && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip(state.opened_mesh ? "Opened from an OBJ file: Save as writes a scene .json that uses it."
                                        : "An embedded scene has no file: Save as writes one.");
  }
  ImGui::SameLine();
  if (ImGui::Button("Save as")) actions.save_as = true;
  ImGui::SameLine();
  ImGui::BeginDisabled(state.file_path.empty());
  if (ImGui::Button("Reload")) actions.reload = true;
  ImGui::EndDisabled();
  if (ImGui::BeginCombo("embedded", "open an embedded scene")) {
    for (const EmbeddedScene& scene : embedded_scenes()) {
      ImGui::PushID(scene.name.data(), scene.name.data() + scene.name.size());
      const std::string name(scene.name);
      if (ImGui::Selectable(name.c_str())) actions.open_embedded = name;
      if (ImGui::IsItemHovered()) {
        const std::string description(scene.description);
        ImGui::SetTooltip("%s", description.c_str());
      }
      ImGui::PopID();
    }
    ImGui::EndCombo();
  }
  ImGui::BeginDisabled(state.file_path.empty());
  ImGui::Checkbox("reload when the file changes", &state.auto_reload);
  ImGui::EndDisabled();
  if (state.changed_on_disk) {
    ImGui::PushStyleColor(ImGuiCol_Text, kWarningColor);
    ImGui::TextWrapped("The file changed on disk. Reload to see it (your edits will be lost).");
    ImGui::PopStyleColor();
  }
  if (!state.error_text.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", state.error_text.c_str());
    ImGui::PopStyleColor();
    ImGui::TextDisabled("The previous scene stays open.");
  }
  if (!state.status.empty()) ImGui::TextDisabled("%s", state.status.c_str());
}

void screenshot_panel(ScreenshotState& state, ScreenshotActions& actions) {
  input_text("##png", state.png_path);
  ImGui::SameLine();
  if (ImGui::Button("Save PNG")) actions.save_png = true;
  input_text("##pfm", state.pfm_path);
  ImGui::SameLine();
  if (ImGui::Button("Save PFM")) actions.save_pfm = true;
  ImGui::TextDisabled("PNG: what is shown. PFM: the linear image.");
  if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
}

void stats_overlay(const StatsView& stats) {
  // One line by default: what the image is and whether it is done.
  const char* state = stats.interacting ? "interacting" : (stats.idle ? "done" : "rendering");
  if (stats.have_frame) {
    char level[16] = "";
    if (stats.level_divisor > 1) std::snprintf(level, sizeof level, " (1/%d)", stats.level_divisor);
    ImGui::Text("%d\xC3\x97%d%s  %u/%d spp  %.1f ms/pass  %s", stats.image_width, stats.image_height, level, stats.spp,
                stats.target_spp, stats.frame.pass_ms, state);
  } else {
    ImGui::TextDisabled("waiting for the first image");
  }
  if (!stats.scene_error.empty()) ImGui::TextColored(kErrorColor, "scene file error: see the Scene panel");
  if (stats.frame.nan_count > 0) ImGui::TextColored(kErrorColor, "%" PRIu64 " NaN/Inf samples", stats.frame.nan_count);
  if (!stats.details) return;
  ImGui::Separator();
  if (ImGui::BeginTable("##figures", 2, ImGuiTableFlags_SizingFixedFit)) {
    const auto row = [](const char* label) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextDisabled("%s", label);
      ImGui::TableSetColumnIndex(1);
    };
    row("UI frame");
    // Frames after an idle sleep are not counted: idle, there is nothing to show.
    if (stats.ui_frame_ms >= 0) ImGui::Text("%.1f ms (max %.1f)", stats.ui_frame_ms, stats.ui_frame_max_ms);
    else ImGui::TextUnformatted("- (idle)");
    row(font_has(0x2192) ? "edit \xE2\x86\x92 image" : "edit -> image");
    if (stats.edit_to_image_ms >= 0) ImGui::Text("%.1f ms", stats.edit_to_image_ms);
    else ImGui::TextUnformatted("-");
    if (stats.have_frame) {
      const FrameStats& f = stats.frame;
      row("pass");
      ImGui::Text("%.1f ms, %.2f Mrays/s", f.pass_ms, f.mrays_per_s);
      row("tracer");
      ImGui::TextUnformatted(f.packets ? "packets, 4 rays wide (AVX2)" : "scalar, ray by ray");
      char primary[16], shadow[16], reflection[16], refraction[16];
      format_count(primary, sizeof primary, f.pass_rays.primary);
      format_count(shadow, sizeof shadow, f.pass_rays.shadow);
      format_count(reflection, sizeof reflection, f.pass_rays.reflection);
      format_count(refraction, sizeof refraction, f.pass_rays.refraction);
      row("rays/pass");
      ImGui::Text("primary %s, shadow %s", primary, shadow);
      row("");
      ImGui::Text("reflection %s, refraction %s", reflection, refraction);
      row("NaN/Inf");
      if (f.nan_count > 0) ImGui::TextColored(kErrorColor, "%" PRIu64, f.nan_count);
      else ImGui::TextUnformatted("0");
    }
    ImGui::EndTable();
  }
}

namespace {

// The last row of a dialog: Cancel (or Esc), a scripted answer in place of the user's, and the
// dialog closed once answered. Call inside BeginPopupModal; ends the popup.
GuardChoice end_choice(GuardChoice choice, GuardChoice scripted) {
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) choice = GuardChoice::kCancel;
  if (scripted != GuardChoice::kNone) choice = scripted;
  if (choice != GuardChoice::kNone) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
  return choice;
}

}  // namespace

GuardChoice unsaved_changes_modal(bool open_now, const GuardView& view, std::string& save_as_path,
                                  GuardChoice scripted) {
  constexpr const char* kTitle = "Unsaved changes";
  if (open_now) ImGui::OpenPopup(kTitle);
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  GuardChoice choice = GuardChoice::kNone;
  if (ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("The scene has unsaved changes.");
    ImGui::Text("Save them before you %s?", view.action.c_str());
    if (view.changed_on_disk) {
      ImGui::PushStyleColor(ImGuiCol_Text, kWarningColor);
      ImGui::Text("The file also changed on disk since it was opened: Save would overwrite that change.");
      ImGui::PopStyleColor();
    }
    ImGui::Spacing();
    ImGui::BeginDisabled(!view.can_save);
    if (ImGui::Button("Save")) choice = GuardChoice::kSave;
    ImGui::EndDisabled();
    ImGui::SameLine();
    if (ImGui::Button("Save as")) choice = GuardChoice::kSaveAs;
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 16);
    input_text("##save_as", save_as_path);
    if (ImGui::Button("Discard")) choice = GuardChoice::kDiscard;
    ImGui::SameLine();
    choice = end_choice(choice, scripted);
  }
  return choice;
}

GuardChoice changed_on_disk_modal(bool open_now, const std::string& file, GuardChoice scripted) {
  constexpr const char* kTitle = "The file changed on disk";
  if (open_now) ImGui::OpenPopup(kTitle);
  const ImGuiViewport* viewport = ImGui::GetMainViewport();
  ImGui::SetNextWindowPos(viewport->GetCenter(), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  GuardChoice choice = GuardChoice::kNone;
  if (ImGui::BeginPopupModal(kTitle, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s changed on disk since it was opened or saved here.", file.c_str());
    ImGui::Text("Saving now would overwrite that change with your version.");
    ImGui::Spacing();
    if (ImGui::Button("Overwrite")) choice = GuardChoice::kOverwrite;
    ImGui::SameLine();
    if (ImGui::Button("Reload from disk (lose my edits)")) choice = GuardChoice::kReload;
    ImGui::SameLine();
    choice = end_choice(choice, scripted);
  }
  return choice;
}

}  // namespace phonglab::ui
