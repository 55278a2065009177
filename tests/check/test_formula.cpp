// The formula language (src/check/formula.h, docs/formulas.md): the reference formulas and
// random expressions against the same C++ expression bit for bit, the language's rules, and
// every kind of error with its position.
//
// The expected values here are plain C++ expressions; like formula.cpp they must not be fused
// into multiply-adds (a -march=native build could otherwise), so this file turns contraction off.
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "check/formula.h"

using namespace phonglab;

namespace {

// Equal bit for bit, or both NaN.
bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
::testing::AssertionResult same_color(const Color& got, const Color& want) {
  if (same(got.x, want.x) && same(got.y, want.y) && same(got.z, want.z)) return ::testing::AssertionSuccess();
  char text[200];
  std::snprintf(text, sizeof text, "got (%.17g, %.17g, %.17g), want (%.17g, %.17g, %.17g)", got.x, got.y, got.z,
                want.x, want.y, want.z);
  return ::testing::AssertionFailure() << text;
}

std::shared_ptr<const Formula> compile_ok(std::string_view text) {
  FormulaError error;
  auto formula = Formula::compile(text, &error);
  EXPECT_NE(formula, nullptr) << text << "\n" << error.text();
  return formula;
}

// The error's full text ("formula:line:column: message"), or "" when the text compiles.
std::string error_of(std::string_view text) {
  FormulaError error;
  const auto formula = Formula::compile(text, &error);
  return formula ? std::string() : error.text();
}

Color value_of(std::string_view text, const FormulaInputs& inputs = {}) {
  const auto formula = compile_ok(text);
  return formula ? formula->evaluate(inputs) : Color(-999);
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Vec3 v(g(rng), g(rng), g(rng));
  return v / std::sqrt(glm::dot(v, v));
}

// Inputs of the kind a hit gives: unit N, L, V; colours in [0, 1]; a shininess n in [1, 200].
FormulaInputs random_hit(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  auto colour = [&] { return Color(unit(rng), unit(rng), unit(rng)); };
  FormulaInputs in;
  in.N = random_unit(rng);
  in.L = random_unit(rng);
  in.V = random_unit(rng);
  in.P = 10.0 * (colour() - 0.5);
  in.ka = colour(), in.kd = colour(), in.ks = colour(), in.kr = colour(), in.kt = colour();
  in.Ia = colour(), in.I = colour();
  in.n = 1 + 199 * unit(rng);
  in.ior = 1 + unit(rng);
  return in;
}

// Inputs anywhere, zeros and negatives included, so that NaNs and infinities come up.
FormulaInputs random_anything(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> wide(-3, 3);
  std::uniform_int_distribution<int> pick(0, 9);
  auto number = [&] { return pick(rng) == 0 ? 0.0 : wide(rng); };
  auto triple = [&] { return Vec3(number(), number(), number()); };
  FormulaInputs in;
  in.N = triple(), in.L = triple(), in.V = triple(), in.P = triple();
  in.ka = triple(), in.kd = triple(), in.ks = triple(), in.kr = triple(), in.kt = triple();
  in.Ia = triple(), in.I = triple();
  in.n = number(), in.ior = number();
  return in;
}

// ---- The reference formulas ----

Color ambient_in_cpp(const FormulaInputs& in) { return in.ka * in.Ia; }
Color diffuse_in_cpp(const FormulaInputs& in) { return in.kd * glm::dot(in.N, in.L); }
Color specular_in_cpp(const FormulaInputs& in) {
  const Vec3 R = -in.L - 2.0 * glm::dot(in.N, -in.L) * in.N;  // reflect(-L, N)
  return in.ks * std::pow(std::max(0.0, glm::dot(R, in.V)), in.n);
}

TEST(FormulaReference, EachSlotIsItsCppExpressionBitForBit) {
  const std::function<Color(const FormulaInputs&)> cpp[] = {ambient_in_cpp, diffuse_in_cpp, specular_in_cpp};
  std::mt19937_64 rng(20240611);
  std::vector<FormulaInputs> inputs(500);
  for (FormulaInputs& in : inputs) in = random_hit(rng);
  for (int s = 0; s < kFormulaSlots; ++s) {
    const auto slot = static_cast<FormulaSlot>(s);
    SCOPED_TRACE(formula_slot_name(slot));
    const auto formula = compile_ok(reference_formula(slot));
    ASSERT_NE(formula, nullptr);
    std::vector<Color> out(inputs.size());
    formula->evaluate(inputs.data(), inputs.size(), out.data());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      ASSERT_TRUE(same_color(out[i], cpp[s](inputs[i]))) << "hit " << i;
      ASSERT_TRUE(same_color(formula->evaluate(inputs[i]), cpp[s](inputs[i]))) << "hit " << i << " alone";
    }
  }
}

