// Scene files (docs/scene-format.md). Loading runs in four passes over the text, none of them recursive:
//   1. prescan: rejects NUL bytes and nesting deeper than kMaxNesting, and finds number tokens
//      that overflow double (nlohmann throws on those instead of returning inf);
//   2. nlohmann parses (syntax errors are translated into positioned plain messages);
//   3. PosIndex maps every value of the now valid text to its byte offsets (nlohmann keeps none);
//   4. Validator walks the DOM and the index together, collecting every independent error.
#include "renderer/scene_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <new>
#include <span>
#include <sstream>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "renderer/accel.h"
#include "renderer/embedded_scenes.h"
#include "renderer/obj_io.h"

namespace phonglab {

std::string Diagnostic::to_string() const {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line) + ":" + std::to_string(column);
  s += ": ";
  if (!path.empty()) s += path + ": ";
  s += message;
  return s;
}

std::string LoadResult::error_text() const {
  std::string s;
  for (const Diagnostic& d : errors) {
    if (!s.empty()) s += '\n';
    s += d.to_string();
  }
  return s;
}

namespace {

using Json = nlohmann::json;

constexpr int kMaxNesting = 64;            // deeper arrays/objects are rejected before parsing
constexpr double kMaxMagnitude = 1e100;    // keeps every product of two scene values finite
constexpr std::size_t kMaxShown = 60;      // bytes of an offending value quoted in a message
constexpr std::size_t kMaxIssues = 100;    // errors collected before validation stops
constexpr std::size_t kMaxFileBytes = std::size_t{256} << 20;  // /dev/zero must not hang us
constexpr std::size_t kMaxTextBytes = std::size_t{1} << 31;    // offsets fit PosNode's 32 bits
constexpr std::size_t kNoOffset = std::numeric_limits<std::size_t>::max();
constexpr int kMaxDepthLimit = 100;        // max_depth range is 0..kMaxDepthLimit
constexpr int kMaxImageSide = 16384;       // image width/height range is 1..kMaxImageSide

// ---------------------------------------------------------------------------------------------
// Small text helpers.

bool is_digit(char c) { return c >= '0' && c <= '9'; }

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Characters that can belong to a number or a bare literal (true, NaN, ...).
bool is_word_char(char c) {
  return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '+' || c == '-' ||
         c == '.' || c == '_';
}

char to_lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }

bool has_bom(std::string_view t) { return t.size() >= 3 && t.substr(0, 3) == "\xEF\xBB\xBF"; }

// Cuts s to at most kMaxShown bytes without splitting a UTF-8 sequence, marking the cut.
std::string truncated(std::string s) {
  if (s.size() <= kMaxShown) return s;
  std::size_t cut = kMaxShown - 3;
  while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
  s.resize(cut);
  return s + "...";
}

// A JSON string literal for s; invalid UTF-8 (from a programmatic Scene) is replaced, not thrown.
std::string json_string(std::string_view s) {
  return Json(std::string(s)).dump(-1, ' ', false, Json::error_handler_t::replace);
}

// The source text of [begin, end) without whitespace outside strings, shortened for messages.
std::string compact_source(std::string_view t, std::size_t begin, std::size_t end) {
  std::string out;
  bool in_string = false;
  for (std::size_t i = begin; i < end && i < t.size() && out.size() <= kMaxShown; ++i) {
    const char c = t[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < end) {
        out += t[++i];
      } else if (c == '"') {
        in_string = false;
      }
    } else if (!is_space(c)) {
      out += c;
      in_string = (c == '"');
    }
  }
  return truncated(std::move(out));
}

// Shows one byte of unknown text safely: printable ASCII quoted, anything else as hex.
std::string describe_byte(unsigned char c) {
  if (c >= 0x21 && c < 0x7F) return std::string("'") + static_cast<char>(c) + "'";
  static constexpr char kHex[] = "0123456789ABCDEF";
  return std::string("byte 0x") + kHex[c >> 4] + kHex[c & 15];
}

// Makes arbitrary (possibly binary) source text printable for a syntax message.
std::string printable(std::string_view s) {
  std::string out;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u < 0x7F) {
      out += c;
    } else {
      static constexpr char kHex[] = "0123456789ABCDEF";
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    }
  }
  return truncated(std::move(out));
}

// Case-insensitive edit distance; only ever called on short words.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t subst = prev[j - 1] + (to_lower(a[i - 1]) == to_lower(b[j - 1]) ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, subst});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// The candidate the user most likely meant: a case-insensitive match, else the nearest within
// edit distance 2 (first one on ties), else nothing.
std::optional<std::string_view> closest(std::string_view word,
                                        std::span<const std::string_view> candidates) {
  constexpr std::size_t kMaxWord = 64;  // longer words are not typos of scene keys
  if (word.size() > kMaxWord) return std::nullopt;
  std::optional<std::string_view> best;
  std::size_t best_distance = 3;
  for (std::string_view c : candidates) {
    if (c.size() > kMaxWord) continue;
    const std::size_t longer = std::max(c.size(), word.size());
    if (longer - std::min(c.size(), word.size()) >= best_distance) continue;
    const std::size_t d = edit_distance(word, c);
    const bool same_ignoring_case = (c.size() == word.size() && d == 0);
    if (same_ignoring_case) return c;
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

// " (did you mean "x"?)", else the list of what is allowed (at most a few entries).
std::string suggestion(std::string_view word, std::span<const std::string_view> candidates,
                       std::string_view list_intro) {
  if (auto c = closest(word, candidates)) return " (did you mean " + json_string(*c) + "?)";
  if (candidates.empty()) return "";
  constexpr std::size_t kMaxListed = 10;
  std::string s = " (" + std::string(list_intro) + ": ";
  for (std::size_t i = 0; i < candidates.size() && i < kMaxListed; ++i) {
    if (i > 0) s += ", ";
    s += truncated(std::string(candidates[i]));
  }
  if (candidates.size() > kMaxListed) s += ", ...";
  return s + ")";
}

// `parent.key`, or `parent["odd key"]` when the key is not a plain identifier.
std::string member_path(const std::string& parent, std::string_view key) {
  const bool plain = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return is_digit(c) || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  });
  if (plain) return parent.empty() ? std::string(key) : parent + "." + std::string(key);
  return parent + "[" + json_string(truncated(std::string(key))) + "]";
}

