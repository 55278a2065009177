#include "io/memory_budget.h"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

namespace phonglab {

namespace {

// Bytes per element, from the peak resident size (/usr/bin/time -v) of phonglab-cli validate on
// a 980 000-triangle, 491 401-vertex OBJ (383 MB, 29 MB of it the text) and on a 10 MB scene of
// 150 000 spheres (162 MB): docs/robustness.md#memory. Close to the measure, not far above it:
// the estimate must not refuse what fits.
constexpr std::size_t kBytesPerVertex = 100;    // tinyobjloader's doubles, the indexed copy, the placed vertex
constexpr std::size_t kBytesPerNormal = 80;
constexpr std::size_t kBytesPerTriangle = 340;  // parser indices, indexed triangle, Triangle in its leaf, BVH share
constexpr std::size_t kJsonBytesPerByte = 16;   // nlohmann's DOM, the position index and the scene per byte of text

std::optional<std::size_t> meminfo_available() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::size_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
  return std::nullopt;
}

std::optional<std::size_t> address_space_left() {
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0;
  if (!(statm >> pages)) return std::nullopt;
  const std::size_t used = pages * 4096;
  // Half of what is left: growing vectors and the threads' malloc arenas reserve about twice the
  // address space they touch (a mesh that peaks at 383 MB resident fails under a 600 MB limit).
  return limit.rlim_cur > used ? (static_cast<std::size_t>(limit.rlim_cur) - used) / 2 : 0;
}

}  // namespace

std::optional<std::size_t> available_memory() {
  const auto a = meminfo_available();
  const auto b = address_space_left();
  if (a && b) return std::min(*a, *b);
  return a ? a : b;
}

std::string byte_size(std::size_t bytes) {
  char text[32];
  const double b = static_cast<double>(bytes);
  if (b < 1024.0 * 1024) std::snprintf(text, sizeof text, "%.0f KiB", b / 1024);
  else if (b < 1024.0 * 1024 * 1024) std::snprintf(text, sizeof text, "%.1f MiB", b / (1024.0 * 1024));
  else std::snprintf(text, sizeof text, "%.1f GiB", b / (1024.0 * 1024 * 1024));
  return text;
}

std::string memory_refusal(std::size_t need, std::optional<std::size_t> available, const std::string& what,
                           const std::string& detail) {
  if (!available || need <= *available) return "";
  return what + " would need about " + byte_size(need) + " (" + detail + ") but about " + byte_size(*available) +
         " are available";
}

std::string refuse_if_too_large(std::size_t need, const std::string& what, const std::string& detail) {
  constexpr std::size_t kAlwaysFits = std::size_t{16} << 20;
  return need < kAlwaysFits ? std::string() : memory_refusal(need, available_memory(), what, detail);
}

std::size_t mesh_bytes_needed(std::size_t vertices, std::size_t normals, std::size_t triangles) {
  return vertices * kBytesPerVertex + normals * kBytesPerNormal + triangles * kBytesPerTriangle;
}

std::size_t json_bytes_needed(std::size_t bytes) { return bytes * kJsonBytesPerByte; }

}  // namespace phonglab
