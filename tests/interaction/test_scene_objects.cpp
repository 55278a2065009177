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

#include "core/accel/accel.h"
#include "core/render/render.h"
#include "interaction/camera_control.h"
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
  apply_preset(m, *find_preset("diamond"), SpecularModel::kPhong, Color(1));
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

// --- Building a scene, gently (issue 25): new objects beside the others, on the floor --------

namespace {

constexpr double kLectureAspect = 960.0 / 540.0;

Aabb bounds_of(const Scene& s, int object) {
  const ObjectRef r = object_at(s, object);
  const auto i = static_cast<std::size_t>(r.index);
  Aabb box;
  if (r.kind == Kind::kSphere) {
    box.grow(s.spheres[i].center - Vec3(s.spheres[i].radius));
    box.grow(s.spheres[i].center + Vec3(s.spheres[i].radius));
  } else if (r.kind == Kind::kTriangle) {
    for (const Vec3& v : {s.triangles[i].v0, s.triangles[i].v1, s.triangles[i].v2}) box.grow(v);
  } else if (r.kind == Kind::kMesh) {
    box = s.meshes[i].geometry->bounds;
  }
  return box;
}

// objects[object]'s bounds overlap no other finite object's.
::testing::AssertionResult apart_from_the_others(const Scene& s, int object) {
  const Aabb a = bounds_of(s, object);
  for (int other = 0; other < object_count(s); ++other) {
    if (other == object || object_at(s, other).kind == Kind::kPlane) continue;
    const Aabb b = bounds_of(s, other);
    if (a.lo.x < b.hi.x && b.lo.x < a.hi.x && a.lo.y < b.hi.y && b.lo.y < a.hi.y && a.lo.z < b.hi.z && b.lo.z < a.hi.z) {
      return ::testing::AssertionFailure() << object_label(s, object) << " overlaps " << object_label(s, other);
    }
  }
  return ::testing::AssertionSuccess();
}

// Every corner of objects[object]'s bounds projects inside a 960x540 view.
::testing::AssertionResult in_view(const Scene& s, int object) {
  const Aabb b = bounds_of(s, object);
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c(corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y, corner & 4 ? b.hi.z : b.lo.z);
    const auto at = project(s.camera, c, 960, 540);
    if (!at || at->x < 0 || at->x > 960 || at->y < 0 || at->y > 540) {
      return ::testing::AssertionFailure() << object_label(s, object) << "'s corner " << corner << " is out of view";
    }
  }
  return ::testing::AssertionSuccess();
}

int add_placed(Scene& s, Kind kind) {
  const int i = add_primitive(s, kind, placement_in_front_of(s.camera), 1);
  EXPECT_EQ(place_new_object(s, s.camera, kLectureAspect, i), "");
  return i;
}

}  // namespace

TEST(SceneObjects, TheFloorIsTheLevelPlaneUnderTheObjects) {
  Scene s = load_scene_or_fail("lecture");
  const std::optional<Floor> floor = find_floor(s, s.camera);
  ASSERT_TRUE(floor);
  EXPECT_EQ(floor->object, 0);
  EXPECT_EQ(floor->normal, Vec3(0, 1, 0));
  // Given upside down, the same floor, its normal turned up; tilted by 25 degrees still a floor,
  // by 40 a slope; a wall is none, and neither is a ceiling over the objects.
  s.planes[0].normal = Vec3(0, -1, 0);
  ASSERT_TRUE(find_floor(s, s.camera));
  EXPECT_EQ(find_floor(s, s.camera)->normal, Vec3(0, 1, 0));
  s.planes[0].point = Vec3(0, -3, 0);
  s.planes[0].normal = Vec3(std::sin(glm::radians(25.0)), std::cos(glm::radians(25.0)), 0);
  EXPECT_TRUE(find_floor(s, s.camera));
  s.planes[0].normal = Vec3(std::sin(glm::radians(40.0)), std::cos(glm::radians(40.0)), 0);
  EXPECT_FALSE(find_floor(s, s.camera));
  s.planes[0] = Plane{Vec3(0, 0, -5), Vec3(0, 0, 1), 0};
  EXPECT_FALSE(find_floor(s, s.camera));
  s.planes[0] = Plane{Vec3(0, 1, 0), Vec3(0, 1, 0), 0};  // through the spheres
  EXPECT_FALSE(find_floor(s, s.camera));
}

TEST(SceneObjects, ANewSphereRestsOnTheFloorBesideTheOthersInView) {
  Scene s = load_scene_or_fail("lecture");
  const Floor floor = *find_floor(s, s.camera);
  EXPECT_EQ(typical_size(s, s.camera), 1.4);  // the median sphere diameter
  for (int k = 0; k < 4; ++k) {  // each one beside the ones before it too
    const int i = add_placed(s, Kind::kSphere);
    const Sphere& ball = s.spheres.back();
    EXPECT_EQ(ball.radius, 0.7);
    EXPECT_NEAR(height_above(floor, ball.center), ball.radius, 1e-9 * ball.radius) << k;
    EXPECT_TRUE(apart_from_the_others(s, i));
    EXPECT_TRUE(in_view(s, i));
    EXPECT_GT(glm::length(ball.center - s.camera.look_at), 1.0) << "not inside the spheres at the look-at point";
  }
  EXPECT_TRUE(indices_are_a_permutation(s));
  EXPECT_TRUE(saves_losslessly(s));
}