std::string element_path(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// ---------------------------------------------------------------------------------------------
// Pass 1: prescan.

// Length of the number nlohmann's lexer reads at t[i]: the longest prefix matching JSON's number
// grammar (it stops there and lexes the rest as the next token), or 0 if none starts at i.
std::size_t number_length(std::string_view t, std::size_t i) {
  const std::size_t start = i;
  const std::size_t n = t.size();
  const auto digits = [&](std::size_t at) {
    while (at < n && is_digit(t[at])) ++at;
    return at;
  };
  if (i < n && t[i] == '-') ++i;
  if (i >= n || !is_digit(t[i])) return 0;
  i = (t[i] == '0') ? i + 1 : digits(i);
  if (i + 1 < n && t[i] == '.' && is_digit(t[i + 1])) i = digits(i + 1);
  if (i < n && (t[i] == 'e' || t[i] == 'E')) {
    std::size_t j = i + 1;
    if (j < n && (t[j] == '+' || t[j] == '-')) ++j;
    if (j < n && is_digit(t[j])) i = digits(j);
  }
  return i - start;
}

// True when the JSON number tok overflows double (nlohmann would throw instead of parsing it).
bool number_overflows(std::string_view tok) {
  std::size_t i = (tok.front() == '-') ? 1 : 0;
  const std::size_t int_begin = i;
  while (i < tok.size() && is_digit(tok[i])) ++i;
  const std::size_t int_end = i;
  std::size_t frac_begin = i, frac_end = i;
  if (i < tok.size() && tok[i] == '.') {
    frac_begin = ++i;
    while (i < tok.size() && is_digit(tok[i])) ++i;
    frac_end = i;
  }
  long long exponent = 0;
  if (i < tok.size()) {  // 'e' or 'E'
    ++i;
    bool negative = false;
    if (tok[i] == '+' || tok[i] == '-') negative = (tok[i++] == '-');
    constexpr long long kSaturate = 1'000'000'000;  // far beyond any double's exponent
    for (; i < tok.size(); ++i) {
      if (exponent < kSaturate) exponent = exponent * 10 + (tok[i] - '0');
    }
    if (negative) exponent = -exponent;
  }
  // Decimal exponent of the leading significant digit: the value is about 10^magnitude.
  constexpr long long kZero = std::numeric_limits<long long>::min();
  long long magnitude = kZero;
  for (std::size_t j = int_begin; j < int_end && magnitude == kZero; ++j) {
    if (tok[j] != '0') magnitude = static_cast<long long>(int_end - 1 - j) + exponent;
  }
  for (std::size_t j = frac_begin; j < frac_end && magnitude == kZero; ++j) {
    if (tok[j] != '0') magnitude = exponent - static_cast<long long>(j - frac_begin + 1);
  }
  constexpr long long kSafe = std::numeric_limits<double>::max_exponent10;  // 308
  if (magnitude < kSafe) return false;  // zero, or surely below DBL_MAX: no need to convert
  if (magnitude > kSafe) return true;
  double value = 0;
  return std::from_chars(tok.data(), tok.data() + tok.size(), value).ec ==
         std::errc::result_out_of_range;
}

// A number token replaced before parsing because it overflows double.
struct Overflow {
  std::size_t offset;  // first byte of the token
  std::size_t length;  // bytes of the token
};

struct Prescan {
  std::size_t too_deep = kNoOffset;     // first bracket nested deeper than kMaxNesting
  std::size_t nul = kNoOffset;          // first NUL byte (nlohmann would stop reading there)
  std::size_t open_string = kNoOffset;  // opening quote of a string still open at the end
  std::vector<Overflow> overflows;      // in text order
};

Prescan prescan(std::string_view t) {
  Prescan r;
  int depth = 0;
  std::size_t i = 0;
  const std::size_t n = t.size();
  while (i < n) {
    const char c = t[i];
    if (c == '\0') {
      r.nul = i;
      return r;
    }
    if (c == '"') {
      const std::size_t start = i++;
      while (i < n && t[i] != '"') {
        if (t[i] == '\0') {
          r.nul = i;
          return r;
        }
        i += (t[i] == '\\') ? 2 : 1;
      }
      if (i >= n) {
        r.open_string = start;
        return r;
      }
      ++i;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxNesting) {
        r.too_deep = i;
        return r;
      }
      ++i;
    } else if (c == ']' || c == '}') {
      if (depth > 0) --depth;
      ++i;
    } else if (c == '-' || is_digit(c)) {
      const std::size_t length = number_length(t, i);
      if (length > 0 && number_overflows(t.substr(i, length))) r.overflows.push_back({i, length});
      i += std::max<std::size_t>(length, 1);
    } else {
      ++i;
    }
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// Pass 2: syntax errors.

// An error before line/column are known: a byte offset into the text.
struct Issue {
  std::size_t offset = kNoOffset;
  std::string path;
  std::string message;
};

// Start of the bare word (number or literal) that contains offset or ends just before it.
std::size_t word_start(std::string_view t, std::size_t off) {
  if (off >= t.size() || !is_word_char(t[off])) {
    if (off == 0 || !is_word_char(t[off - 1])) return off;
    --off;
  }
  while (off > 0 && is_word_char(t[off - 1])) --off;
  return off;
}

std::size_t word_end(std::string_view t, std::size_t start) {
  std::size_t e = start;
  while (e < t.size() && is_word_char(t[e])) ++e;
  return e;
}

// Opening quote of the (valid) string token whose closing quote is at `close`.
std::size_t string_start(std::string_view t, std::size_t close) {
  std::size_t j = close;
  while (j > 0) {
    --j;
    if (t[j] != '"') continue;
    std::size_t backslashes = 0;
    while (j >= backslashes + 1 && t[j - backslashes - 1] == '\\') ++backslashes;
    if (backslashes % 2 == 0) return j;
  }
  return close;
}

// What the parser wanted, in plain words, from nlohmann's parse context and expected token.
std::string expectation(std::string_view context, std::string_view expected) {
  if (expected == "end of input") return "the end of the file after the scene's closing '}'";
  if (context == "object key") return "a key in double quotes";
  if (context == "object separator") return "':' after the key";
  if (context == "object") return "',' or '}'";
  if (context == "array") return "',' or ']'";
  if (context == "value") return "a value";
  return std::string(expected);
}

// Turns nlohmann's parse_error into a positioned plain message such as
// `syntax error: unexpected "b"; expected ',' or '}'`.
Issue syntax_issue(std::string_view t, const Json::parse_error& e, const Prescan& pre) {
  std::size_t off = std::min<std::size_t>(e.byte == 0 ? 0 : e.byte - 1, t.size());
  const std::string what = e.what();
  constexpr std::string_view kMarker = "syntax error while parsing ";
  const std::size_t m = what.find(kMarker);
  if (m == std::string::npos) {
    const std::size_t colon = what.find(": ");
    const std::string plain = colon == std::string::npos ? what : what.substr(colon + 2);
    return {off, "", "syntax error: " + plain};
  }
  const std::string rest = what.substr(m + kMarker.size());
  const std::size_t dash = rest.find(" - ");
  const std::string context = rest.substr(0, dash);
  std::string detail = dash == std::string::npos ? "" : rest.substr(dash + 3);

  // nlohmann appends the token it wanted as "; expected X". Lexer messages can contain that text
  // too ("invalid number; expected digit after '-'"), so there it only counts after the quoted
  // "last read: '...'" part.
  std::string expected;
  constexpr std::string_view kExpected = "; expected ";
  const std::size_t last_read = detail.find("; last read: '");
  std::size_t exp_pos = std::string::npos;
  if (detail.rfind("unexpected ", 0) == 0) {
    exp_pos = detail.find(kExpected);
  } else if (last_read != std::string::npos) {
    exp_pos = detail.rfind(kExpected);
    if (exp_pos != std::string::npos && (exp_pos <= last_read || detail[exp_pos - 1] != '\'')) {
      exp_pos = std::string::npos;
    }
  }
  if (exp_pos != std::string::npos) {
    expected = detail.substr(exp_pos + kExpected.size());
    detail.resize(exp_pos);
  }
  std::string want = expectation(context, expected);

  constexpr std::string_view kUnexpected = "unexpected ";
  std::string found;
  std::string problem;
  if (detail.rfind(kUnexpected, 0) == 0) {
    const std::string token = detail.substr(kUnexpected.size());
    if (token == "end of input") {
      off = t.size();
      found = "end of file";
    } else if (token == "string literal") {
      const std::size_t start = string_start(t, off);
      found = printable(t.substr(start, off + 1 - start));
      off = start;
    } else if (token.size() == 3 && token.front() == '\'') {
      found = token;
    } else {
      off = word_start(t, off);
      found = "'" + printable(t.substr(off, word_end(t, off) - off)) + "'";
    }
    if ((found == "'}'" || found == "']'") && off > 0) {
      std::size_t p = off;
      while (p > 0 && is_space(t[p - 1])) --p;
      if (p > 0 && t[p - 1] == ',') want += " (JSON allows no trailing comma)";
    }
    problem = "unexpected " + found;
  } else {
    const std::string lexer = detail.substr(0, std::min(last_read, detail.size()));
    if (lexer.find("missing closing quote") != std::string::npos && pre.open_string != kNoOffset) {
      off = pre.open_string;
      problem = "unterminated string (missing closing quote)";
      want.clear();
    } else if (lexer.rfind("invalid literal", 0) == 0 || lexer.rfind("invalid number", 0) == 0) {
      const std::size_t start = word_start(t, off);
      const std::size_t end = word_end(t, start);
      if (end > start) {
        off = start;
        found = "'" + printable(t.substr(start, end - start)) + "'";
      } else if (off < t.size()) {
        found = describe_byte(static_cast<unsigned char>(t[off]));
      } else {
        found = "end of file";
      }
      problem = "unexpected " + found;
      const std::size_t semi = lexer.find("; ");
      if (lexer.rfind("invalid number", 0) == 0 && semi != std::string::npos) {
        problem = "invalid number " + found + ": " + lexer.substr(semi + 2);
        want.clear();
      }
    } else {
      problem = lexer;  // "invalid string: ...", "invalid BOM; ...": already plain
      want.clear();
    }
  }
  std::string message = "syntax error: " + problem;
  if (!want.empty()) message += "; expected " + want;
  return {off, "", std::move(message)};
}

// ---------------------------------------------------------------------------------------------
// Pass 3: the position index.

// Where one JSON value sits in the text. 32-bit fields keep the index small for 10 MB inputs;
// load_text rejects texts of kMaxTextBytes or more, so every offset fits.
struct PosNode {
  std::uint32_t begin = 0;        // first byte of the value
  std::uint32_t end = 0;          // one past its last byte
  std::uint32_t key_begin = 0;    // opening quote of its key, for object members
  std::uint32_t child_begin = 0;  // first entry in PosIndex::children_
  std::uint32_t child_count = 0;  // members or elements, in file order
};

// Maps every value of a valid JSON text to its offsets, and every member to its key's offset:
// together with the DOM this is the map from JSON path to position. Built iteratively.
class PosIndex {
 public:
  explicit PosIndex(std::string_view text) : text_(text) { build(); }

  std::size_t begin(std::size_t id) const { return nodes_[id].begin; }
  std::size_t end(std::size_t id) const { return nodes_[id].end; }
  std::size_t key_begin(std::size_t id) const { return nodes_[id].key_begin; }

  std::span<const std::uint32_t> children(std::size_t id) const {
    const PosNode& n = nodes_[id];
    return std::span<const std::uint32_t>(children_).subspan(n.child_begin, n.child_count);
  }

  // The decoded key of an object member.
  std::string key(std::size_t id) const {
    const std::size_t b = nodes_[id].key_begin;
    const std::string_view raw = text_.substr(b, string_end(b) - b);
    if (raw.find('\\') == std::string_view::npos) return std::string(raw.substr(1, raw.size() - 2));
    return Json::parse(raw).get<std::string>();  // escapes decode exactly as the DOM's keys did
  }

 private:
  // A container still being read.
  struct Open {
    std::uint32_t node;
    bool is_object;
    bool expect_key;
    std::uint32_t key_begin;
    std::vector<std::uint32_t> kids;
  };

  std::size_t string_end(std::size_t i) const {
    ++i;
    while (i < text_.size() && text_[i] != '"') i += (text_[i] == '\\') ? 2 : 1;
    return std::min(i + 1, text_.size());
  }

  static std::uint32_t u32(std::size_t x) { return static_cast<std::uint32_t>(x); }

  std::uint32_t add(std::vector<Open>& stack, std::size_t begin, std::size_t end) {
    PosNode n;
    n.begin = u32(begin);
    n.end = u32(end);
    const std::uint32_t id = u32(nodes_.size());
    if (!stack.empty()) {
      Open& top = stack.back();
      if (top.is_object) n.key_begin = top.key_begin;
      top.kids.push_back(id);
    }
    nodes_.push_back(n);
    return id;
  }

  void build() {
    std::vector<Open> stack;
    std::size_t i = has_bom(text_) ? 3 : 0;
    bool root_done = false;
    while (i < text_.size() && !root_done) {
      const char c = text_[i];
      if (is_space(c) || c == ':') {
        ++i;
      } else if (c == ',') {
        if (!stack.empty() && stack.back().is_object) stack.back().expect_key = true;
        ++i;
      } else if (c == '"') {
        const std::size_t end = string_end(i);
        if (!stack.empty() && stack.back().is_object && stack.back().expect_key) {
          stack.back().expect_key = false;
          stack.back().key_begin = u32(i);
        } else {
          add(stack, i, end);
          root_done = stack.empty();
        }
        i = end;
      } else if (c == '{' || c == '[') {
        const std::uint32_t id = add(stack, i, i + 1);
        stack.push_back({id, c == '{', c == '{', 0, {}});
        ++i;
      } else if (c == '}' || c == ']') {
        if (stack.empty()) break;
        Open& top = stack.back();
        PosNode& n = nodes_[top.node];
        n.end = u32(i + 1);
        n.child_begin = u32(children_.size());
        n.child_count = u32(top.kids.size());
        children_.insert(children_.end(), top.kids.begin(), top.kids.end());
        stack.pop_back();
        root_done = stack.empty();
        ++i;
      } else {
        const std::size_t end = std::max(word_end(text_, i), i + 1);
        add(stack, i, end);
        root_done = stack.empty();
        i = end;
      }
    }
  }

  std::string_view text_;
  std::vector<PosNode> nodes_;            // node 0 is the root value
  std::vector<std::uint32_t> children_;   // each container's children, contiguous
};

// ---------------------------------------------------------------------------------------------
// Pass 4: validation.

// A JSON value with its position and its path.
struct Val {
  const Json* json = nullptr;
  std::size_t node = 0;
  std::string path;
};

// The known members of one JSON object (unknown and duplicate keys already reported).
struct Fields {
  std::vector<std::pair<std::string, Val>> members;  // file order

  const Val* find(std::string_view key) const {
    for (const auto& [k, v] : members) {
      if (k == key) return &v;
    }
    return nullptr;
  }
};

constexpr std::array<std::string_view, 10> kSceneKeys = {
    "camera", "image", "ambient", "background", "max_depth", "min_weight", "specular_model",
    "lights", "materials", "objects"};
constexpr std::array<std::string_view, 4> kCameraKeys = {"position", "look_at", "up", "fov_y"};
constexpr std::array<std::string_view, 2> kImageKeys = {"width", "height"};
constexpr std::array<std::string_view, 2> kSpecularModels = {"phong", "blinn"};
constexpr std::array<std::string_view, 2> kLightTypes = {"point", "directional"};
constexpr std::array<std::string_view, 4> kPointLightKeys = {"type", "position", "intensity",
                                                             "enabled"};
constexpr std::array<std::string_view, 4> kDirectionalLightKeys = {"type", "direction", "intensity",
                                                                   "enabled"};
constexpr std::array<std::string_view, 8> kMaterialKeys = {"ka", "kd", "ks", "n",
                                                           "kr", "kt", "ior", "fresnel"};
constexpr std::array<std::string_view, 4> kObjectTypes = {"sphere", "plane", "triangle", "mesh"};
constexpr std::array<std::string_view, 4> kSphereKeys = {"type", "center", "radius", "material"};
constexpr std::array<std::string_view, 4> kPlaneKeys = {"type", "point", "normal", "material"};
constexpr std::array<std::string_view, 4> kTriangleKeys = {"type", "vertices", "normals",
                                                           "material"};
constexpr std::array<std::string_view, 5> kMeshKeys = {"type", "file", "material", "transform", "ns"};
constexpr std::array<std::string_view, 3> kTransformKeys = {"scale", "rotate_deg", "translate"};
constexpr std::array<std::string_view, 2> kNsMappings = {"as_is", "blinn_to_phong"};
constexpr std::size_t kMaxMeshFileBytes = std::size_t{1} << 31;  // a 1.3M-triangle OBJ is ~100 MB

// True when v has a usable direction: normalising it in double gives a finite unit vector.
bool normalizable(const Vec3& v) {
  const double d = glm::dot(v, v);
  if (!(d > 0) || !std::isfinite(d)) return false;
  const Vec3 u = v / std::sqrt(d);
  return all_finite(u) && std::abs(glm::length(u) - 1.0) < 1e-6;
}

// Collects issues. After kMaxIssues the validator stops, as compilers do: a file with thousands
// of errors is not helped by thousands of lines, and 10 MB of bad values must stay fast.
class Issues {
 public:
  void add(Issue issue) {
    if (list_.size() < kMaxIssues) list_.push_back(std::move(issue));
  }
  bool full() const { return list_.size() >= kMaxIssues; }
  std::vector<Issue>& list() { return list_; }

 private:
  std::vector<Issue> list_;
};

std::string os_reason(int err) { return std::generic_category().message(err); }

// A whole file as text, or nullopt and the reason; files over `limit` bytes are refused
// (reading /dev/zero must not hang or exhaust memory).
std::optional<std::string> read_text_file(const std::string& path, std::size_t limit, std::string& error) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    error = "cannot read file: " + os_reason(errno);
    return std::nullopt;
  }
  std::string text;
  // Room for the whole file up front (when its size is known and within the limit): a 55 MB
  // mesh grown by doubling is copied about twice over, and each copy touches fresh pages.
  std::error_code size_ec;
  const std::uintmax_t size = std::filesystem::file_size(path, size_ec);
  if (!size_ec && size <= limit) text.reserve(static_cast<std::size_t>(size) + 1);
  std::array<char, 1 << 16> buffer;
  bool too_large = false;
  int read_error = 0;
  for (;;) {
    const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), f);
    text.append(buffer.data(), got);
    if (text.size() > limit) {
      too_large = true;
      break;
    }
    if (got < buffer.size()) {
      if (std::ferror(f)) read_error = errno != 0 ? errno : EIO;
      break;
    }
  }
  std::fclose(f);
  if (read_error != 0) {
    error = "cannot read file: " + os_reason(read_error);
    return std::nullopt;
  }
  if (too_large) {
    error = "cannot read file: larger than " + std::to_string(limit >> 20) + " MiB";
    return std::nullopt;
  }
  return text;
}