TEST(FormulaReference, SlotsAndTheirNames) {
  EXPECT_EQ(reference_formula(FormulaSlot::kAmbient), "ka * Ia");
  EXPECT_EQ(reference_formula(FormulaSlot::kDiffuse), "kd * dot(N, L)");
  EXPECT_EQ(reference_formula(FormulaSlot::kSpecular), "R = reflect(-L, N)\nks * pow(max(0, dot(R, V)), n)");
  for (int s = 0; s < kFormulaSlots; ++s) {
    const auto slot = static_cast<FormulaSlot>(s);
    EXPECT_EQ(formula_slot_from_name(formula_slot_name(slot)), slot);
  }
  EXPECT_EQ(formula_slot_from_name("emission"), std::nullopt);
  const std::vector<std::string_view> given = {"N", "L", "V", "P", "ka", "kd", "ks", "n", "kr", "kt", "ior", "Ia", "I"};
  EXPECT_EQ(formula_given_names(), given);
  EXPECT_EQ(formula_function_signatures().front(), "dot(a, b)");
  EXPECT_EQ(formula_function_signatures().size(), 16u);
}

TEST(FormulaReference, NamesReadAreTheFormulasOwn) {
  auto bit = [](std::string_view name) {
    const auto& names = formula_given_names();
    return 1u << (std::find(names.begin(), names.end(), name) - names.begin());
  };
  EXPECT_EQ(compile_ok(reference_formula(FormulaSlot::kAmbient))->names_read(), bit("ka") | bit("Ia"));
  EXPECT_EQ(compile_ok(reference_formula(FormulaSlot::kDiffuse))->names_read(), bit("kd") | bit("N") | bit("L"));
  EXPECT_EQ(compile_ok(reference_formula(FormulaSlot::kSpecular))->names_read(),
            bit("L") | bit("N") | bit("ks") | bit("V") | bit("n"));
  EXPECT_EQ(compile_ok("x = ior\nkt * kr * I * P.x + 1")->names_read(),
            bit("ior") | bit("kt") | bit("kr") | bit("I") | bit("P"));
  EXPECT_EQ(compile_ok("0.5")->names_read(), 0u);
}

TEST(FormulaReference, TraceGivesEachStatementThenTheValue) {
  std::mt19937_64 rng(7);
  const FormulaInputs in = random_hit(rng);
  const auto formula = compile_ok("R = reflect(-L, N)\nc = max(0, dot(R, V))\nc = c * 2\nks * pow(c / 2, n)");
  ASSERT_NE(formula, nullptr);
  const auto trace = formula->trace(in);
  ASSERT_EQ(trace.size(), 4u);
  const Vec3 R = -in.L - 2.0 * glm::dot(in.N, -in.L) * in.N;
  const double c = std::max(0.0, glm::dot(R, in.V));
  EXPECT_EQ(trace[0].first, "R");
  EXPECT_TRUE(trace[0].second.triple);
  EXPECT_TRUE(same_color({trace[0].second.x, trace[0].second.y, trace[0].second.z}, R));
  EXPECT_EQ(trace[1].first, "c");
  EXPECT_FALSE(trace[1].second.triple);
  EXPECT_TRUE(same(trace[1].second.x, c));
  EXPECT_EQ(trace[2].first, "c");
  EXPECT_TRUE(same(trace[2].second.x, c * 2));
  EXPECT_EQ(trace[3].first, "=");
  EXPECT_TRUE(trace[3].second.triple);
  EXPECT_TRUE(same_color({trace[3].second.x, trace[3].second.y, trace[3].second.z}, specular_in_cpp(in)));
  // A number's trace is the number alone.
  const auto grey = compile_ok("0.25")->trace(in);
  ASSERT_EQ(grey.size(), 1u);
  EXPECT_FALSE(grey[0].second.triple);
  EXPECT_EQ(grey[0].second.x, 0.25);
}

// ---- Random expressions against their direct C++ evaluation ----

// A value while evaluating directly: a number (x) or a triple.
struct Val {
  bool triple = false;
  Vec3 v{0};
  double at(int c) const { return triple ? v[c] : v.x; }
};
Val num(double x) { return {false, Vec3(x, 0, 0)}; }
Val tri(const Vec3& v) { return {true, v}; }

struct Env {
  const FormulaInputs& in;
  const std::vector<Val>& defined;  // the statements' values so far
};

// An expression: its text, its precedence as written (1 "?:", 2 "< >", 3 "+ -", 4 "* /",
// 5 unary, 6 postfix and primary), its type, and its value computed directly in C++.
struct Expr {
  std::string text;
  int precedence = 6;
  bool triple = false;
  std::function<Val(const Env&)> eval;
};

// The names of the statements so far, with their types.
struct Scope {
  std::vector<std::string> names;
  std::vector<bool> triple;
};

class Generator {
 public:
  explicit Generator(std::uint64_t seed) : rng_(seed) {}

  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  bool chance(int percent) { return pick(100) < percent; }

  // The expression's text where an operand of at least `precedence` stands (in parentheses when
  // it binds less tightly, and now and then when it does not).
  std::string at_least(const Expr& e, int precedence) {
    return e.precedence < precedence || chance(10) ? "(" + e.text + ")" : e.text;
  }

