// The formula language of a student's term (docs/formulas.md): one statement per line or per
// `;`, `name = expression`, then a final expression, over numbers and triples, with the names a
// hit gives (N, L, V, P, ka, kd, ks, n, kr, kt, ior, Ia, I) and GLSL's functions. A formula is
// compiled once to a flat list of instructions over typed registers and evaluated for many hits
// at a time, one instruction over all of them (lanes), so a formula costs close to the
// built-in shading. No Debian library fits: muparser has no vectors, muparserx is slow and does
// not build for WebAssembly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/math.h"

namespace phonglab {

// The local terms of the equation a formula can replace (SPEC: ambient once per hit; diffuse
// and specular per hit and visible light with N.L > 0, the light's I still multiplying them).
enum class FormulaSlot : std::uint8_t { kAmbient, kDiffuse, kSpecular };
inline constexpr int kFormulaSlots = 3;
std::optional<FormulaSlot> formula_slot_from_name(std::string_view name);  // "ambient", "diffuse", "specular"
std::string_view formula_slot_name(FormulaSlot slot);
// The reference's own formula for the slot: "ka * Ia", "kd * dot(N, L)",
// "R = reflect(-L, N)\nks * pow(max(0, dot(R, V)), n)".
std::string_view reference_formula(FormulaSlot slot);

// What a formula reads at one hit (and light): the names of the language.
struct FormulaInputs {
  Vec3 N{0}, L{0}, V{0}, P{0};  // L = 0 in the ambient slot
  Color ka{0}, kd{0}, ks{0}, kr{0}, kt{0}, Ia{0};
  Color I{0};                    // the light's intensity; 0 in the ambient slot
  double n = 0, ior = 1;
};
// The given names, in the order the language lists them (for the panel and did-you-mean).
const std::vector<std::string_view>& formula_given_names();
// The functions, each with its signature as the panel shows it ("dot(a, b)").
const std::vector<std::string_view>& formula_function_signatures();

// A position in the formula's text (1-based line and column, in bytes) and what is wrong there.
struct FormulaError {
  std::string source = "formula";  // "formula", or the file a SLOT=@FILE named
  int line = 1, column = 1;
  std::string message;  // e.g. `unknown name "nrm" (did you mean "N"?)`
  // "formula:1:31: unknown name ..." (source:line:column: message)
  std::string text() const;
};

// A value of a statement, for the probe: a number (triple = false, x only) or a triple.
struct FormulaValue {
  bool triple = false;
  double x = 0, y = 0, z = 0;
};

// The given names of many hits, handed over a block of lanes at a time, for a caller whose hits
// are not FormulaInputs (a re-shade's stored hits): fill() writes the components of given name
// `name` (formula_given_names() order) of hits [first, first + n) to x, y, z (y and z null for a
// number). Asked only for the names the formula reads.
class FormulaSource {
 public:
  virtual ~FormulaSource() = default;
  virtual void fill(int name, std::size_t first, std::size_t n, double* x, double* y, double* z) const = 0;
  // Hit i's given names, all of them.
  FormulaInputs at(std::size_t i) const;
};

class Formula {
 public:
  // Hits evaluated per instruction (the register arrays' length).
  static constexpr std::size_t kLanes = 64;

  // Compiles `text`; on an error, `error` is set and the formula is empty.
  static std::shared_ptr<const Formula> compile(std::string_view text, FormulaError* error,
                                                std::string_view source = "formula");

  // The final value for `count` hits (any count; taken kLanes at a time); a number final value
  // is grey (the same in all three channels). NaN and infinities are kept as they come.
  void evaluate(const FormulaInputs* inputs, std::size_t count, Color* out) const;
  Color evaluate(const FormulaInputs& inputs) const;
  void evaluate(const FormulaSource& source, std::size_t count, Color* out) const;

  // The statements' values at one hit, in order, for the probe: (name, value), then ("=", the
  // final value).
  std::vector<std::pair<std::string, FormulaValue>> trace(const FormulaInputs& inputs) const;

  const std::string& text() const { return text_; }
  // Which given names the formula reads (bit i: formula_given_names()[i]), so a caller can skip
  // what it does not need.
  std::uint32_t names_read() const { return names_read_; }

  struct Program;  // formula.cpp
  ~Formula();
  Formula(const Formula&) = delete;
  Formula& operator=(const Formula&) = delete;

 private:
  Formula();
  std::string text_;
  std::uint32_t names_read_ = 0;
  std::unique_ptr<Program> program_;
};

}  // namespace phonglab
