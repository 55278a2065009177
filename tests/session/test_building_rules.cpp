// Building a scene in the previewer (tests/gui's objects session), the rules under its panels and
// scripts: every edit made as SceneBuilder::edit_scene makes it (a copy of the scene edited by
// src/interaction/scene_objects, handed to the session as one scene edit, or refused with the
// reason and nothing changed): the gold preset on the lecture, refusals in the user's words, a
// broken OBJ named by its own line, deletions undone one step at a time.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>

#include "interaction/camera_control.h"
#include "interaction/material_presets.h"
#include "interaction/scene_objects.h"
#include "io/scene/scene_io.h"
#include "session/session.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;
using Kind = ObjectRef::Kind;

// The viewport beside the panels in a 1280x720 window: new objects are placed for its aspect.
constexpr double kViewAspect = 880.0 / 720.0;

struct BuildingTheLecture : ::testing::Test {
  Session session{""};  // no recovery files
  void SetUp() override { ASSERT_TRUE(session.open("lecture")); }

  // SceneBuilder::edit_scene: the scene's copy changed; one scene edit when nothing was refused.
  std::string build(const std::function<std::string(Scene&)>& change) {
    Scene scene = session.scene();
    ui::complete_object_indices(scene);
    const std::string why = change(scene);
    if (why.empty()) session.apply({edit::SetScene{std::move(scene)}});
    return why;
  }
  Camera view_camera() const {
    const Scene& s = session.scene();
    return ui::fit_to_view(s.camera, static_cast<double>(s.width) / s.height, kViewAspect);
  }
  // SceneBuilder::add_object for a sphere, a plane or a triangle: a copy of the selected material
  // (the floor's, the first) of its own, placed beside the others in the view.
  int add(Kind kind) {
    int added = -1;
    const Camera view = view_camera();
    EXPECT_EQ(build([&](Scene& s) {
                int material = -1;
                std::string failed = ui::duplicate_material(s, 0, material);
                if (!failed.empty()) return failed;
                added = ui::add_primitive(s, kind, ui::placement_in_front_of(view), material);
                return ui::place_new_object(s, view, kViewAspect, added);
              }),
              "");
    return added;
  }
  // ... and for a mesh (`add_object mesh PATH`, a dropped .obj): its geometry loaded from the file,
  // placed, loaded again where it was placed (SceneBuilder::place_meshes).
  std::string add_mesh(const std::string& path) {
    const Camera view = view_camera();
    return build([&](Scene& s) {
      Mesh mesh;
      mesh.file = path;
      const int added = ui::append_mesh_object(s, std::move(mesh));
      for (int pass = 0; pass < 2; ++pass) {
        LoadResult loaded = reload_meshes(s, "", true);  // the lecture is embedded
        if (!loaded.ok()) return "cannot load the mesh: " + loaded.error_text();
        s = std::move(*loaded.scene);
        if (pass == 0) {
          const std::string failed = ui::place_new_object(s, view, kViewAspect, added);
          if (!failed.empty()) return failed;
        }
      }
      return std::string();
    });
  }
  int objects() const { return ui::object_count(session.scene()); }
  std::string kind_of(int object) const { return std::string(ui::kind_name(ui::object_at(session.scene(), object).kind)); }
};

// `material_preset shiny_gold gold` (SceneBuilder::apply_material_preset): a new material of that
// name with the table's gold, its exponent for the lecture's Phong model 51.2 / 4, on the new sphere.
TEST_F(BuildingTheLecture, TheGoldPresetGivesTheTablesKdAndAQuarterOfItsExponentUnderPhong) {
  const int sphere = add(Kind::kSphere);
  EXPECT_EQ(sphere, 6) << "last, after the lecture's six";
  EXPECT_EQ(kind_of(sphere), "sphere");
  int gold = -1;
  ASSERT_EQ(build([&](Scene& s) {
              std::string failed = ui::new_material(s, "shiny_gold", gold);
              if (!failed.empty()) return failed;
              ui::apply_preset(s.materials[static_cast<std::size_t>(gold)], *ui::find_preset("gold"), s.specular_model, s.ambient);
              return std::string();
            }),
            "");
  ASSERT_EQ(build([&](Scene& s) { return ui::set_object_field(s, sphere, "material", {}, "shiny_gold"); }), "");
  const Scene& scene = session.scene();
  ASSERT_EQ(scene.specular_model, SpecularModel::kPhong);
  const Material& m = scene.materials.at(static_cast<std::size_t>(gold));
  EXPECT_EQ(m.name, "shiny_gold");
  EXPECT_EQ(m.kd, Color(0.75164, 0.60648, 0.22648));
  EXPECT_EQ(m.n, 12.8);
  EXPECT_EQ(ui::object_material(scene, sphere), gold);
  EXPECT_EQ(session.undo_count(), 3U) << "added, preset, material: one step each";
}

