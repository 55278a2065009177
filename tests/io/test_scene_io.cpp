// Scene files (docs/scene-format.md): defaults, every class of error with its exact positioned message, the
// JSON round trip, the atomic writer, and inputs that must never crash or hang the loader.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "io/embedded_scenes.h"
#include "io/scene/scene_io.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

// Loads `text` as "scene.json".
LoadResult load(const std::string& text) { return load_scene_text(text, "scene.json"); }

// All error lines for `text`, or "OK" when it loads.
std::string errors(const std::string& text) {
  const LoadResult r = load(text);
  return r.ok() ? "OK" : r.error_text();
}

// A fresh, empty directory for one test.
fs::path temp_dir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("phonglab_scene_io_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> directory_entries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A scene that uses every field with non-default values.
const char* const kRichScene = R"({
  "camera": {"position": [0.25, 1.5, 6], "look_at": [0, 0.8, -0.1], "up": [0, 2, 0.5], "fov_y": 47.5},
  "image": {"width": 320, "height": 200},
  "ambient": [0.1, 0.2, 0.3],
  "background": 0.05,
  "max_depth": 7,
  "min_weight": 1e-7,
  "specular_model": "blinn",
  "lights": [
    {"type": "point", "position": [2, 6, 4], "intensity": [0.9, 0.8, 0.7]},
    {"type": "directional", "direction": [-1, -1, -0.5], "intensity": 0.2, "enabled": false}
  ],
  "materials": {
    "glass": {"ka": 0, "kd": 0, "ks": 0.5, "n": 300, "kt": 0.9, "ior": 1.33, "fresnel": true},
    "blue": {"ka": [0.02, 0.02, 0.1], "kd": [0.1, 0.2, 0.8], "ks": 0.5, "n": 40},
    "mirror": {"kd": 0.05, "ks": 0.6, "n": 200, "kr": [0.85, 0.8, 0.75]}
  },
  "objects": [
    {"type": "plane", "point": [0, -0.001, 0], "normal": [0, 3, 0], "material": "blue"},
    {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "glass"},
    {"type": "triangle", "vertices": [[-1, 0, -2], [1, 0, -2], [0, 2, -2]], "material": "mirror"},
    {"type": "sphere", "center": [123456.789, -1e-5, 3], "radius": 0.125, "material": "mirror"},
    {"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
     "normals": [[0, 0, 1], [0, 0.1, 1], [0.1, 0, 1]], "material": "blue"}
  ]
})";

void expect_vec_eq(const Vec3& a, const Vec3& b, const std::string& what) {
  EXPECT_EQ(a.x, b.x) << what;
  EXPECT_EQ(a.y, b.y) << what;
  EXPECT_EQ(a.z, b.z) << what;
}

// Compares every field of two scenes exactly.
void expect_scenes_equal(const Scene& a, const Scene& b) {
  expect_vec_eq(a.camera.position, b.camera.position, "camera.position");
  expect_vec_eq(a.camera.look_at, b.camera.look_at, "camera.look_at");
  expect_vec_eq(a.camera.up, b.camera.up, "camera.up");
  EXPECT_EQ(a.camera.fov_y_deg, b.camera.fov_y_deg);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  expect_vec_eq(a.ambient, b.ambient, "ambient");
  expect_vec_eq(a.background, b.background, "background");
  EXPECT_EQ(a.max_depth, b.max_depth);
  EXPECT_EQ(a.min_weight, b.min_weight);
  EXPECT_EQ(a.specular_model, b.specular_model);
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (std::size_t i = 0; i < a.lights.size(); ++i) {
    const std::string w = "lights[" + std::to_string(i) + "]";
    EXPECT_EQ(a.lights[i].type, b.lights[i].type) << w;
    expect_vec_eq(a.lights[i].position, b.lights[i].position, w);
    expect_vec_eq(a.lights[i].direction, b.lights[i].direction, w);
    expect_vec_eq(a.lights[i].intensity, b.lights[i].intensity, w);
    EXPECT_EQ(a.lights[i].enabled, b.lights[i].enabled) << w;
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    const Material& x = a.materials[i];
    const Material& y = b.materials[i];
    const std::string w = "materials[" + std::to_string(i) + "]";
    EXPECT_EQ(x.name, y.name) << w;
    expect_vec_eq(x.ka, y.ka, w + ".ka");
    expect_vec_eq(x.kd, y.kd, w + ".kd");
    expect_vec_eq(x.ks, y.ks, w + ".ks");
    EXPECT_EQ(x.n, y.n) << w;
    expect_vec_eq(x.kr, y.kr, w + ".kr");
    expect_vec_eq(x.kt, y.kt, w + ".kt");
    EXPECT_EQ(x.ior, y.ior) << w;
    EXPECT_EQ(x.fresnel, y.fresnel) << w;
  }
  ASSERT_EQ(a.spheres.size(), b.spheres.size());
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    expect_vec_eq(a.spheres[i].center, b.spheres[i].center, "sphere center");
    EXPECT_EQ(a.spheres[i].radius, b.spheres[i].radius);
    EXPECT_EQ(a.spheres[i].material, b.spheres[i].material);
  }
  ASSERT_EQ(a.planes.size(), b.planes.size());
  for (std::size_t i = 0; i < a.planes.size(); ++i) {
    expect_vec_eq(a.planes[i].point, b.planes[i].point, "plane point");
    expect_vec_eq(a.planes[i].normal, b.planes[i].normal, "plane normal");
    EXPECT_EQ(a.planes[i].material, b.planes[i].material);
  }
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    const Triangle& x = a.triangles[i];
    const Triangle& y = b.triangles[i];
    expect_vec_eq(x.v0, y.v0, "v0");
    expect_vec_eq(x.v1, y.v1, "v1");
    expect_vec_eq(x.v2, y.v2, "v2");
    EXPECT_EQ(x.material, y.material);
    EXPECT_EQ(x.has_vertex_normals, y.has_vertex_normals);
    if (x.has_vertex_normals && y.has_vertex_normals) {
      expect_vec_eq(x.n0, y.n0, "n0");
      expect_vec_eq(x.n1, y.n1, "n1");
      expect_vec_eq(x.n2, y.n2, "n2");
    }
  }
  EXPECT_EQ(a.sphere_object, b.sphere_object);
  EXPECT_EQ(a.plane_object, b.plane_object);
  EXPECT_EQ(a.triangle_object, b.triangle_object);
}

// ----- Messages and positions ------------------------------------------------------------------

TEST(SceneLoader, ReportsFileLineColumnPathMessageAndValueAsInTheSpec) {
  const std::string text =
      "{\n"
      "  \"materials\": {\"blue\": {\"kd\": [0.1, 0.2, 0.8]}},\n"
      "  \"objects\": [\n"
      "    {\"type\": \"sphere\", \"center\": [0, 1, 0], \"radius\": 1, \"material\": \"blue\"},\n"
      "    {\"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 1, 0], \"material\": \"blue\"},\n"
      "    {\"type\": \"sphere\", \"center\": [2, 1, 0],\n"
      "     \"radius\": -1, \"material\": \"blue\"}\n"
      "  ]\n"
      "}\n";
  EXPECT_EQ(errors(text), "scene.json:7:16: objects[2].radius: must be > 0 (got -1)");
}