  Expr leaf(bool triple, const Scope& scope) {
    // A statement's name of the right type, now and then.
    std::vector<std::size_t> fitting;
    for (std::size_t i = 0; i < scope.names.size(); ++i) {
      if (scope.triple[i] == triple) fitting.push_back(i);
    }
    if (!fitting.empty() && chance(30)) {
      const std::size_t i = fitting[static_cast<std::size_t>(pick(static_cast<int>(fitting.size())))];
      return {scope.names[i], 6, triple, [i](const Env& env) { return env.defined[i]; }};
    }
    if (triple) {
      static const char* const names[] = {"N", "L", "V", "P", "ka", "kd", "ks", "kr", "kt", "Ia", "I"};
      static Vec3 FormulaInputs::*const fields[] = {&FormulaInputs::N,  &FormulaInputs::L,  &FormulaInputs::V,
                                                   &FormulaInputs::P,  &FormulaInputs::ka, &FormulaInputs::kd,
                                                   &FormulaInputs::ks, &FormulaInputs::kr, &FormulaInputs::kt,
                                                   &FormulaInputs::Ia, &FormulaInputs::I};
      const int i = pick(11);
      const auto field = fields[i];
      return {names[i], 6, true, [field](const Env& env) { return tri(env.in.*field); }};
    }
    switch (pick(4)) {
      case 0: return {"n", 6, false, [](const Env& env) { return num(env.in.n); }};
      case 1: return {"ior", 6, false, [](const Env& env) { return num(env.in.ior); }};
      case 2: {
        // The spellings of a number.
        static const std::pair<const char*, double> spelled[] = {
            {"1", 1}, {"0.5", 0.5}, {".5", .5}, {"1e-3", 1e-3}, {"2.5E+2", 2.5E+2}, {"0", 0}, {"2", 2}, {"3.", 3.}};
        const auto& [text, value] = spelled[pick(8)];
        const double x = value;
        return {text, 6, false, [x](const Env&) { return num(x); }};
      }
      default: {
        const double x = std::uniform_real_distribution<double>(0, 4)(rng_);
        char text[40];
        std::snprintf(text, sizeof text, "%.17g", x);
        return {text, 6, false, [x](const Env&) { return num(x); }};
      }
    }
  }

