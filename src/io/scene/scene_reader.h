// Pass 4's reading of JSON values (the scene loader's internals, like scene_load.h): each value
// with its position and JSON path, checked for its type and range, every problem reported as an
// Issue. The Validator (scene_validate.cpp) reads a scene's members through it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/scene/camera.h"
#include "io/scene/scene_load.h"

namespace phonglab::scene_load {

// A JSON value with its position and its path.
struct Val {
  const Json* json = nullptr;
  std::size_t node = 0;
  std::string path;
};

// The known members of one JSON object (unknown and duplicate keys already reported).
struct Fields {
  std::vector<std::pair<std::string, Val>> members;  // file order

  const Val* find(std::string_view key) const {
    for (const auto& [k, v] : members) {
      if (k == key) return &v;
    }
    return nullptr;
  }
};

// True when v has a usable direction: normalising it in double gives a finite unit vector.
inline bool normalizable(const Vec3& v) {
  const double d = glm::dot(v, v);
  if (!(d > 0) || !std::isfinite(d)) return false;
  const Vec3 u = v / std::sqrt(d);
  return all_finite(u) && std::abs(glm::length(u) - 1.0) < 1e-6;
}

// Collects issues. After kMaxIssues the validator stops, as compilers do: a file with thousands
// of errors is not helped by thousands of lines, and 10 MB of bad values must stay fast.
class Issues {
 public:
  void add(Issue issue) {
    if (list_.size() < kMaxIssues) list_.push_back(std::move(issue));
  }
  bool full() const { return list_.size() >= kMaxIssues; }
  std::vector<Issue>& list() { return list_; }

 private:
  std::vector<Issue> list_;
};

class JsonReader {
 protected:
  JsonReader(std::string_view original, const PosIndex& index, const Json& root, const std::vector<Overflow>& overflows,
             Issues& issues)
      : text_(original), index_(index), root_(root), overflows_(overflows), issues_(issues) {}

  template <typename T, typename U>
  static void set(T& target, const std::optional<U>& value) {
    if (value) target = static_cast<T>(*value);
  }

  void report(const Val& v, std::string message) {
    issues_.add({index_.begin(v.node), v.path, std::move(message)});
  }

  // The value as written (the index only knows the patched "0" of an overflowing number).
  std::string shown(const Val& v) const {
    const std::size_t begin = index_.begin(v.node);
    const Overflow* o = overflow(v);
    return compact_source(text_, begin, o != nullptr ? begin + o->length : index_.end(v.node));
  }

  // The overflowing number token this value was parsed from, if any.
  const Overflow* overflow(const Val& v) const {
    const std::size_t off = index_.begin(v.node);
    const auto it = std::lower_bound(
        overflows_.begin(), overflows_.end(), off,
        [](const Overflow& o, std::size_t offset) { return o.offset < offset; });
    return (it != overflows_.end() && it->offset == off) ? &*it : nullptr;
  }

  Val element(const Val& v, std::size_t i) const {
    return {&(*v.json)[i], index_.children(v.node)[i], element_path(v.path, i)};
  }

  // Number of elements of an array value (0 if the DOM and the index ever disagreed).
  std::size_t element_count(const Val& v) const {
    return index_.children(v.node).size() == v.json->size() ? v.json->size() : 0;
  }

  // Members in file order with the last duplicate's position (the value the DOM kept);
  // later duplicates are reported.
  std::vector<std::pair<std::string, Val>> members(const Val& v) {
    std::vector<std::pair<std::string, Val>> out;
    std::unordered_map<std::string, std::size_t> seen;
    for (std::size_t child : index_.children(v.node)) {
      std::string key = index_.key(child);
      const auto it = v.json->find(key);
      if (it == v.json->end()) continue;
      const auto [pos, inserted] = seen.emplace(key, out.size());
      if (!inserted) {
        issues_.add({index_.key_begin(child), member_path(v.path, key), "duplicate key"});
        out[pos->second].second.node = child;
        continue;
      }
      Val member{&*it, child, member_path(v.path, key)};
      out.emplace_back(std::move(key), std::move(member));
    }
    return out;
  }

  // The members of an object value, reporting keys outside `allowed`.
  Fields fields(const Val& v, std::span<const std::string_view> allowed) {
    Fields f;
    for (auto& [key, member] : members(v)) {
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        issues_.add({index_.key_begin(member.node), member.path,
                     "unknown key" + suggestion(key, allowed, "expected one of")});
        continue;
      }
      f.members.emplace_back(std::move(key), std::move(member));
    }
    return f;
  }

  // One member looked up without any key checks (to read "type" before choosing the keys).
  std::optional<Val> member(const Val& v, std::string_view key) {
    const auto it = v.json->find(std::string(key));
    if (it == v.json->end()) return std::nullopt;
    const auto kids = index_.children(v.node);
    for (std::size_t k = kids.size(); k-- > 0;) {
      if (index_.key(kids[k]) == key) return Val{&*it, kids[k], member_path(v.path, key)};
    }
    return std::nullopt;
  }

