// Writing scenes: the scene file text of a Scene (shortest round-trip numbers, or plain decimal
// ones for a student's own parser) and files written through a temporary and a rename, so a crash
// never leaves half a file.
#include "io/scene/scene_load.h"

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
#include <cstdlib>
#include <cstring>
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

namespace phonglab {

using namespace scene_load;

namespace {

// The fewest significant digits that read back to x, and the exponent of x's leading digit as
// the exponent form with that many digits has it (after its rounding): x's shortest text in
// exponent notation is "%.*e" of digits - 1, in plain notation "%.*f" of max(0, digits - 1 -
// exponent) decimals (the same rounding place, so the same number).
struct ShortestDigits {
  int digits = 1;
  int exponent = 0;
  std::string sci;
};
ShortestDigits shortest_digits(double x) {
  ShortestDigits out;
  std::array<char, 40> sci{};
  for (; out.digits < 17; ++out.digits) {
    std::snprintf(sci.data(), sci.size(), "%.*e", out.digits - 1, x);
    if (std::strtod(sci.data(), nullptr) == x) break;
  }
  std::snprintf(sci.data(), sci.size(), "%.*e", out.digits - 1, x);
  out.exponent = std::atoi(std::strchr(sci.data(), 'e') + 1);
  out.sci = sci.data();
  return out;
}

// "%.*f" of x, however long (1e100 has 101 digits, 5e-324 over 300 decimals).
std::string fixed_text(double x, int decimals) {
  const int n = std::snprintf(nullptr, 0, "%.*f", decimals, x);
  std::string s(static_cast<std::size_t>(std::max(0, n)), '\0');
  std::snprintf(s.data(), s.size() + 1, "%.*f", decimals, x);
  return s;
}

}  // namespace

std::string shortest_number_text(double x) {
  const ShortestDigits d = shortest_digits(x);
  const std::string plain = fixed_text(x, std::max(0, d.digits - 1 - d.exponent));
  return plain.size() <= d.sci.size() ? plain : d.sci;
}

std::string plain_number_text(double x) {
  if (!std::isfinite(x)) return "null";
  if (x == 0) return std::signbit(x) ? "-0.0" : "0";  // "-0" would be read as the integer 0
  const ShortestDigits d = shortest_digits(x);
  return fixed_text(x, std::max(0, d.digits - 1 - d.exponent));
}

namespace {

// How the numbers of a scene's text are written.
enum class Numbers : std::uint8_t {
  kShortest,  // the shortest text that reads back, plain or exponent (scene files)
  kPlain,     // plain decimal, never an exponent (scene --plain, for a student's own parser)
};

// Shortest text that reads back to the same double; JSON has no inf/NaN, so those become null
// (which the loader rejects rather than silently changing).
std::string number_text(double x, Numbers numbers) {
  if (numbers == Numbers::kPlain) return plain_number_text(x);
  if (!std::isfinite(x)) return "null";
  if (x == 0 && std::signbit(x)) return "-0.0";  // "-0" would be read as the integer 0
#if defined(__EMSCRIPTEN__)
  return shortest_number_text(x);  // Emscripten's libc++ has no floating-point to_chars
#else
  std::array<char, 32> buf;
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), r.ptr);
#endif
}

std::string vec_text(const Vec3& v, Numbers numbers) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "x" + std::string here.
  std::string s = "[";
  s += number_text(v.x, numbers);
  s += ", ";
  s += number_text(v.y, numbers);
  s += ", ";
  s += number_text(v.z, numbers);
  s += ']';
  return s;
}

std::string bool_text(bool b) { return b ? "true" : "false"; }

// One primitive's line in "objects", keyed by the file index it came from.
struct ObjectLine {
  long long order;
  std::string text;
};

