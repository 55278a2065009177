#include "apps/previewer/formula_shell.h"

#include <algorithm>

#include "apps/previewer/viewer_app.h"

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
  const FormulaBook& book = v_.session_.formulas();
  for (int s = 0; s < kFormulaSlots; ++s) {
    const auto i = static_cast<std::size_t>(s);
    const FormulaBook::Slot& slot = book.slot(static_cast<FormulaSlot>(s));
    panel_.errors[i] = slot.error ? slot.error->text() : std::string();
  }
  if (panel_.names.empty()) panel_.names = names_text();
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
  if (!ImGui::IsAnyItemActive()) panel_.texts = v_.session_.formulas().texts();
  refresh_panel();
  panel_.hints_left = v_.lesson_shell_.exercise() ? v_.lesson_shell_.hints_left() : -1;
  const auto& probe = v_.tools_.probe().tree;
  panel_.probe = probe && v_.schedule_.snapshot()
                     ? formula_probe_text(v_.schedule_.snapshot()->scene(), probe->root, v_.session_.formulas().rules())
                     : std::string();
  const ui::FormulaPanelEdits edits = ui::formula_panel(panel_);
  if (edits.hint) v_.lesson_shell_.show_hint();
  if (edits.starter >= 0) {
    const auto slot = static_cast<FormulaSlot>(edits.starter);
    set_text(slot, std::string(reference_formula(slot)));
  }
  if (edits.slot >= 0) {
    const auto slot = static_cast<FormulaSlot>(edits.slot);
    v_.session_.set_formula(slot, panel_.texts[static_cast<std::size_t>(edits.slot)], edits.held);
  }
  if (edits.view) v_.upload_pending_ = true;
}

void FormulaShell::set_text(FormulaSlot slot, const std::string& text) {
  panel_.texts[static_cast<std::size_t>(slot)] = text;
  v_.session_.set_formula(slot, text, false);
  refresh_panel();
}

bool FormulaShell::set_view(std::string_view name) {
  const std::optional<ui::FormulaView> view = ui::formula_view_from_name(name);
  if (!view) return false;
  panel_.view = *view;
  v_.upload_pending_ = true;
  return true;
}

bool FormulaShell::sync_rules() {
  const FormulaBook& book = v_.session_.formulas();
  // The reference view renders the equation's own terms; the difference view shows the check.
  const bool traced = book.any() && panel_.view != ui::FormulaView::kReference;
  if (traced == rules_sent_any_ && (!traced || book.version() == rules_version_)) return false;
  rules_sent_any_ = traced;
  rules_version_ = book.version();
  v_.schedule_.set_rules(traced ? book.rules() : LocalRules{});
  return true;
}

void FormulaShell::poll_check() {
  if (!running_.load() && worker_.joinable()) {
    worker_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) result_ = std::move(finished_);
    finished_.reset();
    v_.upload_pending_ = true;
  }
  const FormulaBook& book = v_.session_.formulas();
  const std::shared_ptr<const PreparedScene>& snapshot = v_.schedule_.snapshot();
  if (!book.any()) {
    result_.reset();
    checked_version_ = ~std::uint64_t{0};
    return;
  }
  if (running_.load() || !snapshot || v_.schedule_.width() < 1 || v_.schedule_.height() < 1) return;
  if (checked_snapshot_ == snapshot.get() && checked_version_ == book.version()) return;
  if (checked_version_ != book.version()) result_.reset();  // the verdict says "checking" until the new one
  checked_snapshot_ = snapshot.get();
  checked_version_ = book.version();
  Scene scene = snapshot->scene();
  const double scale = std::min(1.0, static_cast<double>(kCheckWidth) / v_.schedule_.width());
  scene.width = std::max(1, static_cast<int>(v_.schedule_.width() * scale));
  scene.height = std::max(1, static_cast<int>(v_.schedule_.height() * scale));
  LocalRules rules = book.rules();
  running_.store(true);
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
  const FormulaBook& book = v_.session_.formulas();
  if (!book.any()) return true;
  return !running_.load() && !worker_.joinable() && result_ && checked_version_ == book.version() &&
         checked_snapshot_ == v_.schedule_.snapshot().get();
}

std::optional<std::vector<glm::vec3>> FormulaShell::difference_pixels(int width, int height) const {
  if (panel_.view != ui::FormulaView::kDifference || !result_ || width < 1 || height < 1) return std::nullopt;
  if (!v_.session_.formulas().any()) return std::nullopt;
  const std::vector<Color> diff = check_difference_image(*result_);
  std::vector<glm::vec3> out(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    const int sy = std::min(result_->height - 1, y * result_->height / height);
    for (int x = 0; x < width; ++x) {
      const int sx = std::min(result_->width - 1, x * result_->width / width);
      out[static_cast<std::size_t>(y) * width + x] = glm::vec3(diff[static_cast<std::size_t>(sy) * result_->width + sx]);
    }
  }
  return out;
}

}  // namespace phonglab
