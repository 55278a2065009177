// --formula SLOT=TEXT|@FILE and --formulas FILE, the words of phonglab-cli render, check and phonglab-bench SCENE
// (docs/formulas.md), turned into the formulas' rules.
#pragma once

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "apps/common/args.h"
#include "check/formula.h"
#include "check/rules.h"
#include "io/diagnostic.h"
#include "io/formula_file.h"

namespace phonglab::cli {

// Reads a whole file; false with a message on failure.
inline bool read_text_file(const std::string& path, std::string& out, std::string& error) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    error = path + ": cannot open (" + std::strerror(errno) + ")";
    return false;
  }
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) error = path + ": cannot read";
  return !failed;
}

// Every --formula SLOT=TEXT|@FILE: the formulas in their slots. A bad slot is a usage error;
// an unreadable file or a formula's error is printed (positioned) and gives nullopt.
inline std::optional<LocalRules> take_formulas(Args& args, bool& any) {
  LocalRules rules;
  any = false;
  // --formulas FILE: a formula file the panel saved (docs/formulas.md); --formula SLOT=... after
  // it replaces a slot.
  while (const auto path = args.take_value("--formulas")) {
    const FormulaFileLoad loaded = load_formula_file(*path);
    if (!loaded.ok()) {
      std::cerr << loaded.error_text();
      return std::nullopt;
    }
    for (int s = 0; s < kFormulaSlots; ++s) {
      const std::string& text = (*loaded.texts)[static_cast<std::size_t>(s)];
      if (text.empty()) continue;
      const std::string source = *path + ": " + std::string(formula_slot_name(static_cast<FormulaSlot>(s))) + ": formula";
      FormulaError error;
      std::shared_ptr<const Formula> formula = Formula::compile(text, &error, source);
      if (!formula) {
        std::cerr << error.text() << "\n";
        return std::nullopt;
      }
      rules.formulas[static_cast<std::size_t>(s)] = std::move(formula);
      any = true;
    }
  }
  while (const auto arg = args.take_value("--formula")) {
    const std::size_t eq = arg->find('=');
    const std::string slot_name = arg->substr(0, eq);
    const auto slot = formula_slot_from_name(slot_name);
    if (eq == std::string::npos || !slot) {
      const std::vector<std::string_view> names = {"ambient", "diffuse", "specular"};
      throw UsageError{"--formula must be SLOT=TEXT or SLOT=@FILE with SLOT one of ambient, diffuse, specular (got '" +
                       *arg + "')" + (eq == std::string::npos ? "" : suggestion_for(slot_name, names, "expected one of"))};
    }
    std::string text = arg->substr(eq + 1);
    std::string source = "formula";
    if (!text.empty() && text[0] == '@') {
      source = text.substr(1);
      std::string error;
      std::string content;
      if (!read_text_file(source, content, error)) {
        std::cerr << error << "\n";
        return std::nullopt;
      }
      text = std::move(content);
    }
    FormulaError error;
    std::shared_ptr<const Formula> formula = Formula::compile(text, &error, source);
    if (!formula) {
      std::cerr << error.text() << "\n";
      return std::nullopt;
    }
    rules.formulas[static_cast<std::size_t>(*slot)] = std::move(formula);
    any = true;
  }
  return rules;
}

}  // namespace phonglab::cli