  // A random expression of the given type, at most `depth` deep.
  Expr expr(bool triple, int depth, const Scope& scope) {
    if (depth <= 0 || chance(15)) return leaf(triple, scope);
    const int d = depth - 1;
    // Operands' types for a per-component operation of this type: any mix, a triple among them
    // when the result is a triple.
    auto operand_types = [&](std::size_t count) {
      std::vector<bool> types(count, false);
      if (!triple) return types;
      for (std::size_t i = 0; i < count; ++i) types[i] = chance(50);
      types[static_cast<std::size_t>(pick(static_cast<int>(count)))] = true;
      return types;
    };
    switch (pick(triple ? 9 : 10)) {
      case 0: {  // + - * /
        const auto types = operand_types(2);
        const Expr a = expr(types[0], d, scope), b = expr(types[1], d, scope);
        const int op = pick(4);
        const int precedence = op < 2 ? 3 : 4;
        const char symbol = "+-*/"[op];
        auto fa = a.eval, fb = b.eval;
        return {at_least(a, precedence) + " " + symbol + " " + at_least(b, precedence + 1), precedence, triple,
                [fa, fb, op, triple](const Env& env) {
                  const Val x = fa(env), y = fb(env);
                  if (!triple) {
                    const double p = x.v.x, q = y.v.x;
                    return num(op == 0 ? p + q : op == 1 ? p - q : op == 2 ? p * q : p / q);
                  }
                  // GLM's own operators, broadcasting a number.
                  if (x.triple && y.triple) {
                    return tri(op == 0 ? x.v + y.v : op == 1 ? x.v - y.v : op == 2 ? x.v * y.v : x.v / y.v);
                  }
                  if (x.triple) {
                    const double q = y.v.x;
                    return tri(op == 0 ? x.v + q : op == 1 ? x.v - q : op == 2 ? x.v * q : x.v / q);
                  }
                  const double p = x.v.x;
                  return tri(op == 0 ? p + y.v : op == 1 ? p - y.v : op == 2 ? p * y.v : p / y.v);
                }};
      }
      case 1: {  // unary minus or plus
        const Expr a = expr(triple, d, scope);
        const bool minus = chance(70);
        auto fa = a.eval;
        return {std::string(minus ? "-" : "+") + at_least(a, 5), 5, triple, [fa, minus](const Env& env) {
                  Val x = fa(env);
                  if (minus) x.v = -x.v;
                  return x;
                }};
      }
      case 2: {  // c ? a : b
        const Expr c = expr(false, d, scope);
        const auto types = operand_types(2);
        const Expr a = expr(types[0], d, scope), b = expr(types[1], d, scope);
        auto fc = c.eval, fa = a.eval, fb = b.eval;
        return {at_least(c, 2) + " ? " + at_least(a, 1) + " : " + at_least(b, 1), 1, triple,
                [fc, fa, fb, triple](const Env& env) {
                  const Val x = fa(env), y = fb(env);
                  const Val& chosen = fc(env).v.x != 0 ? x : y;
                  return triple ? tri(Vec3(chosen.at(0), chosen.at(1), chosen.at(2))) : chosen;
                }};
      }
      case 3: {  // pow max min step: two arguments
        static const char* const names[] = {"pow", "max", "min", "step"};
        const int f = pick(4);
        const auto types = operand_types(2);
        const Expr a = expr(types[0], d, scope), b = expr(types[1], d, scope);
        auto fa = a.eval, fb = b.eval;
        return call(names[f], {a, b}, triple, [fa, fb, f, triple](const Env& env) {
          const Val x = fa(env), y = fb(env);
          Val out{triple, Vec3(0)};
          for (int c = 0; c < (triple ? 3 : 1); ++c) {
            const double p = x.at(c), q = y.at(c);
            out.v[c] = f == 0 ? std::pow(p, q) : f == 1 ? std::max(p, q) : f == 2 ? std::min(p, q) : (q < p ? 0.0 : 1.0);
          }
          return out;
        });
      }
      case 4: {  // abs sqrt exp log: one argument
        static const char* const names[] = {"abs", "sqrt", "exp", "log"};
        const int f = pick(4);
        const Expr a = expr(triple, d, scope);
        auto fa = a.eval;
        return call(names[f], {a}, triple, [fa, f, triple](const Env& env) {
          Val x = fa(env);
          for (int c = 0; c < (triple ? 3 : 1); ++c) {
            const double p = x.v[c];
            x.v[c] = f == 0 ? std::abs(p) : f == 1 ? std::sqrt(p) : f == 2 ? std::exp(p) : std::log(p);
          }
          return x;
        });
      }
      case 5: {  // clamp mix: three arguments
        const bool is_mix = chance(50);
        const auto types = operand_types(3);
        const Expr a = expr(types[0], d, scope), b = expr(types[1], d, scope), t = expr(types[2], d, scope);
        auto fa = a.eval, fb = b.eval, ft = t.eval;
        return call(is_mix ? "mix" : "clamp", {a, b, t}, triple, [fa, fb, ft, is_mix, triple](const Env& env) {
          const Val x = fa(env), y = fb(env), z = ft(env);
          Val out{triple, Vec3(0)};
          for (int c = 0; c < (triple ? 3 : 1); ++c) {
            const double p = x.at(c), q = y.at(c), r = z.at(c);
            out.v[c] = is_mix ? p * (1 - r) + q * r : std::min(std::max(p, q), r);
          }
          return out;
        });
      }
      case 6: {
        if (!triple) {  // a component
          const Expr a = expr(true, d, scope);
          const int c = pick(3);
          auto fa = a.eval;
          const std::string field = chance(50) ? std::string(1, "xyz"[c]) : std::string(1, "rgb"[c]);
          return {at_least(a, 6) + "." + field, 6, false, [fa, c](const Env& env) { return num(fa(env).v[c]); }};
        }
        // cross, normalize, reflect
        const int f = pick(3);
        const Expr a = expr(true, d, scope);
        auto fa = a.eval;
        if (f == 1) return call("normalize", {a}, true, [fa](const Env& env) { return tri(glm::normalize(fa(env).v)); });
        const Expr b = expr(true, d, scope);
        auto fb = b.eval;
        if (f == 0) {
          return call("cross", {a, b}, true, [fa, fb](const Env& env) { return tri(glm::cross(fa(env).v, fb(env).v)); });
        }
        return call("reflect", {a, b}, true, [fa, fb](const Env& env) {
          const Vec3 i = fa(env).v, n = fb(env).v;
          return tri(i - 2.0 * glm::dot(n, i) * n);
        });
      }
      case 7: {
        if (!triple) {  // dot, length
          const Expr a = expr(true, d, scope);
          auto fa = a.eval;
          if (chance(50)) return call("length", {a}, false, [fa](const Env& env) { return num(glm::length(fa(env).v)); });
          const Expr b = expr(true, d, scope);
          auto fb = b.eval;
          return call("dot", {a, b}, false, [fa, fb](const Env& env) { return num(glm::dot(fa(env).v, fb(env).v)); });
        }
        // (a, b, c), vec3(a, b, c), vec3(a), vec3(v)
        const int form = pick(4);
        if (form == 2 || form == 3) {
          const Expr a = expr(form == 3, d, scope);
          auto fa = a.eval;
          return call("vec3", {a}, true, [fa](const Env& env) {
            const Val x = fa(env);
            return tri(Vec3(x.at(0), x.at(1), x.at(2)));
          });
        }
        const Expr a = expr(false, d, scope), b = expr(false, d, scope), c = expr(false, d, scope);
        auto fa = a.eval, fb = b.eval, fc = c.eval;
        auto eval = [fa, fb, fc](const Env& env) { return tri(Vec3(fa(env).v.x, fb(env).v.x, fc(env).v.x)); };
        if (form == 1) return call("vec3", {a, b, c}, true, eval);
        return {"(" + a.text + ", " + b.text + ", " + c.text + ")", 6, true, eval};
      }
      case 8: {  // parentheses around anything of the type
        Expr a = expr(triple, d, scope);
        a.text = "(" + a.text + ")";
        a.precedence = 6;
        return a;
      }
      default: {  // a < b, a > b (numbers only)
        const Expr a = expr(false, d, scope), b = expr(false, d, scope);
        const bool less = chance(50);
        auto fa = a.eval, fb = b.eval;
        return {at_least(a, 2) + (less ? " < " : " > ") + at_least(b, 3), 2, false, [fa, fb, less](const Env& env) {
                  const double p = fa(env).v.x, q = fb(env).v.x;
                  return num((less ? p < q : p > q) ? 1.0 : 0.0);
                }};
      }
    }
  }