  // Reports each missing key at the object's '{'; true when all are present.
  bool require(const Val& v, const Fields& f, std::initializer_list<std::string_view> keys) {
    bool ok = true;
    for (std::string_view k : keys) {
      if (f.find(k) == nullptr) {
        report(v, "missing key " + json_string(k));
        ok = false;
      }
    }
    return ok;
  }

  bool expect_object(const Val& v) {
    if (v.json->is_object()) return true;
    report(v, "must be an object (got " + shown(v) + ")");
    return false;
  }

  bool expect_array(const Val& v) {
    if (v.json->is_array()) return true;
    report(v, "must be an array (got " + shown(v) + ")");
    return false;
  }

  std::optional<double> read_number(const Val& v) {
    if (!v.json->is_number()) {
      report(v, "must be a number (got " + shown(v) + ")");
      return std::nullopt;
    }
    const double x = v.json->get<double>();
    if (overflow(v) != nullptr || !std::isfinite(x)) {
      report(v, "must be a finite number (got " + shown(v) + ")");
      return std::nullopt;
    }
    if (std::abs(x) > kMaxMagnitude) {
      report(v, "out of range: magnitude must be <= 1e100 (got " + shown(v) + ")");
      return std::nullopt;
    }
    return x;
  }

  std::optional<double> read_at_least_zero(const Val& v) {
    const auto x = read_number(v);
    if (x && *x < 0) {
      report(v, "must be >= 0 (got " + shown(v) + ")");
      return std::nullopt;
    }
    return x;
  }

  std::optional<double> read_positive(const Val& v) {
    const auto x = read_number(v);
    if (x && !(*x > 0)) {
      report(v, "must be > 0 (got " + shown(v) + ")");
      return std::nullopt;
    }
    return x;
  }

  std::optional<int> read_int(const Val& v, int lo, int hi) {
    const auto x = read_number(v);
    if (!x) return std::nullopt;
    if (*x != std::floor(*x) || *x < lo || *x > hi) {
      report(v, "must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi) +
                    " (got " + shown(v) + ")");
      return std::nullopt;
    }
    return static_cast<int>(*x);
  }

  std::optional<bool> read_bool(const Val& v) {
    if (v.json->is_boolean()) return v.json->get<bool>();
    report(v, "must be true or false (got " + shown(v) + ")");
    return std::nullopt;
  }

  std::optional<std::string> read_string(const Val& v) {
    if (v.json->is_string()) return v.json->get<std::string>();
    report(v, "must be a string (got " + shown(v) + ")");
    return std::nullopt;
  }

  // A string that must be one of `choices`; `what` names it in the message.
  std::optional<std::string> read_choice(const Val& v, std::span<const std::string_view> choices,
                                         std::string_view what) {
    auto s = read_string(v);
    if (!s) return std::nullopt;
    if (std::find(choices.begin(), choices.end(), *s) != choices.end()) return s;
    report(v, "unknown " + std::string(what) + " " + shown(v) +
                  suggestion(*s, choices, "expected one of"));
    return std::nullopt;
  }

  std::optional<Vec3> read_vec3(const Val& v) {
    if (!v.json->is_array() || v.json->size() != 3) {
      report(v, "must be an array of 3 numbers (got " + shown(v) + ")");
      return std::nullopt;
    }
    return read_triple(v, &JsonReader::read_number);
  }

  // The three elements of an array checked by `read_one`; every element's error is reported.
  std::optional<Vec3> read_triple(const Val& v, std::optional<double> (JsonReader::*read_one)(const Val&)) {
    if (element_count(v) != 3) return std::nullopt;
    Vec3 out;
    bool ok = true;
    for (int i = 0; i < 3; ++i) {
      if (auto x = (this->*read_one)(element(v, static_cast<std::size_t>(i)))) {
        out[i] = *x;
      } else {
        ok = false;
      }
    }
    return ok ? std::optional<Vec3>(out) : std::nullopt;
  }

  // A direction: three numbers, not of zero length.
  std::optional<Vec3> read_direction(const Val& v) {
    auto d = read_vec3(v);
    if (d && !normalizable(*d)) {
      report(v, "must have non-zero length (got " + shown(v) + ")");
      return std::nullopt;
    }
    return d;
  }

  // A colour: one number (grey) or three, every channel >= 0.
  std::optional<Color> read_color(const Val& v) {
    if (v.json->is_number()) {
      const auto x = read_at_least_zero(v);
      return x ? std::optional<Color>(Color(*x)) : std::nullopt;
    }
    if (!v.json->is_array() || v.json->size() != 3) {
      report(v, "must be a number or an array of 3 numbers (got " + shown(v) + ")");
      return std::nullopt;
    }
    return read_triple(v, &JsonReader::read_at_least_zero);
  }

  std::string_view text_;
  const PosIndex& index_;
  const Json& root_;
  const std::vector<Overflow>& overflows_;
  Issues& issues_;
};

