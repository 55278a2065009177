// One problem in an input file, the same type for every format the program reads: scene JSON,
// OBJ and MTL. Errors make the input unusable; warnings say what was tolerated or replaced.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace phonglab {

struct Diagnostic {
  enum class Severity : std::uint8_t { kError, kWarning };
  std::string file;     // file name as given (or the embedded scene's name)
  int line = 0;         // 1-based; 0 when unknown
  int column = 0;       // 1-based; 0 when unknown (OBJ and MTL problems name a line only)
  std::string path;     // JSON path such as `objects[2].radius`; empty for syntax errors, OBJ, MTL
  std::string message;  // what is wrong, with the offending value: `must be > 0 (got -1)`
  Severity severity = Severity::kError;
  // "file:line:column: path: message", leaving out what is unknown.
  std::string to_string() const;
};

// A problem on one line of a file (0: the file as a whole).
inline Diagnostic line_diagnostic(std::string file, int line, std::string message,
                                  Diagnostic::Severity severity = Diagnostic::Severity::kError) {
  Diagnostic d;
  d.file = std::move(file);
  d.line = line;
  d.message = std::move(message);
  d.severity = severity;
  return d;
}

// Every diagnostic of `list` by to_string(), one a line.
std::string diagnostics_text(const std::vector<Diagnostic>& list);

// Sets the severity of every diagnostic of `list` (a producer's warnings, on its way out).
inline void set_severity(std::vector<Diagnostic>& list, Diagnostic::Severity severity) {
  for (Diagnostic& d : list) d.severity = severity;
}

// What a message says after a word the user typed that is none of `candidates`: the loaders'
// suggestion, " (did you mean "x"?)" for the nearest within two edits (any case), else
// " (LIST_INTRO: a, b, ...)". For any reader of typed names (scene keys, a CLI option's value).
std::string suggestion_for(std::string_view word, std::span<const std::string_view> candidates,
                           std::string_view list_intro);

// "1 plane", "2 planes", "0 planes": a count and its noun (`many`: the plural when not one + s).
std::string counted(std::size_t n, std::string_view one, std::string_view many = {});

}  // namespace phonglab
