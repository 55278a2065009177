// The formula language (formula.h, docs/formulas.md). Three parts:
//   - the lexer: the text to tokens, stopping at the first character it cannot read;
//   - the compiler: a recursive-descent parser (precedence climbing for the binary operators)
//     that emits instructions as it reads, so there is no syntax tree. Every value is statically
//     a number (one register) or a triple (three registers); a number's three "components" are
//     its one register, which makes broadcasting free;
//   - the evaluator: each instruction is one operation on number registers, run as a loop over
//     the hits of a block (up to kLanes), which the compiler can vectorise.
// Registers are assigned once (no register is ever overwritten), so after a run every
// statement's value is still in its registers for trace().
// This file is compiled with -ffp-contract=off: a formula's value is the plain C++ expression's,
// bit for bit, never a fused multiply-add.
#include "check/formula.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <string>
#include <system_error>
#include <tuple>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/scene/chars.h"

namespace phonglab {

std::optional<FormulaSlot> formula_slot_from_name(std::string_view name) {
  for (int i = 0; i < kFormulaSlots; ++i) {
    const auto slot = static_cast<FormulaSlot>(i);
    if (formula_slot_name(slot) == name) return slot;
  }
  return std::nullopt;
}

std::string_view formula_slot_name(FormulaSlot slot) {
  switch (slot) {
    case FormulaSlot::kAmbient: return "ambient";
    case FormulaSlot::kDiffuse: return "diffuse";
    case FormulaSlot::kSpecular: return "specular";
  }
  return "";
}

std::string_view reference_formula(FormulaSlot slot) {
  switch (slot) {
    case FormulaSlot::kAmbient: return "ka * Ia";
    case FormulaSlot::kDiffuse: return "kd * dot(N, L)";
    case FormulaSlot::kSpecular: return "R = reflect(-L, N)\nks * pow(max(0, dot(R, V)), n)";
  }
  return "";
}

std::string FormulaError::text() const {
  return source + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message;
}

namespace {

constexpr std::size_t kMaxTextBytes = 64 * 1024;
constexpr int kMaxDepth = 256;
constexpr std::size_t kMaxInstructions = 4096;  // operations and constants together
constexpr std::size_t kMaxSuggestedLength = 64;  // longer names are not compared for did-you-mean

// ---- The names a hit gives ----

// A given name and the field of FormulaInputs it reads (a triple or a number).
struct Given {
  std::string_view name;
  Vec3 FormulaInputs::*triple;
  double FormulaInputs::*number;
};
constexpr std::array<Given, 13> kGiven = {{
    {"N", &FormulaInputs::N, nullptr},
    {"L", &FormulaInputs::L, nullptr},
    {"V", &FormulaInputs::V, nullptr},
    {"P", &FormulaInputs::P, nullptr},
    {"ka", &FormulaInputs::ka, nullptr},
    {"kd", &FormulaInputs::kd, nullptr},
    {"ks", &FormulaInputs::ks, nullptr},
    {"n", nullptr, &FormulaInputs::n},
    {"kr", &FormulaInputs::kr, nullptr},
    {"kt", &FormulaInputs::kt, nullptr},
    {"ior", nullptr, &FormulaInputs::ior},
    {"Ia", &FormulaInputs::Ia, nullptr},
    {"I", &FormulaInputs::I, nullptr},
}};

// The given names own the first registers, in the list's order (three for a triple): the first
// of each, and then how many there are.
constexpr std::array<std::uint32_t, kGiven.size() + 1> given_registers() {
  std::array<std::uint32_t, kGiven.size() + 1> first{};
  for (std::size_t i = 0; i < kGiven.size(); ++i) first[i + 1] = first[i] + (kGiven[i].triple != nullptr ? 3 : 1);
  return first;
}
constexpr auto kGivenRegister = given_registers();
constexpr std::uint32_t kGivenRegisters = kGivenRegister.back();

// ---- The functions ----

enum class Function : std::uint8_t {
  kDot, kCross, kNormalize, kLength, kReflect, kPow, kMax, kMin, kClamp, kAbs, kSqrt, kExp, kLog,
  kMix, kStep, kVec3
};
struct FunctionInfo {
  std::string_view name, signature;
  Function function;
};
constexpr std::array<FunctionInfo, 16> kFunctions = {{
    {"dot", "dot(a, b)", Function::kDot},
    {"cross", "cross(a, b)", Function::kCross},
    {"normalize", "normalize(v)", Function::kNormalize},
    {"length", "length(v)", Function::kLength},
    {"reflect", "reflect(I, N)", Function::kReflect},
    {"pow", "pow(x, y)", Function::kPow},
    {"max", "max(a, b)", Function::kMax},
    {"min", "min(a, b)", Function::kMin},
    {"clamp", "clamp(x, lo, hi)", Function::kClamp},
    {"abs", "abs(x)", Function::kAbs},
    {"sqrt", "sqrt(x)", Function::kSqrt},
    {"exp", "exp(x)", Function::kExp},
    {"log", "log(x)", Function::kLog},
    {"mix", "mix(a, b, t)", Function::kMix},
    {"step", "step(edge, x)", Function::kStep},
    {"vec3", "vec3(x, y, z)", Function::kVec3},
}};

const FunctionInfo* find_function(std::string_view name) {
  for (const FunctionInfo& f : kFunctions) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

int find_given(std::string_view name) {
  for (std::size_t i = 0; i < kGiven.size(); ++i) {
    if (kGiven[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

// ---- Did you mean ----

char fold(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

// Damerau-Levenshtein distance (insertions, deletions, substitutions and transpositions of
// adjacent characters, with edits between them allowed), ignoring case. Names are short: the
// caller compares names of at most kMaxSuggestedLength characters.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t rows = a.size() + 2, cols = b.size() + 2;
  const std::size_t infinity = a.size() + b.size();
  std::vector<std::size_t> d(rows * cols, 0);
  auto at = [&](std::size_t i, std::size_t j) -> std::size_t& { return d[i * cols + j]; };
  std::array<std::size_t, 256> last_row{};  // the last row of a where each character was seen
  at(0, 0) = infinity;
  for (std::size_t i = 0; i <= a.size(); ++i) {
    at(i + 1, 0) = infinity;
    at(i + 1, 1) = i;
  }
  for (std::size_t j = 0; j <= b.size(); ++j) {
    at(0, j + 1) = infinity;
    at(1, j + 1) = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t last_match_col = 0;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t k = last_row[static_cast<unsigned char>(fold(b[j - 1]))];
      const std::size_t l = last_match_col;
      const bool same = fold(a[i - 1]) == fold(b[j - 1]);
      if (same) last_match_col = j;
      at(i + 1, j + 1) = std::min({at(i, j) + (same ? 0 : 1), at(i + 1, j) + 1, at(i, j + 1) + 1,
                                   at(k, l) + (i - k - 1) + 1 + (j - l - 1)});
    }
    last_row[static_cast<unsigned char>(fold(a[i - 1]))] = i;
  }
  return at(a.size() + 1, b.size() + 1);
}

// The nearest candidate within reach (distance at most 2, or a third of the longer name), the
// earlier on a tie; empty when none is.
std::string_view nearest(std::string_view name, const std::vector<std::string_view>& candidates) {
  std::string_view best;
  std::size_t best_distance = 0;
  if (name.size() > kMaxSuggestedLength) return best;
  for (const std::string_view candidate : candidates) {
    if (candidate.size() > kMaxSuggestedLength) continue;
    const std::size_t distance = edit_distance(name, candidate);
    const std::size_t longer = std::max(name.size(), candidate.size());
    if (distance > 2 && distance * 3 > longer) continue;
    if (best.empty() || distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

std::string did_you_mean(std::string_view name, const std::vector<std::string_view>& candidates) {
  const std::string_view best = nearest(name, candidates);
  return best.empty() ? std::string() : " (did you mean \"" + std::string(best) + "\"?)";
}

// 1-based line and column (in bytes) of a byte offset.
std::pair<int, int> line_and_column(std::string_view text, std::size_t at) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < at && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  }
  return {line, static_cast<int>(at - line_start + 1)};
}

// ---- Tokens ----

enum class Kind : std::uint8_t { kNumber, kName, kSymbol, kNewline, kEnd, kBad };
struct Token {
  Kind kind;
  char symbol = 0;  // kSymbol: one of + - * / < > ? : ( ) , ; = .
  std::size_t begin = 0, end = 0;  // bytes of the text
  double number = 0;
};

struct Lexed {
  std::vector<Token> tokens;  // ends with kEnd, or with kBad where the text cannot be read
  std::string bad;            // what is wrong at the kBad token
};

bool is_name_start(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }

// How to show a character the lexer cannot read: itself when printable or a whole UTF-8
// character (with the ASCII to type for the usual mathematical ones), else its byte.
std::string describe_unexpected(std::string_view text, std::size_t at, std::size_t* length) {
  const auto lead = static_cast<unsigned char>(text[at]);
  *length = 1;
  if (lead >= 0x21 && lead < 0x7f) return "unexpected \"" + std::string(1, text[at]) + "\"";
  const std::size_t size = lead >= 0xc2 && lead < 0xe0 ? 2 : lead >= 0xe0 && lead < 0xf0 ? 3 : lead >= 0xf0 && lead < 0xf5 ? 4 : 0;
  bool whole = size > 0 && at + size <= text.size();
  for (std::size_t i = 1; whole && i < size; ++i) whole = (static_cast<unsigned char>(text[at + i]) & 0xc0) == 0x80;
  if (!whole) {
    static constexpr char kHex[] = "0123456789abcdef";
    return std::string("unexpected byte 0x") + kHex[lead >> 4] + kHex[lead & 15];
  }
  *length = size;
  const std::string character(text.substr(at, size));
  std::string hint;
  if (character == "\u2212") hint = " (type - for minus)";
  if (character == "\u00d7" || character == "\u00b7" || character == "\u22c5") hint = " (type * to multiply)";
  if (character == "\u00f7") hint = " (type / to divide)";
  return "unexpected \"" + character + "\"" + hint;
}

Lexed lex(std::string_view text) {
  Lexed out;
  std::size_t i = 0;
  auto push = [&](Kind kind, std::size_t begin, std::size_t end) {
    Token t{kind};
    t.begin = begin;
    t.end = end;
    out.tokens.push_back(t);
    return &out.tokens.back();
  };
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') {
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '\n') {
      push(Kind::kNewline, i, i + 1);
      ++i;
    } else if (is_name_start(c)) {
      const std::size_t begin = i;
      while (i < text.size() && is_name_char(text[i])) ++i;
      push(Kind::kName, begin, i);
    } else if (is_digit(c) || (c == '.' && i + 1 < text.size() && is_digit(text[i + 1]))) {
      // digits [. digits] [e [+-] digits], or . digits [...]; anything glued on is part of a
      // malformed number ("1e", "1.5f", "2x").
      const std::size_t begin = i;
      bool ok = true;
      while (i < text.size() && is_digit(text[i])) ++i;
      if (i < text.size() && text[i] == '.') {
        ++i;
        while (i < text.size() && is_digit(text[i])) ++i;
      }
      if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
        ok = i < text.size() && is_digit(text[i]);
        while (i < text.size() && is_digit(text[i])) ++i;
      }
      if (i < text.size() && (is_name_char(text[i]) || text[i] == '.')) {
        ok = false;
        while (i < text.size() && (is_name_char(text[i]) || text[i] == '.')) ++i;
      }
      const std::string_view digits = text.substr(begin, i - begin);
      Token* t = push(Kind::kNumber, begin, i);
      if (ok) {
        const auto [end, ec] = double_from_chars(digits.data(), digits.data() + digits.size(), t->number);
        if (ec == std::errc::result_out_of_range) {
          t->kind = Kind::kBad;
          out.bad = "number \"" + std::string(digits) + "\" is out of range";
          return out;
        }
        ok = ec == std::errc() && end == digits.data() + digits.size();
      }
      if (!ok) {
        t->kind = Kind::kBad;
        out.bad = "malformed number \"" + std::string(digits) + "\"";
        return out;
      }
    } else if (std::strchr("+-*/<>?:(),;=.", c) != nullptr && c != 0) {
      push(Kind::kSymbol, i, i + 1)->symbol = c;
      ++i;
    } else {
      std::size_t length = 1;
      out.bad = describe_unexpected(text, i, &length);
      push(Kind::kBad, i, i + length);
      return out;
    }
  }
  push(Kind::kEnd, text.size(), text.size());
  return out;
}

// ---- Instructions ----

// One operation on number registers, per lane: d = op(a, b, c).
enum class Op : std::uint8_t {
  kAdd, kSub, kMul, kDiv, kNeg,
  kLess, kGreater,  // 1 or 0
  kSelect,          // a != 0 ? b : c
  kPow, kMax, kMin, kAbs, kSqrt, kExp, kLog,
  kStep,            // b < a ? 0 : 1 (a the edge)
};
struct Instruction {
  Op op;
  std::uint32_t d, a, b, c;
};

// A value at compile time: a number (its register three times) or a triple.
struct Value {
  bool triple = false;
  std::array<std::uint32_t, 3> r{};
};
Value number_value(std::uint32_t r) { return {false, {r, r, r}}; }

struct CompileError {
  std::size_t at;  // byte offset
  std::string message;
};

}  // namespace

struct Formula::Program {
  std::uint32_t registers = kGivenRegisters;
  std::vector<std::pair<std::uint32_t, double>> constants;  // filled once per evaluate
  std::vector<Instruction> code;
  struct Statement {
    std::string name;
    Value value;
  };
  std::vector<Statement> statements;
  Value result;

  void run(const FormulaSource& source, std::size_t count, std::uint32_t names_read, double* regs,
           std::size_t stride, Color* out) const;
};

namespace {

// ---- The compiler ----

class Compiler {
 public:
  Compiler(std::string_view text, const Lexed& lexed, Formula::Program& program)
      : text_(text), lexed_(lexed), tokens_(lexed.tokens), program_(program) {}

  std::uint32_t names_read() const { return names_read_; }

  // formula = { statement (newline | ";") } expression, with blank statements anywhere.
  void compile() {
    std::size_t pending_final = 0;  // where a bare expression not (yet) the last began
    bool have_final = false;
    for (;;) {
      while (at_separator()) ++pos_;
      if (peek().kind == Kind::kEnd) break;
      if (have_final) {
        fail(pending_final, "only the last statement is the term's value: name this one (\"name = ...\") or remove it");
      }
      const Token& first = peek();
      if (first.kind == Kind::kName && tokens_[pos_ + 1].kind == Kind::kSymbol && tokens_[pos_ + 1].symbol == '=') {
        const std::string_view name = spelling(first);
        if (find_given(name) >= 0) fail(first.begin, quoted(name) + " is given: choose a name of its own");
        if (find_function(name) != nullptr) fail(first.begin, quoted(name) + " is a function: choose another name");
        pos_ += 2;
        const Value value = expression();
        define(name, value);
        program_.statements.push_back({std::string(name), value});
      } else {
        pending_final = first.begin;
        program_.result = expression();
        have_final = true;
      }
      const Token& after = peek();
      if (!at_separator() && after.kind != Kind::kEnd) {
        if (after.kind == Kind::kSymbol && after.symbol == ')') fail(after.begin, "unexpected \")\" (no \"(\" to close)");
        unexpected(after, "expected an operator, \";\" or a new line (got " + describe(after) + ")");
      }
    }
    if (!have_final) fail(text_.size(), "a formula ends with an expression (the term's value)");
  }

 private:
  // -- Reading tokens --

  // The next token; inside parentheses a new line is only space. A token the lexer could not
  // read is reported when the parser takes it or finds it where something else was expected, so
  // an earlier error in the text is reported first.
  const Token& peek() {
    while (paren_depth_ > 0 && tokens_[pos_].kind == Kind::kNewline) ++pos_;
    return tokens_[pos_];
  }
  const Token& next() {
    const Token& t = peek();
    if (t.kind == Kind::kBad) fail(t.begin, lexed_.bad);
    if (t.kind != Kind::kEnd) ++pos_;
    return t;
  }
  // `t` is not what the grammar expects here: `message` (or what the lexer found wrong there).
  [[noreturn]] void unexpected(const Token& t, const std::string& message) const {
    fail(t.begin, t.kind == Kind::kBad ? lexed_.bad : message);
  }
  bool at_symbol(char symbol) {
    const Token& t = peek();
    return t.kind == Kind::kSymbol && t.symbol == symbol;
  }
  bool at_separator() {
    const Token& t = peek();
    return t.kind == Kind::kNewline || (t.kind == Kind::kSymbol && t.symbol == ';');
  }
  std::string_view spelling(const Token& t) const { return text_.substr(t.begin, t.end - t.begin); }
  static std::string quoted(std::string_view s) {
    std::string out(1, '"');
    out.append(s).push_back('"');
    return out;
  }
  std::string describe(const Token& t) const {
    if (t.kind == Kind::kEnd) return "the end of the formula";
    if (t.kind == Kind::kNewline) return "the end of the line";
    return quoted(spelling(t));
  }

  [[noreturn]] static void fail(std::size_t at, std::string message) { throw CompileError{at, std::move(message)}; }

  std::string position(std::size_t at) const {
    const auto [line, column] = line_and_column(text_, at);
    return std::to_string(line) + ":" + std::to_string(column);
  }

  // Nesting (parentheses, calls, unary operators, "?:") is bounded, so no text can exhaust the
  // stack: a binary operator's operand adds at most three levels more (its precedence rises).
  // `at`: the "(", operator or "?" that opens the level.
  struct Nest {
    Nest(Compiler& c, std::size_t at) : compiler(c) {
      if (++compiler.depth_ > kMaxDepth) fail(at, "nesting deeper than " + std::to_string(kMaxDepth));
    }
    ~Nest() { --compiler.depth_; }
    Nest(const Nest&) = delete;
    Nest& operator=(const Nest&) = delete;
    Compiler& compiler;
  };

  // -- Emitting --

  std::uint32_t new_register() {
    if (program_.code.size() + program_.constants.size() >= kMaxInstructions) {
      fail(tokens_[pos_].begin, "the formula is too long: more than " + std::to_string(kMaxInstructions) + " instructions");
    }
    return program_.registers++;
  }
  std::uint32_t emit(Op op, std::uint32_t a, std::uint32_t b = 0, std::uint32_t c = 0) {
    const std::uint32_t d = new_register();
    program_.code.push_back({op, d, a, b, c});
    return d;
  }
  std::uint32_t constant(double v) {
    std::uint64_t key = 0;  // the bits (std::bit_cast is missing from the page's libc++)
    std::memcpy(&key, &v, sizeof key);
    const auto found = constants_.find(key);
    if (found != constants_.end()) return found->second;
    const std::uint32_t r = new_register();
    program_.constants.emplace_back(r, v);
    constants_.emplace(key, r);
    return r;
  }
  // The operation per component; a number with a triple is broadcast (its register serves all
  // three components).
  Value apply(Op op, std::initializer_list<Value> args) {
    bool triple = false;
    for (const Value& v : args) triple = triple || v.triple;
    const Value* a = args.begin();
    auto reg = [&](std::size_t i, int c) { return i < args.size() ? a[i].r[static_cast<std::size_t>(c)] : 0u; };
    if (!triple) return number_value(emit(op, reg(0, 0), reg(1, 0), reg(2, 0)));
    Value out{true, {}};
    for (int c = 0; c < 3; ++c) out.r[static_cast<std::size_t>(c)] = emit(op, reg(0, c), reg(1, c), reg(2, c));
    return out;
  }
  // dot(a, b) as GLM computes it: (a.x*b.x + a.y*b.y) + a.z*b.z.
  std::uint32_t dot(const Value& a, const Value& b) {
    const std::uint32_t x = emit(Op::kMul, a.r[0], b.r[0]);
    const std::uint32_t y = emit(Op::kMul, a.r[1], b.r[1]);
    const std::uint32_t z = emit(Op::kMul, a.r[2], b.r[2]);
    return emit(Op::kAdd, emit(Op::kAdd, x, y), z);
  }

  // -- Names --

  void define(std::string_view name, const Value& value) {
    const auto [it, added] = names_.insert_or_assign(std::string(name), value);
    if (added) defined_.push_back(it->first);
  }
  std::vector<std::string_view> name_candidates() const {
    std::vector<std::string_view> all;
    for (const Given& g : kGiven) all.push_back(g.name);
    all.insert(all.end(), defined_.begin(), defined_.end());
    return all;
  }
  bool is_name(std::string_view name) const { return find_given(name) >= 0 || names_.count(std::string(name)) > 0; }

  Value read_name(const Token& t) {
    const std::string_view name = spelling(t);
    const int given = find_given(name);
    if (given >= 0) {
      names_read_ |= 1u << given;
      const auto first = kGivenRegister[static_cast<std::size_t>(given)];
      return kGiven[static_cast<std::size_t>(given)].triple != nullptr ? Value{true, {first, first + 1, first + 2}}
                                                                         : number_value(first);
    }
    const auto found = names_.find(std::string(name));
    if (found != names_.end()) return found->second;
    if (const FunctionInfo* f = find_function(name)) {
      fail(t.begin, quoted(name) + " is a function: call it, as in " + std::string(f->signature));
    }
    fail(t.begin, "unknown name " + quoted(name) + did_you_mean(name, name_candidates()));
  }

  // -- Expressions --

  // Binding strength of a binary operator at the next token (0: none). "?:" is 1, handled apart.
  int binary_precedence() {
    const Token& t = peek();
    if (t.kind != Kind::kSymbol) return 0;
    switch (t.symbol) {
      case '<': case '>': return 2;
      case '+': case '-': return 3;
      case '*': case '/': return 4;
      default: return 0;
    }
  }

  Value expression(int min_precedence = 1) {
    Value left = unary();
    for (;;) {
      if (at_symbol('?') && min_precedence <= 1) {
        const Token question = next();
        if (left.triple) fail(question.begin, "the condition before \"?\" must be a number (got a triple)");
        const Nest nest(*this, question.begin);
        const Value then_value = expression(1);
        if (!at_symbol(':')) {
          unexpected(peek(), "expected \":\" for the \"?\" at " + position(question.begin) + " (got " + describe(peek()) + ")");
        }
        next();
        const Value else_value = expression(1);  // right associative: a ? b : c ? d : e
        left = apply(Op::kSelect, {left, then_value, else_value});
        continue;
      }
      const int precedence = binary_precedence();
      if (precedence == 0 || precedence < min_precedence) return left;
      const Token op = next();
      const Value right = expression(precedence + 1);  // left associative
      switch (op.symbol) {
        case '+': left = apply(Op::kAdd, {left, right}); break;
        case '-': left = apply(Op::kSub, {left, right}); break;
        case '*': left = apply(Op::kMul, {left, right}); break;
        case '/': left = apply(Op::kDiv, {left, right}); break;
        default:  // < >
          if (left.triple || right.triple) {
            fail(op.begin, quoted(spelling(op)) + " compares numbers (got a triple)");
          }
          left = number_value(emit(op.symbol == '<' ? Op::kLess : Op::kGreater, left.r[0], right.r[0]));
      }
    }
  }

  // An operand may stand on the line after its operator (or "=").
  void skip_newlines() {
    while (tokens_[pos_].kind == Kind::kNewline) ++pos_;
  }

  Value unary() {
    skip_newlines();
    if (at_symbol('-') || at_symbol('+')) {
      const Token op = next();
      const bool minus = op.symbol == '-';
      const Nest nest(*this, op.begin);
      const Value operand = unary();
      return minus ? apply(Op::kNeg, {operand}) : operand;
    }
    return postfix();
  }

  // A primary followed by component accesses: .x .y .z (or .r .g .b).
  Value postfix() {
    Value v = primary();
    while (at_symbol('.')) {
      const Token dot_token = next();
      const Token& field = peek();
      const std::string_view name = field.kind == Kind::kName ? spelling(field) : std::string_view();
      int c = -1;
      if (name == "x" || name == "r") c = 0;
      if (name == "y" || name == "g") c = 1;
      if (name == "z" || name == "b") c = 2;
      if (c < 0) {
        unexpected(field, field.kind == Kind::kName
                              ? "unknown component \"." + std::string(name) + "\" (a triple has .x .y .z or .r .g .b)"
                              : "expected a component after \".\": x, y, z or r, g, b (got " + describe(field) + ")");
      }
      if (!v.triple) fail(dot_token.begin, "\"." + std::string(name) + "\" needs a triple (got a number)");
      next();
      v = number_value(v.r[static_cast<std::size_t>(c)]);
    }
    return v;
  }

  // Expressions separated by commas up to the ")" closing the "(" at `open`.
  std::vector<std::pair<Value, std::size_t>> list(const Token& open) {
    std::vector<std::pair<Value, std::size_t>> items;
    const Nest nest(*this, open.begin);
    ++paren_depth_;
    if (!at_symbol(')')) {
      for (;;) {
        const std::size_t begin = peek().begin;
        items.emplace_back(expression(), begin);
        if (!at_symbol(',')) break;
        next();
      }
    }
    if (!at_symbol(')')) unexpected(peek(), "expected \")\" to close \"(\" at " + position(open.begin));
    --paren_depth_;
    next();
    return items;
  }

  Value primary() {
    const Token& t = peek();
    if (t.kind == Kind::kNumber) {
      next();
      return number_value(constant(t.number));
    }
    if (t.kind == Kind::kName) {
      const Token name = next();
      if (at_symbol('(')) return call(name);
      return read_name(name);
    }
    if (t.kind == Kind::kSymbol && t.symbol == '(') {
      const Token open = next();
      const auto items = list(open);
      if (items.size() == 1) return items[0].first;
      if (items.size() != 3) {
        fail(open.begin, "a triple has three components, (a, b, c) (got " + std::to_string(items.size()) + ")");
      }
      return triple_of(items, "a triple's components are numbers");
    }
    unexpected(t, "expected an expression (got " + describe(t) + ")");
  }

  Value triple_of(const std::vector<std::pair<Value, std::size_t>>& items, const char* rule) {
    for (const auto& [value, begin] : items) {
      if (value.triple) fail(begin, std::string(rule) + " (got a triple)");
    }
    return {true, {items[0].first.r[0], items[1].first.r[0], items[2].first.r[0]}};
  }

  Value call(const Token& name_token) {
    const std::string_view name = spelling(name_token);
    const FunctionInfo* f = find_function(name);
    if (f == nullptr) {
      if (is_name(name)) fail(name_token.begin, quoted(name) + " is a name, not a function");
      std::vector<std::string_view> functions;
      for (const FunctionInfo& info : kFunctions) functions.push_back(info.name);
      fail(name_token.begin, "unknown function " + quoted(name) + did_you_mean(name, functions));
    }
    const Token open = next();
    const auto items = list(open);
    std::vector<Value> args;
    for (const auto& item : items) args.push_back(item.first);
    const std::string head = std::string(name) + "() takes ";
    const std::size_t count = args.size();
    auto arguments = [&](std::size_t wanted, const char* words) {
      if (count != wanted) {
        fail(name_token.begin, head + words + (wanted == 1 ? " argument" : " arguments") + " (got " + std::to_string(count) + ")");
      }
    };
    // Functions of vectors: the count and the type of each argument.
    auto vectors = [&](std::size_t wanted, const char* words) {
      if (count != wanted) {
        fail(name_token.begin, head + words + " (got " + std::to_string(count) + (count == 1 ? " argument)" : " arguments)"));
      }
      for (const Value& v : args) {
        if (!v.triple) fail(name_token.begin, head + words + " (got a number)");
      }
    };
    switch (f->function) {
      case Function::kDot: vectors(2, "two vectors"); return number_value(dot(args[0], args[1]));
      case Function::kCross: {
        // As GLM: (a.y*b.z - b.y*a.z, a.z*b.x - b.z*a.x, a.x*b.y - b.x*a.y).
        vectors(2, "two vectors");
        const Value& a = args[0];
        const Value& b = args[1];
        Value out{true, {}};
        for (std::size_t c = 0; c < 3; ++c) {
          const std::size_t i = (c + 1) % 3, j = (c + 2) % 3;
          out.r[c] = emit(Op::kSub, emit(Op::kMul, a.r[i], b.r[j]), emit(Op::kMul, b.r[i], a.r[j]));
        }
        return out;
      }
      case Function::kNormalize: {
        // As GLM: v * (1 / sqrt(dot(v, v))).
        vectors(1, "one vector");
        const std::uint32_t inverse = emit(Op::kDiv, constant(1), emit(Op::kSqrt, dot(args[0], args[0])));
        return apply(Op::kMul, {args[0], number_value(inverse)});
      }
      case Function::kLength: vectors(1, "one vector"); return number_value(emit(Op::kSqrt, dot(args[0], args[0])));
      case Function::kReflect: {
        // GLSL's: I - 2*dot(N, I)*N.
        vectors(2, "two vectors");
        const Value scale = number_value(emit(Op::kMul, constant(2), dot(args[1], args[0])));
        return apply(Op::kSub, {args[0], apply(Op::kMul, {scale, args[1]})});
      }
      case Function::kPow: arguments(2, "two"); return apply(Op::kPow, {args[0], args[1]});
      case Function::kMax: arguments(2, "two"); return apply(Op::kMax, {args[0], args[1]});
      case Function::kMin: arguments(2, "two"); return apply(Op::kMin, {args[0], args[1]});
      case Function::kClamp:  // GLSL's: min(max(x, lo), hi)
        arguments(3, "three");
        return apply(Op::kMin, {apply(Op::kMax, {args[0], args[1]}), args[2]});
      case Function::kAbs: arguments(1, "one"); return apply(Op::kAbs, {args[0]});
      case Function::kSqrt: arguments(1, "one"); return apply(Op::kSqrt, {args[0]});
      case Function::kExp: arguments(1, "one"); return apply(Op::kExp, {args[0]});
      case Function::kLog: arguments(1, "one"); return apply(Op::kLog, {args[0]});
      case Function::kMix: {
        // GLSL's: a*(1-t) + b*t.
        arguments(3, "three");
        const Value weight = apply(Op::kSub, {number_value(constant(1)), args[2]});
        return apply(Op::kAdd, {apply(Op::kMul, {args[0], weight}), apply(Op::kMul, {args[1], args[2]})});
      }
      case Function::kStep: arguments(2, "two"); return apply(Op::kStep, {args[0], args[1]});
      case Function::kVec3:
        if (count == 1) return {true, args[0].r};  // vec3(x) = (x, x, x); vec3(v) = v
        if (count != 3) fail(name_token.begin, head + "one or three arguments (got " + std::to_string(count) + ")");
        return triple_of(items, "vec3() takes three numbers");
    }
    fail(name_token.begin, "unknown function " + quoted(name));
  }

  std::string_view text_;
  const Lexed& lexed_;
  const std::vector<Token>& tokens_;
  Formula::Program& program_;
  std::size_t pos_ = 0;
  int depth_ = 0;
  int paren_depth_ = 0;
  std::uint32_t names_read_ = 0;
  std::unordered_map<std::string, Value> names_;
  std::vector<std::string_view> defined_;  // the names defined so far, in order (keys of names_)
  std::unordered_map<std::uint64_t, std::uint32_t> constants_;  // by bit pattern
};

// The instruction over lanes [0, n) of registers `stride` doubles apart. No instruction writes a
// register it reads (each writes a fresh one), hence restrict.
void execute(const Instruction& in, double* regs, std::size_t stride, std::size_t n) {
  double* __restrict d = regs + in.d * stride;
  const double* __restrict a = regs + in.a * stride;
  const double* __restrict b = regs + in.b * stride;
  const double* __restrict c = regs + in.c * stride;
  switch (in.op) {
    case Op::kAdd: for (std::size_t i = 0; i < n; ++i) d[i] = a[i] + b[i]; break;
    case Op::kSub: for (std::size_t i = 0; i < n; ++i) d[i] = a[i] - b[i]; break;
    case Op::kMul: for (std::size_t i = 0; i < n; ++i) d[i] = a[i] * b[i]; break;
    case Op::kDiv: for (std::size_t i = 0; i < n; ++i) d[i] = a[i] / b[i]; break;
    case Op::kNeg: for (std::size_t i = 0; i < n; ++i) d[i] = -a[i]; break;
    case Op::kLess: for (std::size_t i = 0; i < n; ++i) d[i] = a[i] < b[i] ? 1.0 : 0.0; break;
    case Op::kGreater: for (std::size_t i = 0; i < n; ++i) d[i] = a[i] > b[i] ? 1.0 : 0.0; break;
    case Op::kSelect: for (std::size_t i = 0; i < n; ++i) d[i] = a[i] != 0 ? b[i] : c[i]; break;
    case Op::kPow: for (std::size_t i = 0; i < n; ++i) d[i] = std::pow(a[i], b[i]); break;
    case Op::kMax: for (std::size_t i = 0; i < n; ++i) d[i] = std::max(a[i], b[i]); break;
    case Op::kMin: for (std::size_t i = 0; i < n; ++i) d[i] = std::min(a[i], b[i]); break;
    case Op::kAbs: for (std::size_t i = 0; i < n; ++i) d[i] = std::abs(a[i]); break;
    case Op::kSqrt: for (std::size_t i = 0; i < n; ++i) d[i] = std::sqrt(a[i]); break;
    case Op::kExp: for (std::size_t i = 0; i < n; ++i) d[i] = std::exp(a[i]); break;
    case Op::kLog: for (std::size_t i = 0; i < n; ++i) d[i] = std::log(a[i]); break;
    case Op::kStep: for (std::size_t i = 0; i < n; ++i) d[i] = b[i] < a[i] ? 0.0 : 1.0; break;
  }
}

}  // namespace

// Runs the code for `count` hits, `stride` (at most kLanes) at a time, in `regs` (registers x
// stride doubles); the final values go to `out` when it is not null.
void Formula::Program::run(const FormulaSource& source, std::size_t count, std::uint32_t names_read, double* regs,
                           std::size_t stride, Color* out) const {
  for (const auto& [r, v] : constants) std::fill_n(regs + r * stride, stride, v);
  for (std::size_t first = 0; first < count; first += stride) {
    const std::size_t n = std::min(stride, count - first);
    // The given names the formula reads, one register per component (hits to lanes).
    for (std::size_t g = 0; g < kGiven.size(); ++g) {
      if ((names_read >> g & 1u) == 0) continue;
      double* r = regs + kGivenRegister[g] * stride;
      const bool triple = kGiven[g].triple != nullptr;
      source.fill(static_cast<int>(g), first, n, r, triple ? r + stride : nullptr, triple ? r + 2 * stride : nullptr);
    }
    for (const Instruction& instruction : code) execute(instruction, regs, stride, n);
    if (out == nullptr) continue;
    const double* x = regs + result.r[0] * stride;
    const double* y = regs + result.r[1] * stride;
    const double* z = regs + result.r[2] * stride;
    for (std::size_t i = 0; i < n; ++i) out[first + i] = Color(x[i], y[i], z[i]);
  }
}

Formula::Formula() = default;
Formula::~Formula() = default;

const std::vector<std::string_view>& formula_given_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> all;
    for (const Given& g : kGiven) all.push_back(g.name);
    return all;
  }();
  return names;
}

const std::vector<std::string_view>& formula_function_signatures() {
  static const std::vector<std::string_view> signatures = [] {
    std::vector<std::string_view> all;
    for (const FunctionInfo& f : kFunctions) all.push_back(f.signature);
    return all;
  }();
  return signatures;
}

std::shared_ptr<const Formula> Formula::compile(std::string_view text, FormulaError* error, std::string_view source) {
  auto report = [&](std::size_t at, std::string message) -> std::shared_ptr<const Formula> {
    if (error == nullptr) return nullptr;
    *error = FormulaError{};
    error->source = std::string(source);
    std::tie(error->line, error->column) = line_and_column(text, at);
    error->message = std::move(message);
    return nullptr;
  };
  if (text.size() > kMaxTextBytes) {
    return report(0, "the formula is longer than " + std::to_string(kMaxTextBytes / 1024) + " KiB (" +
                         std::to_string(text.size()) + " bytes)");
  }
  std::shared_ptr<Formula> formula(new Formula());
  formula->program_ = std::make_unique<Program>();
  const Lexed lexed = lex(text);
  try {
    Compiler compiler(text, lexed, *formula->program_);
    compiler.compile();
    formula->names_read_ = compiler.names_read();
  } catch (const CompileError& e) {
    return report(e.at, e.message);
  }
  formula->text_ = std::string(text);
  return formula;
}

namespace {
// The registers of the evaluations on this thread, kept between calls (no allocation per hit).
std::vector<double>& scratch(std::size_t size) {
  thread_local std::vector<double> registers;
  if (registers.size() < size) registers.resize(size);
  return registers;
}

// FormulaInputs as a source: the fields the names point to.
class InputsSource final : public FormulaSource {
 public:
  explicit InputsSource(const FormulaInputs* inputs) : inputs_(inputs) {}
  void fill(int name, std::size_t first, std::size_t n, double* x, double* y, double* z) const override {
    const Given& g = kGiven[static_cast<std::size_t>(name)];
    const FormulaInputs* in = inputs_ + first;
    if (g.triple != nullptr) {
      for (std::size_t i = 0; i < n; ++i) {
        const Vec3& v = in[i].*g.triple;
        x[i] = v.x, y[i] = v.y, z[i] = v.z;
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) x[i] = in[i].*g.number;
    }
  }

