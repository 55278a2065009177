#include "apps/previewer/formula_shell.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "apps/previewer/viewer_app.h"
#include "io/formula_file.h"
#include "io/image_read.h"
#include "session/student_image.h"

namespace phonglab {

namespace {

// The check runs at most this wide (the view's aspect kept): a verdict within a second of a
// keystroke on two cores, beside the renderer.
constexpr int kCheckWidth = 480;

std::string names_text() {
  std::string out;
  for (const std::string_view n : formula_given_names()) {
    if (!out.empty()) out += ' ';
    out += n;
  }
  return out + "; functions: dot cross normalize length reflect pow max min clamp abs sqrt exp log mix step";
}

}  // namespace

FormulaShell::~FormulaShell() {
  if (worker_.joinable()) worker_.join();
}

void FormulaShell::refresh_panel() {
  const FormulaBook& book = s_.session.formulas();
  for (int s = 0; s < kFormulaSlots; ++s) {
    const auto i = static_cast<std::size_t>(s);
    const FormulaBook::Slot& slot = book.slot(static_cast<FormulaSlot>(s));
    panel_.errors[i] = slot.error ? slot.error->text() : std::string();
  }
  if (panel_.names.empty()) panel_.names = names_text();
  panel_.image_name = image_name_;
  panel_.image_error = image_error_;
  panel_.image_verdict = image_result_ ? check_summary(*image_result_) : "checking against the reference...";
  panel_.image_matches = image_result_ && image_result_->match;
  panel_.image_probe.clear();
  const auto& probed = tools_.probe();
  if (image_result_ && probed.tree && probed.x < image_result_->width && probed.y < image_result_->height) {
    const std::size_t i = static_cast<std::size_t>(probed.y) * image_result_->width + probed.x;
    const Color yours = image_result_->yours[i], reference = image_result_->reference[i];
    char text[256];
    std::snprintf(text, sizeof text, "at pixel (%d, %d): yours (%.4g, %.4g, %.4g), reference (%.4g, %.4g, %.4g) linear; "
                  "the reference's terms and ray tree: the Probe panel",
                  probed.x, probed.y, yours.x, yours.y, yours.z, reference.x, reference.y, reference.z);
    panel_.image_probe = text;
  }
  if (!book.any()) {
    panel_.verdict.clear();
  } else if (result_) {
    panel_.verdict = check_summary(*result_);
    panel_.matches = result_->match;
  } else {
    panel_.verdict = "checking against the reference...";
    panel_.matches = false;
  }
}

void FormulaShell::sidebar_formulas() {
  // The boxes follow the session unless one is being typed in (undo, a script, a lesson).
  if (!ImGui::IsAnyItemActive()) panel_.texts = s_.session.formulas().texts();
  refresh_panel();
  panel_.hints_left = lesson_shell_.exercise() ? lesson_shell_.hints_left() : -1;
  const auto& probe = tools_.probe().tree;
  panel_.probe = probe && s_.schedule.snapshot()
                     ? formula_probe_text(s_.schedule.snapshot()->scene(), probe->root, s_.session.formulas().rules())
                     : std::string();
  const ui::FormulaPanelEdits edits = ui::formula_panel(panel_);
  if (edits.hint) lesson_shell_.show_hint();
  if (edits.starter >= 0) {
    const auto slot = static_cast<FormulaSlot>(edits.starter);
    set_text(slot, std::string(reference_formula(slot)));
  }
  if (edits.slot >= 0) {
    const auto slot = static_cast<FormulaSlot>(edits.slot);
    s_.session.set_formula(slot, panel_.texts[static_cast<std::size_t>(edits.slot)], edits.held);
  }
  if (edits.view) s_.upload_pending = true;
  if (edits.open_image) open_image(panel_.image_path);
  if (edits.close_image) close_image();
  if (edits.save_formulas) save_formulas(panel_.formulas_path);
  if (edits.open_formulas) open_formulas(panel_.formulas_path);
}

std::string FormulaShell::formulas_path() const {
  if (!panel_.formulas_path.empty()) return panel_.formulas_path;
  // Beside the scene file, named after it; an embedded scene's in the working folder.
  const std::filesystem::path scene(s_.doc.file_path());
  if (scene.empty()) return "formulas.json";
  return (scene.parent_path() / (scene.stem().string() + ".formulas.json")).string();
}

bool FormulaShell::save_formulas(const std::string& path) {
  panel_.formulas_path = path.empty() ? formulas_path() : path;
  const std::string error = save_formula_file(panel_.formulas_path, s_.session.formulas().texts());
  panel_.formulas_failed = !error.empty();
  panel_.formulas_status = error.empty() ? "saved to " + panel_.formulas_path : error;
  return error.empty();
}

bool FormulaShell::open_formulas(const std::string& path) {
  panel_.formulas_path = path.empty() ? formulas_path() : path;
  const FormulaFileLoad loaded = load_formula_file(panel_.formulas_path);
  panel_.formulas_failed = !loaded.ok();
  if (!loaded.ok()) {
    // Nothing changes: the formulas on screen stay, the file's first error says why.
    panel_.formulas_status = loaded.errors.empty() ? "cannot read " + panel_.formulas_path : loaded.errors.front().to_string();
    return false;
  }
  s_.session.set_formulas(*loaded.texts);
  panel_.texts = s_.session.formulas().texts();
  panel_.formulas_status = "opened " + panel_.formulas_path;
  refresh_panel();
  return true;
}

void FormulaShell::set_text(FormulaSlot slot, const std::string& text) {
  panel_.texts[static_cast<std::size_t>(slot)] = text;
  s_.session.set_formula(slot, text, false);
  refresh_panel();
}

bool FormulaShell::set_view(std::string_view name) {
  const std::optional<ui::FormulaView> view = ui::formula_view_from_name(name);
  if (!view) return false;
  panel_.view = *view;
  s_.upload_pending = true;
  return true;
}

bool FormulaShell::sync_rules() {
  const FormulaBook& book = s_.session.formulas();
  // The reference view renders the equation's own terms; the difference view shows the check.
  const bool traced = book.any() && panel_.view != ui::FormulaView::kReference;
  if (traced == rules_sent_any_ && (!traced || book.version() == rules_version_)) return false;
  rules_sent_any_ = traced;
  rules_version_ = book.version();
  s_.schedule.set_rules(traced ? book.rules() : LocalRules{});
  return true;
}

std::string FormulaShell::open_image(const std::string& path) {
  OpenedStudentImage opened = open_student_image(path, s_.schedule.width(), s_.schedule.height(),
                                                 "phonglab-cli probe's command in the Probe panel names it");
  if (!opened.image) {
    image_error_ = opened.error;  // the last image, if any, stays
    return opened.error;
  }
  image_ = std::move(opened.image);
  image_name_ = opened.name;
  image_error_.clear();
  image_result_.reset();
  image_check_pending_ = true;
  // A of the compare: the student's image as linear values, as the screen shows a render.
  tools_.compare().set_file_image(compare_frame(*image_), image_name_);
  s_.instruments.compare = 2;  // |live - A|: where yours differs
  panel_.view = ui::FormulaView::kDifference;
  unfold_ = true;
  s_.upload_pending = true;
  return "";
}

void FormulaShell::close_image() {
  image_.reset();
  image_result_.reset();
  image_name_.clear();
  image_check_pending_ = false;
  if (!tools_.compare().file_name().empty()) tools_.compare().clear();
  s_.upload_pending = true;
}

void FormulaShell::poll_check() {
  if (!running_.load() && worker_.joinable()) {
    worker_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_ && finished_image_) image_result_ = std::move(finished_);
    else if (finished_) result_ = std::move(finished_);
    finished_.reset();
    s_.upload_pending = true;
  }
  const FormulaBook& book = s_.session.formulas();
  const std::shared_ptr<const PreparedScene>& snapshot = s_.schedule.snapshot();
  if (image_ && image_check_pending_ && !running_.load() && snapshot) {
    // The image against the view's scene at its own size: the reference the renderer's rules
    // would give without formulas.
    image_check_pending_ = false;
    Scene scene = snapshot->scene();
    running_.store(true);
    finished_image_ = true;
    worker_ = std::thread([this, scene = std::move(scene), image = *image_] {
      CheckOptions options;
      options.threads = 1;
      CheckResult r = check_image(scene, image, options);
      {
        std::lock_guard<std::mutex> lock(mutex_);
        finished_ = std::move(r);
      }
      running_.store(false);
    });
    return;
  }
  if (!book.any()) {
    result_.reset();
    checked_version_ = ~std::uint64_t{0};
    return;
  }
  if (running_.load() || !snapshot || s_.schedule.width() < 1 || s_.schedule.height() < 1) return;
  if (checked_snapshot_ == snapshot.get() && checked_version_ == book.version()) return;
  if (checked_version_ != book.version()) result_.reset();  // the verdict says "checking" until the new one
  checked_snapshot_ = snapshot.get();
  checked_version_ = book.version();
  Scene scene = snapshot->scene();
  const double scale = std::min(1.0, static_cast<double>(kCheckWidth) / s_.schedule.width());
  scene.width = std::max(1, static_cast<int>(s_.schedule.width() * scale));
  scene.height = std::max(1, static_cast<int>(s_.schedule.height() * scale));
  LocalRules rules = book.rules();
  running_.store(true);
  finished_image_ = false;
  worker_ = std::thread([this, scene = std::move(scene), rules = std::move(rules)] {
    CheckOptions options;
    options.threads = 1;  // beside the renderer's threads
    CheckResult r = check_formulas(scene, rules, options);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finished_ = std::move(r);
    }
    running_.store(false);
  });
}