 private:
  Expr call(const char* name, std::vector<Expr> args, bool triple, std::function<Val(const Env&)> eval) {
    std::string text = std::string(name) + "(";
    for (std::size_t i = 0; i < args.size(); ++i) text += (i ? ", " : "") + args[i].text;
    return {text + ")", 6, triple, std::move(eval)};
  }

  std::mt19937_64 rng_;
};

// A random formula: a few statements, then a final expression, with its direct evaluation.
struct RandomFormula {
  std::string text;
  std::vector<Expr> statements;
  Expr final_value;

  Color direct(const FormulaInputs& in) const {
    std::vector<Val> defined;
    const Env env{in, defined};
    for (const Expr& s : statements) defined.push_back(s.eval(env));
    const Val v = final_value.eval(env);
    return v.triple ? v.v : Color(v.v.x);
  }
};

RandomFormula random_formula(Generator& gen) {
  RandomFormula f;
  Scope scope;
  const int statements = gen.pick(4);
  for (int i = 0; i < statements; ++i) {
    const bool triple = gen.chance(50);
    Expr e = gen.expr(triple, 1 + gen.pick(4), scope);
    std::string name = "t";
    name += std::to_string(i);
    f.text += name + " = " + e.text + (gen.chance(50) ? "\n" : "; ");
    scope.names.push_back(name);
    scope.triple.push_back(triple);
    f.statements.push_back(std::move(e));
  }
  f.final_value = gen.expr(gen.chance(60), 1 + gen.pick(5), scope);
  f.text += f.final_value.text;
  return f;
}

TEST(FormulaProperty, RandomExpressionsEqualTheirCppEvaluationBitForBit) {
  Generator gen(424242);
  std::mt19937_64 rng(99);
  constexpr std::size_t kHits = 200;  // more than three blocks of Formula::kLanes
  std::size_t nans = 0, values = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const RandomFormula f = random_formula(gen);
    SCOPED_TRACE(f.text);
    const auto formula = compile_ok(f.text);
    ASSERT_NE(formula, nullptr);
    std::vector<FormulaInputs> inputs(kHits);
    for (std::size_t i = 0; i < kHits; ++i) inputs[i] = i % 2 ? random_hit(rng) : random_anything(rng);
    std::vector<Color> out(kHits);
    formula->evaluate(inputs.data(), kHits, out.data());
    for (std::size_t i = 0; i < kHits; ++i) {
      const Color want = f.direct(inputs[i]);
      ASSERT_TRUE(same_color(out[i], want)) << "hit " << i << " of " << kHits;
      if (i % 16 == 0) {
        ASSERT_TRUE(same_color(formula->evaluate(inputs[i]), want)) << "hit " << i << " alone";
        const auto trace = formula->trace(inputs[i]);
        ASSERT_EQ(trace.size(), f.statements.size() + 1);
        const FormulaValue& last = trace.back().second;
        ASSERT_TRUE(same_color(last.triple ? Color(last.x, last.y, last.z) : Color(last.x), want));
      }
      nans += std::isnan(want.x) ? 1 : 0;
      ++values;
    }
  }
  // The inputs reach NaN now and then, and mostly do not.
  EXPECT_GT(nans, 0u);
  EXPECT_LT(nans, values / 2);
}

// ---- The language ----

TEST(FormulaLanguage, PrecedenceAndAssociativity) {
  EXPECT_EQ(value_of("1 + 2 * 3"), Color(7));
  EXPECT_EQ(value_of("(1 + 2) * 3"), Color(9));
  EXPECT_EQ(value_of("8 - 4 - 2"), Color(2));
  EXPECT_EQ(value_of("8 / 4 / 2"), Color(1));
  EXPECT_EQ(value_of("-2 * -3"), Color(6));
  EXPECT_EQ(value_of("- -2"), Color(2));
  EXPECT_EQ(value_of("+2"), Color(2));
  EXPECT_EQ(value_of("1 + 2 < 4"), Color(1));  // (1 + 2) < 4
  EXPECT_EQ(value_of("1 < 2 ? 5 : 6"), Color(5));
  EXPECT_EQ(value_of("0 ? 1 : 0 ? 2 : 3"), Color(3));  // 0 ? 1 : (0 ? 2 : 3)
  EXPECT_EQ(value_of("1 ? 0 ? 7 : 8 : 9"), Color(8));
  EXPECT_EQ(value_of("3 > 2 > 0"), Color(1));  // (3 > 2) > 0
  EXPECT_EQ(value_of("-(1, 2, 3).y"), Color(-2));  // -((1, 2, 3).y)
}

