// libFuzzer target: any bytes as a formula file (src/io/formula_file.h). A rejected file must
// say where and why; an accepted one must write back to a file that reads to the same texts.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "io/formula_file.h"

using namespace phonglab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const FormulaFileLoad loaded = load_formula_text(text, "fuzz.json");
  if (!loaded.ok()) {
    if (loaded.errors.empty() || loaded.errors.front().message.empty()) std::abort();
    return 0;
  }
  const FormulaFileLoad again = load_formula_text(formula_file_text(*loaded.texts), "again.json");
  if (!again.ok() || *again.texts != *loaded.texts) std::abort();
  return 0;
}