inline constexpr std::array<std::string_view, 4> kCameraKeys = {"position", "look_at", "up", "fov_y"};
inline constexpr std::array<std::string_view, 2> kLightTypes = {"point", "directional"};
inline constexpr std::array<std::string_view, 4> kPointLightKeys = {"type", "position", "intensity", "enabled"};
inline constexpr std::array<std::string_view, 4> kDirectionalLightKeys = {"type", "direction", "intensity", "enabled"};
inline constexpr std::array<std::string_view, 8> kMaterialKeys = {"ka", "kd", "ks", "n", "kr", "kt", "ior", "fresnel"};

// The scene members that other files carry too (a lesson step's changes): the camera, a light
// and a material's coefficients, read by one set of rules.
class SceneMembers : protected JsonReader {
 protected:
  using JsonReader::JsonReader;

  // The camera's members over `cam` (a member left out keeps its value), each checked, and the
  // view checked as a whole.
  void read_camera(const Val& v, Camera& cam) {
    if (!expect_object(v)) return;
    const Fields f = fields(v, kCameraKeys);
    const Val* position = f.find("position");
    const Val* look_at = f.find("look_at");
    const Val* up = f.find("up");
    bool position_ok = true, look_ok = true, up_ok = true;
    if (position) position_ok = assign(cam.position, read_vec3(*position));
    if (look_at) look_ok = assign(cam.look_at, read_vec3(*look_at));
    if (up) up_ok = assign(cam.up, read_direction(*up));
    if (const Val* fov = f.find("fov_y")) {
      if (auto x = read_number(*fov)) {
        if (*x > 0 && *x < 180) {
          cam.fov_y_deg = *x;
        } else {
          report(*fov, "must be in (0, 180) (got " + shown(*fov) + ")");
        }
      }
    }
    if (!position_ok || !look_ok) return;
    const Vec3 view = cam.look_at - cam.position;
    if (!normalizable(view)) {
      if (look_at) {
        report(*look_at, "must differ from camera.position (got " + shown(*look_at) + ")");
      } else {
        report(*position, "must differ from camera.look_at (got " + shown(*position) + ")");
      }
      return;
    }
    if (!up_ok) return;
    if (!(view_up_sine(cam) > kMinViewUpSine)) {
      if (up) {
        report(*up, "must not be parallel to the view direction (got " + shown(*up) + ")");
      } else {
        const Val& at = look_at ? *look_at : *position;
        report(at, "makes the view direction parallel to camera.up (got " + shown(at) + ")");
      }
    }
  }

  template <typename T>
  static bool assign(T& target, const std::optional<T>& value) {
    if (value) target = *value;
    return value.has_value();
  }

  // Reads an element's "type" member (reporting it missing or not a string).
  std::optional<std::pair<Val, std::string>> type_of(const Val& v) {
    auto t = member(v, "type");
    if (!t) {
      report(v, "missing key \"type\"");
      return std::nullopt;
    }
    auto s = read_string(*t);
    if (!s) return std::nullopt;
    return std::make_pair(std::move(*t), std::move(*s));
  }

  // One element of "lights"; nullopt (reported) when it is not a usable light.
  std::optional<Light> read_light(const Val& e) {
    if (!expect_object(e)) return std::nullopt;
    const auto type = type_of(e);
    if (!type) return std::nullopt;
    Light light;
    const bool point = type->second == "point";
    if (!point && type->second != "directional") {
      report(type->first, "unknown light type " + shown(type->first) +
                              suggestion(type->second, kLightTypes, "expected one of"));
      return std::nullopt;
    }
    const Fields f = fields(e, point ? std::span<const std::string_view>(kPointLightKeys)
                                     : std::span<const std::string_view>(kDirectionalLightKeys));
    bool ok = require(e, f, {point ? "position" : "direction"});
    if (point) {
      light.type = LightType::kPoint;
      if (const Val* p = f.find("position")) ok = assign(light.position, read_vec3(*p)) && ok;
    } else {
      light.type = LightType::kDirectional;
      if (const Val* d = f.find("direction")) ok = assign(light.direction, read_direction(*d)) && ok;
    }
    if (const Val* x = f.find("intensity")) ok = assign(light.intensity, read_color(*x)) && ok;
    if (const Val* en = f.find("enabled")) ok = assign(light.enabled, read_bool(*en)) && ok;
    return ok ? std::optional<Light>(light) : std::nullopt;
  }

  // A material's coefficients over `mat` (a member left out keeps its value).
  void read_material_fields(const Val& m, Material& mat) {
    if (!expect_object(m)) return;
    const Fields f = fields(m, kMaterialKeys);
    if (const Val* x = f.find("ka")) set(mat.ka, read_color(*x));
    if (const Val* x = f.find("kd")) set(mat.kd, read_color(*x));
    if (const Val* x = f.find("ks")) set(mat.ks, read_color(*x));
    if (const Val* x = f.find("n")) set(mat.n, read_at_least_zero(*x));
    if (const Val* x = f.find("kr")) set(mat.kr, read_color(*x));
    if (const Val* x = f.find("kt")) set(mat.kt, read_color(*x));
    if (const Val* x = f.find("ior")) set(mat.ior, read_positive(*x));
    if (const Val* x = f.find("fresnel")) set(mat.fresnel, read_bool(*x));
  }
};

}  // namespace phonglab::scene_load
