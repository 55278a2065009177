// `check SCENE IMAGE` against a second ray tracer (SPEC §7.2, §7.3; docs/your-ray-tracer.md).
// The tracer below is written here from the contract alone (SPEC §1 and §2: the equation, the
// camera, the pixel centres), as a student would write theirs: it shares no code with phonglab's
// renderer, its experiment hook or the check's catalogue. It renders a scene with every kind of
// material correctly, then making each known mistake itself; check_image must say `match` for the
// first and name the mistake for each of the others. Its values at three pixels of the minimal
// scene in docs/your-ray-tracer.md are the ones the document states, and phonglab's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "check/check.h"
#include "check/mistakes.h"
#include "core/accel/prepared_scene.h"
#include "core/render/render.h"
#include "core/scene/display8.h"
#include "core/scene/scene.h"
#include "io/image_io.h"
#include "io/image_read.h"
#include "io/scene/scene_io.h"

namespace {

using glm::dvec3;
using phonglab::CheckResult;
using phonglab::StudentImage;

// ----- A student's ray tracer ----------------------------------------------------------------

// The known mistakes as a student's program makes them (SPEC §7.3), one flag each.
enum class Slip : std::uint8_t {
  kSpecularUnclamped,  // pow(R·V, n) without max(0, ·)
  kReflectSign,        // R = L - 2(N·L)N
  kBlinnForPhong,      // N·H in a Phong scene
  kViewReversed,       // V = D
  kExponentOutside,    // pow(ks·max(0, R·V), n)
  kAmbientPerLight,    // ka·Ia inside the loop over the lights
  kNoShadows,          // no shadow rays
  kNoRecursion,        // kr and kt ignored
  kDepthDeeper,        // recursion while depth <= max_depth
  kDepthShallower,     // recursion while depth < max_depth - 1
  kEtaInverted,        // ior entering, 1/ior leaving
  kPixelCorner,        // rays through (x, y)
  kFovHorizontal,      // fov_y taken as the horizontal angle
  kFlippedY,           // rows written bottom to top
  kLinearPng,          // 8-bit codes without the sRGB curve
};
using Slips = std::set<Slip>;

struct Mat {
  std::string name;
  dvec3 ka{0}, kd{0}, ks{0};
  double n = 32;
  dvec3 kr{0}, kt{0};
  double ior = 1.5;
  bool fresnel = false;
};
struct Ball {
  dvec3 centre{0};
  double radius = 1;
  int mat = 0;
};
struct Floor {
  dvec3 point{0}, normal{0, 1, 0};
  int mat = 0;
};
struct Lamp {
  bool directional = false;
  dvec3 where{0};  // a point light's position, a directional light's direction of travel
  dvec3 intensity{1};
};
// A scene as the student's program holds it, with the defaults of SPEC §3.
struct World {
  dvec3 eye{0, 1.5, 6}, look_at{0, 0.8, 0}, up{0, 1, 0};
  double fov_y = 40;
  int width = 960, height = 540;
  dvec3 ambient{1}, background{0};
  int max_depth = 5;
  double min_weight = 0.001;
  bool blinn = false;
  std::vector<Lamp> lamps;
  std::vector<Mat> mats;
  std::vector<Ball> balls;
  std::vector<Floor> floors;
};

bool zero(const dvec3& c) { return c.x == 0 && c.y == 0 && c.z == 0; }
double largest(const dvec3& c) { return std::max({c.x, c.y, c.z}); }

// How far secondary rays start off the surface, along its geometric normal (times the scene's size).
constexpr double kEpsilon = 1e-7;

class Tracer {
 public:
  Tracer(const World& world, Slips slips) : w_(world), slips_(std::move(slips)) {
    for (Floor& f : w_.floors) f.normal = glm::normalize(f.normal);
    for (Lamp& l : w_.lamps) {
      if (l.directional) l.where = glm::normalize(l.where);
    }
  }

  // The radiance of pixel (x, y) of the image as the program stores it (row 0 at the top).
  dvec3 pixel(int x, int y) const {
    const int row = has(Slip::kFlippedY) ? w_.height - 1 - y : y;
    return camera_pixel(x, row);
  }

  std::vector<dvec3> image() const {
    std::vector<dvec3> out;
    out.reserve(static_cast<std::size_t>(w_.width) * static_cast<std::size_t>(w_.height));
    for (int y = 0; y < w_.height; ++y) {
      for (int x = 0; x < w_.width; ++x) out.push_back(pixel(x, y));
    }
    return out;
  }

  bool has(Slip s) const { return slips_.count(s) != 0; }

 private:
  struct Found {
    double t = 0;
    dvec3 p{0}, ng{0};  // the point, the outward geometric normal
    int mat = 0;
  };