// Where a scene's mesh files come from: the disk, relative to the scene file's folder, or the
// files compiled in beside the embedded scenes.
struct SceneFiles {
  std::string base_dir = ".";
  bool embedded = false;

  // `relative` as written in the scene (or in an OBJ's mtllib, joined to the OBJ's folder).
  std::optional<std::string> read(const std::string& relative, std::string& error) const {
    namespace fs = std::filesystem;
    const fs::path p(relative);
    if (embedded) {
      const std::string key = p.lexically_normal().generic_string();
      if (auto text = embedded_file(key)) return text;
      error = "no such embedded file";
      return std::nullopt;
    }
    const std::string path = resolve(relative);
    std::error_code ec;
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec)) {
      error = "not a regular file";  // a device such as /dev/zero would be read for ever
      return std::nullopt;
    }
    return read_text_file(path, kMaxMeshFileBytes, error);
  }

  // The absolute path `relative` names on disk; empty for embedded files.
  std::string resolve(const std::string& relative) const {
    namespace fs = std::filesystem;
    if (embedded) return "";
    const fs::path p(relative);
    std::error_code ec;
    const fs::path full = fs::absolute(p.is_absolute() ? p : fs::path(base_dir) / p, ec);
    return ec ? (fs::path(base_dir) / p).string() : full.lexically_normal().string();
  }
};

