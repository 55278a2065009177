// Building a scene (src/interaction/scene_objects.h, material_presets.h): every edit keeps the
// scene a file can hold (a seeded chain of random edits, each saved and loaded back to the same
// text and the same image), refusals leave the scene as it was and say why, and the preset
// library is the published table.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <set>
#include <string>

#include "core/render/render.h"
#include "interaction/material_presets.h"
#include "interaction/scene_objects.h"
#include "io/scene/scene_io.h"
#include "tests/support/test_support.h"

using namespace phonglab;
using namespace phonglab::ui;
using Kind = ObjectRef::Kind;

namespace {

// The file indices of the scene's primitives are 0..count-1, each once.
::testing::AssertionResult indices_are_a_permutation(const Scene& s) {
  std::vector<int> all;
  for (const std::vector<int>* v : {&s.sphere_object, &s.plane_object, &s.triangle_object, &s.mesh_object}) {
    all.insert(all.end(), v->begin(), v->end());
  }
  std::sort(all.begin(), all.end());
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (all[i] != static_cast<int>(i)) return ::testing::AssertionFailure() << "index " << i << " is " << all[i];
  }
  if (static_cast<int>(all.size()) != object_count(s)) return ::testing::AssertionFailure() << "count differs";
  return ::testing::AssertionSuccess();
}

Accumulator image_of(const Scene& s) {
  Accumulator a;
  a.reset(24, 16);
  RenderOptions options;
  options.threads = 1;
  render_pass(PreparedScene(s), options, a);
  return a;
}

// Saved and loaded back, the scene is the same text and gives the same image, bit for bit.
::testing::AssertionResult saves_losslessly(const Scene& s) {
  const std::string text = scene_to_json(s);
  const LoadResult back = load_scene_text(text, "edited.json");
  if (!back.ok()) return ::testing::AssertionFailure() << back.error_text() << "\n" << text;
  if (scene_to_json(*back.scene) != text) return ::testing::AssertionFailure() << "the text changed on reload";
  const Accumulator a = image_of(s), b = image_of(*back.scene);
  if (std::memcmp(a.sum.data(), b.sum.data(), a.sum.size() * sizeof(Color)) != 0) {
    return ::testing::AssertionFailure() << "the loaded scene renders differently";
  }
  return ::testing::AssertionSuccess();
}

}  // namespace

TEST(SceneObjects, NewObjectsGoLastInFrontOfTheCameraAndSaveLosslessly) {
  Scene s = load_scene_or_fail("lecture");
  const int before = object_count(s);
  const Placement where = placement_in_front_of(s.camera);
  for (const Kind kind : {Kind::kSphere, Kind::kPlane, Kind::kTriangle}) {
    const int i = add_primitive(s, kind, where, 1);
    EXPECT_EQ(i, object_count(s) - 1);
    EXPECT_EQ(object_at(s, i).kind, kind);
    EXPECT_EQ(object_material(s, i), 1);
    EXPECT_LT(glm::length(object_anchor(s, i) - s.camera.look_at), where.size) << kind_name(kind);
  }
  EXPECT_EQ(object_count(s), before + 3);
  // The triangle faces the eye: its geometric normal points towards the camera.
  const Triangle& t = s.triangles.back();
  EXPECT_GT(glm::dot(glm::cross(t.v1 - t.v0, t.v2 - t.v0), s.camera.position - t.v0), 0);
  // A sphere at the look-at point is seen at the image centre.
  const Accumulator plain = image_of(load_scene_or_fail("lecture"));
  const Accumulator added = image_of(s);
  const std::size_t centre = static_cast<std::size_t>(8 * 24 + 12);
  EXPECT_NE(plain.sum[centre], added.sum[centre]);
  EXPECT_TRUE(indices_are_a_permutation(s));
  EXPECT_TRUE(saves_losslessly(s));
}

TEST(SceneObjects, DeleteAndDuplicateKeepTheFileOrder) {
  Scene s = load_scene_or_fail("lecture");
  const std::string first_sphere = object_label(s, 1);
  ASSERT_EQ(delete_object(s, 0), "");  // the floor plane
  EXPECT_EQ(object_at(s, 0).kind, Kind::kSphere);
  EXPECT_EQ(object_label(s, 0).substr(std::string("objects[0]").size()), first_sphere.substr(std::string("objects[1]").size()));
  int copy = -1;
  ASSERT_EQ(duplicate_object(s, 0, copy), "");
  EXPECT_EQ(copy, object_count(s) - 1);
  EXPECT_EQ(s.spheres.back(), s.spheres[static_cast<std::size_t>(object_at(s, 0).index)]);
  EXPECT_NE(delete_object(s, 99).find("no objects[99]"), std::string::npos);
  EXPECT_TRUE(indices_are_a_permutation(s));
  EXPECT_TRUE(saves_losslessly(s));
  while (object_count(s) > 0) ASSERT_EQ(delete_object(s, 0), "");
  EXPECT_EQ(delete_object(s, 0), "the scene has no objects");
  EXPECT_TRUE(saves_losslessly(s));  // an empty scene is a valid file: the background alone
}