TEST(FormulaLanguage, NumbersTriplesAndBroadcasting) {
  EXPECT_EQ(value_of(".5"), Color(0.5));
  EXPECT_EQ(value_of("1e-3"), Color(1e-3));
  EXPECT_EQ(value_of("2.5E+2"), Color(250));
  EXPECT_EQ(value_of("(1, 2, 3)"), Color(1, 2, 3));
  EXPECT_EQ(value_of("vec3(1, 2, 3) * 2"), Color(2, 4, 6));
  EXPECT_EQ(value_of("vec3(0.5)"), Color(0.5));
  EXPECT_EQ(value_of("vec3((1, 2, 3))"), Color(1, 2, 3));
  EXPECT_EQ(value_of("1 - (1, 2, 3)"), Color(0, -1, -2));
  EXPECT_EQ(value_of("(1, 2, 3).z + (4, 5, 6).g"), Color(8));
  EXPECT_EQ(value_of("max(2, (1, 2, 3))"), Color(2, 2, 3));
  EXPECT_EQ(value_of("pow((1, 2, 3), 2)"), Color(1, 4, 9));
  EXPECT_EQ(value_of("clamp((-1, 0.5, 2), 0, 1)"), Color(0, 0.5, 1));
  EXPECT_EQ(value_of("step(0.5, (0, 0.5, 1))"), Color(0, 1, 1));
  EXPECT_EQ(value_of("mix(0, (2, 4, 8), 0.5)"), Color(1, 2, 4));
  EXPECT_EQ(value_of("1 ? (1, 2, 3) : 0"), Color(1, 2, 3));
  EXPECT_EQ(value_of("0 ? (1, 2, 3) : 7"), Color(7));
  EXPECT_EQ(value_of("cross((1, 0, 0), (0, 1, 0))"), Color(0, 0, 1));
  EXPECT_EQ(value_of("length((3, 4, 0))"), Color(5));
  EXPECT_EQ(value_of("reflect((1, -1, 0), (0, 1, 0))"), Color(1, 1, 0));
  EXPECT_EQ(value_of("abs(-2) + sqrt(9) + exp(0) + log(1)"), Color(6));
}

TEST(FormulaLanguage, NaNAndInfinitiesAreKept) {
  const Color root = value_of("sqrt(-1)");
  EXPECT_TRUE(std::isnan(root.x) && std::isnan(root.y) && std::isnan(root.z));
  EXPECT_EQ(value_of("1 / 0"), Color(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(value_of("-1 / 0").x, -std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(value_of("normalize((0, 0, 0))").x));
  EXPECT_EQ(value_of("max(0, sqrt(-1))"), Color(0));  // std::max(0, NaN) is 0
  EXPECT_TRUE(std::isnan(value_of("max(sqrt(-1), 0)").x));
}

TEST(FormulaLanguage, StatementsCommentsAndLines) {
  FormulaInputs in;
  in.kd = Color(0.5, 0.25, 1);
  in.N = Vec3(0, 0, 1);
  in.L = Vec3(0, 0.6, 0.8);
  const Color want = in.kd * 0.8;
  EXPECT_EQ(value_of("# Lambert\nc = dot(N, L)  # the cosine\n\n\nkd * c\n\n", in), want);
  EXPECT_EQ(value_of("c = dot(N, L); kd * c;", in), want);
  EXPECT_EQ(value_of(";;c = 1; c = c + 1;\n c * 2", in), Color(4));  // reassigning: later wins
  EXPECT_EQ(value_of("kd * dot(N,\n        L)", in), want);    // a new line inside parentheses
  EXPECT_EQ(value_of("kd *\n  dot(N, L)", in), want);         // ... or after an operator
  EXPECT_EQ(value_of("c = 1 > 0 ?\n  2 :\n  3\nc", in), Color(2));
  EXPECT_EQ(value_of("x = 1\r\nx + 1\r\n", in), Color(2));
  EXPECT_EQ(value_of("kd * dot(N, L)", in), compile_ok("kd*dot(N,L)")->evaluate(in));
}

TEST(FormulaLanguage, EvaluatesAnyCountInBlocks) {
  const auto formula = compile_ok("kd * P.x + 1");
  ASSERT_NE(formula, nullptr);
  for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{63}, std::size_t{64}, std::size_t{65},
                                  std::size_t{129}, std::size_t{1000}}) {
    std::vector<FormulaInputs> inputs(count);
    for (std::size_t i = 0; i < count; ++i) {
      inputs[i].kd = Color(1, 2, 3);
      inputs[i].P.x = static_cast<double>(i);
    }
    std::vector<Color> out(count, Color(-1));
    formula->evaluate(inputs.data(), count, out.data());
    for (std::size_t i = 0; i < count; ++i) {
      const double x = static_cast<double>(i);
      ASSERT_EQ(out[i], Color(x + 1, 2 * x + 1, 3 * x + 1)) << i << " of " << count;
    }
  }
}

// ---- Errors: one of each kind, with its position ----

TEST(FormulaErrors, UnknownNameWithSuggestion) {
  EXPECT_EQ(error_of("kd * max(0, dot(normalize(P), nrm))"), "formula:1:31: unknown name \"nrm\" (did you mean \"N\"?)");
  EXPECT_EQ(error_of("ia * ka"), "formula:1:1: unknown name \"ia\" (did you mean \"Ia\"?)");  // case aside
  // The names defined so far are candidates too, after the given ones.
  EXPECT_EQ(error_of("diffuse = kd * dot(N, L)\ndifuse"), "formula:2:1: unknown name \"difuse\" (did you mean \"diffuse\"?)");
  EXPECT_EQ(error_of("shiny = ks\nshnie"), "formula:2:1: unknown name \"shnie\" (did you mean \"shiny\"?)");
}