// The rotation of a mesh transform: about x, then y, then z (degrees, right-handed).
glm::dmat3 rotation_of(const MeshTransform& t) {
  const Vec3 r = glm::radians(t.rotate_deg);
  const double cx = std::cos(r.x), sx = std::sin(r.x);
  const double cy = std::cos(r.y), sy = std::sin(r.y);
  const double cz = std::cos(r.z), sz = std::sin(r.z);
  const glm::dmat3 rx(1, 0, 0, 0, cx, sx, 0, -sx, cx);  // glm is column-major
  const glm::dmat3 ry(cy, 0, -sy, 0, 1, 0, sy, 0, cy);
  const glm::dmat3 rz(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
  return rz * ry * rx;
}

struct MeshLoad {
  std::shared_ptr<const MeshGeometry> geometry;
  std::vector<Material> materials;  // the MTL's, to append to the scene's (none with an override)
  std::vector<std::string> errors;  // "file.obj:LINE: message"
  std::vector<std::string> warnings;
  std::vector<Emitter> emitters;    // centroids in world coordinates
};

// Reads an OBJ (and its MTL) and places it in the world. MTL materials get indices from
// `material_base` on; with `override_material` >= 0 every face uses that instead.
MeshLoad load_mesh(const SceneFiles& files, const std::string& file, const MeshTransform& transform,
                   NsMapping ns, int override_material, int material_base) {
  MeshLoad out;
  std::string error;
  const std::optional<std::string> text = files.read(file, error);
  if (!text) {
    out.errors.push_back("cannot load mesh '" + file + "': " + error);
    return out;
  }
  const std::string obj_dir = std::filesystem::path(file).parent_path().generic_string();
  const FileReader read_mtl = [&](const std::string& mtl, std::string& err) {
    return files.read(obj_dir.empty() ? mtl : obj_dir + "/" + mtl, err);
  };
  // The room for the mesh's Triangles is allocated and first touched (0.15 s for 1.3M of them)
  // on the prescan's thread, which finishes well before tinyobjloader's parse on this one.
  std::vector<Triangle> room;
  ObjIndexedMesh obj = load_obj_indexed(*text, file, read_mtl, ns, [&](std::size_t n) { room.resize(n); });
  for (const ObjProblem& w : obj.warnings) out.warnings.push_back(w.to_string());
  for (const ObjProblem& e : obj.errors) out.errors.push_back(e.to_string());
  if (!out.errors.empty()) return out;
  if (obj.triangles.empty()) {
    out.errors.push_back(file + ": no faces (a mesh needs at least one triangle of non-zero area)");
    return out;
  }
  const std::string stem = std::filesystem::path(file).stem().string();
  if (override_material < 0) {
    for (Material& m : obj.materials) {
      m.name = stem + "/" + m.name;
      m.source = file;
      out.materials.push_back(std::move(m));
    }
  }
  const glm::dmat3 rotation = rotation_of(transform);
  const glm::dmat3 linear = rotation * glm::dmat3(glm::scale(glm::dmat4(1), transform.scale));
  const glm::dmat3 normal_matrix = rotation * glm::dmat3(glm::scale(glm::dmat4(1), 1.0 / transform.scale));
  const auto place = [&](const Vec3& p) { return linear * p + transform.translate; };
  // Each vertex and normal is placed once (the same arithmetic as placing every triangle's
  // corners, a vertex being shared by six triangles or so), and the triangles stay indices until
  // make_mesh_geometry makes each once, in its leaf slot: a 1.3M-triangle mesh is 200 MB of
  // Triangles, made and copied three times over before.
  for (Vec3& v : obj.vertices) v = place(v);
  for (Vec3& n : obj.normals) n = normal_matrix * n;
  std::vector<ObjIndexedTriangle>& placed = obj.triangles;
  std::size_t kept = 0;
  // A mirroring transform (an odd number of negative scales) reverses the winding: swapping two
  // vertices keeps Ng on the side the OBJ's winding put it (outward for a closed mesh).
  const bool mirrored = glm::determinant(linear) < 0;
  int degenerate = 0;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    const ObjIndexedTriangle t = placed[i];
    const Vec3& v0 = obj.vertices[t.v[0]];
    const Vec3& v1 = obj.vertices[t.v[1]];
    const Vec3& v2 = obj.vertices[t.v[2]];
    if (!all_finite(v0) || !all_finite(v1) || !all_finite(v2)) {
      out.errors.push_back(file + ": the transform takes face " + std::to_string(t.face + 1) +
                           " beyond the range of doubles");
      return out;
    }
    const Vec3 cross = glm::cross(v1 - v0, v2 - v0);
    if (!(glm::dot(cross, cross) > 0)) {
      ++degenerate;
      continue;
    }
    placed[kept++] = t;
  }
  placed.resize(kept);
  if (degenerate > 0) {
    out.warnings.push_back(file + ": " + std::to_string(degenerate) + " triangles have zero area after the transform; left out");
  }
  if (placed.empty()) {
    out.errors.push_back(file + ": no triangle of non-zero area after the transform");
    return out;
  }
  for (Emitter e : obj.emitters) {
    e.centroid = place(e.centroid);
    std::ostringstream hint;
    hint << file << ": material '" << e.material << "' emits light (Ke " << e.ke.x << " " << e.ke.y << " "
         << e.ke.z << ") from " << e.faces << " face(s); phonglab has point lights only: place one near ["
         << e.centroid.x << ", " << e.centroid.y << ", " << e.centroid.z << "], their centre";
    out.warnings.push_back(hint.str());
    out.emitters.push_back(e);
  }
  std::vector<int> faces(placed.size());
  for (std::size_t i = 0; i < placed.size(); ++i) faces[i] = placed[i].face;
  const auto make = [&](std::size_t i) {
    Triangle t = obj.triangle(i);
    if (mirrored) {
      std::swap(t.v1, t.v2);
      std::swap(t.n1, t.n2);
    }
    t.material = override_material >= 0 ? override_material : material_base + t.material;
    return t;
  };
  // triangle_bounds(make(i)) without making the Triangle: its corners grown in the same order.
  const auto box_of = [&](std::size_t i) {
    const ObjIndexedTriangle& t = placed[i];
    Aabb b;
    b.grow(obj.vertices[t.v[0]]);
    b.grow(obj.vertices[t.v[mirrored ? 2 : 1]]);
    b.grow(obj.vertices[t.v[mirrored ? 1 : 2]]);
    return b;
  };
  out.geometry = make_mesh_geometry(placed.size(), make, std::move(faces), std::move(room), box_of);
  return out;
}

class Validator {
 public:
  Validator(std::string_view original, const PosIndex& index, const Json& root,
            const std::vector<Overflow>& overflows, Issues& issues, const SceneFiles& files, Issues& warnings)
      : text_(original), index_(index), root_(root), overflows_(overflows), issues_(issues), files_(files),
        warnings_(warnings) {}

  Scene run() {
    Scene s;
    const Val root{&root_, 0, ""};
    if (!root_.is_object()) {
      report(root, "the scene must be a JSON object (got " + shown(root) + ")");
      return s;
    }
    const Fields top = fields(root, kSceneKeys);
    if (const Val* v = top.find("camera")) camera(*v, s.camera);
    if (const Val* v = top.find("image")) image(*v, s);
    if (const Val* v = top.find("ambient")) set(s.ambient, read_color(*v));
    if (const Val* v = top.find("background")) set(s.background, read_color(*v));
    if (const Val* v = top.find("max_depth")) set(s.max_depth, read_int(*v, 0, kMaxDepthLimit));
    if (const Val* v = top.find("min_weight")) set(s.min_weight, read_at_least_zero(*v));
    if (const Val* v = top.find("specular_model")) {
      if (auto name = read_choice(*v, kSpecularModels, "specular model")) {
        s.specular_model = (*name == "blinn") ? SpecularModel::kBlinn : SpecularModel::kPhong;
      }
    }
    if (const Val* v = top.find("lights")) lights(*v, s);
    // Materials before objects: objects refer to them by name.
    if (const Val* v = top.find("materials")) materials(*v, s);
    if (const Val* v = top.find("objects")) objects(*v, s);
    return s;
  }

 private:
  template <typename T, typename U>
  static void set(T& target, const std::optional<U>& value) {
    if (value) target = static_cast<T>(*value);
  }

  void report(const Val& v, std::string message) {
    issues_.add({index_.begin(v.node), v.path, std::move(message)});
  }

  // The value as written (the index only knows the patched "0" of an overflowing number).
  std::string shown(const Val& v) const {
    const std::size_t begin = index_.begin(v.node);
    const Overflow* o = overflow(v);
    return compact_source(text_, begin, o != nullptr ? begin + o->length : index_.end(v.node));
  }

  // The overflowing number token this value was parsed from, if any.
  const Overflow* overflow(const Val& v) const {
    const std::size_t off = index_.begin(v.node);
    const auto it = std::lower_bound(
        overflows_.begin(), overflows_.end(), off,
        [](const Overflow& o, std::size_t offset) { return o.offset < offset; });
    return (it != overflows_.end() && it->offset == off) ? &*it : nullptr;
  }

  Val element(const Val& v, std::size_t i) const {
    return {&(*v.json)[i], index_.children(v.node)[i], element_path(v.path, i)};
  }

  // Number of elements of an array value (0 if the DOM and the index ever disagreed).
  std::size_t element_count(const Val& v) const {
    return index_.children(v.node).size() == v.json->size() ? v.json->size() : 0;
  }