TEST(SceneObjects, OnATiltedFloorAndWithoutOneTheNewSphereStillFits) {
  Scene s = load_scene_or_fail("lecture");
  // A floor tilted by 20 degrees about z through a point under the spheres.
  s.planes[0] = Plane{Vec3(0, -1.5, 0), Vec3(-std::sin(glm::radians(20.0)), std::cos(glm::radians(20.0)), 0), 0};
  const std::optional<Floor> floor = find_floor(s, s.camera);
  ASSERT_TRUE(floor);
  const int i = add_placed(s, Kind::kSphere);
  const Sphere& ball = s.spheres.back();
  EXPECT_NEAR(height_above(*floor, ball.center), ball.radius, 1e-9 * ball.radius);
  EXPECT_TRUE(apart_from_the_others(s, i));
  EXPECT_TRUE(in_view(s, i));
  // No floor: beside the others at the look-at point's depth.
  Scene bare = load_scene_or_fail("lecture");
  ASSERT_EQ(delete_object(bare, 0), "");
  ASSERT_FALSE(find_floor(bare, bare.camera));
  const int j = add_placed(bare, Kind::kSphere);
  // (its coordinates kept to float precision, as typed numbers are)
  EXPECT_NEAR(view_depth(bare.camera, bare.spheres.back().center), view_depth(bare.camera, bare.camera.look_at), 1e-6);
  EXPECT_TRUE(apart_from_the_others(bare, j));
  EXPECT_TRUE(in_view(bare, j));
}

TEST(SceneObjects, ANewTriangleStandsOnTheFloorFacingTheEye) {
  Scene s = load_scene_or_fail("lecture");
  const Floor floor = *find_floor(s, s.camera);
  const int i = add_placed(s, Kind::kTriangle);
  const Triangle& t = s.triangles.back();
  EXPECT_EQ(height_above(floor, t.v0), 0);
  EXPECT_EQ(height_above(floor, t.v1), 0);
  EXPECT_GT(height_above(floor, t.v2), 1.0);
  EXPECT_GT(glm::dot(glm::cross(t.v1 - t.v0, t.v2 - t.v0), s.camera.position - t.v0), 0);
  EXPECT_TRUE(apart_from_the_others(s, i));
  EXPECT_TRUE(in_view(s, i));
}

TEST(SceneObjects, ANewMeshIsScaledToTheSceneAndRestsOnTheFloor) {
  Scene s = load_scene_or_fail("lecture");
  const Floor floor = *find_floor(s, s.camera);
  Mesh mesh;
  mesh.file = "cornell/CornellBox-Sphere.obj";  // about 2 units across, where its file puts it
  const int i = append_mesh_object(s, mesh);
  LoadResult loaded = reload_meshes(s, "", true);
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  s = *loaded.scene;
  ASSERT_EQ(place_new_object(s, s.camera, kLectureAspect, i), "");
  loaded = reload_meshes(s, "", true);  // placed again where its new transform puts it
  ASSERT_TRUE(loaded.ok()) << loaded.error_text();
  s = *loaded.scene;
  const Mesh& placed = s.meshes.back();
  const Vec3 sides = placed.geometry->bounds.hi - placed.geometry->bounds.lo;
  EXPECT_NEAR(std::max({sides.x, sides.y, sides.z}), typical_size(s, s.camera, i), 0.01 * 1.4);
  // Its lowest vertex a hair above the floor (a thousandth of its size), not in the floor's plane.
  const double hair = floor_clearance(s, i);
  EXPECT_NEAR(hair, kMeshClearance * typical_size(s, s.camera, i), 0.01 * kMeshClearance * 1.4);
  EXPECT_NEAR(lowest_above(s, i, floor), hair, 1e-9);
  EXPECT_TRUE(apart_from_the_others(s, i));
  EXPECT_TRUE(in_view(s, i));
  EXPECT_EQ(placed.transform.rotate_deg, Vec3(0));
  // The room's own floor is what a ray coming down inside it meets, everywhere: two coplanar
  // floors would take turns at the nearest hit (the speckle the rehearsal saw).
  const PreparedScene prepared(s);
  const Aabb box = placed.geometry->bounds;
  int rays = 0;
  for (int a = 1; a < 20; ++a) {
    for (int b = 1; b < 20; ++b) {
      const Vec3 at(box.lo.x + (box.hi.x - box.lo.x) * a / 20.0, 0, box.lo.z + (box.hi.z - box.lo.z) * b / 20.0);
      const Vec3 on_floor = at - height_above(floor, at) * floor.normal;
      const Ray down = make_ray(on_floor + 0.01 * typical_size(s, s.camera, i) * floor.normal, -floor.normal);
      const std::optional<Hit> hit = intersect(prepared, down);
      ASSERT_TRUE(hit);
      EXPECT_EQ(hit->object.kind, Kind::kMesh) << a << "," << b;
      ++rays;
    }
  }
  EXPECT_EQ(rays, 19 * 19);
}