bool FormulaShell::check_settled() const {
  const FormulaBook& book = s_.session.formulas();
  if (image_ && (image_check_pending_ || !image_result_ || running_.load())) return false;
  if (!book.any()) return !running_.load() && !worker_.joinable();
  return !running_.load() && !worker_.joinable() && result_ && checked_version_ == book.version() &&
         checked_snapshot_ == s_.schedule.snapshot().get();
}

std::optional<std::vector<glm::vec3>> FormulaShell::difference_pixels(int width, int height) const {
  if (width < 1 || height < 1 || panel_.view == ui::FormulaView::kReference) return std::nullopt;
  // A student's image: "yours" is the image itself, "difference" its check's.
  const CheckResult* check = image_result_ ? &*image_result_ : nullptr;
  if (check && panel_.view == ui::FormulaView::kYours) {
    if (check->width != width || check->height != height) return std::nullopt;
    std::vector<glm::vec3> out(check->yours.size());
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(check->yours[i]);
    return out;
  }
  if (!check && s_.session.formulas().any() && result_) check = &*result_;
  if (panel_.view != ui::FormulaView::kDifference || !check) return std::nullopt;
  const CheckResult* result = check;
  const std::vector<Color> diff = check_difference_image(*result);
  std::vector<glm::vec3> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    const int sy = std::min(result->height - 1, y * result->height / height);
    for (int x = 0; x < width; ++x) {
      const int sx = std::min(result->width - 1, x * result->width / width);
      out[static_cast<std::size_t>(y) * width + x] = glm::vec3(diff[static_cast<std::size_t>(sy) * result->width + sx]);
    }
  }
  return out;
}

}  // namespace phonglab