TEST(SceneLoader, DiagnosticToStringOmitsUnknownPositionAndEmptyPath) {
  Diagnostic d;
  d.file = "a.json";
  d.message = "cannot read file: No such file or directory";
  EXPECT_EQ(d.to_string(), "a.json: cannot read file: No such file or directory");
  d.line = 3;
  d.column = 9;
  d.path = "camera.fov_y";
  d.message = "must be in (0, 180) (got 180)";
  EXPECT_EQ(d.to_string(), "a.json:3:9: camera.fov_y: must be in (0, 180) (got 180)");
}

TEST(SceneLoader, ColumnsCountCharactersNotBytes) {
  // "é" is two bytes in UTF-8 but one column.
  EXPECT_EQ(errors(R"({"materials": {"é": {"n": -1}}})"),
            "scene.json:1:27: materials[\"é\"].n: must be >= 0 (got -1)");
}

TEST(SceneLoader, CollectsAllIndependentErrorsInOnePassInFileOrder) {
  const std::string text =
      R"({"camera": {"fov_y": 0}, "max_depth": -1, "materials": {"m": {"kd": -0.5}}, )"
      R"("objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 0, "material": "m"}]})";
  EXPECT_EQ(errors(text),
            "scene.json:1:22: camera.fov_y: must be in (0, 180) (got 0)\n"
            "scene.json:1:39: max_depth: must be an integer in 0..100 (got -1)\n"
            "scene.json:1:69: materials.m.kd: must be >= 0 (got -0.5)\n"
            "scene.json:1:139: objects[0].radius: must be > 0 (got 0)");
}

TEST(SceneLoader, StopsAfterAHundredErrors) {
  std::string text = R"({"lights": [)";
  for (int i = 0; i < 500; ++i) text += i == 0 ? "1" : ",1";
  text += "]}";
  const LoadResult r = load(text);
  ASSERT_EQ(r.errors.size(), 101u);
  EXPECT_EQ(r.errors[0].to_string(), "scene.json:1:13: lights[0]: must be an object (got 1)");
  EXPECT_EQ(r.errors[100].to_string(), "scene.json: too many errors; stopped after the first 100");
}

// ----- Defaults --------------------------------------------------------------------------------

TEST(SceneLoader, EmptyObjectGivesEverySceneDefaultOfTheSpec) {
  const LoadResult r = load("{}");
  ASSERT_TRUE(r.ok()) << r.error_text();
  const Scene& s = *r.scene;
  expect_vec_eq(s.camera.position, Vec3(0, 1.5, 6), "position");
  expect_vec_eq(s.camera.look_at, Vec3(0, 0.8, 0), "look_at");
  expect_vec_eq(s.camera.up, Vec3(0, 1, 0), "up");
  EXPECT_EQ(s.camera.fov_y_deg, 40);
  EXPECT_EQ(s.width, 960);
  EXPECT_EQ(s.height, 540);
  expect_vec_eq(s.ambient, Color(1, 1, 1), "ambient");
  expect_vec_eq(s.background, Color(0, 0, 0), "background");
  EXPECT_EQ(s.max_depth, 5);
  EXPECT_EQ(s.min_weight, 0.001);
  EXPECT_EQ(s.specular_model, SpecularModel::kPhong);
  EXPECT_TRUE(s.lights.empty());
  EXPECT_TRUE(s.materials.empty());
  EXPECT_TRUE(s.spheres.empty() && s.planes.empty() && s.triangles.empty());
}