// The scene's objects, one line each, in the order of the file they came from.
std::vector<ObjectLine> object_lines(const Scene& scene, const std::string& save_dir, Numbers numbers) {
  const auto vec_text = [numbers](const Vec3& v) { return phonglab::vec_text(v, numbers); };
  const auto number_text = [numbers](double x) { return phonglab::number_text(x, numbers); };
  const auto material_name = [&](int m) {
    const bool valid = m >= 0 && static_cast<std::size_t>(m) < scene.materials.size();
    return json_string(valid ? scene.materials[static_cast<std::size_t>(m)].name : std::string());
  };
  // Primitives without a file index go after all indexed ones, in vector order.
  long long unindexed = static_cast<long long>(std::numeric_limits<int>::max()) + 1;
  const auto order_of = [&](const std::vector<int>& objects, std::size_t i) {
    if (i < objects.size() && objects[i] >= 0) return static_cast<long long>(objects[i]);
    return unindexed++;
  };

  // `"type": ...` and, for a named object, its name after it.
  const auto head = [&](const char* type, long long order) {
    std::string text = std::string("{\"type\": \"") + type + "\"";
    const auto i = static_cast<std::size_t>(order);
    if (order >= 0 && i < scene.object_names.size() && !scene.object_names[i].empty()) {
      text += ", \"name\": " + json_string(scene.object_names[i]);
    }
    return text;
  };
  std::vector<ObjectLine> lines;
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& s = scene.spheres[i];
    const long long order = order_of(scene.sphere_object, i);
    lines.push_back({order, head("sphere", order) + ", \"center\": " + vec_text(s.center) +
                         ", \"radius\": " + number_text(s.radius) +
                         ", \"material\": " + material_name(s.material) + "}"});
  }
  for (std::size_t i = 0; i < scene.planes.size(); ++i) {
    const Plane& p = scene.planes[i];
    const long long order = order_of(scene.plane_object, i);
    lines.push_back({order, head("plane", order) + ", \"point\": " + vec_text(p.point) +
                         ", \"normal\": " + vec_text(p.normal) +
                         ", \"material\": " + material_name(p.material) + "}"});
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    const Triangle& t = scene.triangles[i];
    const long long order = order_of(scene.triangle_object, i);
    std::string line = head("triangle", order) + ", \"vertices\": [" + vec_text(t.v0) + ", " +
                       vec_text(t.v1) + ", " + vec_text(t.v2) + "]";
    if (t.has_vertex_normals) {
      line += ", \"normals\": [" + vec_text(t.n0) + ", " + vec_text(t.n1) + ", " +
              vec_text(t.n2) + "]";
    }
    line += ", \"material\": " + material_name(t.material) + "}";
    lines.push_back({order, std::move(line)});
  }
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    const Mesh& m = scene.meshes[i];
    const MeshTransform& tr = m.transform;
    // A mesh read from disk is named relative to where this text will be saved.
    std::string file = m.file;
    if (!save_dir.empty() && !m.resolved_path.empty()) {
      std::error_code ec;
      const auto dir = std::filesystem::absolute(save_dir, ec);
      const auto rel = std::filesystem::path(m.resolved_path).lexically_relative(dir.lexically_normal());
      if (!ec && !rel.empty()) file = rel.generic_string();
    }
    const long long order = order_of(scene.mesh_object, i);
    std::string line = head("mesh", order) + ", \"file\": " + json_string(file);
    if (!m.material_override.empty()) line += ", \"material\": " + json_string(m.material_override);
    line += ", \"transform\": {\"scale\": " + vec_text(tr.scale) + ", \"rotate_deg\": " + vec_text(tr.rotate_deg) +
            ", \"translate\": " + vec_text(tr.translate) + "}";
    if (m.ns == NsMapping::kBlinnToPhong) line += ", \"ns\": \"blinn_to_phong\"";
    line += "}";
    lines.push_back({order, std::move(line)});
  }
  std::stable_sort(lines.begin(), lines.end(),
                   [](const ObjectLine& a, const ObjectLine& b) { return a.order < b.order; });

  return lines;
}

// The "lights" and "materials" members (an MTL's materials stay with their mesh).
void append_lights_and_materials(const Scene& scene, Numbers numbers, std::string& out) {
  const auto vec_text = [numbers](const Vec3& v) { return phonglab::vec_text(v, numbers); };
  const auto number_text = [numbers](double x) { return phonglab::number_text(x, numbers); };
  out += "  \"lights\": [";
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    out += i == 0 ? "\n    " : ",\n    ";
    if (l.type == LightType::kDirectional) {
      out += "{\"type\": \"directional\", \"direction\": " + vec_text(l.direction);
    } else {
      out += "{\"type\": \"point\", \"position\": " + vec_text(l.position);
    }
    out += ", \"intensity\": " + vec_text(l.intensity) +
           ", \"enabled\": " + bool_text(l.enabled) + "}";
  }
  out += scene.lights.empty() ? "],\n" : "\n  ],\n";

  out += "  \"materials\": {";
  bool first_material = true;
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    if (!m.source.empty()) continue;  // an MTL's: the mesh brings it back
    out += first_material ? "\n    " : ",\n    ";
    first_material = false;
    out += json_string(m.name) + ": {\n";
    out += "      \"ka\": " + vec_text(m.ka) + ",\n";
    out += "      \"kd\": " + vec_text(m.kd) + ",\n";
    out += "      \"ks\": " + vec_text(m.ks) + ",\n";
    out += "      \"n\": " + number_text(m.n) + ",\n";
    out += "      \"kr\": " + vec_text(m.kr) + ",\n";
    out += "      \"kt\": " + vec_text(m.kt) + ",\n";
    out += "      \"ior\": " + number_text(m.ior) + ",\n";
    out += "      \"fresnel\": " + bool_text(m.fresnel) + "\n";
    out += "    }";
  }
  out += first_material ? "},\n" : "\n  },\n";
}