  dvec3 camera_pixel(int x, int y) const {
    const double at = has(Slip::kPixelCorner) ? 0.0 : 0.5;
    const dvec3 f = glm::normalize(w_.look_at - w_.eye);
    const dvec3 r = glm::normalize(glm::cross(f, w_.up));
    const dvec3 u = glm::cross(r, f);
    const double aspect = static_cast<double>(w_.width) / w_.height;
    const double half = std::tan(w_.fov_y * M_PI / 180 / 2);
    double hx = half * aspect, hy = half;
    if (has(Slip::kFovHorizontal)) {
      hx = half;
      hy = half / aspect;
    }
    const double sx = 2 * (x + at) / w_.width - 1;
    const double sy = 1 - 2 * (y + at) / w_.height;
    return trace(w_.eye, glm::normalize(f + sx * hx * r + sy * hy * u), 0, 1.0);
  }

  std::optional<Found> nearest(const dvec3& o, const dvec3& d, double t_max) const {
    std::optional<Found> best;
    const auto keep = [&](double t, const dvec3& ng, int mat) {
      if (t > 0 && t < t_max && (!best || t < best->t)) best = Found{t, o + t * d, ng, mat};
    };
    for (const Ball& b : w_.balls) {
      const dvec3 oc = o - b.centre;
      const double half_b = glm::dot(oc, d);
      const double disc = half_b * half_b - (glm::dot(oc, oc) - b.radius * b.radius);
      if (disc < 0) continue;
      const double s = std::sqrt(disc);
      for (const double t : {-half_b - s, -half_b + s}) {
        if (t > 0) {
          keep(t, (o + t * d - b.centre) / b.radius, b.mat);
          break;
        }
      }
    }
    for (const Floor& f : w_.floors) {
      const double denom = glm::dot(f.normal, d);
      if (denom == 0) continue;
      keep(glm::dot(f.point - o, f.normal) / denom, f.normal, f.mat);
    }
    return best;
  }

  // Whether something lies between the (offset) point and the light.
  bool blocked(const dvec3& from, const Lamp& lamp) const {
    if (lamp.directional) return nearest(from, -lamp.where, std::numeric_limits<double>::infinity()).has_value();
    const dvec3 to = lamp.where - from;
    const double dist = glm::length(to);
    return nearest(from, to / dist, dist).has_value();
  }

  static dvec3 off(const dvec3& p, const dvec3& ng, const dvec3& dir) {
    return glm::dot(dir, ng) >= 0 ? p + kEpsilon * ng : p - kEpsilon * ng;
  }

  // The exact unpolarised Fresnel reflectance, eta = n_incident / n_transmitted.
  static double fresnel(double cos_i, double eta) {
    const double sin2_t = eta * eta * (1 - cos_i * cos_i);
    if (sin2_t >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin2_t);
    const double rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const double rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5 * (rs * rs + rp * rp);
  }

  dvec3 child(const dvec3& k, const Found& h, const dvec3& dir, int depth, double weight) const {
    if (zero(k)) return dvec3(0);
    const double w = weight * largest(k);
    if (w < w_.min_weight) return dvec3(0);
    return k * trace(off(h.p, h.ng, dir), dir, depth + 1, w);
  }