TEST(SceneObjects, DraggingMovesOverTheFloorKeepingTheHeight) {
  const Scene s = load_scene_or_fail("lecture");
  const Floor floor = *find_floor(s, s.camera, 2);
  const Vec3 start = object_anchor(s, 2);  // objects[2]: the plastic sphere at (-0.75, 0.7, 0), radius 0.7
  const Vec3 grab = start + Vec3(0.1, 0.2, 0);  // grabbed a little above and right of its centre
  const Vec3 eye = s.camera.position;
  // The pointer now over the point (0.6, 0.9, -1) of the plane through the grab point.
  const std::optional<Vec3> moved = drag_over_floor(s, 2, floor, start, grab, eye, Vec3(0.6, 0.9, -1) - eye, false);
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->y, start.y);  // its height kept exactly
  EXPECT_NEAR(glm::length(*moved - (start + Vec3(0.6, 0.9, -1) - grab)), 0, 1e-12);
  // Pointing above the horizon: nothing to move to.
  EXPECT_FALSE(drag_over_floor(s, 2, floor, start, grab, eye, Vec3(0, 0.2, -1), false));
  // Vertically: up to where the pointer is, x and z kept.
  const std::optional<Vec3> up = drag_over_floor(s, 2, floor, start, grab, eye, Vec3(-0.65, 2.5, 0) - eye, true);
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->y, start.y + 2.5 - grab.y, 1e-12);
  EXPECT_EQ(up->x, start.x);
  EXPECT_EQ(up->z, start.z);
  // Down past the floor: stopped with its lowest point on it.
  const std::optional<Vec3> down = drag_over_floor(s, 2, floor, start, grab, eye, Vec3(-0.65, -3, 0) - eye, true);
  ASSERT_TRUE(down);
  EXPECT_NEAR(down->y, 0.7, 1e-12);
  // The X, Y and Z drags are kept above it as well.
  EXPECT_NEAR(keep_above_floor(s, 2, floor, start, start - Vec3(0, 5, 0)).y, 0.7, 1e-12);
  EXPECT_EQ(keep_above_floor(s, 2, floor, start, start + Vec3(1, 5, 0)), start + Vec3(1, 5, 0));
  // One that was typed half under the floor may move, but not further down.
  Scene sunk = s;
  ASSERT_EQ(set_object_field(sunk, 2, "center", {-0.75, 0.3, 0}), "");
  EXPECT_NEAR(keep_above_floor(sunk, 2, floor, object_anchor(sunk, 2), Vec3(-0.75, -4, 0)).y, 0.3, 1e-12);
}

TEST(MaterialPresets, KaIsScaledFromTheAmbientThePresetAssumesToTheScenes) {
  const MaterialPreset& gold = *find_preset("gold");
  EXPECT_EQ(gold.assumed_ambient, 0.2);  // OpenGL's default global ambient
  EXPECT_EQ(find_preset("plastic")->assumed_ambient, 1);  // the lecture's own
  Material m;
  Color scale = apply_preset(m, gold, SpecularModel::kPhong, Color(1));
  EXPECT_EQ(scale, Color(0.2));
  for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(m.ka[c], 0.2 * gold.ka[c]);
  // Written as the table's decimals scaled, to six significant digits: no float noise in a file.
  for (int c = 0; c < 3; ++c) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", m.ka[c]);
    char six[32];
    std::snprintf(six, sizeof six, "%.6g", 0.2 * gold.ka[c]);
    EXPECT_EQ(m.ka[c], std::strtod(six, nullptr)) << text;
  }
  Scene scene;
  scene.materials = {m};
  const std::string file = scene_to_json(scene, ".");
  EXPECT_EQ(file.find("000000"), std::string::npos) << file;
  EXPECT_EQ(file.find("99999"), std::string::npos) << file;
  EXPECT_EQ(preset_applied_text(gold, scale, Color(1)),
            "gold: ka scaled by 0.2 for this scene's I\u2090 = 1 (the preset assumes I\u2090 = 0.2)");
  scale = apply_preset(m, gold, SpecularModel::kPhong, Color(0.2));
  EXPECT_EQ(m.ka, gold.ka);  // the table's, exactly
  EXPECT_NE(preset_applied_text(gold, scale, Color(0.2)).find("ka as in the table"), std::string::npos);
  // Channel by channel; a channel without ambient keeps the table's ka.
  scale = apply_preset(m, gold, SpecularModel::kPhong, Color(1, 0.5, 0));
  EXPECT_EQ(scale, Color(0.2, 0.4, 1));
  EXPECT_NE(preset_applied_text(gold, scale, Color(1, 0.5, 0)).find("(0.2, 0.4, 1)"), std::string::npos);
  apply_preset(m, *find_preset("plastic"), SpecularModel::kPhong, Color(1));
  EXPECT_EQ(m.ka, find_preset("plastic")->ka);
  EXPECT_NE(preset_note(gold).find("0.2"), std::string::npos);
}