TEST(FormulaErrors, UnknownNameWithoutSuggestion) {
  EXPECT_EQ(error_of("kd * shininess"), "formula:1:6: unknown name \"shininess\"");
  EXPECT_EQ(error_of("x = kd\nspecularity"), "formula:2:1: unknown name \"specularity\"");
}

TEST(FormulaErrors, UnknownFunction) {
  EXPECT_EQ(error_of("kd * dott(N, L)"), "formula:1:6: unknown function \"dott\" (did you mean \"dot\"?)");
  EXPECT_EQ(error_of("normalise(N)"), "formula:1:1: unknown function \"normalise\" (did you mean \"normalize\"?)");
  EXPECT_EQ(error_of("saturate(n)"), "formula:1:1: unknown function \"saturate\"");
}

TEST(FormulaErrors, NameAsFunctionAndFunctionAsValue) {
  EXPECT_EQ(error_of("kd * N(1)"), "formula:1:6: \"N\" is a name, not a function");
  EXPECT_EQ(error_of("c = 1\nc(2)"), "formula:2:1: \"c\" is a name, not a function");
  EXPECT_EQ(error_of("kd * dot"), "formula:1:6: \"dot\" is a function: call it, as in dot(a, b)");
  EXPECT_EQ(error_of("max = 1\nmax"), "formula:1:1: \"max\" is a function: choose another name");
}

TEST(FormulaErrors, WrongArgumentTypes) {
  EXPECT_EQ(error_of("dot(N, 1)"), "formula:1:1: dot() takes two vectors (got a number)");
  EXPECT_EQ(error_of("kd * dot(n, L)"), "formula:1:6: dot() takes two vectors (got a number)");
  EXPECT_EQ(error_of("normalize(n)"), "formula:1:1: normalize() takes one vector (got a number)");
  EXPECT_EQ(error_of("cross(N, 2)"), "formula:1:1: cross() takes two vectors (got a number)");
  EXPECT_EQ(error_of("length(ior)"), "formula:1:1: length() takes one vector (got a number)");
  EXPECT_EQ(error_of("reflect(-L, 1)"), "formula:1:1: reflect() takes two vectors (got a number)");
  EXPECT_EQ(error_of("vec3(N, 1, 2)"), "formula:1:6: vec3() takes three numbers (got a triple)");
  EXPECT_EQ(error_of("(1, V, 2)"), "formula:1:5: a triple's components are numbers (got a triple)");
  EXPECT_EQ(error_of("N < L"), "formula:1:3: \"<\" compares numbers (got a triple)");
  EXPECT_EQ(error_of("1 > V"), "formula:1:3: \">\" compares numbers (got a triple)");
  EXPECT_EQ(error_of("N ? 1 : 2"), "formula:1:3: the condition before \"?\" must be a number (got a triple)");
  EXPECT_EQ(error_of("n.x"), "formula:1:2: \".x\" needs a triple (got a number)");
  EXPECT_EQ(error_of("N.w"), "formula:1:3: unknown component \".w\" (a triple has .x .y .z or .r .g .b)");
}

TEST(FormulaErrors, WrongArgumentCounts) {
  EXPECT_EQ(error_of("pow(1, 2, 3)"), "formula:1:1: pow() takes two arguments (got 3)");
  EXPECT_EQ(error_of("ks * clamp(1, 2)"), "formula:1:6: clamp() takes three arguments (got 2)");
  EXPECT_EQ(error_of("abs()"), "formula:1:1: abs() takes one argument (got 0)");
  EXPECT_EQ(error_of("dot(N)"), "formula:1:1: dot() takes two vectors (got 1 argument)");
  EXPECT_EQ(error_of("normalize(N, L)"), "formula:1:1: normalize() takes one vector (got 2 arguments)");
  EXPECT_EQ(error_of("vec3(1, 2)"), "formula:1:1: vec3() takes one or three arguments (got 2)");
  EXPECT_EQ(error_of("(1, 2)"), "formula:1:1: a triple has three components, (a, b, c) (got 2)");
}