  dvec3 trace(const dvec3& o, const dvec3& d, int depth, double weight) const {
    const std::optional<Found> found = nearest(o, d, std::numeric_limits<double>::infinity());
    if (!found) return w_.background;
    const Found& h = *found;
    const Mat& m = w_.mats[static_cast<std::size_t>(h.mat)];
    const bool entering = glm::dot(h.ng, d) < 0;
    const dvec3 n = entering ? h.ng : -h.ng;
    const dvec3 v = has(Slip::kViewReversed) ? d : -d;

    dvec3 colour = m.ka * w_.ambient;
    if (has(Slip::kAmbientPerLight)) colour *= static_cast<double>(w_.lamps.size());
    for (const Lamp& lamp : w_.lamps) {
      dvec3 l = -lamp.where;
      if (!lamp.directional) l = glm::normalize(lamp.where - h.p);
      const double n_dot_l = glm::dot(n, l);
      if (n_dot_l <= 0) continue;
      if (!has(Slip::kNoShadows) && blocked(off(h.p, h.ng, l), lamp)) continue;
      double c = 0;
      if (w_.blinn || has(Slip::kBlinnForPhong)) {
        c = glm::dot(n, glm::normalize(l + v));
      } else {
        const dvec3 r = has(Slip::kReflectSign) ? l - 2 * n_dot_l * n : 2 * n_dot_l * n - l;
        c = glm::dot(r, v);
      }
      dvec3 spec(0);
      if (has(Slip::kExponentOutside)) {
        spec = glm::pow(m.ks * std::max(0.0, c), dvec3(m.n));
      } else if (has(Slip::kSpecularUnclamped)) {
        spec = m.ks * std::pow(c, m.n);
      } else {
        spec = m.ks * std::pow(std::max(0.0, c), m.n);
      }
      colour += lamp.intensity * (m.kd * n_dot_l + spec);
    }

    int limit = w_.max_depth;
    if (has(Slip::kDepthDeeper)) limit += 1;
    if (has(Slip::kDepthShallower)) limit -= 1;
    if (has(Slip::kNoRecursion) || depth >= limit || (zero(m.kr) && zero(m.kt))) return colour;
    const bool inverted = has(Slip::kEtaInverted);
    const double eta = entering != inverted ? 1 / m.ior : m.ior;
    const double cos_i = -glm::dot(d, n);
    const double k = 1 - eta * eta * (1 - cos_i * cos_i);
    dvec3 kr = m.kr, kt = m.kt;
    if (m.fresnel && !zero(m.kt)) {
      const double f = k < 0 ? 1.0 : fresnel(cos_i, eta);
      kr = m.kr + m.kt * f;
      kt = m.kt * (1 - f);
    }
    const dvec3 mirror = glm::normalize(d - 2 * glm::dot(d, n) * n);
    colour += child(kr, h, mirror, depth, weight);
    if (!zero(kt)) {
      const dvec3 through = k < 0 ? mirror : glm::normalize(eta * d + (eta * cos_i - std::sqrt(k)) * n);
      colour += child(kt, h, through, depth, weight);
    }
    return colour;
  }

