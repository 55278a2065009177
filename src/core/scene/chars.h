// std::from_chars for a double, where the standard library has it, and the same contract over
// strtod where it does not (Emscripten's libc++ of the web page): no leading space or '+', the
// longest number at `first`, result_out_of_range beyond a double's range. One definition for the
// scene and OBJ readers.
#pragma once

#include <charconv>
#include <system_error>

#if defined(__EMSCRIPTEN__)
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <string>
#endif

namespace phonglab {

inline std::from_chars_result double_from_chars(const char* first, const char* last, double& value) {
#if defined(__EMSCRIPTEN__)
  if (first == last || std::isspace(static_cast<unsigned char>(*first)) || *first == '+') {
    return {first, std::errc::invalid_argument};
  }
  const std::string text(first, last);
  char* end = nullptr;
  errno = 0;
  const double parsed = std::strtod(text.c_str(), &end);
  if (end == text.c_str()) return {first, std::errc::invalid_argument};
  const char* ptr = first + (end - text.c_str());
  if (errno == ERANGE) return {ptr, std::errc::result_out_of_range};
  value = parsed;
  return {ptr, std::errc{}};
#else
  return std::from_chars(first, last, value);
#endif
}

}  // namespace phonglab
