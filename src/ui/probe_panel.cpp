// The probe panel (the equation of one pixel, term by term and light by light) and the "move
// your head" plot. Functions over plain data, as the other panels.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "interaction/numbers.h"
#include "ui/panels.h"
#include "ui/widgets.h"

namespace phonglab::ui {

namespace {

// Probe numbers: `digits` significant digits (4 by default, 17 with "all digits").
// Where the values' column starts: past the widest label ("max(0,R·V)^n"), so no value
// overlaps its label.
float value_column() {
  return std::max(ImGui::GetFontSize() * 6.0f,
                  ImGui::CalcTextSize("max(0,R\xC2\xB7V)^n").x + ImGui::GetStyle().ItemSpacing.x * 2);
}

void rgb_text(const char* label, const Color& c, int digits) {
  // The label, then the values in a column of their own (a proportional font does not pad).
  ImGui::TextUnformatted(label);
  ImGui::SameLine(value_column());
  ImGui::Text("(%s, %s, %s)", probe_number(c.x, digits).c_str(), probe_number(c.y, digits).c_str(),
              probe_number(c.z, digits).c_str());
}

void vec_text(const char* label, const Vec3& v, int digits) { rgb_text(label, v, digits); }

// One number in the values' column.
void number_row(const char* label, double value, int digits, const char* name = nullptr) {
  ImGui::TextUnformatted(label);
  if (name != nullptr) locate(std::string(name) + "_label");
  ImGui::SameLine(value_column());
  ImGui::TextUnformatted(probe_number(value, digits).c_str());
  if (name != nullptr) locate(name);
}

// What ambient stands in for at the pixel: ka·Ia, the indirect term's estimate with its standard
// error, and the ka that would make ka·Ia equal to it.
void indirect_rows(const IndirectProbe& p, int d) {
  ImGui::Separator();
  ImGui::TextWrapped("what ka\xC2\xB7%s stands in for: the indirect term kd\xC2\xB7" "E, its standard error over %d "
                     "samples (%d bounces), and the ka with ka\xC2\xB7%s equal to it:",
                     i_a().c_str(), p.samples, p.bounces, i_a().c_str());
  rgb_text("indirect", p.mean, d);
  rgb_text("\xC2\xB1 error", p.standard_error, d);
  rgb_text("ka match", p.fitted_ka, d);
}

}  // namespace

void head_plot(const HeadPlotView& view) {
  if (view.hit == nullptr || !view.hit->hit) {
    ImGui::TextDisabled("Probe a pixel on a surface to plot its highlight against the head angle.");
    return;
  }
  const ProbeNode& hit = *view.hit;
  const ProbeLight* light = nullptr;
  for (const ProbeLight& l : hit.lights) {
    if (l.lit_side) {
      light = &l;
      break;
    }
  }
  if (light == nullptr) {
    ImGui::TextDisabled("No light on the lit side of the probed point: no highlight.");
    return;
  }
  constexpr int kSamples = 181;  // one per degree, -90..90
  std::array<float, kSamples> values{};
  const Vec3 d = view.eye_at_zero - hit.p;
  auto factor = [&](double angle_deg) {
    const double a = -glm::radians(angle_deg);  // as ui::head_eye
    const Vec3 to_eye =
        d * std::cos(a) + glm::cross(view.axis, d) * std::sin(a) + view.axis * glm::dot(view.axis, d) * (1 - std::cos(a));
    const double len = glm::length(to_eye);
    const Vec3 v = len > 0 ? to_eye / len : hit.v;
    double c;
    if (view.blinn) {
      const Vec3 h = light->l + v;
      c = glm::length(h) > 0 ? glm::dot(hit.n, glm::normalize(h)) : 0;
    } else {
      c = glm::dot(light->r, v);  // R does not depend on V
    }
    const double base = std::clamp(c, 0.0, 1.0);
    return base == 0 && view.shininess > 0 ? 0.0 : std::pow(base, view.shininess);
  };
  for (int i = 0; i < kSamples; ++i) values[static_cast<std::size_t>(i)] = static_cast<float>(factor(i - 90.0));
  const double current = factor(static_cast<double>(view.angle_deg));
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%s^n = %.4g at %.0f deg (L%d)", view.blinn ? "N\xC2\xB7H" : "R\xC2\xB7V",
                current, static_cast<double>(view.angle_deg), light->index);
  // The title above the plot (not inside it, where the dot would cover it), the curve, then
  // ticks: 0 and 1 on the left, -90, 0 and +90 degrees below.
  ImGui::TextUnformatted(overlay);
  const float tick_w = ImGui::CalcTextSize("1.0 ").x;
  ImGui::Dummy(ImVec2(tick_w, 0));
  ImGui::SameLine(0, 0);
  ImGui::PlotLines("##head", values.data(), kSamples, 0, nullptr, 0.0f, 1.0f,
                   ImVec2(view.width - tick_w, 90 * ImGui::GetFontSize() / 13));
  const ImVec2 lo = ImGui::GetItemRectMin();
  const ImVec2 hi = ImGui::GetItemRectMax();
  const ImVec2 pad = ImGui::GetStyle().FramePadding;
  const float x0 = lo.x + pad.x, x1 = hi.x - pad.x, y0 = hi.y - pad.y, y1 = lo.y + pad.y;
  const float x = x0 + (view.angle_deg + 90.0f) / 180.0f * (x1 - x0);
  const float y = y0 - static_cast<float>(current) * (y0 - y1);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImU32 tick = IM_COL32(200, 200, 200, 255);
  const float h = ImGui::GetTextLineHeight();
  draw->AddText(ImVec2(lo.x - tick_w, y1 - h / 2), tick, "1");
  draw->AddText(ImVec2(lo.x - tick_w, y0 - h / 2), tick, "0");
  // The current angle: a vertical line and a dot on the curve.
  draw->AddLine(ImVec2(x, lo.y), ImVec2(x, hi.y), IM_COL32(255, 230, 0, 160), 1.0f);
  draw->AddCircleFilled(ImVec2(x, y), 4.0f, IM_COL32(255, 230, 0, 255));
  ImGui::Dummy(ImVec2(tick_w, h));
  for (const int deg : {-90, 0, 90}) {
    char label[8];
    std::snprintf(label, sizeof label, deg > 0 ? "+%d" : "%d", deg);
    const float tx = x0 + static_cast<float>(deg + 90) / 180.0f * (x1 - x0);
    draw->AddLine(ImVec2(tx, hi.y), ImVec2(tx, hi.y + 4), tick, 1.0f);
    const float w = ImGui::CalcTextSize(label).x;
    draw->AddText(ImVec2(std::clamp(tx - w / 2, lo.x, hi.x - w), hi.y + 4), tick, label);
  }
  ImGui::TextDisabled("head angle (degrees) about the camera's up, around the probed point P");
}