TEST(SceneLoader, EmptyMaterialGetsEveryMaterialDefaultOfTheSpec) {
  const LoadResult r = load(R"({"materials": {"plain": {}}})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  ASSERT_EQ(r.scene->materials.size(), 1u);
  const Material& m = r.scene->materials[0];
  EXPECT_EQ(m.name, "plain");
  for (const Color& c : {m.ka, m.kd, m.ks, m.kr, m.kt}) expect_vec_eq(c, Color(0, 0, 0), "coefficient");
  EXPECT_EQ(m.n, 32);
  EXPECT_EQ(m.ior, 1.5);
  EXPECT_FALSE(m.fresnel);
}

TEST(SceneLoader, LightIntensityDefaultsToOneAndLightsAreEnabled) {
  const LoadResult r = load(R"({"lights": [{"type": "point", "position": [1, 2, 3]}]})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  ASSERT_EQ(r.scene->lights.size(), 1u);
  EXPECT_EQ(r.scene->lights[0].type, LightType::kPoint);
  expect_vec_eq(r.scene->lights[0].position, Vec3(1, 2, 3), "position");
  expect_vec_eq(r.scene->lights[0].intensity, Color(1, 1, 1), "intensity");
  EXPECT_TRUE(r.scene->lights[0].enabled);
}

TEST(SceneLoader, ColourMayBeOneNumberMeaningGrey) {
  const LoadResult r = load(
      R"({"ambient": 0.25, "background": [0.1, 0.2, 0.3], "materials": {"m": {"kd": 0.5, "ks": [1, 0, 2]}}})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  expect_vec_eq(r.scene->ambient, Color(0.25, 0.25, 0.25), "ambient");
  expect_vec_eq(r.scene->background, Color(0.1, 0.2, 0.3), "background");
  expect_vec_eq(r.scene->materials[0].kd, Color(0.5, 0.5, 0.5), "kd");
  expect_vec_eq(r.scene->materials[0].ks, Color(1, 0, 2), "ks");
}

TEST(SceneLoader, FillsMaterialsInFileOrderAndObjectsWithMaterialAndFileIndex) {
  const LoadResult r = load(kRichScene);
  ASSERT_TRUE(r.ok()) << r.error_text();
  const Scene& s = *r.scene;
  ASSERT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.materials[0].name, "glass");
  EXPECT_EQ(s.materials[1].name, "blue");
  EXPECT_EQ(s.materials[2].name, "mirror");
  ASSERT_EQ(s.spheres.size(), 2u);
  ASSERT_EQ(s.planes.size(), 1u);
  ASSERT_EQ(s.triangles.size(), 2u);
  EXPECT_EQ(s.sphere_object, (std::vector<int>{1, 3}));
  EXPECT_EQ(s.plane_object, (std::vector<int>{0}));
  EXPECT_EQ(s.triangle_object, (std::vector<int>{2, 4}));
  EXPECT_EQ(s.spheres[0].material, 0);
  EXPECT_EQ(s.spheres[1].material, 2);
  EXPECT_EQ(s.planes[0].material, 1);
  EXPECT_EQ(s.triangles[0].material, 2);
  EXPECT_EQ(s.spheres[1].radius, 0.125);
  EXPECT_FALSE(s.triangles[0].has_vertex_normals);
  EXPECT_TRUE(s.triangles[1].has_vertex_normals);
  EXPECT_EQ(s.specular_model, SpecularModel::kBlinn);
  EXPECT_FALSE(s.lights[1].enabled);
  EXPECT_TRUE(s.materials[0].fresnel);
  EXPECT_EQ(s.materials[0].ior, 1.33);
}

TEST(SceneLoader, StoresVectorsAsWrittenWithoutNormalising) {
  const LoadResult r = load(kRichScene);
  ASSERT_TRUE(r.ok()) << r.error_text();
  expect_vec_eq(r.scene->planes[0].normal, Vec3(0, 3, 0), "plane normal");
  expect_vec_eq(r.scene->camera.up, Vec3(0, 2, 0.5), "camera up");
  expect_vec_eq(r.scene->lights[1].direction, Vec3(-1, -1, -0.5), "light direction");
}

TEST(SceneLoader, AcceptsIntegersWrittenWithAFraction) {
  const LoadResult r = load(R"({"max_depth": 5.0, "image": {"width": 64.0, "height": 1e1}})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  EXPECT_EQ(r.scene->max_depth, 5);
  EXPECT_EQ(r.scene->width, 64);
  EXPECT_EQ(r.scene->height, 10);
}

TEST(SceneLoader, AcceptsAUtf8ByteOrderMark) {
  EXPECT_EQ(errors("\xEF\xBB\xBF{\"max_depth\": 2}"), "OK");
  EXPECT_EQ(errors("\xEF\xBB\xBF{\"max_depth\": 2.5}"),
            "scene.json:1:15: max_depth: must be an integer in 0..100 (got 2.5)");
}

// ----- Syntax errors ---------------------------------------------------------------------------

TEST(SceneLoader, SyntaxErrorNamesLineColumnAndWhatWasExpected) {
  EXPECT_EQ(errors("{\n  \"max_depth\": 5\n  \"min_weight\": 0.1\n}"),
            "scene.json:3:3: syntax error: unexpected \"min_weight\"; expected ',' or '}'");
  EXPECT_EQ(errors(R"({"ambient": [1 2 3]})"),
            "scene.json:1:16: syntax error: unexpected '2'; expected ',' or ']'");
  EXPECT_EQ(errors(R"({"max_depth" 5})"),
            "scene.json:1:14: syntax error: unexpected '5'; expected ':' after the key");
  EXPECT_EQ(errors(R"({max_depth: 5})"),
            "scene.json:1:2: syntax error: unexpected 'max_depth'; expected a key in double quotes");
}

TEST(SceneLoader, SyntaxErrorExplainsTrailingCommas) {
  EXPECT_EQ(errors("{\"max_depth\": 5,\n}"),
            "scene.json:2:1: syntax error: unexpected '}'; expected a key in double quotes "
            "(JSON allows no trailing comma)");
  EXPECT_EQ(errors(R"({"ambient": [1, 2, 3,]})"),
            "scene.json:1:22: syntax error: unexpected ']'; expected a value (JSON allows no trailing comma)");
}

TEST(SceneLoader, EmptyFileIsAnError) {
  EXPECT_EQ(errors(""), "scene.json:1:1: the file is empty (expected a JSON object)");
  EXPECT_EQ(errors(" \n\t\n"), "scene.json:1:1: the file is empty (expected a JSON object)");
}

TEST(SceneLoader, TruncatedFileIsAnErrorAtTheEnd) {
  EXPECT_EQ(errors("{\"max_depth\": 5,\n \"lights\": [\n"),
            "scene.json:3:1: syntax error: unexpected end of file; expected a value");
  EXPECT_EQ(errors(R"({"materials": {"m": {"kd": )"),
            "scene.json:1:28: syntax error: unexpected end of file; expected a value");
  EXPECT_EQ(errors(R"({"objects": [{"type": "sphe)"),
            "scene.json:1:23: syntax error: unterminated string (missing closing quote)");
}

TEST(SceneLoader, NaNAndInfinityAreNotJson) {
  EXPECT_EQ(errors(R"({"min_weight": NaN})"),
            "scene.json:1:16: syntax error: unexpected 'NaN'; expected a value");
  EXPECT_EQ(errors(R"({"min_weight": -Infinity})"),
            "scene.json:1:16: syntax error: invalid number '-Infinity': expected digit after '-'");
}

TEST(SceneLoader, BinaryGarbageIsAnError) {
  EXPECT_EQ(errors(std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16)),
            "scene.json:1:1: syntax error: unexpected byte 0x89; expected a value");
  EXPECT_EQ(errors(std::string("{\"max_depth\": 5}\0\0\0\0", 20)),
            "scene.json:1:17: syntax error: unexpected byte 0x00 (a scene file is text)");
  EXPECT_EQ(errors("{\"objects\": \"\xff\xfe\"}"),
            "scene.json:1:14: syntax error: invalid string: ill-formed UTF-8 byte");
  EXPECT_EQ(errors(R"({"max_depth": 5} x)"),
            "scene.json:1:18: syntax error: unexpected 'x'; expected the end of the file after the "
            "scene's closing '}'");
}

TEST(SceneLoader, TopLevelMustBeAnObject) {
  EXPECT_EQ(errors("  [1, 2, 3]"),
            "scene.json:1:3: the scene must be a JSON object (got [1,2,3])");
  EXPECT_EQ(errors("42"), "scene.json:1:1: the scene must be a JSON object (got 42)");
}

// ----- Nesting and size ------------------------------------------------------------------------

TEST(SceneLoader, RejectsNestingDeeperThan64BeforeParsing) {
  const std::string ok = R"({"ambient": )" + std::string(63, '[') + std::string(63, ']') + "}";
  EXPECT_EQ(errors(ok), "scene.json:1:13: ambient: must be a number or an array of 3 numbers (got " +
                          std::string(57, '[') + "...)");
  const std::string deep = R"({"ambient": )" + std::string(64, '[') + std::string(64, ']') + "}";
  EXPECT_EQ(errors(deep), "scene.json:1:76: nesting deeper than 64 levels of arrays and objects");
}

TEST(SceneLoader, TenMegabytesOfOpenBracketsFailFastWithoutRecursion) {
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(errors(std::string(10 << 20, '[')),
            "scene.json:1:65: nesting deeper than 64 levels of arrays and objects");
  EXPECT_EQ(errors(std::string(5 << 20, '[') + std::string(5 << 20, ']')),
            "scene.json:1:65: nesting deeper than 64 levels of arrays and objects");
  EXPECT_EQ(errors(std::string(5 << 20, '{') + std::string(5 << 20, '}')),
            "scene.json:1:65: nesting deeper than 64 levels of arrays and objects");
  // A hang guard, not a benchmark: generous for a sanitizer build on a busy machine.
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(60));
}

TEST(SceneLoader, TenMegabytesOfValidJsonLoadWithoutHanging) {
  std::string text = R"({"lights": [)";
  while (text.size() < (10u << 20)) text += R"({"type": "point", "position": [1, 2, 3]},)";
  text += R"({"type": "point", "position": [1, 2, 3]}]})";
  const auto t0 = std::chrono::steady_clock::now();
  const LoadResult r = load(text);
  // A hang guard, not a benchmark (about 2 s under ASan on an idle machine; 36 s seen beside a
  // second build on the same 2 cores).
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(180));
  ASSERT_TRUE(r.ok()) << r.error_text();
  EXPECT_GT(r.scene->lights.size(), 200000u);
}

// ----- Numbers ---------------------------------------------------------------------------------