  // Members in file order with the last duplicate's position (the value the DOM kept);
  // later duplicates are reported.
  std::vector<std::pair<std::string, Val>> members(const Val& v) {
    std::vector<std::pair<std::string, Val>> out;
    std::unordered_map<std::string, std::size_t> seen;
    for (std::size_t child : index_.children(v.node)) {
      std::string key = index_.key(child);
      const auto it = v.json->find(key);
      if (it == v.json->end()) continue;
      const auto [pos, inserted] = seen.emplace(key, out.size());
      if (!inserted) {
        issues_.add({index_.key_begin(child), member_path(v.path, key), "duplicate key"});
        out[pos->second].second.node = child;
        continue;
      }
      Val member{&*it, child, member_path(v.path, key)};
      out.emplace_back(std::move(key), std::move(member));
    }
    return out;
  }

  // The members of an object value, reporting keys outside `allowed`.
  Fields fields(const Val& v, std::span<const std::string_view> allowed) {
    Fields f;
    for (auto& [key, member] : members(v)) {
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        issues_.add({index_.key_begin(member.node), member.path,
                     "unknown key" + suggestion(key, allowed, "expected one of")});
        continue;
      }
      f.members.emplace_back(std::move(key), std::move(member));
    }
    return f;
  }

  // One member looked up without any key checks (to read "type" before choosing the keys).
  std::optional<Val> member(const Val& v, std::string_view key) {
    const auto it = v.json->find(std::string(key));
    if (it == v.json->end()) return std::nullopt;
    const auto kids = index_.children(v.node);
    for (std::size_t k = kids.size(); k-- > 0;) {
      if (index_.key(kids[k]) == key) return Val{&*it, kids[k], member_path(v.path, key)};
    }
    return std::nullopt;
  }

  // Reports each missing key at the object's '{'; true when all are present.
  bool require(const Val& v, const Fields& f, std::initializer_list<std::string_view> keys) {
    bool ok = true;
    for (std::string_view k : keys) {
      if (f.find(k) == nullptr) {
        report(v, "missing key " + json_string(k));
        ok = false;
      }
    }
    return ok;
  }

  bool expect_object(const Val& v) {
    if (v.json->is_object()) return true;
    report(v, "must be an object (got " + shown(v) + ")");
    return false;
  }

  bool expect_array(const Val& v) {
    if (v.json->is_array()) return true;
    report(v, "must be an array (got " + shown(v) + ")");
    return false;
  }

  std::optional<double> read_number(const Val& v) {
    if (!v.json->is_number()) {
      report(v, "must be a number (got " + shown(v) + ")");
      return std::nullopt;
    }
    const double x = v.json->get<double>();
    if (overflow(v) != nullptr || !std::isfinite(x)) {
      report(v, "must be a finite number (got " + shown(v) + ")");
      return std::nullopt;
    }
    if (std::abs(x) > kMaxMagnitude) {
      report(v, "out of range: magnitude must be <= 1e100 (got " + shown(v) + ")");
      return std::nullopt;
    }
    return x;
  }

  std::optional<double> read_at_least_zero(const Val& v) {
    const auto x = read_number(v);
    if (x && *x < 0) {
      report(v, "must be >= 0 (got " + shown(v) + ")");
      return std::nullopt;
    }
    return x;
  }

  std::optional<double> read_positive(const Val& v) {
    const auto x = read_number(v);
    if (x && !(*x > 0)) {
      report(v, "must be > 0 (got " + shown(v) + ")");
      return std::nullopt;
    }
    return x;
  }

  std::optional<int> read_int(const Val& v, int lo, int hi) {
    const auto x = read_number(v);
    if (!x) return std::nullopt;
    if (*x != std::floor(*x) || *x < lo || *x > hi) {
      report(v, "must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                    " (got " + shown(v) + ")");
      return std::nullopt;
    }
    return static_cast<int>(*x);
  }

  std::optional<bool> read_bool(const Val& v) {
    if (v.json->is_boolean()) return v.json->get<bool>();
    report(v, "must be true or false (got " + shown(v) + ")");
    return std::nullopt;
  }

  std::optional<std::string> read_string(const Val& v) {
    if (v.json->is_string()) return v.json->get<std::string>();
    report(v, "must be a string (got " + shown(v) + ")");
    return std::nullopt;
  }

  // A string that must be one of `choices`; `what` names it in the message.
  std::optional<std::string> read_choice(const Val& v, std::span<const std::string_view> choices,
                                         std::string_view what) {
    auto s = read_string(v);
    if (!s) return std::nullopt;
    if (std::find(choices.begin(), choices.end(), *s) != choices.end()) return s;
    report(v, "unknown " + std::string(what) + " " + shown(v) +
                  suggestion(*s, choices, "expected one of"));
    return std::nullopt;
  }

  std::optional<Vec3> read_vec3(const Val& v) {
    if (!v.json->is_array() || v.json->size() != 3) {
      report(v, "must be an array of 3 numbers (got " + shown(v) + ")");
      return std::nullopt;
    }
    return read_triple(v, &Validator::read_number);
  }

  // The three elements of an array checked by `read_one`; every element's error is reported.
  std::optional<Vec3> read_triple(const Val& v, std::optional<double> (Validator::*read_one)(const Val&)) {
    if (element_count(v) != 3) return std::nullopt;
    Vec3 out;
    bool ok = true;
    for (int i = 0; i < 3; ++i) {
      if (auto x = (this->*read_one)(element(v, static_cast<std::size_t>(i)))) {
        out[i] = *x;
      } else {
        ok = false;
      }
    }
    return ok ? std::optional<Vec3>(out) : std::nullopt;
  }

  // A direction: three numbers, not of zero length.
  std::optional<Vec3> read_direction(const Val& v) {
    auto d = read_vec3(v);
    if (d && !normalizable(*d)) {
      report(v, "must have non-zero length (got " + shown(v) + ")");
      return std::nullopt;
    }
    return d;
  }

  // A colour: one number (grey) or three, every channel >= 0.
  std::optional<Color> read_color(const Val& v) {
    if (v.json->is_number()) {
      const auto x = read_at_least_zero(v);
      return x ? std::optional<Color>(Color(*x)) : std::nullopt;
    }
    if (!v.json->is_array() || v.json->size() != 3) {
      report(v, "must be a number or an array of 3 numbers (got " + shown(v) + ")");
      return std::nullopt;
    }
    return read_triple(v, &Validator::read_at_least_zero);
  }

  void camera(const Val& v, Camera& cam) {
    if (!expect_object(v)) return;
    const Fields f = fields(v, kCameraKeys);
    const Val* position = f.find("position");
    const Val* look_at = f.find("look_at");
    const Val* up = f.find("up");
    bool position_ok = true, look_ok = true, up_ok = true;
    if (position) position_ok = assign(cam.position, read_vec3(*position));
    if (look_at) look_ok = assign(cam.look_at, read_vec3(*look_at));
    if (up) up_ok = assign(cam.up, read_direction(*up));
    if (const Val* fov = f.find("fov_y")) {
      if (auto x = read_number(*fov)) {
        if (*x > 0 && *x < 180) {
          cam.fov_y_deg = *x;
        } else {
          report(*fov, "must be in (0, 180) (got " + shown(*fov) + ")");
        }
      }
    }
    if (!position_ok || !look_ok) return;
    const Vec3 view = cam.look_at - cam.position;
    if (!normalizable(view)) {
      if (look_at) {
        report(*look_at, "must differ from camera.position (got " + shown(*look_at) + ")");
      } else {
        report(*position, "must differ from camera.look_at (got " + shown(*position) + ")");
      }
      return;
    }
    if (!up_ok) return;
    // |F x up| <= 1e-9 |F||up|, computed on the normalised vectors so nothing under/overflows.
    const double sine = glm::length(glm::cross(glm::normalize(view), glm::normalize(cam.up)));
    if (!(sine > 1e-9)) {
      if (up) {
        report(*up, "must not be parallel to the view direction (got " + shown(*up) + ")");
      } else {
        const Val& at = look_at ? *look_at : *position;
        report(at, "makes the view direction parallel to camera.up (got " + shown(at) + ")");
      }
    }
  }

  template <typename T>
  static bool assign(T& target, const std::optional<T>& value) {
    if (value) target = *value;
    return value.has_value();
  }

  void image(const Val& v, Scene& s) {
    if (!expect_object(v)) return;
    const Fields f = fields(v, kImageKeys);
    if (const Val* w = f.find("width")) set(s.width, read_int(*w, 1, kMaxImageSide));
    if (const Val* h = f.find("height")) set(s.height, read_int(*h, 1, kMaxImageSide));
  }

  // Reads an element's "type" member (reporting it missing or not a string).
  std::optional<std::pair<Val, std::string>> type_of(const Val& v) {
    auto t = member(v, "type");
    if (!t) {
      report(v, "missing key \"type\"");
      return std::nullopt;
    }
    auto s = read_string(*t);
    if (!s) return std::nullopt;
    return std::make_pair(std::move(*t), std::move(*s));
  }

  void lights(const Val& v, Scene& s) {
    if (!expect_array(v)) return;
    const std::size_t count = element_count(v);
    for (std::size_t i = 0; i < count && !issues_.full(); ++i) {
      const Val e = element(v, i);
      if (!expect_object(e)) continue;
      const auto type = type_of(e);
      if (!type) continue;
      Light light;
      const bool point = type->second == "point";
      if (!point && type->second != "directional") {
        report(type->first, "unknown light type " + shown(type->first) +
                                suggestion(type->second, kLightTypes, "expected one of"));
        continue;
      }
      const Fields f = fields(e, point ? std::span<const std::string_view>(kPointLightKeys)
                                       : std::span<const std::string_view>(kDirectionalLightKeys));
      bool ok = require(e, f, {point ? "position" : "direction"});
      if (point) {
        light.type = LightType::kPoint;
        if (const Val* p = f.find("position")) ok = assign(light.position, read_vec3(*p)) && ok;
      } else {
        light.type = LightType::kDirectional;
        if (const Val* d = f.find("direction")) {
          ok = assign(light.direction, read_direction(*d)) && ok;
        }
      }
      if (const Val* x = f.find("intensity")) ok = assign(light.intensity, read_color(*x)) && ok;
      if (const Val* en = f.find("enabled")) ok = assign(light.enabled, read_bool(*en)) && ok;
      if (ok) s.lights.push_back(light);
    }
  }

  void materials(const Val& v, Scene& s) {
    has_materials_ = true;
    if (!expect_object(v)) {
      materials_unusable_ = true;
      return;
    }
    for (auto& [name, m] : members(v)) {
      if (issues_.full()) break;
      material_index_.emplace(name, static_cast<int>(s.materials.size()));
      material_names_.push_back(name);
      Material mat;
      mat.name = name;
      if (expect_object(m)) {
        const Fields f = fields(m, kMaterialKeys);
        if (const Val* x = f.find("ka")) set(mat.ka, read_color(*x));
        if (const Val* x = f.find("kd")) set(mat.kd, read_color(*x));
        if (const Val* x = f.find("ks")) set(mat.ks, read_color(*x));
        if (const Val* x = f.find("n")) set(mat.n, read_at_least_zero(*x));
        if (const Val* x = f.find("kr")) set(mat.kr, read_color(*x));
        if (const Val* x = f.find("kt")) set(mat.kt, read_color(*x));
        if (const Val* x = f.find("ior")) set(mat.ior, read_positive(*x));
        if (const Val* x = f.find("fresnel")) set(mat.fresnel, read_bool(*x));
      }
      s.materials.push_back(std::move(mat));
    }
  }

  // The index of the material an object names; one error per bad reference, none when the
  // "materials" section itself was broken (that error says it all).
  std::optional<int> material_ref(const Val& v) {
    const auto name = read_string(v);
    if (!name) return std::nullopt;
    if (!has_materials_) {
      // Every object would repeat this; once is enough.
      if (!reported_no_materials_) {
        report(v, "unknown material " + shown(v) + " (the scene has no \"materials\")");
        reported_no_materials_ = true;
      }
      return std::nullopt;
    }
    if (materials_unusable_) return std::nullopt;
    if (const auto it = material_index_.find(*name); it != material_index_.end()) return it->second;
    std::vector<std::string_view> names(material_names_.begin(), material_names_.end());
    report(v, "unknown material " + shown(v) + suggestion(*name, names, "defined materials"));
    return std::nullopt;
  }

  void objects(const Val& v, Scene& s) {
    if (!expect_array(v)) return;
    const std::size_t count = element_count(v);
    for (std::size_t i = 0; i < count && !issues_.full(); ++i) {
      const Val e = element(v, i);
      if (!expect_object(e)) continue;
      const auto type = type_of(e);
      if (!type) continue;
      const std::string& t = type->second;
      const int object = static_cast<int>(i);
      if (t == "sphere") {
        sphere(e, s, object);
      } else if (t == "plane") {
        plane(e, s, object);
      } else if (t == "triangle") {
        triangle(e, s, object);
      } else if (t == "mesh") {
        mesh(e, s, object);
      } else {
        report(type->first, "unknown object type " + shown(type->first) +
                                suggestion(t, kObjectTypes, "expected one of"));
      }
    }
  }

  void sphere(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kSphereKeys);
    bool ok = require(e, f, {"center", "radius", "material"});
    Sphere sp;
    if (const Val* x = f.find("center")) ok = assign(sp.center, read_vec3(*x)) && ok;
    if (const Val* x = f.find("radius")) ok = assign(sp.radius, read_positive(*x)) && ok;
    if (const Val* x = f.find("material")) ok = assign(sp.material, material_ref(*x)) && ok;
    if (!ok) return;
    s.spheres.push_back(sp);
    s.sphere_object.push_back(object);
  }

  void plane(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kPlaneKeys);
    bool ok = require(e, f, {"point", "normal", "material"});
    Plane pl;
    if (const Val* x = f.find("point")) ok = assign(pl.point, read_vec3(*x)) && ok;
    if (const Val* x = f.find("normal")) ok = assign(pl.normal, read_direction(*x)) && ok;
    if (const Val* x = f.find("material")) ok = assign(pl.material, material_ref(*x)) && ok;
    if (!ok) return;
    s.planes.push_back(pl);
    s.plane_object.push_back(object);
  }

  // Three vectors (`what` each: points or directions), as for "vertices" and "normals".
  std::optional<std::array<Vec3, 3>> read_three(const Val& v, bool directions) {
    if (!v.json->is_array() || v.json->size() != 3) {
      report(v, std::string("must be an array of 3 ") + (directions ? "directions" : "points") +
                    " (got " + shown(v) + ")");
      return std::nullopt;
    }
    std::array<Vec3, 3> out;
    bool ok = true;
    if (element_count(v) != 3) return std::nullopt;
    for (std::size_t i = 0; i < 3; ++i) {
      const Val e = element(v, i);
      ok = assign(out[i], directions ? read_direction(e) : read_vec3(e)) && ok;
    }
    return ok ? std::optional<std::array<Vec3, 3>>(out) : std::nullopt;
  }

  void triangle(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kTriangleKeys);
    bool ok = require(e, f, {"vertices", "material"});
    Triangle tri;
    if (const Val* x = f.find("vertices")) {
      if (const auto v = read_three(*x, false)) {
        tri.v0 = (*v)[0];
        tri.v1 = (*v)[1];
        tri.v2 = (*v)[2];
        if (!normalizable(glm::cross(tri.v1 - tri.v0, tri.v2 - tri.v0))) {
          report(*x, "degenerate triangle: the vertices are collinear (got " + shown(*x) + ")");
          ok = false;
        }
      } else {
        ok = false;
      }
    }
    if (const Val* x = f.find("normals")) {
      if (const auto n = read_three(*x, true)) {
        tri.has_vertex_normals = true;
        tri.n0 = (*n)[0];
        tri.n1 = (*n)[1];
        tri.n2 = (*n)[2];
      } else {
        ok = false;
      }
    }
    if (const Val* x = f.find("material")) ok = assign(tri.material, material_ref(*x)) && ok;
    if (!ok) return;
    s.triangles.push_back(tri);
    s.triangle_object.push_back(object);
  }

  // A mesh transform: "scale" (a number or 3, none zero), "rotate_deg", "translate".
  bool transform(const Val& v, MeshTransform& out) {
    if (!expect_object(v)) return false;
    const Fields f = fields(v, kTransformKeys);
    bool ok = true;
    if (const Val* x = f.find("scale")) {
      std::optional<Vec3> scale;
      if (x->json->is_number()) {
        if (const auto k = read_number(*x)) scale = Vec3(*k);
      } else {
        scale = read_vec3(*x);
      }
      if (scale && (scale->x == 0 || scale->y == 0 || scale->z == 0)) {
        report(*x, "must not be zero (got " + shown(*x) + ")");
        scale.reset();
      }
      ok = assign(out.scale, scale) && ok;
    }
    if (const Val* x = f.find("rotate_deg")) ok = assign(out.rotate_deg, read_vec3(*x)) && ok;
    if (const Val* x = f.find("translate")) ok = assign(out.translate, read_vec3(*x)) && ok;
    return ok;
  }

  void mesh(const Val& e, Scene& s, int object) {
    const Fields f = fields(e, kMeshKeys);
    bool ok = require(e, f, {"file"});
    Mesh mesh;
    const Val* file = f.find("file");
    if (file) {
      if (auto name = read_string(*file)) {
        mesh.file = *name;
        if (mesh.file.empty()) {
          report(*file, "must name an OBJ file (got \"\")");
          ok = false;
        }
      } else {
        ok = false;
      }
    }
    int override_material = -1;
    if (const Val* x = f.find("material")) {
      const auto m = material_ref(*x);
      ok = m.has_value() && ok;
      if (m) {
        override_material = *m;
        mesh.material_override = s.materials[static_cast<std::size_t>(*m)].name;
      }
    }
    if (const Val* x = f.find("transform")) ok = transform(*x, mesh.transform) && ok;
    NsMapping ns = NsMapping::kAsIs;
    if (const Val* x = f.find("ns")) {
      const auto choice = read_choice(*x, kNsMappings, "Ns mapping");
      ok = choice.has_value() && ok;
      if (choice && *choice == "blinn_to_phong") ns = NsMapping::kBlinnToPhong;
    }
    if (!ok || file == nullptr) return;
    MeshLoad loaded = load_mesh(files_, mesh.file, mesh.transform, ns, override_material,
                                static_cast<int>(s.materials.size()));
    for (std::string& w : loaded.warnings) warnings_.add({index_.begin(file->node), file->path, std::move(w)});
    if (!loaded.errors.empty()) {
      for (std::string& message : loaded.errors) report(*file, std::move(message));
      return;
    }
    mesh.geometry = std::move(loaded.geometry);
    mesh.ns = ns;
    mesh.resolved_path = files_.resolve(mesh.file);
    for (Material& m : loaded.materials) s.materials.push_back(std::move(m));
    s.meshes.push_back(std::move(mesh));
    s.mesh_object.push_back(object);
  }

  std::string_view text_;
  const PosIndex& index_;
  const Json& root_;
  const std::vector<Overflow>& overflows_;
  Issues& issues_;
  const SceneFiles& files_;
  Issues& warnings_;  // problems that do not stop the scene from loading (mesh files' quirks)
  bool has_materials_ = false;       // the scene has a "materials" member
  bool materials_unusable_ = false;  // ... but it is not an object
  bool reported_no_materials_ = false;
  std::unordered_map<std::string, int> material_index_;
  std::vector<std::string> material_names_;  // file order, for suggestions
};

