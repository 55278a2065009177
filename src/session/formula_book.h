// A student's formulas in a session (docs/formulas.md): per slot the text as typed, the last
// formula that compiled (what renders: a text with an error keeps the last good one rendering),
// and the text's error. Plain data; the session owns it with its undo (Session::set_formula),
// and the desktop and the page show it.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "check/formula.h"
#include "check/rules.h"

namespace phonglab {

class FormulaBook {
 public:
  struct Slot {
    std::string text;                        // as typed ("" : the equation's own term)
    std::shared_ptr<const Formula> formula;  // the last text that compiled; null: the equation's
    std::optional<FormulaError> error;       // the text's error, when it has one
  };
  using Texts = std::array<std::string, kFormulaSlots>;

  // A slot's text: compiled; on an error the last good formula stays and the error is kept.
  // An empty (or blank) text gives the slot back to the equation. True when what renders changed.
  bool set(FormulaSlot slot, const std::string& text);
  // Every slot's text at once (undo, a lesson's exercise); true when what renders changed.
  bool set_all(const Texts& texts);

  const Slot& slot(FormulaSlot s) const { return slots_[static_cast<std::size_t>(s)]; }
  Texts texts() const;
  // The formulas that render (src/check/rules.h), for the renderer's snapshot and the check.
  LocalRules rules() const;
  bool any() const;  // some slot renders a formula
  // Bumped whenever what renders changes (the renderer's snapshot and the check follow it).
  std::uint64_t version() const { return version_; }

 private:
  std::array<Slot, kFormulaSlots> slots_{};
  std::uint64_t version_ = 0;
};

}  // namespace phonglab