TEST(SceneLoader, NumberTooLargeForDoubleMustBeFinite) {
  EXPECT_EQ(errors(R"({"min_weight": 1e400})"),
            "scene.json:1:16: min_weight: must be a finite number (got 1e400)");
  EXPECT_EQ(errors(R"({"ambient": [1, -1E+999, 0]})"),
            "scene.json:1:17: ambient[1]: must be a finite number (got -1E+999)");
  // 400 digits: larger than any double, too.
  EXPECT_EQ(errors(R"({"max_depth": 1)" + std::string(400, '0') + "}"),
            "scene.json:1:15: max_depth: must be a finite number (got 1" + std::string(56, '0') +
                "...)");
  // Where no number belongs, it is the type that is wrong.
  EXPECT_EQ(errors(R"({"specular_model": 1e400})"),
            "scene.json:1:20: specular_model: must be a string (got 1e400)");
  // Underflow is just zero.
  EXPECT_EQ(errors(R"({"min_weight": 1e-400})"), "OK");
}

TEST(SceneLoader, NumberOfMagnitudeAbove1e100IsOutOfRange) {
  EXPECT_EQ(errors(R"({"camera": {"position": [0, 0, 1e101]}})"),
            "scene.json:1:32: camera.position[2]: out of range: magnitude must be <= 1e100 (got 1e101)");
  EXPECT_EQ(errors(R"({"min_weight": 123456789012345678901234567890})"), "OK");
  EXPECT_EQ(errors(R"({"camera": {"position": [0, 0, -1e100]}})"), "OK");
}

TEST(SceneLoader, HugeIntegersAreRangeCheckedNotWrapped) {
  EXPECT_EQ(errors(R"({"max_depth": 18446744073709551617})"),
            "scene.json:1:15: max_depth: must be an integer in 0..100 (got 18446744073709551617)");
  EXPECT_EQ(errors(R"({"image": {"width": -9223372036854775809}})"),
            "scene.json:1:21: image.width: must be an integer in 1..16384 (got -9223372036854775809)");
}

// ----- Wrong types -----------------------------------------------------------------------------

TEST(SceneLoader, StringWhereNumberExpectedIsATypeError) {
  EXPECT_EQ(errors(R"({"camera": {"fov_y": "40"}})"),
            "scene.json:1:22: camera.fov_y: must be a number (got \"40\")");
  EXPECT_EQ(errors(R"({"max_depth": true})"), "scene.json:1:15: max_depth: must be a number (got true)");
  EXPECT_EQ(errors(R"({"min_weight": null})"), "scene.json:1:16: min_weight: must be a number (got null)");
}

TEST(SceneLoader, VectorMustBeThreeNumbers) {
  EXPECT_EQ(errors(R"({"camera": {"look_at": [0, 1]}})"),
            "scene.json:1:24: camera.look_at: must be an array of 3 numbers (got [0,1])");
  EXPECT_EQ(errors(R"({"camera": {"look_at": [0, "1", 2]}})"),
            "scene.json:1:28: camera.look_at[1]: must be a number (got \"1\")");
  EXPECT_EQ(errors(R"({"camera": {"look_at": {"x": 0}}})"),
            "scene.json:1:24: camera.look_at: must be an array of 3 numbers (got {\"x\":0})");
}

TEST(SceneLoader, ColourMustBeANumberOrThreeNumbers) {
  EXPECT_EQ(errors(R"({"background": "black"})"),
            "scene.json:1:16: background: must be a number or an array of 3 numbers (got \"black\")");
  EXPECT_EQ(errors(R"({"background": [0, 0, 0, 1]})"),
            "scene.json:1:16: background: must be a number or an array of 3 numbers (got [0,0,0,1])");
}

TEST(SceneLoader, BooleansMustBeJsonBooleans) {
  EXPECT_EQ(errors(R"({"materials": {"glass": {"fresnel": 1}}})"),
            "scene.json:1:37: materials.glass.fresnel: must be true or false (got 1)");
  EXPECT_EQ(errors(R"({"materials": {"glass": {"fresnel": "true"}}})"),
            "scene.json:1:37: materials.glass.fresnel: must be true or false (got \"true\")");
}

TEST(SceneLoader, SectionsMustHaveTheirJsonType) {
  EXPECT_EQ(errors(R"({"camera": [], "lights": {}, "materials": [], "objects": "none"})"),
            "scene.json:1:12: camera: must be an object (got [])\n"
            "scene.json:1:26: lights: must be an array (got {})\n"
            "scene.json:1:43: materials: must be an object (got [])\n"
            "scene.json:1:58: objects: must be an array (got \"none\")");
  EXPECT_EQ(errors(R"({"lights": [1], "materials": {"m": 2}, "objects": [null]})"),
            "scene.json:1:13: lights[0]: must be an object (got 1)\n"
            "scene.json:1:36: materials.m: must be an object (got 2)\n"
            "scene.json:1:52: objects[0]: must be an object (got null)");
}

TEST(SceneLoader, ShowsLongValuesShortened) {
  EXPECT_EQ(errors(R"({"specular_model": ")" + std::string(100, 'x') + "\"}"),
            "scene.json:1:20: specular_model: unknown specular model \"" + std::string(56, 'x') +
                "... (expected one of: phong, blinn)");
}

// ----- Unknown keys and values -----------------------------------------------------------------

TEST(SceneLoader, UnknownKeyPointsAtTheKeyAndSuggestsTheClosest) {
  EXPECT_EQ(errors(R"({"materials": {"m": {}}, "objects": [{"type": "sphere", "center": [0, 0, 0], )"
                   R"("radious": 1, "material": "m"}]})"),
            "scene.json:1:38: objects[0]: missing key \"radius\"\n"
            "scene.json:1:78: objects[0].radious: unknown key (did you mean \"radius\"?)");
}

TEST(SceneLoader, UnknownKeySuggestionIgnoresCase) {
  EXPECT_EQ(errors(R"({"Max_Depth": 3})"),
            "scene.json:1:2: Max_Depth: unknown key (did you mean \"max_depth\"?)");
}

TEST(SceneLoader, UnknownKeyWithoutCloseMatchListsTheAllowedKeys) {
  EXPECT_EQ(errors(R"({"camera": {"zoom": 2}})"),
            "scene.json:1:13: camera.zoom: unknown key (expected one of: position, look_at, up, fov_y)");
}

TEST(SceneLoader, UnknownKeysAreErrorsAtEveryLevel) {
  EXPECT_EQ(errors(R"({"lihgts": [], "image": {"widht": 10}, "lights": [{"type": "point", "position": [0, 0, 0], "colour": 1}], "materials": {"m": {"kdd": 1}}})"),
            "scene.json:1:2: lihgts: unknown key (did you mean \"lights\"?)\n"
            "scene.json:1:26: image.widht: unknown key (did you mean \"width\"?)\n"
            "scene.json:1:92: lights[0].colour: unknown key (expected one of: type, position, intensity, enabled)\n"
            "scene.json:1:127: materials.m.kdd: unknown key (did you mean \"kd\"?)");
}

TEST(SceneLoader, DuplicateKeyIsAnError) {
  EXPECT_EQ(errors(R"({"max_depth": 3, "max_depth": 4})"), "scene.json:1:18: max_depth: duplicate key");
}

TEST(SceneLoader, KeysThatAreNotIdentifiersAreQuotedInThePath) {
  EXPECT_EQ(errors(R"({"materials": {"dark blue": {"ks": -1}}})"),
            "scene.json:1:36: materials[\"dark blue\"].ks: must be >= 0 (got -1)");
}