TEST(FormulaErrors, Syntax) {
  EXPECT_EQ(error_of("kd * max(0, dot(N, L)"), "formula:1:22: expected \")\" to close \"(\" at 1:9");
  EXPECT_EQ(error_of("kd * (dot(N, L); 1"), "formula:1:16: expected \")\" to close \"(\" at 1:6");
  EXPECT_EQ(error_of("kd * * N"), "formula:1:6: expected an expression (got \"*\")");
  EXPECT_EQ(error_of("kd *"), "formula:1:5: expected an expression (got the end of the formula)");
  EXPECT_EQ(error_of("x = ; 1"), "formula:1:5: expected an expression (got \";\")");
  EXPECT_EQ(error_of("ka @ Ia"), "formula:1:4: unexpected \"@\"");
  EXPECT_EQ(error_of("ka \xe2\x88\x92 Ia"), "formula:1:4: unexpected \"\xe2\x88\x92\" (type - for minus)");
  EXPECT_EQ(error_of("ka \xff"), "formula:1:4: unexpected byte 0xff");
  EXPECT_EQ(error_of("1e * kd"), "formula:1:1: malformed number \"1e\"");
  EXPECT_EQ(error_of("kd * 0.5f"), "formula:1:6: malformed number \"0.5f\"");
  EXPECT_EQ(error_of("1.2.3"), "formula:1:1: malformed number \"1.2.3\"");
  EXPECT_EQ(error_of("1e999"), "formula:1:1: number \"1e999\" is out of range");
  EXPECT_EQ(error_of("kd dot(N, L)"), "formula:1:4: expected an operator, \";\" or a new line (got \"dot\")");
  EXPECT_EQ(error_of("kd)"), "formula:1:3: unexpected \")\" (no \"(\" to close)");
  EXPECT_EQ(error_of("1 ? 2"), "formula:1:6: expected \":\" for the \"?\" at 1:3 (got the end of the formula)");
  EXPECT_EQ(error_of("N."), "formula:1:3: expected a component after \".\": x, y, z or r, g, b (got the end of the formula)");
  // Only the first error: the unknown name comes before the unexpected character.
  EXPECT_EQ(error_of("nrm @"), "formula:1:1: unknown name \"nrm\" (did you mean \"N\"?)");
}

TEST(FormulaErrors, GivenNameAssigned) {
  EXPECT_EQ(error_of("N = normalize(P)\nkd * dot(N, L)"), "formula:1:1: \"N\" is given: choose a name of its own");
  EXPECT_EQ(error_of("x = 1\n  L = V\nx"), "formula:2:3: \"L\" is given: choose a name of its own");
}

TEST(FormulaErrors, MissingFinalExpression) {
  EXPECT_EQ(error_of("R = reflect(-L, N)"), "formula:1:19: a formula ends with an expression (the term's value)");
  EXPECT_EQ(error_of("R = reflect(-L, N)\n"), "formula:2:1: a formula ends with an expression (the term's value)");
  EXPECT_EQ(error_of(""), "formula:1:1: a formula ends with an expression (the term's value)");
  EXPECT_EQ(error_of("# nothing yet\n"), "formula:2:1: a formula ends with an expression (the term's value)");
  EXPECT_EQ(error_of("kd * dot(N, L)\nc = 1"),
            "formula:1:1: only the last statement is the term's value: name this one (\"name = ...\") or remove it");
}

TEST(FormulaErrors, PositionsOnLaterLines) {
  EXPECT_EQ(error_of("R = reflect(-L, N)\nks * pow(max(0, dot(R, V)), nn)"),
            "formula:2:29: unknown name \"nn\" (did you mean \"N\"?)");
  EXPECT_EQ(error_of("# the specular term\nR = reflect(-L, N)\n\n  ks * pow(max(0, dot(R, V)), n"),
            "formula:4:32: expected \")\" to close \"(\" at 4:11");
  FormulaError error;
  EXPECT_EQ(Formula::compile("x = 1\n\tx +", &error, "spec.txt"), nullptr);
  EXPECT_EQ(error.text(), "spec.txt:2:5: expected an expression (got the end of the formula)");
  EXPECT_EQ(error.line, 2);
  EXPECT_EQ(error.column, 5);
  EXPECT_EQ(Formula::compile("@", nullptr), nullptr);  // no error wanted: just nothing
}

TEST(FormulaErrors, Limits) {
  // Text: 64 KiB at most.
  std::string longest = "1";
  longest.append(64 * 1024 - 1, ' ');
  EXPECT_EQ(error_of(longest), "");
  EXPECT_EQ(error_of(longest + " "), "formula:1:1: the formula is longer than 64 KiB (65537 bytes)");
  // Nesting: 256 at most.
  EXPECT_EQ(error_of(std::string(256, '(') + "1" + std::string(256, ')')), "");
  EXPECT_EQ(error_of(std::string(257, '(') + "1" + std::string(257, ')')), "formula:1:257: nesting deeper than 256");
  EXPECT_EQ(error_of(std::string(256, '-') + "1"), "");
  EXPECT_EQ(error_of(std::string(257, '-') + "1"), "formula:1:257: nesting deeper than 256");
  std::string calls;
  for (int i = 0; i < 300; ++i) calls += "abs(";
  EXPECT_EQ(error_of(calls + "1" + std::string(300, ')')), "formula:1:1028: nesting deeper than 256");
  std::string ternaries;
  for (int i = 0; i < 300; ++i) ternaries += "1 ? 2 : ";
  EXPECT_NE(error_of(ternaries + "3").find("nesting deeper than 256"), std::string::npos);
  // Instructions: 4096 at most (one constant, 4095 additions; then one more).
  std::string sum = "1";
  for (int i = 0; i < 4095; ++i) sum += "+1";
  EXPECT_EQ(error_of(sum), "");
  EXPECT_EQ(value_of(sum), Color(4096));
  EXPECT_EQ(error_of(sum + "+1"), "formula:1:8194: the formula is too long: more than 4096 instructions");
  // Many distinct constants count too.
  std::string constants;
  for (int i = 0; i < 5000; ++i) constants += "c = " + std::to_string(i) + "\n";
  EXPECT_NE(error_of(constants + "c").find("more than 4096 instructions"), std::string::npos);
}

}  // namespace
