// libFuzzer target: any bytes as a formula (docs/formulas.md). A rejected formula must say where
// and why; an accepted one is evaluated at a few fixed hits as each slot would give them (the
// ambient slot's L and I are 0), one hit at a time and as one block crossing Formula::kLanes, and
// traced: the ways must agree bit for bit (NaN with NaN). NaN and infinities themselves are the
// student's and allowed.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "check/formula.h"

using namespace phonglab;

namespace {

bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same(const Color& a, const Color& b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }

// Hits for each slot: a lit front face, a grazing light, a degenerate one with zeros.
std::vector<FormulaInputs> fixed_hits() {
  std::vector<FormulaInputs> hits;
  for (int slot = 0; slot < kFormulaSlots; ++slot) {
    for (int k = 0; k < 3; ++k) {
      FormulaInputs in;
      in.N = k == 2 ? Vec3(0) : Vec3(0, 0, 1);
      in.V = glm::normalize(Vec3(0.3, -0.2, 1));
      in.L = k == 0 ? glm::normalize(Vec3(-0.5, 0.4, 1)) : Vec3(1, 0, 1e-9);
      in.P = Vec3(0.25, -1.5, 3);
      in.ka = Color(0.1, 0.2, 0.3), in.kd = Color(0.7, 0.5, 0.2), in.ks = Color(0.3);
      in.kr = Color(0.2), in.kt = k == 2 ? Color(0) : Color(0.5, 0.6, 0.7);
      in.Ia = Color(0.2), in.I = Color(1, 0.9, 0.8);
      in.n = k == 2 ? 0 : 32, in.ior = 1.5;
      if (static_cast<FormulaSlot>(slot) == FormulaSlot::kAmbient) in.L = Vec3(0), in.I = Color(0);
      hits.push_back(in);
    }
  }
  return hits;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<FormulaInputs> hits = fixed_hits();
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  FormulaError error;
  const auto formula = Formula::compile(text, &error);
  if (!formula) {
    if (error.message.empty() || error.line < 1 || error.column < 1) std::abort();  // rejected without saying where or why
    if (Formula::compile(text, nullptr) != nullptr) std::abort();
    return 0;
  }
  if (formula->text() != text || formula->names_read() >= (1u << formula_given_names().size())) std::abort();
  // A block longer than kLanes: the fixed hits over and over.
  std::vector<FormulaInputs> block;
  while (block.size() < Formula::kLanes + 7) block.insert(block.end(), hits.begin(), hits.end());
  std::vector<Color> out(block.size());
  formula->evaluate(block.data(), block.size(), out.data());
  for (std::size_t i = 0; i < block.size(); ++i) {
    const Color alone = formula->evaluate(block[i]);
    if (!same(alone, out[i])) std::abort();  // a hit's value depends on its neighbours
    if (i < hits.size()) {
      const auto trace = formula->trace(block[i]);
      if (trace.empty() || trace.back().first != "=") std::abort();
      const FormulaValue& v = trace.back().second;
      if (!same(v.triple ? Color(v.x, v.y, v.z) : Color(v.x), alone)) std::abort();
    }
  }
  return 0;
}
