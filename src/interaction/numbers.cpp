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

double shown_value(double value, const char* format) {
  std::array<char, 64> shown{};
  std::snprintf(shown.data(), shown.size(), format, value);
  const char* start = shown.data();
  while (*start != '\0' && !(std::isdigit(static_cast<unsigned char>(*start)) || *start == '-' || *start == '.')) ++start;
  double parsed = 0;
  return std::sscanf(start, "%lf", &parsed) == 1 && std::isfinite(parsed) ? parsed : value;
}

}  // namespace phonglab::ui