// A sphere's radius of -1 and a triangle's corners typed into a line are refused in the user's
// words, and the scene keeps what it had (no undo step either).
TEST_F(BuildingTheLecture, ANegativeRadiusAndATriangleAlongALineAreRefusedWithTheirReasons) {
  const int sphere = add(Kind::kSphere);
  const std::string before = scene_to_json(session.scene());
  EXPECT_EQ(build([&](Scene& s) { return ui::set_object_field(s, sphere, "radius", {-1.0}); }), "radius must be > 0 (got -1)");
  EXPECT_EQ(scene_to_json(session.scene()), before);
  const int triangle = add(Kind::kTriangle);
  ASSERT_EQ(triangle, 7);
  ASSERT_EQ(build([&](Scene& s) { return ui::set_object_field(s, triangle, "v0", {0, 0, 0}); }), "");
  ASSERT_EQ(build([&](Scene& s) { return ui::set_object_field(s, triangle, "v1", {1, 0, 0}); }), "");
  const std::string corners = scene_to_json(session.scene());
  const std::size_t steps = session.undo_count();
  EXPECT_EQ(build([&](Scene& s) { return ui::set_object_field(s, triangle, "v2", {2, 0, 0}); }),
            "degenerate triangle: the corners would lie on one line (kept as it was)");
  EXPECT_EQ(scene_to_json(session.scene()), corners);
  EXPECT_EQ(session.undo_count(), steps);
  EXPECT_EQ(objects(), 8);
}

// An OBJ added as an object becomes a mesh object; a broken one is refused with its own file and
// line (the loader's diagnostic, as the Objects panel shows it), the objects as they were.
TEST_F(BuildingTheLecture, ABrokenObjIsRefusedWithItsOwnLineAndTheObjectsStay) {
  const fs::path dir = fs::temp_directory_path() / ("phonglab-building-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string tetra = (dir / "tetra.obj").string(), broken = (dir / "broken.obj").string();
  std::ofstream(tetra) << "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::ofstream(broken) << "v 0 0 0\nf 1 2 3\n";
  ASSERT_EQ(add_mesh(tetra), "");
  EXPECT_EQ(objects(), 7);
  EXPECT_EQ(kind_of(6), "mesh");
  const std::string before = scene_to_json(session.scene());
  const std::size_t steps = session.undo_count();
  const std::string why = add_mesh(broken);
  EXPECT_NE(why.find("broken.obj:2"), std::string::npos) << why;
  EXPECT_EQ(objects(), 7);
  EXPECT_EQ(scene_to_json(session.scene()), before);
  EXPECT_EQ(session.undo_count(), steps);
  fs::remove_all(dir);
}

// Deleting objects[0] (the floor) is one undo step; every object deleted leaves an empty scene
// that refuses a further delete, and one undo brings the last object back.
TEST_F(BuildingTheLecture, DeletionsAreUndoneOneStepAtATime) {
  ASSERT_EQ(kind_of(0), "plane");
  ASSERT_EQ(build([](Scene& s) { return ui::delete_object(s, 0); }), "");
  EXPECT_EQ(objects(), 5);
  EXPECT_EQ(kind_of(0), "sphere");
  EXPECT_TRUE(session.dirty());
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(objects(), 6);
  EXPECT_EQ(kind_of(0), "plane");
  EXPECT_FALSE(session.dirty());
  for (int k = 0; k < 6; ++k) ASSERT_EQ(build([](Scene& s) { return ui::delete_object(s, 0); }), "") << k;
  EXPECT_EQ(objects(), 0);
  EXPECT_EQ(session.undo_count(), 6U);
  EXPECT_EQ(build([](Scene& s) { return ui::delete_object(s, 0); }), "the scene has no objects");
  ASSERT_TRUE(session.undo());
  EXPECT_EQ(objects(), 1);
  EXPECT_EQ(kind_of(0), "sphere") << "the last one deleted: the glass sphere";
}

}  // namespace
}  // namespace phonglab
