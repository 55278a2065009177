#include "io/diagnostic.h"

#include "io/scene/scene_load.h"

namespace phonglab {

std::string Diagnostic::to_string() const {
  // A problem of no particular file (a mesh that cannot be read, told by the scene's) has no
  // "file: " in front.
  if (file.empty() && line == 0) return message;
  std::string s = file;
  if (line > 0) {
    // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "x" + std::string here.
    s += ':';
    s += std::to_string(line);
    if (column > 0) {
      s += ':';
      s += std::to_string(column);
    }
  }
  s += ": ";
  if (!path.empty()) s += path + ": ";
  s += message;
  return s;
}

std::string diagnostics_text(const std::vector<Diagnostic>& list) {
  std::string s;
  for (const Diagnostic& d : list) {
    if (!s.empty()) s += '\n';
    s += d.to_string();
  }
  return s;
}

std::string suggestion_for(std::string_view word, std::span<const std::string_view> candidates,
                           std::string_view list_intro) {
  return scene_load::suggestion(word, candidates, list_intro);
}

std::string counted(std::size_t n, std::string_view one, std::string_view many) {
  std::string s = std::to_string(n) + ' ';
  if (n == 1) return s += one;
  if (many.empty()) return (s += one) += 's';
  return s += many;
}

}  // namespace phonglab