TEST(SceneLoader, UnknownObjectTypeSuggestsTheClosest) {
  EXPECT_EQ(errors(R"({"objects": [{"type": "sphre", "center": [0, 0, 0]}]})"),
            "scene.json:1:23: objects[0].type: unknown object type \"sphre\" (did you mean \"sphere\"?)");
  EXPECT_EQ(errors(R"({"objects": [{"type": "cube"}]})"),
            "scene.json:1:23: objects[0].type: unknown object type \"cube\" (expected one of: sphere, "
            "plane, triangle, mesh)");
}

TEST(SceneLoader, UnknownLightTypeSuggestsTheClosest) {
  EXPECT_EQ(errors(R"({"lights": [{"type": "Directional", "direction": [0, -1, 0]}]})"),
            "scene.json:1:22: lights[0].type: unknown light type \"Directional\" (did you mean "
            "\"directional\"?)");
  EXPECT_EQ(errors(R"({"lights": [{"type": "spot"}]})"),
            "scene.json:1:22: lights[0].type: unknown light type \"spot\" (expected one of: point, directional)");
}

TEST(SceneLoader, UnknownSpecularModelSuggestsTheClosest) {
  EXPECT_EQ(errors(R"({"specular_model": "blin"})"),
            "scene.json:1:20: specular_model: unknown specular model \"blin\" (did you mean \"blinn\"?)");
}

TEST(SceneLoader, UnknownMaterialSuggestsTheClosestDefinedMaterial) {
  EXPECT_EQ(errors(R"({"materials": {"blue": {}, "red": {}}, )"
                   R"("objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "bleu"}]})"),
            "scene.json:1:117: objects[0].material: unknown material \"bleu\" (did you mean \"blue\"?)");
  EXPECT_EQ(errors(R"({"materials": {"blue": {}, "red": {}}, )"
                   R"("objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "chrome"}]})"),
            "scene.json:1:117: objects[0].material: unknown material \"chrome\" (defined materials: blue, red)");
}

TEST(SceneLoader, ObjectWithUnknownMaterialGivesExactlyOneError) {
  const LoadResult r = load(R"({"materials": {"blue": {}}, )"
                            R"("objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "gren"}]})");
  ASSERT_EQ(r.errors.size(), 1u) << r.error_text();
  EXPECT_EQ(r.errors[0].path, "objects[0].material");
}

TEST(SceneLoader, MaterialReferencedWithoutMaterialsSectionIsReportedOnce) {
  EXPECT_EQ(errors(R"({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"},)"
                   R"( {"type": "sphere", "center": [3, 0, 0], "radius": 1, "material": "m"}]})"),
            "scene.json:1:79: objects[0].material: unknown material \"m\" (the scene has no \"materials\")");
}

TEST(SceneLoader, BrokenMaterialsSectionDoesNotCascadeIntoObjects) {
  EXPECT_EQ(errors(R"({"materials": 3, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})"),
            "scene.json:1:15: materials: must be an object (got 3)");
  // A material with a bad field is still defined: referring to it adds no error.
  EXPECT_EQ(errors(R"({"materials": {"m": {"n": -2}}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})"),
            "scene.json:1:27: materials.m.n: must be >= 0 (got -2)");
}

TEST(SceneLoader, MeshErrorsComeWithTheObjectsPositionAndTheMeshFilesLine) {
  EXPECT_EQ(errors(R"({"materials": {"m": {}}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}, )"
                   R"({}, {}, {"type": "mesh", "file": "no/such/mesh.obj"}]})"),
            "scene.json:1:109: objects[1]: missing key \"type\"\n"
            "scene.json:1:113: objects[2]: missing key \"type\"\n"
            "scene.json:1:142: objects[3].file: cannot load mesh 'no/such/mesh.obj': cannot read file: No such file or directory");
  EXPECT_EQ(errors(R"({"objects": [{"type": "mesh", "file": "a.obj", "transform": {"scale": 0, "rotat_deg": [0, 0, 0]}, "ns": "phong"}]})"),
            "scene.json:1:71: objects[0].transform.scale: must not be zero (got 0)\n"
            "scene.json:1:74: objects[0].transform.rotat_deg: unknown key (did you mean \"rotate_deg\"?)\n"
            "scene.json:1:105: objects[0].ns: unknown Ns mapping \"phong\" (expected one of: as_is, blinn_to_phong)");
}

// ----- Missing keys ----------------------------------------------------------------------------

TEST(SceneLoader, MissingRequiredKeyPointsAtTheObjectsBrace) {
  EXPECT_EQ(errors("{\"materials\": {\"m\": {}},\n \"objects\": [\n  {\"type\": \"sphere\", \"center\": [0, 0, 0], \"material\": \"m\"}]}"),
            "scene.json:3:3: objects[0]: missing key \"radius\"");
  EXPECT_EQ(errors(R"({"objects": [{"type": "triangle"}]})"),
            "scene.json:1:14: objects[0]: missing key \"vertices\"\n"
            "scene.json:1:14: objects[0]: missing key \"material\"");
  EXPECT_EQ(errors(R"({"objects": [{"type": "plane", "normal": [0, 1, 0]}]})"),
            "scene.json:1:14: objects[0]: missing key \"point\"\n"
            "scene.json:1:14: objects[0]: missing key \"material\"");
}

TEST(SceneLoader, LightsNeedATypeAndTheirPositionOrDirection) {
  EXPECT_EQ(errors(R"({"lights": [{"position": [0, 0, 0]}, {"type": "point"}, {"type": "directional"}]})"),
            "scene.json:1:13: lights[0]: missing key \"type\"\n"
            "scene.json:1:38: lights[1]: missing key \"position\"\n"
            "scene.json:1:57: lights[2]: missing key \"direction\"");
}

// ----- Value checks ----------------------------------------------------------------------------

TEST(SceneLoader, RadiusMustBePositive) {
  const std::string head = R"({"materials": {"m": {}}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": )";
  EXPECT_EQ(errors(head + R"(0, "material": "m"}]})"), "scene.json:1:88: objects[0].radius: must be > 0 (got 0)");
  EXPECT_EQ(errors(head + R"(-2.5, "material": "m"}]})"),
            "scene.json:1:88: objects[0].radius: must be > 0 (got -2.5)");
}

TEST(SceneLoader, PlaneNormalMustNotHaveZeroLength) {
  EXPECT_EQ(errors(R"({"materials": {"m": {}}, "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 0], "material": "m"}]})"),
            "scene.json:1:86: objects[0].normal: must have non-zero length (got [0,0,0])");
  // 1e-200 squared underflows to zero: no usable direction in double either.
  EXPECT_EQ(errors(R"({"materials": {"m": {}}, "objects": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1e-200, 0], "material": "m"}]})"),
            "scene.json:1:86: objects[0].normal: must have non-zero length (got [0,1e-200,0])");
}

TEST(SceneLoader, LightDirectionMustNotHaveZeroLength) {
  EXPECT_EQ(errors(R"({"lights": [{"type": "directional", "direction": [0, 0, 0]}]})"),
            "scene.json:1:50: lights[0].direction: must have non-zero length (got [0,0,0])");
}

