// The command-line words of phonglab-cli and phonglab-bench, consumed option by option.
#pragma once

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/embedded_scenes.h"
#include "io/scene/scene_io.h"

namespace phonglab::cli {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 1;
constexpr int kExitUsage = 2;

struct UsageError {
  std::string message;
};

// Command-line words after the command name, consumed option by option.
class Args {
 public:
  explicit Args(std::vector<std::string> words) : words_(std::move(words)) {}

  // Value of `--name VALUE` (or `--name=VALUE`), removed from the words.
  std::optional<std::string> take_value(const std::string& name) {
    for (std::size_t i = 0; i < words_.size(); ++i) {
      if (words_[i] == name) {
        if (i + 1 >= words_.size()) throw UsageError{name + " needs a value"};
        std::string v = words_[i + 1];
        words_.erase(words_.begin() + static_cast<long>(i), words_.begin() + static_cast<long>(i) + 2);
        return v;
      }
      if (words_[i].rfind(name + "=", 0) == 0) {
        std::string v = words_[i].substr(name.size() + 1);
        words_.erase(words_.begin() + static_cast<long>(i));
        return v;
      }
    }
    return std::nullopt;
  }

  bool take_flag(const std::string& name) {
    auto it = std::find(words_.begin(), words_.end(), name);
    if (it == words_.end()) return false;
    words_.erase(it);
    return true;
  }

  std::optional<int> take_int(const std::string& name, int lo, int hi) {
    auto v = take_value(name);
    if (!v) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const long x = std::strtol(v->c_str(), &end, 10);
    if (v->empty() || *end != '\0' || errno != 0 || x < lo || x > hi) {
      throw UsageError{name + " must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                       " (got '" + *v + "')"};
    }
    return static_cast<int>(x);
  }

  // A number strictly between lo and hi.
  std::optional<double> take_open_range(const std::string& name, double lo, double hi) {
    auto v = take_value(name);
    if (!v) return std::nullopt;
    char* end = nullptr;
    const double x = std::strtod(v->c_str(), &end);
    if (v->empty() || *end != '\0' || !(x > lo && x < hi)) {
      throw UsageError{name + " must be a number in (" + std::to_string(static_cast<int>(lo)) + ", " +
                       std::to_string(static_cast<int>(hi)) + ") (got '" + *v + "')"};
    }
    return x;
  }

  // The next positional word (an option left over is an error), or nullopt when none is left.
  std::optional<std::string> take_positional_word() {
    for (const std::string& w : words_) {
      if (w.size() > 1 && w[0] == '-') throw UsageError{"unknown option '" + w + "'"};
    }
    if (words_.empty()) return std::nullopt;
    std::string w = words_.front();
    words_.erase(words_.begin());
    return w;
  }

  // The optional positional SCENE; anything else left over is an error.
  std::optional<std::string> take_positional() {
    std::optional<std::string> pos;
    for (const std::string& w : words_) {
      if (w.size() > 1 && w[0] == '-') throw UsageError{"unknown option '" + w + "'"};
      if (pos) throw UsageError{"unexpected argument '" + w + "'"};
      pos = w;
    }
    words_.clear();
    return pos;
  }

 private:
  std::vector<std::string> words_;
};

// Loads SCENE (or the default) and prints its warnings and errors. nullopt when it has errors.
inline std::optional<Scene> load_or_report(const std::string& arg) {
  LoadResult r = load_scene_arg(arg);
  for (const Diagnostic& w : r.warnings) std::cerr << "warning: " << w.to_string() << "\n";
  if (!r.ok()) {
    std::cerr << r.error_text() << "\n";
    return std::nullopt;
  }
  return std::move(*r.scene);
}

inline std::string default_scene_name() { return std::string(embedded_scenes().front().name); }

}  // namespace phonglab::cli