void probe_panel(const ProbeView& view, bool& all_digits) {
  if (view.probe == nullptr || view.scene == nullptr) {
    ImGui::TextDisabled("Ctrl+click a pixel (or turn on probe mode and click) to probe it: its equation, term by "
                        "term and light by light, appears here.");
    return;
  }
  const int d = all_digits ? 17 : 4;
  const PixelProbe& probe = *view.probe;
  const ProbeNode& root = probe.root;
  const bool blinn = view.scene->specular_model == SpecularModel::kBlinn;
  ImGui::Text("pixel (%d, %d) of %dx%d, centre ray", probe.x, probe.y, view.image_width, view.image_height);
  if (!view.cli_command.empty()) {
    // The same pixel from the command line (the saved scene's): a student's own numbers to diff.
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s", view.cli_command.c_str());
    ImGui::PopTextWrapPos();
    locate("probe.cli_command");
  }
  ImGui::SameLine();
  ImGui::Checkbox("all digits", &all_digits);
  rgb_text("linear", root.total, d);
  ImGui::TextUnformatted("displayed");
  ImGui::SameLine(value_column());
  ImGui::Text("(%d, %d, %d) at %+.1f EV", view.srgb[0], view.srgb[1], view.srgb[2], static_cast<double>(view.exposure_ev));
  if (!root.hit) {
    ImGui::TextDisabled("The ray misses: the pixel is the background.");
    return;
  }
  vec_text("P", root.p, d);
  vec_text("N", root.n, d);
  vec_text("V", root.v, d);
  ImGui::Separator();
  rgb_text(("ka\xC2\xB7" + i_a()).c_str(), root.terms.ambient, d);
  rgb_text("diffuse", root.terms.diffuse, d);
  rgb_text("specular", root.terms.specular, d);
  rgb_text("reflection", root.terms.reflection, d);
  rgb_text("refraction", root.terms.refraction, d);
  rgb_text("= total", root.terms.sum(), d);
  rgb_text("kr'", root.kr_eff, d);
  rgb_text("kt'", root.kt_eff, d);
  ImGui::Text("F = %.*g  TIR: %s  entering: %s", d, root.fresnel, root.tir ? "yes" : "no", root.entering ? "yes" : "no");
  if (view.indirect && view.indirect->hit) indirect_rows(*view.indirect, d);
  for (std::size_t i = 0; i < root.lights.size(); ++i) {
    const ProbeLight& light = root.lights[i];
    ImGui::PushID(static_cast<int>(i));
    ImGui::Separator();
    ImGui::Text("light L%d: %s", light.index,
                !light.lit_side ? "behind the surface (N\xC2\xB7L <= 0)"
                : light.visible ? "visible"
                                : "in shadow");
    if (!light.visible && light.lit_side && i < view.occluders.size()) {
      ImGui::SameLine();
      ImGui::Text("(blocked by %s)", view.occluders[i].c_str());
    }
    vec_text("L", light.l, d);
    vec_text(blinn ? "H" : "R", light.r, d);
    // One cosine a row: each fits the panel's width at any number of digits.
    number_row("N\xC2\xB7L", light.n_dot_l, d);
    number_row(blinn ? "N\xC2\xB7H" : "R\xC2\xB7V", light.r_dot_v, d);
    number_row(blinn ? "(N\xC2\xB7H)^n" : "max(0,R\xC2\xB7V)^n", light.spec_factor, d, "probe.spec_factor");
    rgb_text("diffuse", light.diffuse, d);
    rgb_text("specular", light.specular, d);
    ImGui::PopID();
  }
  ImGui::Separator();
  if (ImGui::TreeNodeEx("The equation with the numbers (and the children)", ImGuiTreeNodeFlags_DefaultOpen)) {
    // Wrapped at the panel's edge, at spaces only: long lines continue below instead of off to
    // the side, and a number is never split at its point (ImGui's own wrap breaks after a '.').
    const std::string wrapped = wrap_at_spaces(view.report, ImGui::GetContentRegionAvail().x, [](std::string_view t) {
      return ImGui::CalcTextSize(t.data(), t.data() + t.size()).x;
    });
    ImGui::TextUnformatted(wrapped.c_str());
    ImGui::TreePop();
  }
}

}  // namespace phonglab::ui