  World w_;
  Slips slips_;
};

// The student's reader of a scene file: the keys of SPEC §3 with their defaults (a colour is a
// number or three); what `phonglab-cli scene --plain` writes out in full.
dvec3 colour_of(const nlohmann::json& j, const char* key, dvec3 fallback) {
  if (!j.contains(key)) return fallback;
  const nlohmann::json& v = j.at(key);
  if (v.is_number()) return dvec3(v.get<double>());
  return {v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()};
}
dvec3 vector_of(const nlohmann::json& j, const char* key, dvec3 fallback) { return colour_of(j, key, fallback); }

World read_world(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  World w;
  if (j.contains("camera")) {
    const nlohmann::json& c = j.at("camera");
    w.eye = vector_of(c, "position", w.eye);
    w.look_at = vector_of(c, "look_at", w.look_at);
    w.up = vector_of(c, "up", w.up);
    w.fov_y = c.value("fov_y", w.fov_y);
  }
  if (j.contains("image")) {
    w.width = j.at("image").value("width", w.width);
    w.height = j.at("image").value("height", w.height);
  }
  w.ambient = colour_of(j, "ambient", w.ambient);
  w.background = colour_of(j, "background", w.background);
  w.max_depth = j.value("max_depth", w.max_depth);
  w.min_weight = j.value("min_weight", w.min_weight);
  w.blinn = j.value("specular_model", std::string("phong")) == "blinn";
  for (const nlohmann::json& l : j.value("lights", nlohmann::json::array())) {
    if (!l.value("enabled", true)) continue;
    Lamp lamp;
    lamp.directional = l.at("type") == "directional";
    lamp.where = vector_of(l, lamp.directional ? "direction" : "position", dvec3(0));
    lamp.intensity = colour_of(l, "intensity", dvec3(1));
    w.lamps.push_back(lamp);
  }
  std::vector<std::string> names;
  const nlohmann::json materials = j.value("materials", nlohmann::json::object());
  for (const auto& [name, m] : materials.items()) {
    Mat mat;
    mat.name = name;
    mat.ka = colour_of(m, "ka", dvec3(0));
    mat.kd = colour_of(m, "kd", dvec3(0));
    mat.ks = colour_of(m, "ks", dvec3(0));
    mat.n = m.value("n", 32.0);
    mat.kr = colour_of(m, "kr", dvec3(0));
    mat.kt = colour_of(m, "kt", dvec3(0));
    mat.ior = m.value("ior", 1.5);
    mat.fresnel = m.value("fresnel", false);
    w.mats.push_back(mat);
  }
  const auto material = [&](const nlohmann::json& o) {
    const std::string name = o.at("material");
    for (std::size_t i = 0; i < w.mats.size(); ++i) {
      if (w.mats[i].name == name) return static_cast<int>(i);
    }
    ADD_FAILURE() << "no material " << name;
    return 0;
  };
  for (const nlohmann::json& o : j.value("objects", nlohmann::json::array())) {
    if (o.at("type") == "sphere") {
      w.balls.push_back({vector_of(o, "center", dvec3(0)), o.at("radius").get<double>(), material(o)});
    } else if (o.at("type") == "plane") {
      w.floors.push_back({vector_of(o, "point", dvec3(0)), vector_of(o, "normal", dvec3(0)), material(o)});
    } else {
      ADD_FAILURE() << "the student's tracer has spheres and planes only";
    }
  }
  return w;
}

// The student's 8-bit encodings: the sRGB curve (IEC 61966-2-1), or none (the linear-png mistake).
int srgb_code(double linear) {
  const double c = std::isnan(linear) ? 0.0 : std::clamp(linear, 0.0, 1.0);
  const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
  return static_cast<int>(std::lround(e * 255));
}
int linear_code(double linear) {
  const double c = std::isnan(linear) ? 0.0 : std::clamp(linear, 0.0, 1.0);
  return static_cast<int>(std::lround(c * 255));
}

// The student's image in the units check_image takes.
StudentImage student_image(const World& world, const Slips& slips, StudentImage::Units units) {
  const Tracer tracer(world, slips);
  StudentImage image;
  image.width = world.width;
  image.height = world.height;
  image.units = units;
  for (const dvec3& c : tracer.image()) {
    for (int i = 0; i < 3; ++i) {
      if (units == StudentImage::Units::kLinear) {
        image.rgb.push_back(c[i]);
      } else {
        image.rgb.push_back(tracer.has(Slip::kLinearPng) ? linear_code(c[i]) : srgb_code(c[i]));
      }
    }
  }
  return image;
}

// The student's data as a phonglab Scene.
phonglab::Scene to_scene(const World& w) {
  phonglab::Scene s;
  s.camera.position = w.eye;
  s.camera.look_at = w.look_at;
  s.camera.up = w.up;
  s.camera.fov_y_deg = w.fov_y;
  s.width = w.width;
  s.height = w.height;
  s.ambient = w.ambient;
  s.background = w.background;
  s.max_depth = w.max_depth;
  s.min_weight = w.min_weight;
  s.specular_model = w.blinn ? phonglab::SpecularModel::kBlinn : phonglab::SpecularModel::kPhong;
  for (const Lamp& l : w.lamps) {
    phonglab::Light light;
    light.type = l.directional ? phonglab::LightType::kDirectional : phonglab::LightType::kPoint;
    (l.directional ? light.direction : light.position) = l.where;
    light.intensity = l.intensity;
    s.lights.push_back(light);
  }
  for (const Mat& m : w.mats) {
    phonglab::Material mat;
    mat.name = m.name;
    mat.ka = m.ka;
    mat.kd = m.kd;
    mat.ks = m.ks;
    mat.n = m.n;
    mat.kr = m.kr;
    mat.kt = m.kt;
    mat.ior = m.ior;
    mat.fresnel = m.fresnel;
    s.materials.push_back(mat);
  }
  for (const Ball& b : w.balls) s.spheres.push_back(phonglab::Sphere{b.centre, b.radius, b.mat});
  for (const Floor& f : w.floors) s.planes.push_back(phonglab::Plane{f.point, f.normal, f.mat});
  return s;
}

// A floor, a diffuse and specular sphere, a mirror and a glass sphere under two point lights with
// Ia > 0: every mistake of the catalogue changes some of its pixels. n = 3 and 7 are odd, so an
// unclamped (R·V)^n is negative where R·V is; max_depth 2 leaves light for one level more (the
// mirror's view of the glass) and takes some away at one less (the glass's far side).
World test_world() {
  World w;
  w.eye = {0, 1.6, 6.5};
  w.look_at = {0, 0.7, 0};
  w.fov_y = 40;
  w.width = 96;
  w.height = 64;
  w.ambient = dvec3(1);
  w.background = {0.1, 0.12, 0.18};
  w.max_depth = 2;
  w.lamps = {{false, {3, 5, 4}, dvec3(0.6)}, {false, {-4, 4, 2}, {0.25, 0.25, 0.3}}};
  w.mats = {
      {"floor", dvec3(0.08), dvec3(0.5), dvec3(0.2), 3, dvec3(0), dvec3(0), 1.5, false},
      {"plastic", {0.1, 0.03, 0.03}, {0.6, 0.15, 0.1}, dvec3(0.4), 7, dvec3(0), dvec3(0), 1.5, false},
      {"mirror", dvec3(0.02), dvec3(0.05), dvec3(0.3), 51, dvec3(0.8), dvec3(0), 1.5, false},
      {"glass", dvec3(0), dvec3(0), dvec3(0.3), 101, dvec3(0), dvec3(0.9), 1.5, true},
  };
  w.floors = {{dvec3(0), {0, 1, 0}, 0}};
  w.balls = {{{-1.3, 0.7, 0}, 0.7, 1}, {{1.2, 0.8, -0.8}, 0.8, 2}, {{0.1, 0.45, 1.3}, 0.45, 3}};
  return w;
}

phonglab::CheckOptions two_thread_options() {
  phonglab::CheckOptions o;
  o.threads = 2;
  return o;
}

// The alternatives of result.mistake ("a or b"), each one mistake or a pair ("a and b").
std::vector<std::string> alternatives(const CheckResult& r) {
  std::vector<std::string> out;
  std::string rest = r.mistake;
  for (std::size_t at; (at = rest.find(" or ")) != std::string::npos;) {
    out.push_back(rest.substr(0, at));
    rest = rest.substr(at + 4);
  }
  if (!rest.empty()) out.push_back(rest);
  return out;
}

// Whether the check names `name` (alone, not in a pair) as the nearest mistake.
bool names_alone(const CheckResult& r, std::string_view name) {
  const std::vector<std::string> alts = alternatives(r);
  return std::find(alts.begin(), alts.end(), name) != alts.end();
}

std::string report(const CheckResult& r) { return phonglab::check_report_text(r); }

// ----- The correct image matches, in every unit and file ---------------------------------------

TEST(CheckImage, TheIndependentTracerMatchesInCodesAndInLinearValues) {
  const World world = test_world();
  const phonglab::Scene scene = to_scene(world);
  for (const auto units : {StudentImage::Units::kCodes8, StudentImage::Units::kLinear}) {
    const CheckResult r = phonglab::check_image(scene, student_image(world, {}, units), two_thread_options());
    EXPECT_TRUE(r.match) << report(r);
    EXPECT_EQ(r.differing, 0u);
    EXPECT_EQ(r.pixels, 96u * 64u);
    EXPECT_TRUE(r.mistake.empty()) << r.mistake;
  }
}

// 16-bit PPM values are linear in [0, 1] (value / 65535): the test scene's every pixel stays in
// that range, so the file can hold the correct image.
TEST(CheckImage, SixteenBitLinearValuesMatch) {
  const World world = test_world();
  const Tracer tracer(world, {});
  StudentImage image;
  image.width = world.width;
  image.height = world.height;
  image.units = StudentImage::Units::kLinear;
  double brightest = 0;
  for (const dvec3& c : tracer.image()) {
    for (int i = 0; i < 3; ++i) {
      brightest = std::max(brightest, c[i]);
      image.rgb.push_back(static_cast<double>(std::lround(std::clamp(c[i], 0.0, 1.0) * 65535)) / 65535);
    }
  }
  ASSERT_LE(brightest, 1.0) << "the scene must stay within what a 16-bit file holds";
  const CheckResult r = phonglab::check_image(to_scene(world), image, two_thread_options());
  EXPECT_TRUE(r.match) << report(r);
}

// The bytes of the files a student's program writes: PNG (through the sRGB curve), P6 with
// maxval 255 and 65535, PFM (rows bottom to top); read back by read_image, then checked.
std::string p6_bytes(const World& world, const std::vector<dvec3>& pixels, int maxval) {
  std::string out = "P6\n" + std::to_string(world.width) + " " + std::to_string(world.height) + "\n" +
                    std::to_string(maxval) + "\n";
  for (const dvec3& c : pixels) {
    for (int i = 0; i < 3; ++i) {
      if (maxval == 255) {
        out += static_cast<char>(srgb_code(c[i]));
      } else {
        const long v = std::lround(std::clamp(c[i], 0.0, 1.0) * maxval);
        out += static_cast<char>(v >> 8);
        out += static_cast<char>(v & 0xFF);
      }
    }
  }
  return out;
}

StudentImage as_student(const phonglab::ReadImage& read) { return phonglab::student_image(read); }

TEST(CheckImage, TheIndependentTracersFilesReadBackAndMatch) {
  const World world = test_world();
  const std::vector<dvec3> pixels = Tracer(world, {}).image();

  // PNG: the student's own sRGB codes, carried by phonglab's PNG writer (each code's linear value
  // encodes back to that code).
  phonglab::Image codes;
  codes.width = world.width;
  codes.height = world.height;
  for (const dvec3& c : pixels) {
    codes.pixels.emplace_back(phonglab::srgb_to_linear(srgb_code(c.x) / 255.0),
                              phonglab::srgb_to_linear(srgb_code(c.y) / 255.0),
                              phonglab::srgb_to_linear(srgb_code(c.z) / 255.0));
  }
  phonglab::Image floats;
  floats.width = world.width;
  floats.height = world.height;
  for (const dvec3& c : pixels) floats.pixels.emplace_back(c);

  struct File {
    std::string name;
    std::string bytes;
    phonglab::ReadImage::Kind kind;
  };
  const std::vector<File> files = {
      {"mine.png", phonglab::encode_png_srgb(codes), phonglab::ReadImage::Kind::kSrgb8},
      {"mine.ppm", p6_bytes(world, pixels, 255), phonglab::ReadImage::Kind::kSrgb8},
      {"mine16.ppm", p6_bytes(world, pixels, 65535), phonglab::ReadImage::Kind::kLinear16},  // every pixel <= 1
      {"mine.pfm", phonglab::encode_pfm(floats), phonglab::ReadImage::Kind::kLinearFloat},
  };
  for (const File& f : files) {
    std::string error;
    const std::optional<phonglab::ReadImage> read = phonglab::read_image(f.bytes, f.name, &error);
    ASSERT_TRUE(read) << f.name << ": " << error;
    EXPECT_EQ(read->kind, f.kind) << f.name;
    ASSERT_EQ(read->width, world.width) << f.name;
    ASSERT_EQ(read->height, world.height) << f.name;
    if (f.kind == phonglab::ReadImage::Kind::kSrgb8) {
      // The codes read are the student's, row 0 at the top.
      EXPECT_EQ(read->rgb[0], srgb_code(pixels[0].x)) << f.name;
      const std::size_t last = pixels.size() - 1;
      EXPECT_EQ(read->rgb[3 * last + 2], srgb_code(pixels[last].z)) << f.name;
    }
    if (f.kind == phonglab::ReadImage::Kind::kLinearFloat) {
      EXPECT_FLOAT_EQ(static_cast<float>(read->rgb[0]), static_cast<float>(pixels[0].x)) << "row 0 is the top";
    }
    const CheckResult r = phonglab::check_image(to_scene(world), as_student(*read), two_thread_options());
    EXPECT_TRUE(r.match) << f.name << "\n" << report(r);
  }
}

// ----- Each mistake of the catalogue, made by the student's tracer, is named -------------------

// The student's image with `slips`, checked: it differs, and `names` (one, or the names the
// catalogue gives the same image) holds the nearest mistake.
void expect_named(const Slips& slips, const std::vector<std::string_view>& names,
                  StudentImage::Units units = StudentImage::Units::kCodes8) {
  const World world = test_world();
  const CheckResult r = phonglab::check_image(to_scene(world), student_image(world, slips, units), two_thread_options());
  const char* unit_name = units == StudentImage::Units::kCodes8 ? "8-bit codes" : "linear values";
  ASSERT_FALSE(r.match) << names.front() << " changes no pixel (" << unit_name << ")";
  EXPECT_GT(r.differing, 20u) << names.front() << " (" << unit_name << ")";
  bool named = false;
  for (const std::string_view name : names) named = named || names_alone(r, name);
  EXPECT_TRUE(named) << "expected " << names.front() << " (" << unit_name << "), got:\n" << report(r);
  EXPECT_GE(r.explained, 99.9) << names.front() << ": the student's image is the mistake's, pixel for pixel\n" << report(r);
  ASSERT_FALSE(r.mistakes.empty()) << report(r);
  EXPECT_EQ(r.mistakes.size(), 1u) << report(r);
  bool listed = false;
  for (const std::string_view name : names) listed = listed || phonglab::mistake_info(r.mistakes.front()).name == name;
  EXPECT_TRUE(listed) << r.mistake;
}

// Both units: 8-bit codes and linear floats (linear-png exists in 8-bit codes only).
void expect_named_in_both(const Slips& slips, const std::vector<std::string_view>& names) {
  expect_named(slips, names, StudentImage::Units::kCodes8);
  expect_named(slips, names, StudentImage::Units::kLinear);
}

TEST(CheckImageMistakes, SpecularUnclamped) { expect_named_in_both({Slip::kSpecularUnclamped}, {"specular-unclamped"}); }
// In a Phong scene reflect(L, N) and V = D both give max(0, -R·V)^n: the same image, either name.
TEST(CheckImageMistakes, ReflectSign) { expect_named_in_both({Slip::kReflectSign}, {"reflect-sign", "view-reversed"}); }
TEST(CheckImageMistakes, BlinnForPhong) { expect_named_in_both({Slip::kBlinnForPhong}, {"blinn-for-phong"}); }
TEST(CheckImageMistakes, ViewReversed) { expect_named_in_both({Slip::kViewReversed}, {"view-reversed", "reflect-sign"}); }
TEST(CheckImageMistakes, ExponentOutside) { expect_named_in_both({Slip::kExponentOutside}, {"exponent-outside"}); }
TEST(CheckImageMistakes, AmbientPerLight) { expect_named_in_both({Slip::kAmbientPerLight}, {"ambient-per-light"}); }
TEST(CheckImageMistakes, NoShadows) { expect_named_in_both({Slip::kNoShadows}, {"no-shadows"}); }
TEST(CheckImageMistakes, NoRecursion) { expect_named_in_both({Slip::kNoRecursion}, {"no-recursion"}); }
TEST(CheckImageMistakes, DepthOffByOneDeeper) { expect_named_in_both({Slip::kDepthDeeper}, {"depth-off-by-one"}); }
TEST(CheckImageMistakes, DepthOffByOneShallower) { expect_named_in_both({Slip::kDepthShallower}, {"depth-off-by-one"}); }
TEST(CheckImageMistakes, EtaInverted) { expect_named_in_both({Slip::kEtaInverted}, {"eta-inverted"}); }
TEST(CheckImageMistakes, PixelCorner) { expect_named_in_both({Slip::kPixelCorner}, {"pixel-corner"}); }
TEST(CheckImageMistakes, FovHorizontal) { expect_named_in_both({Slip::kFovHorizontal}, {"fov-horizontal"}); }
TEST(CheckImageMistakes, FlippedY) { expect_named_in_both({Slip::kFlippedY}, {"flipped-y"}); }
TEST(CheckImageMistakes, LinearPng) { expect_named({Slip::kLinearPng}, {"linear-png"}); }

// In a Blinn scene there is no R: view-reversed is N·H with H = normalize(L - V), named alone.
TEST(CheckImageMistakes, ViewReversedInABlinnScene) {
  World world = test_world();
  world.blinn = true;
  const CheckResult r = phonglab::check_image(to_scene(world), student_image(world, {Slip::kViewReversed},
                                                                              StudentImage::Units::kCodes8),
                                              two_thread_options());
  ASSERT_FALSE(r.match);
  EXPECT_EQ(r.mistake, "view-reversed") << report(r);
}

// Every entry of the catalogue that shows in an image is exercised above.
TEST(CheckImageMistakes, TheTestsCoverTheWholeCatalogue) {
  const std::set<std::string_view> tested = {
      "specular-unclamped", "reflect-sign", "blinn-for-phong", "view-reversed", "exponent-outside",
      "ambient-per-light",  "no-shadows",   "no-recursion",    "depth-off-by-one", "eta-inverted",
      "pixel-corner",       "fov-horizontal", "flipped-y",      "linear-png"};
  for (const phonglab::MistakeInfo& info : phonglab::mistake_catalogue()) {
    if (info.images) {
      EXPECT_TRUE(tested.count(info.name)) << info.name;
    }
  }
  EXPECT_EQ(tested.size(), static_cast<std::size_t>(phonglab::kMistakeCount));
}

// Two mistakes at once, where neither alone explains half the differing pixels: named as a pair.
TEST(CheckImageMistakes, TwoMistakesAreNamedAsAPair) {
  const World world = test_world();
  struct Pair {
    Slips slips;
    std::string name;
    StudentImage::Units units;
  };
  for (const Pair& pair : {Pair{{Slip::kFlippedY, Slip::kLinearPng}, "flipped-y and linear-png", StudentImage::Units::kCodes8},
                           Pair{{Slip::kBlinnForPhong, Slip::kAmbientPerLight}, "blinn-for-phong and ambient-per-light",
                                StudentImage::Units::kLinear}}) {
    const CheckResult r = phonglab::check_image(to_scene(world), student_image(world, pair.slips, pair.units), two_thread_options());
    ASSERT_FALSE(r.match) << pair.name;
    EXPECT_TRUE(names_alone(r, pair.name)) << report(r);
    ASSERT_EQ(r.mistakes.size(), 2u) << report(r);
    EXPECT_GE(r.explained, 99.9) << report(r);
  }
}

// A pair is tried only when no single mistake explains half: with no-shadows and flipped-y, the
// shadows are a small part of a flipped image, and flipped-y alone explains most of it.
TEST(CheckImageMistakes, ASingleMistakeThatExplainsHalfIsNamedAloneEvenBesideAnother) {
  const World world = test_world();
  const CheckResult r = phonglab::check_image(
      to_scene(world), student_image(world, {Slip::kNoShadows, Slip::kFlippedY}, StudentImage::Units::kLinear),
      two_thread_options());
  ASSERT_FALSE(r.match);
  EXPECT_EQ(r.mistake, "flipped-y") << report(r);
  EXPECT_GE(r.explained, 50.0) << report(r);
  EXPECT_LT(r.explained, 99.0) << "the shadows the student left out are not explained\n" << report(r);
}

// ----- docs/your-ray-tracer.md: its minimal scene and its three pixels ----------------------------

// The page's §7: the scene (its json block) and the table of three pixels.
struct DocPixel {
  int x = 0, y = 0;
  dvec3 linear{0};
  int codes[3] = {0, 0, 0};
};
struct DocScene {
  std::string page;
  std::string json;
  std::vector<DocPixel> pixels;
};

DocScene read_doc() {
  DocScene doc;
  std::ifstream in(std::string(PHONGLAB_SOURCE_DIR) + "/docs/your-ray-tracer.md");
  std::stringstream ss;
  ss << in.rdbuf();
  doc.page = ss.str();
  const std::size_t section = doc.page.find("## 7. A minimal scene");
  if (section == std::string::npos) return doc;
  const std::size_t open = doc.page.find("```json\n", section);
  const std::size_t close = doc.page.find("\n```", open + 8);
  if (open == std::string::npos || close == std::string::npos) return doc;
  doc.json = doc.page.substr(open + 8, close - open - 8);
  std::istringstream lines(doc.page.substr(close));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| (", 0) != 0) continue;
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, '|');) cells.push_back(cell);
    if (cells.size() < 5) continue;
    DocPixel p;
    if (std::sscanf(cells[1].c_str(), " (%d, %d)", &p.x, &p.y) != 2) continue;
    if (std::sscanf(cells[3].c_str(), " %lf, %lf, %lf", &p.linear.x, &p.linear.y, &p.linear.z) != 3) continue;
    if (std::sscanf(cells[4].c_str(), " %d, %d, %d", &p.codes[0], &p.codes[1], &p.codes[2]) != 3) continue;
    doc.pixels.push_back(p);
  }
  return doc;
}