 private:
  const FormulaInputs* inputs_;
};

}  // namespace

FormulaInputs FormulaSource::at(std::size_t i) const {
  FormulaInputs in;
  for (std::size_t g = 0; g < kGiven.size(); ++g) {
    if (kGiven[g].triple != nullptr) {
      Vec3& v = in.*kGiven[g].triple;
      fill(static_cast<int>(g), i, 1, &v.x, &v.y, &v.z);
    } else {
      fill(static_cast<int>(g), i, 1, &(in.*kGiven[g].number), nullptr, nullptr);
    }
  }
  return in;
}

void Formula::evaluate(const FormulaSource& source, std::size_t count, Color* out) const {
  if (count == 0) return;
  const std::size_t stride = std::min(count, kLanes);
  std::vector<double>& regs = scratch(program_->registers * stride);
  program_->run(source, count, names_read_, regs.data(), stride, out);
}

void Formula::evaluate(const FormulaInputs* inputs, std::size_t count, Color* out) const {
  evaluate(InputsSource(inputs), count, out);
}

Color Formula::evaluate(const FormulaInputs& inputs) const {
  Color out;
  evaluate(&inputs, 1, &out);
  return out;
}

std::vector<std::pair<std::string, FormulaValue>> Formula::trace(const FormulaInputs& inputs) const {
  std::vector<double>& regs = scratch(program_->registers);
  program_->run(InputsSource(&inputs), 1, names_read_, regs.data(), 1, nullptr);
  auto value = [&](const Value& v) {
    return v.triple ? FormulaValue{true, regs[v.r[0]], regs[v.r[1]], regs[v.r[2]]} : FormulaValue{false, regs[v.r[0]], 0, 0};
  };
  std::vector<std::pair<std::string, FormulaValue>> values;
  for (const Program::Statement& s : program_->statements) values.emplace_back(s.name, value(s.value));
  values.emplace_back("=", value(program_->result));
  return values;
}

}  // namespace phonglab
