// The scene loader's text side: small text helpers, did-you-mean suggestions and JSON paths;
// pass 1, the prescan (NUL bytes, nesting, numbers that overflow double); pass 2, nlohmann's
// syntax errors as positioned plain messages; pass 3, the position index (every value's offsets).
#include "io/scene/scene_load.h"
#include "core/scene/chars.h"
#include "io/scene/scene_reader.h"
#include "io/memory_budget.h"

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

#include "core/accel/accel.h"
#include "io/embedded_scenes.h"
#include "io/obj_io.h"

namespace phonglab::scene_load {

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
  return double_from_chars(tok.data(), tok.data() + tok.size(), value).ec ==
         std::errc::result_out_of_range;
}



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

bool parse_text(const std::string& text, std::string_view kind, Issues& issues, ParsedText& out) {
  if (text.size() >= kMaxTextBytes) {
    issues.add({kNoOffset, "", "the text is too large (2 GiB or more)"});
    return false;
  }
  const std::size_t start = has_bom(text) ? 3 : 0;
  if (std::all_of(text.begin() + static_cast<std::ptrdiff_t>(start), text.end(), is_space)) {
    issues.add({start, "", "the file is empty (expected a JSON object)"});
    return false;
  }
  // Refused before the DOM is built when it would not fit (the kernel would kill us instead).
  if (std::string refusal = refuse_if_too_large(json_bytes_needed(text.size()), "reading " + std::string(kind),
                                                byte_size(text.size()) + " of JSON");
      !refusal.empty()) {
    issues.add({kNoOffset, "", std::move(refusal)});
    return false;
  }
  Prescan pre = prescan(text);
  if (pre.too_deep != kNoOffset) {
    issues.add({pre.too_deep, "", "nesting deeper than " + std::to_string(kMaxNesting) + " levels of arrays and objects"});
    return false;
  }
  // Overflowing numbers become "0" plus spaces: the text keeps every offset and parses, and the
  // readers report them as non-finite from the original text.
  if (!pre.overflows.empty()) {
    out.patched = text;
    for (const Overflow& o : pre.overflows) {
      out.patched.replace(o.offset, o.length, std::string(o.length, ' '));
      out.patched[o.offset] = '0';
    }
  }
  // nlohmann reads a NUL byte as the end of the input, so it only parses the text before one:
  // a syntax error there is reported as such, else the NUL itself is the error.
  std::string_view parsed_text = pre.overflows.empty() ? std::string_view(text) : std::string_view(out.patched);
  if (pre.nul != kNoOffset) parsed_text = parsed_text.substr(0, pre.nul);
  const std::string nul_message = "syntax error: unexpected byte 0x00 (" + std::string(kind) + " is text)";
  try {
    out.root = Json::parse(parsed_text);
  } catch (const Json::parse_error& e) {
    Issue issue = syntax_issue(std::string_view(text).substr(0, parsed_text.size()), e, pre);
    if (pre.nul != kNoOffset && issue.offset >= pre.nul) issue = {pre.nul, "", nul_message};
    issues.add(std::move(issue));
    return false;
  } catch (const Json::exception& e) {
    issues.add({kNoOffset, "", std::string("cannot parse: ") + e.what()});
    return false;
  }
  if (pre.nul != kNoOffset) {
    issues.add({pre.nul, "", nul_message});
    return false;
  }
  out.overflows = std::move(pre.overflows);
  out.index.emplace(parsed_text);
  return true;
}

}  // namespace phonglab::scene_load