TEST(SceneLoader, CameraUpMustNotHaveZeroLength) {
  EXPECT_EQ(errors(R"({"camera": {"up": [0, 0, 0]}})"),
            "scene.json:1:19: camera.up: must have non-zero length (got [0,0,0])");
}

TEST(SceneLoader, CameraPositionMustDifferFromLookAt) {
  EXPECT_EQ(errors(R"({"camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]}})"),
            "scene.json:1:47: camera.look_at: must differ from camera.position (got [1,2,3])");
  // Against the default look_at [0, 0.8, 0].
  EXPECT_EQ(errors(R"({"camera": {"position": [0, 0.8, 0]}})"),
            "scene.json:1:25: camera.position: must differ from camera.look_at (got [0,0.8,0])");
}

TEST(SceneLoader, CameraUpMustNotBeParallelToTheViewDirection) {
  EXPECT_EQ(errors(R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, -2, 0]}})"),
            "scene.json:1:64: camera.up: must not be parallel to the view direction (got [0,-2,0])");
  // Nearly parallel within 1e-9 counts as parallel.
  EXPECT_EQ(errors(R"({"camera": {"position": [0, 0, 0], "look_at": [1, 0, 0], "up": [1, 1e-12, 0]}})"),
            "scene.json:1:64: camera.up: must not be parallel to the view direction (got [1,1e-12,0])");
  // With the default up, the view direction is to blame.
  EXPECT_EQ(errors(R"({"camera": {"position": [0, 5, 0], "look_at": [0, 0, 0]}})"),
            "scene.json:1:47: camera.look_at: makes the view direction parallel to camera.up (got [0,0,0])");
  EXPECT_EQ(errors(R"({"camera": {"position": [0, 0, 0], "look_at": [1, 0, 0], "up": [1, 1e-6, 0]}})"), "OK");
}

TEST(SceneLoader, FieldOfViewMustBeBetween0And180Exclusive) {
  EXPECT_EQ(errors(R"({"camera": {"fov_y": 180}})"), "scene.json:1:22: camera.fov_y: must be in (0, 180) (got 180)");
  EXPECT_EQ(errors(R"({"camera": {"fov_y": -5}})"), "scene.json:1:22: camera.fov_y: must be in (0, 180) (got -5)");
  EXPECT_EQ(errors(R"({"camera": {"fov_y": 179.9}})"), "OK");
}

TEST(SceneLoader, CoefficientsMustNotBeNegative) {
  EXPECT_EQ(errors(R"({"materials": {"m": {"ka": -0.1, "kd": [0.5, -0.5, 0.5], "ks": 0, "kr": [0, 0, -1e-9], "kt": -1}}})"),
            "scene.json:1:28: materials.m.ka: must be >= 0 (got -0.1)\n"
            "scene.json:1:46: materials.m.kd[1]: must be >= 0 (got -0.5)\n"
            "scene.json:1:80: materials.m.kr[2]: must be >= 0 (got -1e-9)\n"
            "scene.json:1:94: materials.m.kt: must be >= 0 (got -1)");
  EXPECT_EQ(errors(R"({"ambient": [-1, 0, 0], "background": -0.5})"),
            "scene.json:1:14: ambient[0]: must be >= 0 (got -1)\n"
            "scene.json:1:39: background: must be >= 0 (got -0.5)");
  EXPECT_EQ(errors(R"({"lights": [{"type": "point", "position": [0, 0, 0], "intensity": -1}]})"),
            "scene.json:1:67: lights[0].intensity: must be >= 0 (got -1)");
}

TEST(SceneLoader, ShininessMustNotBeNegativeAndIorMustBePositive) {
  EXPECT_EQ(errors(R"({"materials": {"m": {"n": -1, "ior": 0}}})"),
            "scene.json:1:27: materials.m.n: must be >= 0 (got -1)\n"
            "scene.json:1:38: materials.m.ior: must be > 0 (got 0)");
  EXPECT_EQ(errors(R"({"materials": {"m": {"n": 0, "ior": 1e-3}}})"), "OK");
}

TEST(SceneLoader, MinWeightMustNotBeNegative) {
  EXPECT_EQ(errors(R"({"min_weight": -0.01})"), "scene.json:1:16: min_weight: must be >= 0 (got -0.01)");
  EXPECT_EQ(errors(R"({"min_weight": 0})"), "OK");
}

TEST(SceneLoader, MaxDepthMustBeAnIntegerFrom0To100) {
  EXPECT_EQ(errors(R"({"max_depth": 5.5})"), "scene.json:1:15: max_depth: must be an integer in 0..100 (got 5.5)");
  EXPECT_EQ(errors(R"({"max_depth": 101})"), "scene.json:1:15: max_depth: must be an integer in 0..100 (got 101)");
  EXPECT_EQ(errors(R"({"max_depth": 0})"), "OK");
  EXPECT_EQ(errors(R"({"max_depth": 100})"), "OK");
}

TEST(SceneLoader, ImageSizeMustBeIntegersFrom1To16384) {
  EXPECT_EQ(errors(R"({"image": {"width": 0, "height": 16385}})"),
            "scene.json:1:21: image.width: must be an integer in 1..16384 (got 0)\n"
            "scene.json:1:34: image.height: must be an integer in 1..16384 (got 16385)");
  EXPECT_EQ(errors(R"({"image": {"width": 100.5, "height": "10"}})"),
            "scene.json:1:21: image.width: must be an integer in 1..16384 (got 100.5)\n"
            "scene.json:1:38: image.height: must be a number (got \"10\")");
  EXPECT_EQ(errors(R"({"image": {"width": 1, "height": 16384}})"), "OK");
}

TEST(SceneLoader, TriangleMustNotBeDegenerate) {
  const std::string head = R"({"materials": {"m": {}}, "objects": [{"type": "triangle", "vertices": )";
  EXPECT_EQ(errors(head + R"([[0, 0, 0], [1, 1, 1], [2, 2, 2]], "material": "m"}]})"),
            "scene.json:1:71: objects[0].vertices: degenerate triangle: the vertices are collinear "
            "(got [[0,0,0],[1,1,1],[2,2,2]])");
  EXPECT_EQ(errors(head + R"([[1, 2, 3], [1, 2, 3], [0, 0, 1]], "material": "m"}]})"),
            "scene.json:1:71: objects[0].vertices: degenerate triangle: the vertices are collinear "
            "(got [[1,2,3],[1,2,3],[0,0,1]])");
}

TEST(SceneLoader, TriangleNeedsThreePointsOfThreeNumbers) {
  const std::string head = R"({"materials": {"m": {}}, "objects": [{"type": "triangle", "vertices": )";
  EXPECT_EQ(errors(head + R"([[0, 0, 0], [1, 0, 0]], "material": "m"}]})"),
            "scene.json:1:71: objects[0].vertices: must be an array of 3 points (got [[0,0,0],[1,0,0]])");
  EXPECT_EQ(errors(head + R"([[0, 0, 0], [1, 0, 0], [0, 1]], "material": "m"}]})"),
            "scene.json:1:94: objects[0].vertices[2]: must be an array of 3 numbers (got [0,1])");
}

// ----- Round trip ------------------------------------------------------------------------------