// The page's values are the independent tracer's and phonglab's (to the six decimals printed),
// and the page's example verdicts are what check prints for the tracer's images.
TEST(CheckImageDoc, TheMinimalScenesThreePixelsAreTheIndependentTracersAndPhonglabs) {
  const DocScene doc = read_doc();
  ASSERT_FALSE(doc.json.empty()) << "docs/your-ray-tracer.md has no json block under \"## 7. A minimal scene\"";
  ASSERT_EQ(doc.pixels.size(), 3u) << "docs/your-ray-tracer.md: the table of three pixels";
  const World world = read_world(doc.json);
  const Tracer mine(world, {});
  const phonglab::LoadResult loaded = phonglab::load_scene_text(doc.json, "your-ray-tracer.md");
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  EXPECT_EQ(loaded.scene->width, world.width);
  EXPECT_EQ(loaded.scene->height, world.height);
  const phonglab::PreparedScene prepared(*loaded.scene);
  phonglab::Accumulator accum;
  accum.reset(loaded.scene->width, loaded.scene->height);
  phonglab::RenderOptions options;
  options.threads = 2;
  phonglab::render_passes(prepared, options, accum, 1);
  constexpr double kSixDecimals = 5e-7 + 1e-12;
  for (const DocPixel& p : doc.pixels) {
    const dvec3 ours = mine.pixel(p.x, p.y);
    const dvec3 theirs = accum.mean(p.x, p.y);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(ours[c], p.linear[c], kSixDecimals) << "the independent tracer at (" << p.x << ", " << p.y << ")";
      EXPECT_NEAR(theirs[c], p.linear[c], kSixDecimals) << "phonglab at (" << p.x << ", " << p.y << ")";
      EXPECT_EQ(srgb_code(ours[c]), p.codes[c]) << "(" << p.x << ", " << p.y << ") channel " << c;
      EXPECT_EQ(static_cast<int>(phonglab::linear_to_srgb8(theirs[c])), p.codes[c]) << "(" << p.x << ", " << p.y << ")";
    }
  }
  // The page's two example verdicts, line for line.
  const auto indented = [](const std::string& text) {
    std::string out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) out += "    " + line + "\n";
    return out;
  };
  const CheckResult right = phonglab::check_image(*loaded.scene, student_image(world, {}, StudentImage::Units::kCodes8),
                                                  two_thread_options());
  EXPECT_TRUE(right.match) << report(right);
  EXPECT_NE(doc.page.find("    $ phonglab-cli check minimal.json mine.png\n" + indented(report(right))), std::string::npos)
      << report(right);
  const CheckResult shadowless = phonglab::check_image(
      *loaded.scene, student_image(world, {Slip::kNoShadows}, StudentImage::Units::kCodes8), two_thread_options());
  EXPECT_EQ(shadowless.mistake, "no-shadows") << report(shadowless);
  EXPECT_NE(doc.page.find("    $ phonglab-cli check minimal.json noshadows.png\n" + indented(report(shadowless))),
            std::string::npos)
      << report(shadowless);
}

}  // namespace