TEST(SceneObjects, RefusalsSayWhyAndChangeNothing) {
  Scene s = load_scene_or_fail("lecture");
  const std::string before = scene_to_json(s);
  EXPECT_EQ(set_object_field(s, 0, "radius", {1.0}), "objects[0] is a plane: it has no radius");
  EXPECT_NE(set_object_field(s, 1, "radius", {-1.0}).find("must be > 0"), std::string::npos);
  EXPECT_NE(set_object_field(s, 1, "center", {1.0, 2.0}).find("three numbers"), std::string::npos);
  EXPECT_NE(set_object_field(s, 0, "normal", {0.0, 0.0, 0.0}).find("must not be zero"), std::string::npos);
  EXPECT_NE(set_object_field(s, 1, "material", {}, "unobtainium").find("no material named 'unobtainium'"),
            std::string::npos);
  EXPECT_NE(set_object_field(s, 1, "colour", {1.0, 1.0, 1.0}).find("unknown field"), std::string::npos);
  const int t = add_primitive(s, Kind::kTriangle, placement_in_front_of(s.camera), 0);
  const std::string with_triangle = scene_to_json(s);
  const Triangle tri = s.triangles.back();
  const Vec3 on_line = tri.v0 + 2.0 * (tri.v1 - tri.v0);
  EXPECT_NE(set_object_field(s, t, "v2", {on_line.x, on_line.y, on_line.z}).find("degenerate triangle"), std::string::npos);
  EXPECT_EQ(scene_to_json(s), with_triangle);
  ASSERT_EQ(delete_object(s, t), "");
  EXPECT_EQ(scene_to_json(s), before);
  int index = -1;
  EXPECT_NE(new_material(s, "glass", index).find("exists already"), std::string::npos);
  const int glass = find_material(s, "glass");
  EXPECT_NE(delete_material(s, glass).find("'glass' is in use by objects["), std::string::npos);
  EXPECT_EQ(scene_to_json(s), before);
}

TEST(SceneObjects, MaterialsAreAddedRenamedAndDeletedWithTheirUsers) {
  Scene s = load_scene_or_fail("lecture");
  int fresh = -1;
  ASSERT_EQ(new_material(s, "gold", fresh), "");
  ASSERT_EQ(set_object_field(s, 1, "material", {}, "gold"), "");
  EXPECT_EQ(material_users(s, fresh), 1);
  ASSERT_EQ(rename_material(s, fresh, "golden"), "");
  EXPECT_EQ(object_material(s, 1), fresh);
  EXPECT_NE(rename_material(s, fresh, "glass").find("exists already"), std::string::npos);
  // The material object 1 used before is now unused: deleting it renumbers the others' indices,
  // and every object keeps its material by name.
  const int matte = find_material(s, "matte");
  ASSERT_EQ(material_users(s, matte), 0);
  std::vector<std::string> names;
  for (int i = 0; i < object_count(s); ++i) names.push_back(s.materials[static_cast<std::size_t>(object_material(s, i))].name);
  ASSERT_EQ(delete_material(s, matte), "");
  for (int i = 0; i < object_count(s); ++i) {
    EXPECT_EQ(s.materials[static_cast<std::size_t>(object_material(s, i))].name, names[static_cast<std::size_t>(i)]);
  }
  int copy = -1;
  ASSERT_EQ(duplicate_material(s, find_material(s, "golden"), copy), "");
  EXPECT_EQ(s.materials[static_cast<std::size_t>(copy)].name, "golden copy");
  EXPECT_TRUE(saves_losslessly(s));
}