TEST(SceneLoader, SceneToJsonReadsBackToAnEqualScene) {
  const LoadResult first = load(kRichScene);
  ASSERT_TRUE(first.ok()) << first.error_text();
  const std::string json = scene_to_json(*first.scene);
  const LoadResult second = load_scene_text(json, "roundtrip.json");
  ASSERT_TRUE(second.ok()) << second.error_text() << "\n" << json;
  expect_scenes_equal(*first.scene, *second.scene);
  // Writing is deterministic: the second pass gives the same text.
  EXPECT_EQ(scene_to_json(*second.scene), json);
}

TEST(SceneLoader, SceneToJsonRoundTripsDefaultsAndAwkwardNumbers) {
  Scene s;
  s.min_weight = 0.1 + 0.2;  // not a short decimal
  s.camera.fov_y_deg = 1e-7;
  s.ambient = Color(1e100, 5e-324, 0);
  s.materials.push_back(Material{});
  s.materials[0].name = "quote \" and \\ and é";
  Sphere sp;
  sp.radius = 1.0 / 3.0;
  s.spheres.push_back(sp);  // no file index: written after indexed objects
  const LoadResult r = load_scene_text(scene_to_json(s), "x.json");
  ASSERT_TRUE(r.ok()) << r.error_text();
  Scene expected = s;
  expected.sphere_object = {0};
  expect_scenes_equal(expected, *r.scene);
}

TEST(SceneLoader, SceneToJsonIsPrettyAndWritesEveryFieldExplicitly) {
  const LoadResult r = load(R"({"materials": {"m": {}}, "lights": [{"type": "point", "position": [0, 1, 0]}],
                                "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  const std::string json = scene_to_json(*r.scene);
  EXPECT_NE(json.find("{\n  \"camera\": {\n    \"position\": [0, 1.5, 6],\n"), std::string::npos) << json;
  for (const char* key : {"\"look_at\"", "\"up\"", "\"fov_y\": 40", "\"width\": 960", "\"height\": 540",
                          "\"ambient\": [1, 1, 1]", "\"background\": [0, 0, 0]", "\"max_depth\": 5",
                          "\"min_weight\": 0.001", "\"specular_model\": \"phong\"",
                          "\"intensity\": [1, 1, 1]", "\"enabled\": true", "\"ka\": [0, 0, 0]",
                          "\"n\": 32", "\"ior\": 1.5", "\"fresnel\": false", "\"kt\": [0, 0, 0]"}) {
    EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << json;
  }
  EXPECT_NE(json.find("    {\"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1, \"material\": \"m\"}"),
            std::string::npos) << json;
}

// ----- Files -----------------------------------------------------------------------------------

TEST(SceneLoader, MissingFileIsOneDiagnosticWithTheOsReason) {
  const fs::path dir = temp_dir("missing");
  const std::string path = (dir / "nope.json").string();
  const LoadResult r = load_scene_file(path);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.error_text(), path + ": cannot read file: No such file or directory");
  EXPECT_EQ(load_scene_file(dir.string()).error_text(), dir.string() + ": cannot read file: Is a directory");
  fs::remove_all(dir);
}

TEST(SceneLoader, AnMtlFileIsNotASceneAndTheMessageSaysWhatToOpen) {
  const std::string mtl = std::string(PHONGLAB_SOURCE_DIR) + "/assets/scenes/cornell/CornellBox-Original.mtl";
  const LoadResult r = load_scene_arg(mtl);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_NE(r.error_text().find("material library (MTL)"), std::string::npos) << r.error_text();
  EXPECT_NE(r.error_text().find("open the .obj"), std::string::npos) << r.error_text();
  EXPECT_EQ(r.error_text().find("syntax"), std::string::npos) << r.error_text();
}

TEST(SceneLoader, LoadsFilesAndNamesThemAsGivenInDiagnostics) {
  const fs::path dir = temp_dir("file");
  const std::string good = (dir / "good.json").string();
  const std::string bad = (dir / "bad.json").string();
  ASSERT_EQ(write_file_atomically(good, kRichScene), "");
  ASSERT_EQ(write_file_atomically(bad, "{\n  \"max_depth\": -3\n}\n"), "");
  EXPECT_TRUE(load_scene_file(good).ok());
  EXPECT_TRUE(load_scene_arg(good).ok());
  EXPECT_EQ(load_scene_file(bad).error_text(), bad + ":2:16: max_depth: must be an integer in 0..100 (got -3)");
  EXPECT_EQ(load_scene_arg(bad).error_text(), bad + ":2:16: max_depth: must be an integer in 0..100 (got -3)");
  fs::remove_all(dir);
}

TEST(SceneLoader, EveryEmbeddedSceneLoadsWithoutErrors) {
  if (embedded_scenes().empty()) GTEST_SKIP() << "no embedded scenes in this build";
  for (const EmbeddedScene& s : embedded_scenes()) {
    const LoadResult r = load_scene_arg(std::string(s.name));
    EXPECT_TRUE(r.ok()) << s.name << ":\n" << r.error_text();
    // Diagnostics of embedded scenes are named after the scene.
    const LoadResult broken = load_scene_text(std::string(s.json) + "x", std::string(s.name));
    ASSERT_FALSE(broken.ok());
    EXPECT_EQ(broken.errors[0].file, s.name);
  }
}

TEST(SceneLoader, AtomicWriterCreatesAndReplacesWithoutLeavingTemporaries) {
  const fs::path dir = temp_dir("atomic");
  const std::string path = (dir / "scene.json").string();
  EXPECT_EQ(write_file_atomically(path, "first"), "");
  EXPECT_EQ(read_file(path), "first");
  EXPECT_EQ(write_file_atomically(path, std::string(1 << 20, 'x')), "");
  EXPECT_EQ(read_file(path), std::string(1 << 20, 'x'));
  EXPECT_EQ(write_file_atomically(path, ""), "");
  EXPECT_EQ(read_file(path), "");
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"scene.json"});
  fs::remove_all(dir);
}

TEST(SceneLoader, AtomicWriterFailureKeepsTheTargetAndRemovesTheTemporary) {
  const fs::path dir = temp_dir("atomic_fail");
  // A directory is never replaced by a file.
  const fs::path target = dir / "taken";
  fs::create_directories(target / "inside");
  const std::string err = write_file_atomically(target.string(), "data");
  EXPECT_EQ(err, target.string() + ": is a folder: nothing was written") << err;
  EXPECT_TRUE(fs::is_directory(target / "inside"));
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"taken"});
  // A missing directory fails before anything is created.
  const std::string missing = (dir / "no" / "such" / "dir.json").string();
  const std::string err2 = write_file_atomically(missing, "data");
  EXPECT_NE(err2.find("No such file or directory"), std::string::npos) << err2;
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"taken"});
  fs::remove_all(dir);
}

