#include "interaction/numbers.h"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace phonglab::ui {

double tidy_float(double value) {
  const auto f = static_cast<float>(value);
  if (!std::isfinite(f)) return value;
  std::array<char, 32> text{};
#if defined(__EMSCRIPTEN__)
  // Emscripten's libc++ has no floating-point to_chars: the fewest %g digits that read back.
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(text.data(), text.size(), "%.*g", digits, static_cast<double>(f));
    if (std::strtof(text.data(), nullptr) == f) break;
  }
  return std::strtod(text.data(), nullptr);
#else
  const auto result = std::to_chars(text.data(), text.data() + text.size(), f);  // shortest round trip
  double tidy = value;
  std::from_chars(text.data(), result.ptr, tidy);
  return tidy;
#endif
}

double significant(double v, int digits) {
  if (!(v > 0) || !std::isfinite(v)) return v;
  const int e = static_cast<int>(std::floor(std::log10(v))) - (digits - 1);
  const double rounded = e < 0 ? std::round(v * std::pow(10.0, -e)) / std::pow(10.0, -e)
                               : std::round(v / std::pow(10.0, e)) * std::pow(10.0, e);
  return tidy_float(rounded);
}

Color tidy_color(const Color& c) { return Color(tidy_float(c.x), tidy_float(c.y), tidy_float(c.z)); }

double shown_value(double value, const char* format) {
  std::array<char, 64> shown{};
  std::snprintf(shown.data(), shown.size(), format, value);
  const char* start = shown.data();
  while (*start != '\0' && !(std::isdigit(static_cast<unsigned char>(*start)) || *start == '-' || *start == '.')) ++start;
  double parsed = 0;
  return std::sscanf(start, "%lf", &parsed) == 1 && std::isfinite(parsed) ? parsed : value;
}

std::string probe_number(double value, int digits) {
  if (value != 0 && std::abs(value) < kProbeZero) return "\xE2\x89\x88 0";
  std::array<char, 48> text{};
  std::snprintf(text.data(), text.size(), "%.*g", digits, value);
  return text.data();
}

std::string wrap_at_spaces(std::string_view text, float width, const std::function<float(std::string_view)>& measure) {
  std::string out;
  for (bool first_line = true; first_line || !text.empty(); first_line = false) {
    const std::size_t end = text.find('\n');
    const std::string_view line = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    std::string current;  // the output line being filled
    bool has_word = false;
    std::size_t i = 0;
    while (i < line.size()) {
      // The next word and the spaces before it: [i, j) spaces, [j, k) the word.
      std::size_t j = i;
      while (j < line.size() && line[j] == ' ') ++j;
      std::size_t k = j;
      while (k < line.size() && line[k] != ' ') ++k;
      std::string candidate = current;
      candidate.append(line.substr(i, k - i));
      if (has_word && j < k && measure(candidate) > width) {
        out += current + "\n";
        current = "  ";
        current.append(line.substr(j, k - j));
      } else {
        current = std::move(candidate);
      }
      has_word = has_word || j < k;
      i = k;
    }
    out += current;
    if (end != std::string_view::npos) out += "\n";
  }
  return out;
}

}  // namespace phonglab::ui
