// The panels that choose what is shown and how: terms, render settings, display, instruments, and the stats overlay.
#include "ui/panels.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

// "12.3k", "4.56M": ray counts that fit a narrow overlay.
void format_count(char* out, std::size_t size, std::uint64_t n) {
  const auto v = static_cast<double>(n);
  if (n >= 1000000) std::snprintf(out, size, "%.2fM", v / 1e6);
  else if (n >= 1000) std::snprintf(out, size, "%.1fk", v / 1e3);
  else std::snprintf(out, size, "%" PRIu64, n);
}

}  // namespace

namespace {
constexpr std::array<std::string_view, 4> kAmbientViewNames = {"constant", "indirect", "beside", "difference"};
}  // namespace

std::string_view ambient_view_name(AmbientView view) { return kAmbientViewNames[static_cast<std::size_t>(view)]; }

std::optional<AmbientView> ambient_view_from_name(std::string_view name) {
  for (std::size_t i = 0; i < kAmbientViewNames.size(); ++i) {
    if (kAmbientViewNames[i] == name) return static_cast<AmbientView>(i);
  }
  return std::nullopt;
}

std::string ambient_view_caption(AmbientView view) {
  const std::string dot = font_has(0x00B7) ? "\xC2\xB7" : "*";
  switch (view) {
    case AmbientView::kConstant: return "";
    case AmbientView::kIndirect: return "with indirect light: ka" + dot + i_a() + " replaced by kd" + dot + "E at every hit";
    case AmbientView::kBeside: return "left: ka" + dot + i_a() + "   |   right: the indirect light kd" + dot + "E it stands in for";
    case AmbientView::kDifference: return "indirect - ka" + dot + i_a() + ": where the constant is most wrong, and which way";
  }
  return "";
}

void show_panel(Term& term, bool& small_multiples, AmbientView& ambient_view, bool blinn) {
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
  int ambient = static_cast<int>(ambient_view);
  const std::string items = std::string("ka") + (font_has(0x00B7) ? "\xC2\xB7" : "*") + "Ia, the lecture" + '\0' +
                            "indirect light" + '\0' + "indirect | ambient" + '\0' + "indirect - ambient (signed)" + '\0';
  if (ImGui::Combo("ambient (I)", &ambient, items.c_str())) {
    ambient_view = static_cast<AmbientView>(ambient);
    if (ambient_view == AmbientView::kBeside || ambient_view == AmbientView::kDifference) small_multiples = false;
  }
  locate("show.ambient");
  help_marker("What the ambient term stands in for: the light that arrives from other surfaces. 'indirect light' "
              "puts it in ka*Ia's place at every hit (a path tracer's estimate: noise that settles); 'indirect | "
              "ambient' shows ka*Ia left of the middle and the indirect term right of it; the last, their "
              "difference as a heat map: where the constant is most wrong.");
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
  edited |= ImGui::SliderInt("live images/s", &settings.live_images_per_s, 0, 120,
                             settings.live_images_per_s == 0 ? "off (1/8 first)" : "%d", ImGuiSliderFlags_AlwaysClamp);
  help_marker("While a drag or slider is held, each new image starts at the finest resolution whose last pass "
              "fits this rate, instead of at 1/8. A faster machine shows more.");
  edited |= ImGui::SliderInt("ray trees", &settings.tree_budget_mib, 0, 4096,
                             settings.tree_budget_mib == 0 ? "none" : "%d MiB", ImGuiSliderFlags_AlwaysClamp);
  help_marker("The first sample's ray trees are kept in this much memory: an edit that moves no ray (ka, kd, ks, n, "
              "light intensity or mute, Phong/Blinn) is then re-shaded at full resolution at once, and a moved "
              "light casts only its shadow rays again. Over the budget nothing is kept and edits are traced.");
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
  edited |= ImGui::Checkbox("light markers", &display.light_markers);
  help_marker("Off hides the lights' markers and labels: ask the hall where the light is.");
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
    // Its own label: a widget that shared the radio button's ID ("wipe") took the button's
    // mouse state for its own and aborted ImGui's button logic.
    edited |= ImGui::SliderFloat("split", &settings.wipe, 0.0f, 1.0f, "A | live at %.2f");
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
  locate("instruments.head_angle");
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

void stats_overlay(const StatsView& stats) {
  // One line by default: what the image is and whether it is done.
  const char* state = stats.interacting ? "interacting" : (stats.idle ? "done" : "rendering");
  if (stats.have_frame) {
    char level[16] = "";
    if (stats.level_divisor > 1) std::snprintf(level, sizeof level, " (1/%d)", stats.level_divisor);
    if (stats.level_quads) std::snprintf(level, sizeof level, " (quads)");
    ImGui::Text("%d\xC3\x97%d%s  %u/%d spp  %.1f ms/%s  %s", stats.image_width, stats.image_height, level, stats.spp,
                stats.target_spp, stats.frame.pass_ms, stats.frame.reshaded ? "re-shade" : "pass", state);
  } else {
    ImGui::TextDisabled("waiting for the first image");
  }
  if (!stats.scene_error.empty()) {
    // Where one looks: the error's first line itself (file:line:col: path: message), the rest
    // in the Scene file panel.
    const std::string first = stats.scene_error.substr(0, stats.scene_error.find('\n'));
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
    ImGui::TextColored(kErrorColor, "%s", first.c_str());
    ImGui::PopTextWrapPos();
    if (first.size() < stats.scene_error.size()) ImGui::TextDisabled("(more in the Scene file panel)");
  }
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
      if (f.reshaded) ImGui::Text("%.1f ms re-shade (%.2f Mrays/s re-cast)", f.pass_ms, f.mrays_per_s);
      else ImGui::Text("%.1f ms, %.2f Mrays/s", f.pass_ms, f.mrays_per_s);
      row("tracer");
      if (f.reshaded) ImGui::TextUnformatted("re-shaded from the stored ray trees");
      else if (f.packets) ImGui::Text("packets, %d rays wide (%s)", f.packet_lanes, f.packet_kernels);
      else ImGui::TextUnformatted("scalar, ray by ray");
      row("ray trees");
      if (f.tree_bytes > 0) ImGui::Text("%.1f MiB kept (first sample)", static_cast<double>(f.tree_bytes) / (1 << 20));
      else ImGui::TextUnformatted("none kept");
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

}  // namespace phonglab::ui