// Positions every issue (1-based line; column in characters, a UTF-8 BOM not counted) in one
// sweep over the text, in text order.
std::vector<Diagnostic> to_diagnostics(std::string_view t, std::vector<Issue> issues,
                                       bool truncated, const std::string& file) {
  std::stable_sort(issues.begin(), issues.end(),
                   [](const Issue& a, const Issue& b) { return a.offset < b.offset; });
  std::vector<Diagnostic> out;
  std::size_t pos = has_bom(t) ? 3 : 0;
  int line = 1, column = 1;
  for (Issue& issue : issues) {
    Diagnostic d;
    d.file = file;
    d.path = std::move(issue.path);
    d.message = std::move(issue.message);
    if (issue.offset != kNoOffset) {
      const std::size_t target = std::min(issue.offset, t.size());
      for (; pos < target; ++pos) {
        if (t[pos] == '\n') {
          ++line;
          column = 1;
        } else if ((static_cast<unsigned char>(t[pos]) & 0xC0) != 0x80) {
          ++column;
        }
      }
      d.line = line;
      d.column = column;
    }
    out.push_back(std::move(d));
  }
  if (truncated) {
    Diagnostic d;
    d.file = file;
    d.message = "too many errors; stopped after the first " + std::to_string(kMaxIssues);
    out.push_back(std::move(d));
  }
  return out;
}