// The scene's text with every key written, numbers as `numbers` says.
std::string scene_text(const Scene& scene, const std::string& save_dir, Numbers numbers) {
  const auto vec_text = [numbers](const Vec3& v) { return phonglab::vec_text(v, numbers); };
  const auto number_text = [numbers](double x) { return phonglab::number_text(x, numbers); };
  const std::vector<ObjectLine> lines = object_lines(scene, save_dir, numbers);
  const Camera& c = scene.camera;
  std::string out = "{\n";
  out += "  \"camera\": {\n";
  out += "    \"position\": " + vec_text(c.position) + ",\n";
  out += "    \"look_at\": " + vec_text(c.look_at) + ",\n";
  out += "    \"up\": " + vec_text(c.up) + ",\n";
  out += "    \"fov_y\": " + number_text(c.fov_y_deg) + "\n";
  out += "  },\n";
  out += "  \"image\": {\n";
  out += "    \"width\": " + std::to_string(scene.width) + ",\n";
  out += "    \"height\": " + std::to_string(scene.height) + "\n";
  out += "  },\n";
  out += "  \"ambient\": " + vec_text(scene.ambient) + ",\n";
  out += "  \"background\": " + vec_text(scene.background) + ",\n";
  out += "  \"max_depth\": " + std::to_string(scene.max_depth) + ",\n";
  out += "  \"min_weight\": " + number_text(scene.min_weight) + ",\n";
  out += std::string("  \"specular_model\": ") +
         (scene.specular_model == SpecularModel::kBlinn ? "\"blinn\"" : "\"phong\"") + ",\n";
  if (scene.indirect_bounces != kDefaultIndirectBounces) {  // a file without it keeps its text
    out += "  \"indirect\": {\"bounces\": " + std::to_string(scene.indirect_bounces) + "},\n";
  }

  append_lights_and_materials(scene, numbers, out);
  out += "  \"objects\": [";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    out += i == 0 ? "\n    " : ",\n    ";
    out += lines[i].text;
  }
  out += lines.empty() ? "]\n" : "\n  ]\n";
  out += "}\n";
  return out;
}

}  // namespace

std::string scene_to_json(const Scene& scene, const std::string& save_dir) {
  return scene_text(scene, save_dir, Numbers::kShortest);
}

std::string scene_to_plain_json(const Scene& scene, const std::string& save_dir) {
  return scene_text(scene, save_dir, Numbers::kPlain);
}

namespace {

// A name for the temporary file that is unlikely to collide with another writer's.
std::string temp_suffix() {
  static std::atomic<std::uint64_t> counter{0};
  std::uint64_t x = static_cast<std::uint64_t>(
                        std::chrono::steady_clock::now().time_since_epoch().count()) ^
                    (static_cast<std::uint64_t>(::getpid()) << 32) ^
                    (counter.fetch_add(1) * 0x9E3779B97F4A7C15ull);
  // splitmix64 finaliser: spreads the bits so close inputs give unrelated names.
  x ^= x >> 30;
  x *= 0xBF58476D1CE4E5B9ull;
  x ^= x >> 27;
  x *= 0x94D049BB133111EBull;
  x ^= x >> 31;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string s;
  for (int i = 0; i < 8; ++i) s += kHex[(x >> (4 * i)) & 15];
  return s;
}

}  // namespace

