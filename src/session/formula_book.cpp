#include "session/formula_book.h"

namespace phonglab {

namespace {
bool blank(const std::string& text) {
  // Blank lines and comments alone leave the term to the equation.
  bool comment = false;
  for (const char c : text) {
    if (c == '\n') comment = false;
    else if (c == '#') comment = true;
    else if (!comment && c != ' ' && c != '\t' && c != '\r' && c != ';') return false;
  }
  return true;
}
}  // namespace

bool FormulaBook::set(FormulaSlot s, const std::string& text) {
  Slot& slot = slots_[static_cast<std::size_t>(s)];
  if (slot.text == text && (slot.formula || slot.error || blank(text))) return false;
  slot.text = text;
  std::shared_ptr<const Formula> compiled;
  if (blank(text)) {
    slot.error.reset();
  } else {
    FormulaError error;
    compiled = Formula::compile(text, &error);
    if (!compiled) {
      slot.error = error;
      return false;  // the last good formula keeps rendering
    }
    slot.error.reset();
  }
  const bool changed = (compiled ? compiled->text() : std::string()) != (slot.formula ? slot.formula->text() : std::string());
  slot.formula = std::move(compiled);
  if (changed) ++version_;
  return changed;
}

bool FormulaBook::set_all(const Texts& texts) {
  bool changed = false;
  for (int s = 0; s < kFormulaSlots; ++s) changed = set(static_cast<FormulaSlot>(s), texts[static_cast<std::size_t>(s)]) || changed;
  return changed;
}

FormulaBook::Texts FormulaBook::texts() const {
  Texts out;
  for (std::size_t s = 0; s < out.size(); ++s) out[s] = slots_[s].text;
  return out;
}

LocalRules FormulaBook::rules() const {
  LocalRules rules;
  for (std::size_t s = 0; s < slots_.size(); ++s) rules.formulas[s] = slots_[s].formula;
  return rules;
}

bool FormulaBook::any() const {
  for (const Slot& s : slots_) {
    if (s.formula) return true;
  }
  return false;
}

}  // namespace phonglab