LoadResult fail(const std::string& file, std::string message) {
  LoadResult r;
  Diagnostic d;
  d.file = file;
  d.message = std::move(message);
  r.errors.push_back(std::move(d));
  return r;
}

LoadResult load_text(const std::string& text, const std::string& file_name, const SceneFiles& files) {
  Issues issues, warnings;
  const auto finish = [&](std::optional<Scene> scene) {
    LoadResult r;
    const bool truncated = issues.full();
    r.errors = to_diagnostics(text, std::move(issues.list()), truncated, file_name);
    r.warnings = to_diagnostics(text, std::move(warnings.list()), false, file_name);
    if (r.errors.empty()) r.scene = std::move(scene);
    return r;
  };

  if (text.size() >= kMaxTextBytes) {
    issues.add({kNoOffset, "", "the scene text is too large (2 GiB or more)"});
    return finish(std::nullopt);
  }
  const std::size_t start = has_bom(text) ? 3 : 0;
  if (std::all_of(text.begin() + static_cast<std::ptrdiff_t>(start), text.end(), is_space)) {
    issues.add({start, "", "the file is empty (expected a JSON object)"});
    return finish(std::nullopt);
  }
  const Prescan pre = prescan(text);
  if (pre.too_deep != kNoOffset) {
    issues.add({pre.too_deep, "", "nesting deeper than " + std::to_string(kMaxNesting) +
                                      " levels of arrays and objects"});
    return finish(std::nullopt);
  }
  // Overflowing numbers become "0" plus spaces: the text keeps every offset and parses, and the
  // validator reports them as non-finite from the original text.
  std::string patched;
  if (!pre.overflows.empty()) {
    patched = text;
    for (const Overflow& o : pre.overflows) {
      patched.replace(o.offset, o.length, std::string(o.length, ' '));
      patched[o.offset] = '0';
    }
  }
  // nlohmann reads a NUL byte as the end of the input, so it only parses the text before one:
  // a syntax error there is reported as such, else the NUL itself is the error.
  std::string_view parsed_text = pre.overflows.empty() ? text : patched;
  if (pre.nul != kNoOffset) parsed_text = parsed_text.substr(0, pre.nul);

  Json root;
  try {
    root = Json::parse(parsed_text);
  } catch (const Json::parse_error& e) {
    Issue issue = syntax_issue(std::string_view(text).substr(0, parsed_text.size()), e, pre);
    if (pre.nul != kNoOffset && issue.offset >= pre.nul) {
      issue = {pre.nul, "", "syntax error: unexpected byte 0x00 (a scene file is text)"};
    }
    issues.add(std::move(issue));
    return finish(std::nullopt);
  } catch (const Json::exception& e) {
    issues.add({kNoOffset, "", std::string("cannot parse: ") + e.what()});
    return finish(std::nullopt);
  }
  if (pre.nul != kNoOffset) {
    issues.add({pre.nul, "", "syntax error: unexpected byte 0x00 (a scene file is text)"});
    return finish(std::nullopt);
  }
  const PosIndex index(parsed_text);
  Validator validator(text, index, root, pre.overflows, issues, files, warnings);
  Scene scene = validator.run();
  return finish(std::move(scene));
}

}  // namespace

namespace {

LoadResult load_scene_text_from(const std::string& text, const std::string& file_name, const SceneFiles& files) {
  try {
    return load_text(text, file_name, files);
  } catch (const std::bad_alloc&) {
    return fail(file_name, "out of memory while loading the scene");
  } catch (const std::exception& e) {
    return fail(file_name, std::string("internal error while loading the scene: ") + e.what());
  }
}

// An OBJ opened on its own: its MTL materials, a camera that frames it from the front (+z)
// and above, a white point light above the camera, a dim ambient term.
LoadResult load_obj_scene(const std::string& path) {
  const std::string dir = std::filesystem::path(path).parent_path().string();
  const SceneFiles files{dir.empty() ? "." : dir, false};
  const std::string name = std::filesystem::path(path).filename().string();
  MeshLoad loaded = load_mesh(files, name, MeshTransform{}, NsMapping::kAsIs, -1, 0);
  LoadResult r;
  const auto diagnostic = [&](std::string message) {
    Diagnostic d;
    d.file = path;
    d.message = std::move(message);
    return d;
  };
  for (std::string& w : loaded.warnings) r.warnings.push_back(diagnostic(std::move(w)));
  for (std::string& e : loaded.errors) r.errors.push_back(diagnostic(std::move(e)));
  if (!r.errors.empty()) return r;
  Scene scene;
  scene.ambient = Color(0.2);
  scene.materials = std::move(loaded.materials);
  Mesh mesh;
  mesh.file = name;
  mesh.resolved_path = files.resolve(name);
  mesh.geometry = std::move(loaded.geometry);
  const Aabb box = mesh.geometry->bounds;
  scene.meshes.push_back(std::move(mesh));
  scene.mesh_object.push_back(0);
  const Vec3 centre = box.centroid();
  const double radius = std::max(0.5 * glm::length(box.hi - box.lo), 1e-12);
  Camera& cam = scene.camera;
  cam.look_at = centre;
  // The bounding sphere fits the vertical field of view with a 10 % margin, seen slightly
  // from above (1 in 4).
  const double distance = 1.1 * radius / std::sin(glm::radians(cam.fov_y_deg) / 2);
  cam.position = centre + distance * glm::normalize(Vec3(0, 0.25, 1));
  Light light;
  light.position = cam.position + Vec3(0, radius, 0);
  scene.lights.push_back(light);
  r.scene = std::move(scene);
  return r;
}

}  // namespace

bool is_obj_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = to_lower(c);
  return ext == ".obj";
}

LoadResult load_scene_text(const std::string& text, const std::string& file_name,
                           const std::string& base_dir) {
  return load_scene_text_from(text, file_name, SceneFiles{base_dir, false});
}

LoadResult load_scene_file(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = to_lower(c);
  if (ext == ".mtl") {
    return fail(path, "a material library (MTL) holds an OBJ mesh's materials and is not a scene: open the .obj "
                      "file that names it (its mtllib line), or a scene .json with a mesh object");
  }
  if (is_obj_path(path)) {
    try {
      return load_obj_scene(path);
    } catch (const std::bad_alloc&) {
      return fail(path, "out of memory while loading the mesh");
    }
  }
  std::string error;
  const std::optional<std::string> text = read_text_file(path, kMaxFileBytes, error);
  if (!text) return fail(path, error);
  std::string dir = std::filesystem::path(path).parent_path().string();
  return load_scene_text(*text, path, dir.empty() ? "." : dir);
}