std::string write_file_atomically(const std::string& given, const std::string& text) {
  namespace fs = std::filesystem;
  std::error_code ec;
  // A link is followed (the file it names is replaced, the link stays); a device or a pipe is
  // never replaced by a file (Save as /dev/full would take the device away).
  std::string path = given;
  if (fs::is_symlink(given, ec)) {
    const fs::path real = fs::weakly_canonical(given, ec);
    if (!ec) path = real.string();
  }
  if (const fs::file_status st = fs::status(path, ec); !ec && fs::exists(st) && !fs::is_regular_file(st)) {
    return given + ": " + (fs::is_directory(st) ? "is a folder" : "is not a regular file (a device or a pipe)") +
           ": nothing was written";
  }
  std::string temp;
  int fd = -1;
  constexpr int kAttempts = 100;
  for (int attempt = 0; attempt < kAttempts && fd < 0; ++attempt) {
    temp = path + ".tmp-" + temp_suffix();
    // O_EXCL: never reuse another writer's file; 0666 lets the umask decide as for any new file.
    fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) {
      return path + ": cannot create temporary file " + temp + ": " + os_reason(errno);
    }
  }
  if (fd < 0) return path + ": cannot create a unique temporary file";

  const auto abandon = [&](const std::string& what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(temp.c_str());
    return path + ": " + what + ": " + os_reason(err);
  };
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return abandon("write failed", errno);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) return abandon("fsync failed", errno);
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) return abandon("close failed", errno);
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    return abandon("cannot replace the file", errno);
  }
  // Make the rename itself durable; a failure here cannot corrupt anything, so it is ignored.
  std::string dir = std::filesystem::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  const int dir_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir_fd >= 0) {
    ::fsync(dir_fd);
    ::close(dir_fd);
  }
  return "";
}


}  // namespace phonglab

namespace phonglab {

namespace {

// The names after `mtllib` in an OBJ's text.
std::vector<std::string> mtl_names(std::string_view obj) {
  std::vector<std::string> names;
  std::size_t at = 0;
  while (at < obj.size()) {
    std::size_t end = obj.find('\n', at);
    if (end == std::string_view::npos) end = obj.size();
    std::string_view line = obj.substr(at, end - at);
    at = end + 1;
    if (line.rfind("mtllib", 0) != 0 || line.size() < 7 || (line[6] != ' ' && line[6] != '\t')) continue;
    std::istringstream words{std::string(line.substr(7))};
    for (std::string name; words >> name;) names.push_back(name);
  }
  return names;
}

// Writes one embedded file to `target` unless the same bytes are there already.
std::string write_embedded(const std::string& target, const std::string& text) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(target, ec)) {
    std::string error;
    const std::optional<std::string> there = read_text_file(target, text.size() + 1, error);
    if (there && *there == text) return {};
    return target + ": exists with other contents, which were kept: save the scene in another folder";
  }
  fs::create_directories(fs::path(target).parent_path(), ec);
  if (ec) return target + ": cannot create its folder: " + ec.message();
  return write_file_atomically(target, text);
}

}  // namespace

std::vector<SceneFileText> embedded_mesh_files(const Scene& scene) {
  namespace fs = std::filesystem;
  std::vector<SceneFileText> files;
  const auto add = [&files](const std::string& path, std::string text) {
    for (const SceneFileText& file : files) {
      if (file.path == path) return;
    }
    files.push_back({path, std::move(text)});
  };
  for (const Mesh& mesh : scene.meshes) {
    if (!mesh.resolved_path.empty()) continue;  // read from disk: named relative to the saved file
    std::optional<std::string> obj = embedded_file(mesh.file);
    if (!obj) continue;  // not an embedded file either: the scene names it as it was written
    const std::vector<std::string> mtls = mtl_names(*obj);
    add(mesh.file, std::move(*obj));
    const std::string obj_folder = fs::path(mesh.file).parent_path().generic_string();
    for (const std::string& mtl : mtls) {
      const std::string path = obj_folder.empty() ? mtl : obj_folder + "/" + mtl;
      if (std::optional<std::string> text = embedded_file(path)) add(path, std::move(*text));
      // (one not embedded: the loader warns about a missing MTL when the scene is read)
    }
  }
  return files;
}

std::string write_embedded_meshes(const Scene& scene, const std::string& dir) {
  for (const SceneFileText& file : embedded_mesh_files(scene)) {
    if (std::string error = write_embedded((std::filesystem::path(dir) / file.path).string(), file.text); !error.empty()) {
      return error;
    }
  }
  return {};
}

}  // namespace phonglab