// A seeded chain of random edits of every kind on the lecture: after each, the file indices are
// a permutation and the scene saves and loads back to the same text and image.
TEST(SceneObjects, RandomEditsAlwaysSaveLosslessly) {
  std::mt19937 rng(7);
  Scene s = load_scene_or_fail("lecture");
  std::uniform_real_distribution<double> u(-1, 1);
  int refused = 0;
  for (int step = 0; step < 200; ++step) {
    const int n = object_count(s);
    std::uniform_int_distribution<int> pick(0, std::max(n - 1, 0));
    const int i = pick(rng);
    std::string error;
    int copy = -1;
    switch (std::uniform_int_distribution<int>(0, 6)(rng)) {
      case 0: add_primitive(s, static_cast<Kind>(step % 3), placement_in_front_of(s.camera), step % 3); break;
      case 1: if (n > 3) error = delete_object(s, i); break;
      case 2: error = duplicate_object(s, i, copy); break;
      case 3: error = move_object(s, i, Vec3(u(rng), u(rng), u(rng))); break;
      case 4: error = set_object_field(s, i, "radius", {u(rng) + 0.5}); break;
      case 5: error = set_object_field(s, i, "v1", {u(rng), u(rng), u(rng)}); break;
      default: error = set_object_field(s, i, "material", {}, s.materials[static_cast<std::size_t>(step) % s.materials.size()].name); break;
    }
    refused += !error.empty();
    ASSERT_TRUE(indices_are_a_permutation(s)) << "step " << step;
    if (step % 10 == 0) {
      ASSERT_TRUE(saves_losslessly(s)) << "step " << step;
    }
  }
  EXPECT_GT(refused, 10);  // radius of a plane, corners of a sphere: refused, and nothing broke
  EXPECT_TRUE(saves_losslessly(s));
}

TEST(MaterialPresets, TheClassicTableAsPublishedAndTheLecturesOwn) {
  std::set<std::string_view> names;
  for (const MaterialPreset& p : material_presets()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    for (const char c : p.name) EXPECT_TRUE(std::islower(static_cast<unsigned char>(c)) || c == '_') << p.name;
  }
  for (const char* required : {"brass", "bronze", "chrome", "copper", "gold", "silver", "pewter", "emerald", "jade",
                               "obsidian", "pearl", "ruby", "turquoise", "black_plastic", "white_plastic",
                               "black_rubber", "white_rubber", "matte", "plastic", "mirror", "glass", "water",
                               "diamond"}) {
    EXPECT_NE(find_preset(required), nullptr) << required;
  }
  const MaterialPreset& gold = *find_preset("gold");
  EXPECT_EQ(gold.kd, Color(0.75164, 0.60648, 0.22648));  // teapots.c
  EXPECT_EQ(gold.shininess, 51.2);                        // 0.4 x 128
  EXPECT_EQ(preset_exponent(gold, SpecularModel::kBlinn), 51.2);
  EXPECT_EQ(preset_exponent(gold, SpecularModel::kPhong), 12.8);
  EXPECT_EQ(preset_exponent(*find_preset("glass"), SpecularModel::kPhong), 300);  // the lecture's n as it is
  Material m;
  m.name = "mine";
  apply_preset(m, *find_preset("diamond"), SpecularModel::kPhong);
  EXPECT_EQ(m.name, "mine");
  EXPECT_EQ(m.ior, 2.417);
  EXPECT_TRUE(m.fresnel);
}

// The optional "name" of an object: read, shown, kept on save, moved with the object when others
// are deleted, copied with a duplicate, and a name that is not a string is an error.
TEST(SceneObjects, NamesAreReadKeptAndFollowTheirObjects) {
  const std::string text = R"({"materials": {"m": {"kd": 0.5}}, "objects": [
    {"type": "sphere", "center": [0, 0, -3], "radius": 1, "material": "m"},
    {"type": "sphere", "name": "red ball", "center": [1, 0, -3], "radius": 0.5, "material": "m"},
    {"type": "plane", "name": "floor", "point": [0, -1, 0], "normal": [0, 1, 0], "material": "m"}]})";
  LoadResult loaded = load_scene_text(text, "named.json");
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  Scene s = *loaded.scene;
  EXPECT_EQ(object_name_of(s, 0), "");
  EXPECT_EQ(object_name_of(s, 1), "red ball");
  EXPECT_EQ(object_label(s, 2), "objects[2] \"floor\": plane, m");
  EXPECT_TRUE(saves_losslessly(s));
  EXPECT_NE(scene_to_json(s).find("\"name\": \"red ball\""), std::string::npos);
  ASSERT_EQ(delete_object(s, 0), "");
  EXPECT_EQ(object_name_of(s, 0), "red ball");
  int copy = -1;
  ASSERT_EQ(duplicate_object(s, 1, copy), "");
  EXPECT_EQ(object_name_of(s, copy), "floor copy");
  ASSERT_EQ(set_object_field(s, 0, "name", {}, "blue ball"), "");
  EXPECT_EQ(object_name_of(s, 0), "blue ball");
  EXPECT_TRUE(saves_losslessly(s));
  const LoadResult bad = load_scene_text(R"({"materials": {"m": {}}, "objects": [
    {"type": "sphere", "name": 7, "center": [0, 0, 0], "radius": 1, "material": "m"}]})", "bad.json");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error_text().find("objects[0].name"), std::string::npos) << bad.error_text();
}