// Saving when the disk is full or the folder cannot be written: a clear error, the old file
// intact, no temporary left (issue 18).
TEST(SceneLoader, AtomicWriterOnAFullDiskKeepsTheOldFile) {
  const fs::path dir = temp_dir("atomic_full");
  const std::string path = (dir / "scene.json").string();
  ASSERT_EQ(write_file_atomically(path, "the old scene"), "");
  // A disk that fills up midway: writes past the file-size limit fail (EFBIG) as ENOSPC would.
  struct rlimit before {};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &before), 0);
  void (*old_handler)(int) = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = before;
  small.rlim_cur = 4096;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string err = write_file_atomically(path, std::string(1 << 20, 'x'));
  setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(err.rfind(path + ": write failed: ", 0), 0u) << err;
  EXPECT_EQ(read_file(path), "the old scene");
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"scene.json"}) << "the temporary is removed";
  // /dev/full is a device: never replaced by a file, nothing written.
  if (fs::exists("/dev/full")) {
    EXPECT_EQ(write_file_atomically("/dev/full", "x"), "/dev/full: is not a regular file (a device or a pipe): nothing was written");
    EXPECT_TRUE(fs::is_character_file("/dev/full"));
  }
  // A folder that cannot be written (root ignores permission bits; /proc refuses everyone).
  const std::string ro = write_file_atomically("/proc/phonglab-test.json", "x");
  EXPECT_EQ(ro.rfind("/proc/phonglab-test.json: cannot create temporary file ", 0), 0u) << ro;
  // A link is followed: the file it names is replaced, the link stays a link.
  const fs::path link = dir / "link.json";
  fs::create_symlink(path, link);
  ASSERT_EQ(write_file_atomically(link.string(), "through the link"), "");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read_file(path), "through the link");
  fs::remove_all(dir);
}

// ----- Robustness ------------------------------------------------------------------------------

// Every error the loader gives for text names the file and a position.
void expect_positioned_errors(const LoadResult& r, const std::string& context) {
  for (const Diagnostic& d : r.errors) {
    EXPECT_EQ(d.file, "scene.json") << context;
    const bool summary = d.message.rfind("too many errors", 0) == 0;
    if (summary) continue;
    EXPECT_GE(d.line, 1) << context << "\n" << d.to_string();
    EXPECT_GE(d.column, 1) << context << "\n" << d.to_string();
  }
}

TEST(SceneLoader, EveryTruncationOfAValidSceneIsAPositionedError) {
  const std::string text = kRichScene;
  for (std::size_t n = 0; n < text.size(); ++n) {
    const LoadResult r = load(text.substr(0, n));
    ASSERT_FALSE(r.ok()) << "prefix of " << n << " bytes loaded";
    expect_positioned_errors(r, text.substr(0, n));
  }
}

TEST(SceneLoader, RandomCorruptionsNeverCrashAndGivePositionedErrors) {
  const std::string base = kRichScene;
  std::uint64_t state = 0x243F6A8885A308D3ull;
  const auto next = [&state] {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  };
  static const std::string kPieces[] = {"[", "]", "{", "}", "\"", ",", ":", "\\", "-", "1e400", "NaN",
                                        "\xff", std::string(1, '\0'), "null", "\"type\"", "\n", "1e-400",
                                        "99999999999999999999999", "[[[[[[[[", "\"\\u00e9\""};
  for (int iteration = 0; iteration < 3000; ++iteration) {
    std::string text = base;
    const int edits = 1 + static_cast<int>(next() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = next() % (text.size() + 1);
      switch (next() % 3) {
        case 0:
          if (at < text.size()) text.erase(at, 1 + next() % 8);
          break;
        case 1:
          text.insert(at, kPieces[next() % std::size(kPieces)]);
          break;
        default:
          if (at < text.size()) text[at] = static_cast<char>(next() & 0xFF);
          break;
      }
    }
    const LoadResult r = load(text);
    EXPECT_EQ(r.ok(), r.errors.empty());
    expect_positioned_errors(r, text);
  }
}

TEST(SceneLoader, RandomBytesNeverCrash) {
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  for (int iteration = 0; iteration < 500; ++iteration) {
    std::string text;
    const std::size_t n = 1 + (iteration * 37) % 300;
    for (std::size_t i = 0; i < n; ++i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      text += static_cast<char>(state >> 56);
    }
    const LoadResult r = load(text);
    EXPECT_FALSE(r.ok());
    expect_positioned_errors(r, "random bytes");
  }
}


// ----- The indirect light's bounces ----------------------------------------------------------------

TEST(SceneLoader, IndirectBouncesDefaultToFourAndAreKeptOnSave) {
  EXPECT_EQ(load("{}").scene->indirect_bounces, 4);
  const LoadResult r = load(R"({"indirect": {"bounces": 16}})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  EXPECT_EQ(r.scene->indirect_bounces, 16);
  const std::string saved = scene_to_json(*r.scene);
  EXPECT_NE(saved.find(R"("indirect": {"bounces": 16})"), std::string::npos) << saved;
  EXPECT_EQ(load(saved).scene->indirect_bounces, 16);
  // The default is not written: a file without it keeps its text.
  EXPECT_EQ(scene_to_json(*load("{}").scene).find("indirect"), std::string::npos);
}

TEST(SceneLoader, IndirectBouncesOutsideOneToSixtyFourAreRefusedWithTheirPlace) {
  EXPECT_EQ(errors(R"({"indirect": {"bounces": 0}})"),
            "scene.json:1:26: indirect.bounces: must be an integer in 1..64 (got 0)");
  EXPECT_EQ(errors("{\n  \"indirect\": {\"bounces\": 65}\n}"),
            "scene.json:2:27: indirect.bounces: must be an integer in 1..64 (got 65)");
  EXPECT_EQ(errors(R"({"indirect": {"bounces": 2.5}})"),
            "scene.json:1:26: indirect.bounces: must be an integer in 1..64 (got 2.5)");
  EXPECT_NE(errors(R"({"indirect": {"bounce": 2}})").find("did you mean \"bounces\""), std::string::npos);
  EXPECT_NE(errors(R"({"indirect": 3})").find("scene.json:1:14: indirect: must be an object"), std::string::npos);
}

}  // namespace
}  // namespace phonglab

// The page's numbers (printf only) are the desktop's (std::to_chars, shortest round trip, plain
// on a tie): 40, not 4e+01; 0.04, not 4e-02; 1e-05. Seeded, across magnitudes and signs.
TEST(SceneWrite, ThePortableShortestNumberIsToCharsText) {
  const auto to_chars_text = [](double x) {
    std::array<char, 40> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), x);
    return std::string(buf.data(), r.ptr);
  };
  EXPECT_EQ(phonglab::shortest_number_text(40), "40");
  EXPECT_EQ(phonglab::shortest_number_text(50), "50");
  EXPECT_EQ(phonglab::shortest_number_text(0.04), "0.04");
  EXPECT_EQ(phonglab::shortest_number_text(1e-05), "1e-05");
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> mantissa(-10, 10);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < 50000; ++i) {
    double x = mantissa(rng) * std::pow(10.0, exponent(rng));
    if (i % 3 == 0) x = std::round(x * 1000) / 1000;  // short decimals, as typed
    if (i % 5 == 0) x = static_cast<double>(static_cast<float>(x));  // float-tidy values
    ASSERT_EQ(phonglab::shortest_number_text(x), to_chars_text(x)) << i;
  }
  for (const double x : {0.0, 1.0, -1.0, 100.0, 1e15, 1e16, 1e21, 123456789012345680.0, 0.1 + 0.2, 5e-324, 1.7976931348623157e308}) {
    EXPECT_EQ(phonglab::shortest_number_text(x), to_chars_text(x)) << x;
  }
}
