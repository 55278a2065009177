// Rules of formulas for the tests: each (slot, text) compiled into its slot, a failure to compile
// reported as the test's own failure.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <utility>

#include "check/rules.h"

namespace phonglab::test {

inline LocalRules rules_of(std::initializer_list<std::pair<FormulaSlot, const char*>> texts) {
  LocalRules rules;
  for (const auto& [slot, text] : texts) {
    FormulaError error;
    rules.formulas[static_cast<std::size_t>(slot)] = Formula::compile(text, &error);
    EXPECT_NE(rules.formulas[static_cast<std::size_t>(slot)], nullptr) << error.text();
  }
  return rules;
}

}  // namespace phonglab::test