LoadResult load_scene_arg(const std::string& scene_arg) {
  if (const EmbeddedScene* s = find_embedded_scene(scene_arg)) {
    return load_scene_text_from(std::string(s->json), std::string(s->name), SceneFiles{"", true});
  }
  LoadResult result = load_scene_file(scene_arg);
  // A bare word that is neither a file nor an embedded scene was most likely meant as a name.
  const bool looks_like_name = scene_arg.find_first_of("/.") == std::string::npos;
  if (!result.ok() && looks_like_name && result.errors.size() == 1 && result.errors[0].line == 0) {
    std::vector<std::string_view> names;
    for (const EmbeddedScene& e : embedded_scenes()) names.push_back(e.name);
    result.errors[0].message += "; not an embedded scene either" + suggestion(scene_arg, names, "embedded scenes");
  }
  return result;
}

namespace {

// Shortest text that reads back to the same double; JSON has no inf/NaN, so those become null
// (which the loader rejects rather than silently changing).
std::string number_text(double x) {
  if (!std::isfinite(x)) return "null";
  if (x == 0 && std::signbit(x)) return "-0.0";  // "-0" would be read as the integer 0
  std::array<char, 32> buf;
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), r.ptr);
}

std::string vec_text(const Vec3& v) {
  return "[" + number_text(v.x) + ", " + number_text(v.y) + ", " + number_text(v.z) + "]";
}

std::string bool_text(bool b) { return b ? "true" : "false"; }

// One primitive's line in "objects", keyed by the file index it came from.
struct ObjectLine {
  long long order;
  std::string text;
};

}  // namespace

std::string scene_to_json(const Scene& scene, const std::string& save_dir) {
  const auto material_name = [&](int m) {
    const bool valid = m >= 0 && static_cast<std::size_t>(m) < scene.materials.size();
    return json_string(valid ? scene.materials[static_cast<std::size_t>(m)].name : std::string());
  };
  // Primitives without a file index go after all indexed ones, in vector order.
  long long unindexed = static_cast<long long>(std::numeric_limits<int>::max()) + 1;
  const auto order_of = [&](const std::vector<int>& objects, std::size_t i) {
    if (i < objects.size() && objects[i] >= 0) return static_cast<long long>(objects[i]);
    return unindexed++;
  };

  std::vector<ObjectLine> lines;
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    lines.push_back({order_of(scene.sphere_object, i),
                     "{\"type\": \"sphere\", \"center\": " + vec_text(s.center) +
                         ", \"radius\": " + number_text(s.radius) +
                         ", \"material\": " + material_name(s.material) + "}"});
  }
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    const Plane& p = scene.planes[i];
    lines.push_back({order_of(scene.plane_object, i),
                     "{\"type\": \"plane\", \"point\": " + vec_text(p.point) +
                         ", \"normal\": " + vec_text(p.normal) +
                         ", \"material\": " + material_name(p.material) + "}"});
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    std::string line = "{\"type\": \"triangle\", \"vertices\": [" + vec_text(t.v0) + ", " +
                       vec_text(t.v1) + ", " + vec_text(t.v2) + "]";
    if (t.has_vertex_normals) {
      line += ", \"normals\": [" + vec_text(t.n0) + ", " + vec_text(t.n1) + ", " +
              vec_text(t.n2) + "]";
    }
    line += ", \"material\": " + material_name(t.material) + "}";
    lines.push_back({order_of(scene.triangle_object, i), std::move(line)});
  }
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    const MeshTransform& tr = m.transform;
    // A mesh read from disk is named relative to where this text will be saved.
    std::string file = m.file;
    if (!save_dir.empty() && !m.resolved_path.empty()) {
      std::error_code ec;
      const auto dir = std::filesystem::absolute(save_dir, ec);
      const auto rel = std::filesystem::path(m.resolved_path).lexically_relative(dir.lexically_normal());
      if (!ec && !rel.empty()) file = rel.generic_string();
    }
    std::string line = "{\"type\": \"mesh\", \"file\": " + json_string(file);
    if (!m.material_override.empty()) line += ", \"material\": " + json_string(m.material_override);
    line += ", \"transform\": {\"scale\": " + vec_text(tr.scale) + ", \"rotate_deg\": " + vec_text(tr.rotate_deg) +
            ", \"translate\": " + vec_text(tr.translate) + "}";
    if (m.ns == NsMapping::kBlinnToPhong) line += ", \"ns\": \"blinn_to_phong\"";
    line += "}";
    lines.push_back({order_of(scene.mesh_object, i), std::move(line)});
  }
  std::stable_sort(lines.begin(), lines.end(),
                   [](const ObjectLine& a, const ObjectLine& b) { return a.order < b.order; });

  const Camera& c = scene.camera;
  std::string out = "{\n";
  out += "  \"camera\": {\n";
  out += "    \"position\": " + vec_text(c.position) + ",\n";
  out += "    \"look_at\": " + vec_text(c.look_at) + ",\n";
  out += "    \"up\": " + vec_text(c.up) + ",\n";
  out += "    \"fov_y\": " + number_text(c.fov_y_deg) + "\n";
  out += "  },\n";
  out += "  \"image\": {\n";
  out += "    \"width\": " + std::to_string(scene.width) + ",\n";
  out += "    \"height\": " + std::to_string(scene.height) + "\n";
  out += "  },\n";
  out += "  \"ambient\": " + vec_text(scene.ambient) + ",\n";
  out += "  \"background\": " + vec_text(scene.background) + ",\n";
  out += "  \"max_depth\": " + std::to_string(scene.max_depth) + ",\n";
  out += "  \"min_weight\": " + number_text(scene.min_weight) + ",\n";
  out += std::string("  \"specular_model\": ") +
         (scene.specular_model == SpecularModel::kBlinn ? "\"blinn\"" : "\"phong\"") + ",\n";

  out += "  \"lights\": [";
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    out += i == 0 ? "\n    " : ",\n    ";
    if (l.type == LightType::kDirectional) {
      out += "{\"type\": \"directional\", \"direction\": " + vec_text(l.direction);
    } else {
      out += "{\"type\": \"point\", \"position\": " + vec_text(l.position);
    }
    out += ", \"intensity\": " + vec_text(l.intensity) +
           ", \"enabled\": " + bool_text(l.enabled) + "}";
  }
  out += scene.lights.empty() ? "],\n" : "\n  ],\n";

  out += "  \"materials\": {";
  bool first_material = true;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    if (!m.source.empty()) continue;  // an MTL's: the mesh brings it back
    out += first_material ? "\n    " : ",\n    ";
    first_material = false;
    out += json_string(m.name) + ": {\n";
    out += "      \"ka\": " + vec_text(m.ka) + ",\n";
    out += "      \"kd\": " + vec_text(m.kd) + ",\n";
    out += "      \"ks\": " + vec_text(m.ks) + ",\n";
    out += "      \"n\": " + number_text(m.n) + ",\n";
    out += "      \"kr\": " + vec_text(m.kr) + ",\n";
    out += "      \"kt\": " + vec_text(m.kt) + ",\n";
    out += "      \"ior\": " + number_text(m.ior) + ",\n";
    out += "      \"fresnel\": " + bool_text(m.fresnel) + "\n";
    out += "    }";
  }
  out += first_material ? "},\n" : "\n  },\n";

  out += "  \"objects\": [";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    out += i == 0 ? "\n    " : ",\n    ";
    out += lines[i].text;
  }
  out += lines.empty() ? "]\n" : "\n  ]\n";
  out += "}\n";
  return out;
}

namespace {

// A name for the temporary file that is unlikely to collide with another writer's.
std::string temp_suffix() {
  static std::atomic<std::uint64_t> counter{0};
  std::uint64_t x = static_cast<std::uint64_t>(
                        std::chrono::steady_clock::now().time_since_epoch().count()) ^
                    (static_cast<std::uint64_t>(::getpid()) << 32) ^
                    (counter.fetch_add(1) * 0x9E3779B97F4A7C15ull);
  // splitmix64 finaliser: spreads the bits so close inputs give unrelated names.
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 31;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string s;
  for (int i = 0; i < 8; ++i) s += kHex[(x >> (4 * i)) & 15];
  return s;
}

}  // namespace

std::string write_file_atomically(const std::string& path, const std::string& text) {
  std::string temp;
  int fd = -1;
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts && fd < 0; ++attempt) {
    temp = path + ".tmp-" + temp_suffix();
    // O_EXCL: never reuse another writer's file; 0666 lets the umask decide as for any new file.
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) {
      return path + ": cannot create temporary file " + temp + ": " + os_reason(errno);
    }
  }
  if (fd < 0) return path + ": cannot create a unique temporary file";

  const auto abandon = [&](const std::string& what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(temp.c_str());
    return path + ": " + what + ": " + os_reason(err);
  };
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return abandon("write failed", errno);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) return abandon("fsync failed", errno);
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) return abandon("close failed", errno);
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    return abandon("cannot replace the file", errno);
  }
  // Make the rename itself durable; a failure here cannot corrupt anything, so it is ignored.
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
  return "";
}

}  // namespace phonglab
