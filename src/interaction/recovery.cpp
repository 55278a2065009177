#include "interaction/recovery.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace phonglab::ui {

namespace {

constexpr const char* kHeader = "phonglab recovery 1";

// FNV-1a, 64 bits: stable across runs and builds (std::hash is not promised to be).
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ULL;
  }
  return h;
}

}  // namespace

std::string state_dir() {
  const char* state = std::getenv("XDG_STATE_HOME");
  const char* home = std::getenv("HOME");
  if (state != nullptr && *state != '\0') return std::string(state) + "/phonglab";
  if (home != nullptr && *home != '\0') return std::string(home) + "/.local/state/phonglab";
  return "";
}

std::string recovery_key(const std::string& source, bool embedded) {
  if (embedded) return "embedded-" + source;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(source)));
  return std::string("file-") + hex;
}

std::string file_identity(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) return "";
  const std::string text = bytes.str();
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(fnv1a(text)));
  return std::to_string(text.size()) + ":" + hex;
}

std::string recovery_source_text(const RecoveryEntry& entry) {
  std::string text = std::string(kHeader) + "\n" + (entry.embedded ? "embedded " : "file ") + entry.source +
                     "\nsaved " + std::to_string(entry.saved) + "\n";
  if (!entry.base.empty()) text += "base " + entry.base + "\n";
  return text;
}

std::optional<RecoveryEntry> parse_recovery_source(const std::string& text, const std::string& json_path) {
  std::istringstream in(text);
  std::string header, source, saved;
  if (!std::getline(in, header) || header != kHeader || !std::getline(in, source) || !std::getline(in, saved)) {
    return std::nullopt;
  }
  RecoveryEntry e;
  e.scene_path = json_path;
  if (source.rfind("embedded ", 0) == 0) {
    e.embedded = true;
    e.source = source.substr(9);
  } else if (source.rfind("file ", 0) == 0) {
    e.source = source.substr(5);
  } else {
    return std::nullopt;
  }
  if (saved.rfind("saved ", 0) != 0 || e.source.empty()) return std::nullopt;
  char* end = nullptr;
  e.saved = std::strtoll(saved.c_str() + 6, &end, 10);
  if (end == saved.c_str() + 6 || *end != '\0') return std::nullopt;
  if (std::string base; std::getline(in, base)) {
    if (base.rfind("base ", 0) != 0) return std::nullopt;
    e.base = base.substr(5);
  }
  return e;
}

std::vector<RecoveryEntry> list_recoveries(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<RecoveryEntry> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path p = it->path();
    if (p.extension() != ".source") continue;
    const fs::path json = fs::path(p).replace_extension(".json");
    if (!fs::is_regular_file(json, ec)) continue;
    std::ifstream in(p);
    std::ostringstream text;
    text << in.rdbuf();
    if (auto e = parse_recovery_source(text.str(), json.string())) out.push_back(*e);
  }
  std::sort(out.begin(), out.end(), [](const RecoveryEntry& a, const RecoveryEntry& b) {
    return a.saved != b.saved ? a.saved > b.saved : a.scene_path < b.scene_path;
  });
  return out;
}

}  // namespace phonglab::ui
