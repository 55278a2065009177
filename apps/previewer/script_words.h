// The words of a test-script command read as numbers (script_driver.cpp, script_driver_set.cpp, lesson_shell.cpp).
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/scene/math.h"

namespace phonglab::script {

inline bool parse_double(const std::string& word, double& value) {
  char* end = nullptr;
  value = std::strtod(word.c_str(), &end);
  return end != word.c_str() && *end == '\0' && std::isfinite(value);
}

inline bool parse_int(const std::string& word, int& value) {
  double d = 0;
  if (!parse_double(word, d) || d != std::floor(d) || std::abs(d) > 1e9) return false;
  value = static_cast<int>(d);
  return true;
}

// Reads `count` numbers from words[first...]; a colour may also be given as one grey number.
inline bool parse_vec3(const std::vector<std::string>& words, std::size_t first, bool grey_allowed, Vec3& out) {
  const std::size_t n = words.size() - first;
  double v[3] = {0, 0, 0};
  if (n == 3) {
    for (std::size_t i = 0; i < 3; ++i) {
      if (!parse_double(words[first + i], v[i])) return false;
    }
  } else if (n == 1 && grey_allowed) {
    if (!parse_double(words[first], v[0])) return false;
    v[1] = v[2] = v[0];
  } else {
    return false;
  }
  out = Vec3(v[0], v[1], v[2]);
  return true;
}

}  // namespace phonglab::script
