#include "apps/web/web_formulas.h"

#include "session/student_image.h"

#include <algorithm>

#include "io/check_report.h"
#include "io/formula_file.h"
#include "io/image_read.h"

namespace phonglab {

std::string WebFormulas::set_formula(int slot, const std::string& text) {
  if (slot < 0 || slot >= kFormulaSlots) return "no such slot";
  if (s_.session.set_formula(static_cast<FormulaSlot>(slot), text)) image_.restart();
  return formula_error(slot);
}

std::string WebFormulas::formulas_file_text() const { return formula_file_text(s_.session.formulas().texts()); }

std::string WebFormulas::open_formulas(const std::string& text, const std::string& name) {
  const FormulaFileLoad loaded = load_formula_text(text, name);
  if (!loaded.ok()) return loaded.errors.empty() ? name + ": cannot read" : loaded.errors.front().to_string();
  if (s_.session.set_formulas(*loaded.texts)) image_.restart();
  return "";
}

std::string WebFormulas::formula_text(int slot) const {
  if (slot < 0 || slot >= kFormulaSlots) return "";
  return s_.session.formulas().slot(static_cast<FormulaSlot>(slot)).text;
}

std::string WebFormulas::formula_error(int slot) const {
  if (slot < 0 || slot >= kFormulaSlots) return "";
  const std::optional<FormulaError>& error = s_.session.formulas().slot(static_cast<FormulaSlot>(slot)).error;
  return error ? error->text() : std::string();
}

void WebFormulas::set_formula_view(int view) {
  const int v = view == 1 ? 1 : 0;
  if (v == s_.formula_view) return;
  s_.formula_view = v;
  if (s_.session.formulas().any()) image_.restart();
}

std::string WebFormulas::check_formulas_json() {
  if (!s_.session.formulas().any()) return "";
  Scene scene = view_scene(s_.session.scene(), s_.view);
  constexpr int kCheckWidth = 320;
  const double scale = std::min(1.0, static_cast<double>(kCheckWidth) / std::max(1, s_.width));
  scene.width = std::max(1, static_cast<int>(s_.width * scale));
  scene.height = std::max(1, static_cast<int>(s_.height * scale));
  CheckOptions options;
  options.threads = s_.threads;
  return check_to_json(check_formulas(scene, s_.session.formulas().rules(), options));
}

std::string WebFormulas::check_image_json(const std::string& path) {
  OpenedStudentImage opened = open_student_image(path, s_.width, s_.height);
  if (!opened.image) return nlohmann::json{{"error", opened.error}}.dump();
  Scene scene = view_scene(s_.session.scene(), s_.view);
  CheckOptions options;
  options.threads = s_.threads;
  s_.image_check = check_image(scene, *opened.image, options);
  s_.a.set_file_image(compare_frame(*opened.image), opened.name);
  s_.check_view = 2;
  image_.reshow();
  return check_to_json(*s_.image_check);
}

void WebFormulas::close_image() {
  s_.image_check.reset();
  s_.check_view = 0;
  if (!s_.a.file_name().empty()) s_.a.clear();
  image_.reshow();
}

void WebFormulas::set_check_view(int view) {
  s_.check_view = std::clamp(view, 0, 2);
  image_.reshow();
}

std::optional<std::vector<glm::vec3>> WebFormulas::check_view_pixels() const {
  if (!s_.image_check || s_.check_view == 0 || s_.image_check->width != s_.shown.width || s_.image_check->height != s_.shown.height) {
    return std::nullopt;
  }
  const std::vector<Color> source = s_.check_view == 1 ? s_.image_check->yours : check_difference_image(*s_.image_check);
  std::vector<glm::vec3> out;
  out.reserve(source.size());
  for (const Color& c : source) out.emplace_back(c);
  return out;
}

}  // namespace phonglab
