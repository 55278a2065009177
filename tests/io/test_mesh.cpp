// Mesh objects (docs/scene-format.md): Wavefront OBJ/MTL through the scene loader. What real files contain
// is tolerated (quads, n-gons, negative indices, missing normals or MTL, stray MTL lines), what
// is broken is an error naming file:line, the MTL maps onto the lecture's coefficients as
// docs/scene-format.md's table says, transforms place vertices and normals exactly, and the BVH
// answers as brute force does.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "core/accel/accel.h"
#include "core/scene/camera.h"
#include "core/geometry/geometry.h"
#include "io/obj_io.h"
#include "tests/support/obj_mesh.h"
#include "io/probe_report.h"
#include "core/render/render.h"
#include "io/scene/scene_io.h"
#include "core/shading/shading.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

// A fresh, empty directory for one test.
fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("phonglab_mesh_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// Writes `scene_json` as dir/scene.json and loads it from disk (mesh paths relative to it).
LoadResult load_in(const fs::path& dir, const std::string& scene_json) {
  write(dir / "scene.json", scene_json);
  return load_scene_file((dir / "scene.json").string());
}

// A scene holding just the mesh `file` (plus `extra` keys in the mesh object).
std::string mesh_scene(const std::string& file, const std::string& extra = "") {
  return R"({"objects": [{"type": "mesh", "file": ")" + file + "\"" + extra + "}]}";
}

std::string all_warnings(const LoadResult& r) {
  std::string s;
  for (const Diagnostic& d : r.warnings) s += d.to_string() + "\n";
  return s;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const MeshGeometry& geometry(const Scene& s, std::size_t mesh = 0) { return *s.meshes.at(mesh).geometry; }

double area(const Triangle& t) { return 0.5 * glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0)); }

const Material* material_named(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

// MTL numbers go through tinyobjloader's own parser, which may be a few ulps off the nearest
// double (OBJ vertex coordinates are re-read exactly by the loader; material values are not).
void expect_color(const Color& c, double r, double g, double b, const std::string& what) {
  EXPECT_DOUBLE_EQ(c.x, r) << what;
  EXPECT_DOUBLE_EQ(c.y, g) << what;
  EXPECT_DOUBLE_EQ(c.z, b) << what;
}

void expect_near(const Vec3& a, const Vec3& b, double tol, const std::string& what) {
  EXPECT_NEAR(a.x, b.x, tol) << what;
  EXPECT_NEAR(a.y, b.y, tol) << what;
  EXPECT_NEAR(a.z, b.z, tol) << what;
}

bool same_bits(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

bool same_triangle(const Triangle& a, const Triangle& b) {
  return same_bits(a.v0, b.v0) && same_bits(a.v1, b.v1) && same_bits(a.v2, b.v2) && a.material == b.material &&
         a.has_vertex_normals == b.has_vertex_normals && same_bits(a.n0, b.n0) && same_bits(a.n1, b.n1) &&
         same_bits(a.n2, b.n2);
}

void expect_same_triangles(const MeshGeometry& a, const MeshGeometry& b) {
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  for (std::size_t i = 0; i < a.triangles.size(); ++i) {
    EXPECT_TRUE(same_triangle(a.triangles[i], b.triangles[i])) << "triangle " << i;
    EXPECT_EQ(a.source_face[i], b.source_face[i]) << "triangle " << i;
  }
}

// The point the emitter hint of `warnings` tells the user to put a light at.
std::optional<Vec3> hinted_light(const std::string& warnings) {
  const std::size_t at = warnings.find("place one near [");
  if (at == std::string::npos) return std::nullopt;
  Vec3 p;
  if (std::sscanf(warnings.c_str() + at, "place one near [%lf, %lf, %lf]", &p.x, &p.y, &p.z) != 3) return std::nullopt;
  return p;
}

PreparedScene prepared(LoadResult r) {
  EXPECT_TRUE(r.ok()) << r.error_text();
  return PreparedScene(r.ok() ? *r.scene : Scene{});
}

// The nearest hit of the ray from `o` along `d` (normalised here).
std::optional<Hit> shoot(const PreparedScene& p, const Vec3& o, const Vec3& d) {
  return intersect(p, make_ray(o, glm::normalize(d)));
}

const char* const kUnitTriangleObj =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0 1 0\n"
    "f 1 2 3\n";

// ----- The Cornell boxes ------------------------------------------------------------------------

TEST(MeshCornell, OriginalLoadsEighteenQuadsAsThirtySixTrianglesWithItsEightMaterials) {
  const LoadResult r = load_scene_arg("cornell");
  ASSERT_TRUE(r.ok()) << r.error_text();
  const Scene& s = *r.scene;
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.mesh_object, std::vector<int>{0});
  EXPECT_EQ(geometry(s).triangles.size(), 36u);
  EXPECT_EQ(*std::max_element(geometry(s).source_face.begin(), geometry(s).source_face.end()), 17);
  ASSERT_EQ(s.materials.size(), 8u);  // the MTL's 8; every face names one, so no default
  for (const char* name : {"leftWall", "rightWall", "floor", "ceiling", "backWall", "shortBox", "tallBox", "light"}) {
    const Material* m = material_named(s, std::string("CornellBox-Original/") + name);
    ASSERT_NE(m, nullptr) << name;
    EXPECT_EQ(m->source, "cornell/CornellBox-Original.obj") << name;
    // Every material is illum 2 with Ks 0: nothing reflects or refracts.
    expect_color(m->kr, 0, 0, 0, name);
    expect_color(m->kt, 0, 0, 0, name);
    EXPECT_FALSE(m->fresnel) << name;
    EXPECT_EQ(m->n, 10) << name;
  }
  const Material& left = *material_named(s, "CornellBox-Original/leftWall");
  expect_color(left.ka, 0.63, 0.065, 0.05, "leftWall.ka");  // "Ka 0.63 0.065 0.05 # Red"
  expect_color(left.kd, 0.63, 0.065, 0.05, "leftWall.kd");
  expect_color(s.materials.at(static_cast<std::size_t>(geometry(s).triangles[0].material)).ks, 0, 0, 0, "ks");
  // The emissive quad (Ke 17 12 4 at y = 1.98) is a hint to place a point light at its centre.
  const std::string w = all_warnings(r);
  EXPECT_TRUE(contains(w, "material 'light' emits light (Ke 17 12 4) from 1 face(s)")) << w;
  const auto hint = hinted_light(w);
  ASSERT_TRUE(hint.has_value()) << w;
  expect_near(*hint, Vec3(-0.005, 1.98, -0.03), 1e-9, "emitter centre (PROVENANCE.md)");
  // ... and the embedded scene has its light just below it.
  ASSERT_EQ(s.lights.size(), 1u);
  expect_near(s.lights[0].position, Vec3(-0.005, 1.9, -0.03), 0, "the scene's light");
}

TEST(MeshCornell, SphereBoxMapsTheMirrorAndGlassSpheresAndSkipsTheMtlsStrayVertexLines) {
  const LoadResult r = load_scene_arg("cornell-sphere");
  ASSERT_TRUE(r.ok()) << r.error_text();
  const Scene& s = *r.scene;
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(geometry(s).triangles.size(), 2188u);  // every face a triangle, none of zero area
  for (const Triangle& t : geometry(s).triangles) ASSERT_TRUE(t.has_vertex_normals);
  // The eight MTL materials, all read although `v 0.2 0 0` and `v 0 0.1 0` sit in the first two.
  ASSERT_EQ(s.materials.size(), 8u);
  const Material* left = material_named(s, "CornellBox-Sphere/leftSphere");
  const Material* right = material_named(s, "CornellBox-Sphere/rightSphere");
  const Material* floor = material_named(s, "CornellBox-Sphere/floor");  // the block after the stray line
  ASSERT_TRUE(left && right && floor);
  // leftSphere: illum 5 = mirror weighted by Fresnel; kr = Ks.
  expect_color(left->kr, 0.95, 0.95, 0.95, "leftSphere.kr");
  expect_color(left->kt, 0, 0, 0, "leftSphere.kt");
  EXPECT_TRUE(left->fresnel);
  EXPECT_EQ(left->n, 1000);
  expect_color(left->kd, 0.01, 0.01, 0.01, "leftSphere.kd");
  // rightSphere: illum 7 = glass with Fresnel; Tf 0.1 as its author (and 3ds Max) means it: 1 - the
  // transmitted fraction, so kt = 0.9, a clear glass; ior = Ni, kr = Ks.
  expect_color(right->kt, 0.9, 0.9, 0.9, "rightSphere.kt");
  // Ks 0.3 is the mirror weight, kept to 1 - kt so the glass sends on no more light than it gets.
  expect_color(right->kr, 1 - 0.9, 1 - 0.9, 1 - 0.9, "rightSphere.kr");
  EXPECT_EQ(right->ior, 2.5);
  EXPECT_TRUE(right->fresnel);
  EXPECT_EQ(right->n, 200);
  expect_color(floor->kd, 0.725, 0.71, 0.68, "floor.kd");
  EXPECT_EQ(floor->ior, 1.5);
  const std::string w = all_warnings(r);
  const auto hint = hinted_light(w);
  ASSERT_TRUE(hint.has_value()) << w;
  expect_near(*hint, Vec3(-0.005, 1.58, -0.03), 1e-9, "emitter centre (PROVENANCE.md)");
}

TEST(MeshCornell, BothSceneFilesLoadFromDiskWithMeshPathsRelativeToTheSceneFile) {
  for (const char* name : {"cornell", "cornell-sphere"}) {
    SCOPED_TRACE(name);
    const LoadResult disk = load_scene_file(std::string(PHONGLAB_SOURCE_DIR) + "/assets/scenes/" + name + ".json");
    const LoadResult embedded = load_scene_arg(name);
    ASSERT_TRUE(disk.ok()) << disk.error_text();
    ASSERT_TRUE(embedded.ok()) << embedded.error_text();
    expect_same_triangles(geometry(*disk.scene), geometry(*embedded.scene));
    ASSERT_EQ(disk.scene->materials.size(), embedded.scene->materials.size());
    for (std::size_t i = 0; i < disk.scene->materials.size(); ++i) {
      EXPECT_EQ(disk.scene->materials[i].name, embedded.scene->materials[i].name);
    }
  }
  // From another folder the relative path is still the scene file's, not the working directory's.
  const fs::path dir = temp_dir("cornell_copy");
  fs::create_directories(dir / "boxes");
  fs::copy(fs::path(PHONGLAB_SOURCE_DIR) / "assets/scenes/cornell", dir / "boxes" / "cornell", fs::copy_options::recursive);
  fs::copy_file(fs::path(PHONGLAB_SOURCE_DIR) / "assets/scenes/cornell.json", dir / "boxes" / "cornell.json");
  const LoadResult copy = load_scene_file((dir / "boxes" / "cornell.json").string());
  ASSERT_TRUE(copy.ok()) << copy.error_text();
  EXPECT_EQ(geometry(*copy.scene).triangles.size(), 36u);
  fs::remove_all(dir);
}

TEST(MeshCornell, RendersWithoutNaNAndTheLitWallsHaveTheirColours) {
  const PreparedScene p = prepared(load_scene_arg("cornell"));
  const Scene& s = p.scene();
  constexpr int kSize = 64;
  Accumulator acc;
  acc.reset(kSize, kSize);
  const PassStats stats = render_pass(p, RenderOptions{}, acc);
  EXPECT_EQ(stats.nan_count, 0u);
  for (const Color& c : acc.sum) ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
  // Pixels a tenth of the width in from either side, half-way down, look at the side walls.
  const auto wall = [&](int x, const char* material, int dominant) {
    SCOPED_TRACE(material);
    const PixelProbe probe = probe_pixel(p, kSize, kSize, x, kSize / 2);
    ASSERT_TRUE(probe.root.hit);
    EXPECT_EQ(s.materials.at(static_cast<std::size_t>(probe.root.material)).name, material);
    const Color c = acc.mean(x, kSize / 2);
    EXPECT_EQ(c, probe.root.total);
    const double channel[3] = {c.x, c.y, c.z};
    for (int k = 0; k < 3; ++k) {
      if (k != dominant) {
        EXPECT_GT(channel[dominant], 1.5 * channel[k]) << "channel " << k;
      }
    }
  };
  wall(kSize / 10, "CornellBox-Original/leftWall", 0);        // red
  wall(kSize - 1 - kSize / 10, "CornellBox-Original/rightWall", 1);  // green
}

// ----- Faces ------------------------------------------------------------------------------------

// A unit square (quad) and a convex pentagon of area 21.
const char* const kPolygonsObj =
    "# a quad and a pentagon\n"
    "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "v 0 0 0\nv 4 0 0\nv 5 3 0\nv 2 5 0\nv -1 3 0\n"
    "f 1 2 3 4\n"
    "f 5 6 7 8 9\n";

TEST(MeshFaces, QuadsAndNGonsBecomeFansFromTheirFirstVertexThatKeepTheirArea) {
  const ObjMesh obj = load_obj(kPolygonsObj, "p.obj", nullptr);
  ASSERT_TRUE(obj.errors.empty());
  ASSERT_EQ(obj.triangles.size(), 5u);  // 2 + 3
  EXPECT_EQ(obj.source_face, (std::vector<int>{0, 0, 1, 1, 1}));
  const Vec3 pentagon[5] = {{0, 0, 0}, {4, 0, 0}, {5, 3, 0}, {2, 5, 0}, {-1, 3, 0}};
  for (int k = 0; k < 3; ++k) {
    const Triangle& t = obj.triangles[static_cast<std::size_t>(2 + k)];
    EXPECT_TRUE(same_bits(t.v0, pentagon[0]) && same_bits(t.v1, pentagon[k + 1]) && same_bits(t.v2, pentagon[k + 2]))
        << "fan triangle " << k;
  }
  // Through a scene: the same areas, whatever order the BVH puts the triangles in.
  const fs::path dir = temp_dir("polygons");
  write(dir / "p.obj", kPolygonsObj);
  const LoadResult r = load_in(dir, mesh_scene("p.obj"));
  ASSERT_TRUE(r.ok()) << r.error_text();
  std::map<int, double> face_area;
  std::map<int, int> face_triangles;
  const MeshGeometry& g = geometry(*r.scene);
  for (std::size_t i = 0; i < g.triangles.size(); ++i) {
    face_area[g.source_face[i]] += area(g.triangles[i]);
    ++face_triangles[g.source_face[i]];
  }
  EXPECT_EQ(face_triangles[0], 2);
  EXPECT_EQ(face_triangles[1], 3);
  EXPECT_EQ(face_area[0], 1.0);
  EXPECT_EQ(face_area[1], 21.0);
  fs::remove_all(dir);
}

TEST(MeshFaces, NegativeIndicesCountBackFromTheLastVertexReadAndEqualThePositiveOnes) {
  const std::string negative =
      "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "f -4 -3 -2 -1\n"
      "v 0 0 0\nv 4 0 0\nv 5 3 0\nv 2 5 0\nv -1 3 0\n"
      "f -5 -4 -3 -2 -1\n"
      "f -9 -8 -5\n";  // mixes the quad's first two vertices with the pentagon's first
  const std::string positive =
      "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
      "f 1 2 3 4\n"
      "v 0 0 0\nv 4 0 0\nv 5 3 0\nv 2 5 0\nv -1 3 0\n"
      "f 5 6 7 8 9\n"
      "f 1 2 5\n";
  const ObjMesh a = load_obj(negative, "n.obj", nullptr);
  const ObjMesh b = load_obj(positive, "p.obj", nullptr);
  ASSERT_TRUE(a.errors.empty() && b.errors.empty());
  ASSERT_EQ(a.triangles.size(), 6u);
  ASSERT_EQ(b.triangles.size(), 6u);
  for (std::size_t i = 0; i < a.triangles.size(); ++i) EXPECT_TRUE(same_triangle(a.triangles[i], b.triangles[i])) << i;
  EXPECT_EQ(a.source_face, b.source_face);
}

TEST(MeshFaces, ZeroAreaFacesAreLeftOutWithAWarning) {
  const fs::path dir = temp_dir("degenerate");
  write(dir / "d.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\n"
        "f 1 2 3\n"     // collinear
        "f 1 2 2\n"     // a repeated vertex
        "f 1 2 4\n");  // the one real triangle
  const LoadResult r = load_in(dir, mesh_scene("d.obj"));
  ASSERT_TRUE(r.ok()) << r.error_text();
  ASSERT_EQ(geometry(*r.scene).triangles.size(), 1u);
  EXPECT_EQ(geometry(*r.scene).source_face, std::vector<int>{2});
  const std::string w = all_warnings(r);
  EXPECT_TRUE(contains(w, "objects[0].file: d.obj: 2 zero-area triangles left out")) << w;
  // Nothing but zero-area faces is an error: a mesh needs something to hit.
  write(dir / "e.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  const LoadResult e = load_in(dir, mesh_scene("e.obj"));
  EXPECT_FALSE(e.ok());
  EXPECT_TRUE(contains(e.error_text(), "e.obj: no faces (a mesh needs at least one triangle of non-zero area)"))
      << e.error_text();
  fs::remove_all(dir);
}

// One diagnostic type for every input format: an OBJ's problems are Diagnostics with the file,
// the line (no column, no JSON path) and their severity; a scene's name the JSON path too.
TEST(Diagnostics, OneTypeForSceneObjAndMtlWithItsSeverity) {
  const ObjMesh obj = load_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 2 9\n", "m.obj", nullptr);
  ASSERT_EQ(obj.errors.size(), 1u);
  EXPECT_EQ(obj.errors[0].severity, Diagnostic::Severity::kError);
  EXPECT_EQ(obj.errors[0].file, "m.obj");
  EXPECT_EQ(obj.errors[0].line, 7);
  EXPECT_EQ(obj.errors[0].column, 0);
  EXPECT_EQ(obj.errors[0].to_string(), "m.obj:7: vertex index 9 is out of range (the file has 4 vertices)");
  const ObjMesh zero = load_obj("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n", "z.obj", nullptr);
  ASSERT_EQ(zero.warnings.size(), 1u);
  EXPECT_EQ(zero.warnings[0].severity, Diagnostic::Severity::kWarning);
  EXPECT_EQ(zero.warnings[0].to_string(), "z.obj: 1 zero-area triangles left out");
  const LoadResult bad = load_scene_text(R"({"objects": [{"type": "sphere", "radius": -1}]})", "s.json");
  ASSERT_FALSE(bad.errors.empty());
  EXPECT_EQ(bad.errors[0].severity, Diagnostic::Severity::kError);
  EXPECT_GT(bad.errors[0].column, 0);
  EXPECT_TRUE(bad.errors[0].to_string().starts_with("s.json:1:")) << bad.errors[0].to_string();
  const fs::path dir = temp_dir("severity");
  write(dir / "d.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
  const LoadResult r = load_in(dir, mesh_scene("d.obj"));
  ASSERT_TRUE(r.ok()) << r.error_text();
  ASSERT_FALSE(r.warnings.empty());
  for (const Diagnostic& w : r.warnings) EXPECT_EQ(w.severity, Diagnostic::Severity::kWarning) << w.to_string();
  fs::remove_all(dir);
}

// ----- Errors name the OBJ's line ---------------------------------------------------------------

const char* const kThreeVertices =
    "# three vertices\n"
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0 1 0\n"
    "vn 0 0 1\n"
    "\n";

TEST(MeshErrors, AVertexIndexOutOfRangeNamesTheFileAndTheFacesLine) {
  const fs::path dir = temp_dir("range");
  write(dir / "bad.obj", std::string(kThreeVertices) + "f 1 2 3\n" + "f 1 2 4\n");  // line 8
  const LoadResult r = load_in(dir, mesh_scene("bad.obj"));
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors.size(), 1u) << r.error_text();
  EXPECT_EQ(r.errors[0].path, "objects[0].file");
  EXPECT_EQ(r.errors[0].message, "bad.obj:8: vertex index 4 is out of range (the file has 3 vertices)");
  // Relative indices reaching before the first vertex, and normal indices, likewise.
  write(dir / "bad.obj", std::string(kThreeVertices) + "f -1 -2 -4\n");  // line 7
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("bad.obj")).error_text(),
                       "bad.obj:7: relative vertex index -4 reaches before the first vertex (3 read so far)"));
  write(dir / "bad.obj", std::string(kThreeVertices) + "\n\nf 1//1 2//1 3//2\n");  // line 9
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("bad.obj")).error_text(),
                       "bad.obj:9: normal index 2 is out of range (the file has 1 normal)"));
  fs::remove_all(dir);
}

TEST(MeshErrors, IndexZeroIsAnErrorNamingItsLine) {
  const fs::path dir = temp_dir("zero");
  write(dir / "zero.obj", std::string(kThreeVertices) + "f 1 2 3\nf 0 1 2\n");  // line 8
  const LoadResult r = load_in(dir, mesh_scene("zero.obj"));
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.errors.size(), 1u) << r.error_text();
  EXPECT_EQ(r.errors[0].message, "zero.obj:8: face vertex '0': index 0 (OBJ indices start at 1; negative ones count back)");
  write(dir / "zero.obj", std::string(kThreeVertices) + "f 1//1 2//0 3//1\n");  // line 7
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("zero.obj")).error_text(), "zero.obj:7: face vertex '2//0': index 0"));
  write(dir / "zero.obj", std::string(kThreeVertices) + "f 1 2 x\n");
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("zero.obj")).error_text(),
                       "zero.obj:7: face vertex 'x' is not made of integer indices"));
  fs::remove_all(dir);
}

TEST(MeshErrors, ACoordinateThatIsNotAFiniteNumberNamesTheFileAndLine) {
  const fs::path dir = temp_dir("nan");
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "1e400", "-1e999", "x"}) {
    SCOPED_TRACE(bad);
    write(dir / "m.obj", std::string("# header\nv 0 0 0\nv 1 ") + bad + " 0\nv 0 1 0\nf 1 2 3\n");
    const LoadResult r = load_in(dir, mesh_scene("m.obj"));
    ASSERT_FALSE(r.ok());
    ASSERT_EQ(r.errors.size(), 1u) << r.error_text();
    EXPECT_EQ(r.errors[0].message,
              std::string("m.obj:3: vertex coordinate 2 must be a finite number (got '") + bad + "')");
  }
  // A missing coordinate is the same error.
  write(dir / "m.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("m.obj")).error_text(),
                       "m.obj:2: vertex coordinate 3 must be a finite number (got nothing)"));
  fs::remove_all(dir);
}

TEST(MeshErrors, AMissingMtlIsAWarningAndItsFacesGetTheDefaultMaterial) {
  const fs::path dir = temp_dir("nomtl");
  write(dir / "m.obj", std::string("mtllib gone.mtl\nusemtl red\n") + kUnitTriangleObj);
  const LoadResult r = load_in(dir, mesh_scene("m.obj"));
  ASSERT_TRUE(r.ok()) << r.error_text();
  EXPECT_TRUE(contains(all_warnings(r), "m.obj: cannot read material library 'gone.mtl'")) << all_warnings(r);
  const Scene& s = *r.scene;
  ASSERT_EQ(s.materials.size(), 1u);
  const Material& m = s.materials[0];
  const Material d = default_mesh_material();
  EXPECT_EQ(m.name, "m/default");
  expect_color(m.ka, 0.1, 0.1, 0.1, "ka");
  expect_color(m.kd, 0.7, 0.7, 0.7, "kd");
  expect_color(m.ks, 0.2, 0.2, 0.2, "ks");
  EXPECT_EQ(m.n, 32);
  expect_color(m.kr, 0, 0, 0, "kr");
  expect_color(m.kt, 0, 0, 0, "kt");
  EXPECT_EQ(m.ior, d.ior);
  EXPECT_FALSE(m.fresnel);
  EXPECT_EQ(geometry(s).triangles[0].material, 0);
  // A `usemtl` the MTL does not define: a warning, and the default material.
  write(dir / "m.mtl", "newmtl blue\nKd 0 0 1\nillum 2\n");
  write(dir / "u.obj", std::string("mtllib m.mtl\nusemtl red\n") + kUnitTriangleObj + "usemtl blue\nf 3 2 1\n");
  const LoadResult u = load_in(dir, mesh_scene("u.obj"));
  ASSERT_TRUE(u.ok()) << u.error_text();
  EXPECT_TRUE(contains(all_warnings(u), "u.obj: material [ 'red' ] not found in .mtl")) << all_warnings(u);
  std::vector<std::string> names;
  for (const Material& x : u.scene->materials) names.push_back(x.name);
  EXPECT_EQ(names, (std::vector<std::string>{"u/blue", "u/default"}));
  // A missing OBJ is an error.
  const LoadResult missing = load_in(dir, mesh_scene("nope.obj"));
  EXPECT_TRUE(contains(missing.error_text(), "objects[0].file: cannot load mesh 'nope.obj'")) << missing.error_text();
  fs::remove_all(dir);
}

// ----- Normals ----------------------------------------------------------------------------------

TEST(MeshNormals, VertexNormalsAreInterpolatedForShadingAndNgStillDecidesEntering) {
  const fs::path dir = temp_dir("normals");
  write(dir / "n.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
        "vn 0 0 1\nvn 0.6 0 0.8\nvn 0 0.6 0.8\n"
        "f 1//1 2//2 3//3\n");
  const PreparedScene p = prepared(load_in(dir, mesh_scene("n.obj")));
  const Scene& s = p.scene();
  ASSERT_EQ(geometry(s).triangles.size(), 1u);
  EXPECT_TRUE(geometry(s).triangles[0].has_vertex_normals);
  // At (0.25, 0.25) the weights are b0 = 0.5, b1 = b2 = 0.25.
  const Vec3 expected = glm::normalize(0.5 * Vec3(0, 0, 1) + 0.25 * Vec3(0.6, 0, 0.8) + 0.25 * Vec3(0, 0.6, 0.8));
  const auto hit = shoot(p, {0.25, 0.25, 2}, {0, 0, -1});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 2);
  expect_near(hit->ns, expected, 1e-15, "ns");
  expect_near(hit->ng, Vec3(0, 0, 1), 0, "ng");
  EXPECT_EQ(hit->object.kind, ObjectRef::Kind::kMesh);
  // Seen from behind: N faces the ray, Ng (from the winding) says the ray is leaving.
  ProbeNode node;
  RayCounts counts;
  trace(p, TraceLimits{}, make_ray({0.25, 0.25, -2}, {0, 0, 1}), 0, 1, counts, &node);
  ASSERT_TRUE(node.hit);
  EXPECT_FALSE(node.entering);
  expect_near(node.n, -expected, 1e-15, "N from behind");
  trace(p, TraceLimits{}, make_ray({0.25, 0.25, 2}, {0, 0, -1}), 0, 1, counts, &node);
  EXPECT_TRUE(node.entering);
  expect_near(node.n, expected, 1e-15, "N from the front");
  fs::remove_all(dir);
}

TEST(MeshNormals, WithoutVertexNormalsShadingIsFlat) {
  const fs::path dir = temp_dir("flat");
  // The second face gives normals for two of its vertices only: flat as well.
  write(dir / "f.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 -1\nv 1 0 -1\nv 0 1 -1\nvn 1 0 0\n"
        "f 1 2 3\nf 4//1 5//1 6\n");
  const PreparedScene p = prepared(load_in(dir, mesh_scene("f.obj")));
  const Scene& s = p.scene();
  for (const Triangle& t : geometry(s).triangles) EXPECT_FALSE(t.has_vertex_normals);
  for (const double z : {2.0, -0.5}) {
    const auto hit = shoot(p, {0.2, 0.3, z}, {0, 0, -1});
    ASSERT_TRUE(hit);
    EXPECT_TRUE(same_bits(hit->ns, hit->ng));
    EXPECT_TRUE(same_bits(hit->ng, Vec3(0, 0, 1)));
  }
  fs::remove_all(dir);
}

// ----- Transforms -------------------------------------------------------------------------------

// The single triangle (1, 2, 3), (-4, 5, 0.5), (0.25, -1, 2) placed by `transform`.
Triangle placed(const std::string& transform) {
  const fs::path dir = temp_dir("transform");
  write(dir / "t.obj", "v 1 2 3\nv -4 5 0.5\nv 0.25 -1 2\nf 1 2 3\n");
  const LoadResult r = load_in(dir, mesh_scene("t.obj", ", \"transform\": " + transform));
  fs::remove_all(dir);
  EXPECT_TRUE(r.ok()) << r.error_text();
  if (!r.ok()) return {};
  EXPECT_EQ(geometry(*r.scene).triangles.size(), 1u);
  return geometry(*r.scene).triangles.at(0);
}

void expect_placed(const std::string& transform, const Vec3& a, const Vec3& b, const Vec3& c, double tol) {
  SCOPED_TRACE(transform);
  const Triangle t = placed(transform);
  expect_near(t.v0, a, tol, "v0");
  expect_near(t.v1, b, tol, "v1");
  expect_near(t.v2, c, tol, "v2");
}

TEST(MeshTransform, ScaleIsANumberOrOnePerAxis) {
  expect_placed(R"({"scale": 2})", {2, 4, 6}, {-8, 10, 1}, {0.5, -2, 4}, 0);
  // A mirroring scale also swaps the last two vertices (so Ng keeps its side; see below).
  expect_placed(R"({"scale": [2, -3, 0.5]})", {2, -6, 1.5}, {0.5, 3, 1}, {-8, -15, 0.25}, 0);
}

TEST(MeshTransform, RotationsAreRightHandedInDegreesAboutXThenYThenZ) {
  // 90 degrees: cos is 6e-17 in double, so the results are exact to within 1e-15.
  // About x: y -> z, z -> -y.
  expect_placed(R"({"rotate_deg": [90, 0, 0]})", {1, -3, 2}, {-4, -0.5, 5}, {0.25, -2, -1}, 1e-15);
  // About y: z -> x, x -> -z.
  expect_placed(R"({"rotate_deg": [0, 90, 0]})", {3, 2, -1}, {0.5, 5, 4}, {2, -1, -0.25}, 1e-15);
  // About z: x -> y, y -> -x.
  expect_placed(R"({"rotate_deg": [0, 0, 90]})", {-2, 1, 3}, {-5, -4, 0.5}, {1, 0.25, 2}, 1e-15);
  // x first, then y: (1, 2, 3) -> (1, -3, 2) -> (2, -3, -1); the other order would give (3, 1, 2)...
  expect_placed(R"({"rotate_deg": [90, 90, 0]})", {2, -3, -1}, {5, -0.5, 4}, {-1, -2, -0.25}, 1e-15);
  // ... and z last: (2, -3, -1) -> (3, 2, -1).
  expect_placed(R"({"rotate_deg": [90, 90, 90]})", {3, 2, -1}, {0.5, 5, 4}, {2, -1, -0.25}, 1e-15);
  expect_placed(R"({"rotate_deg": [180, 0, 0]})", {1, -2, -3}, {-4, -5, -0.5}, {0.25, 1, -2}, 1e-15);
  expect_placed(R"({"rotate_deg": [0, 0, -90]})", {2, -1, 3}, {5, 4, 0.5}, {-1, -0.25, 2}, 1e-15);
}

TEST(MeshTransform, TranslationComesLastAfterScaleAndRotation) {
  expect_placed(R"({"translate": [10, -20, 0.5]})", {11, -18, 3.5}, {6, -15, 1}, {10.25, -21, 2.5}, 0);
  // Scale 2, then z by 90 ((x, y) -> (-y, x)), then translate.
  expect_placed(R"({"scale": 2, "rotate_deg": [0, 0, 90], "translate": [1, 1, 1]})", {-3, 3, 7}, {-9, -7, 2},
                {3, 1.5, 5}, 1e-14);
}

TEST(MeshTransform, NormalsFollowTheInverseTransposeUnderNonUniformScale) {
  const fs::path dir = temp_dir("normal_transform");
  // The plane x + y + z = 1 with its true normal at every vertex.
  write(dir / "n.obj",
        "v 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0.5773502691896258 0.5773502691896258 0.5773502691896258\nf 1//1 2//1 3//1\n");
  // Scaled by (2, 1, 1) the plane is x/2 + y + z = 1, normal (0.5, 1, 1) / 1.5; a normal
  // transformed like the vertices would point along (2, 1, 1) instead.
  const PreparedScene p = prepared(load_in(dir, mesh_scene("n.obj", R"(, "transform": {"scale": [2, 1, 1]})")));
  const Vec3 expected(1.0 / 3, 2.0 / 3, 2.0 / 3);
  const auto hit = shoot(p, {0, 0, 0}, {0.5, 0.25, 0.25});
  ASSERT_TRUE(hit);
  expect_near(hit->ng, expected, 1e-15, "Ng from the placed vertices");
  expect_near(hit->ns, expected, 1e-15, "N from the placed vertex normals");
  // With a rotation too: still the placed plane's normal.
  const PreparedScene r = prepared(
      load_in(dir, mesh_scene("n.obj", R"(, "transform": {"scale": [2, 1, 1], "rotate_deg": [0, 0, 90]})")));
  const auto h2 = shoot(r, {0, 0, 0}, {-0.25, 0.5, 0.25});
  ASSERT_TRUE(h2);
  expect_near(h2->ng, Vec3(-2.0 / 3, 1.0 / 3, 2.0 / 3), 1e-15, "Ng");
  expect_near(h2->ns, Vec3(-2.0 / 3, 1.0 / 3, 2.0 / 3), 1e-15, "N");
  fs::remove_all(dir);
}

TEST(MeshTransform, AMirroringScaleKeepsAClosedMeshsGeometricNormalsOutward) {
  // A tetrahedron wound counter-clockwise seen from outside, with outward vertex normals.
  const fs::path dir = temp_dir("mirror");
  write(dir / "tet.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
        "vn 0 0 -1\nvn 0 -1 0\nvn -1 0 0\nvn 0.5773502691896258 0.5773502691896258 0.5773502691896258\n"
        "f 1//1 3//1 2//1\nf 1//2 2//2 4//2\nf 1//3 4//3 3//3\nf 2//4 3//4 4//4\n");
  for (const char* scale : {"1", "[-1, 1, 1]", "[1, -2, 1]", "[1, 1, -0.5]", "-1", "[-1, -1, 1]"}) {
    SCOPED_TRACE(scale);
    const LoadResult r = load_in(dir, mesh_scene("tet.obj", std::string(R"(, "transform": {"scale": )") + scale + "}"));
    ASSERT_TRUE(r.ok()) << r.error_text();
    const MeshGeometry& g = geometry(*r.scene);
    Vec3 centre(0);
    for (const Triangle& t : g.triangles) centre += (t.v0 + t.v1 + t.v2) / 12.0;
    for (const Triangle& t : g.triangles) {
      const Vec3 ng = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
      const Vec3 out = (t.v0 + t.v1 + t.v2) / 3.0 - centre;
      EXPECT_GT(glm::dot(ng, out), 0) << "Ng must point out of the solid (glass enters through it)";
      EXPECT_GT(glm::dot(ng, glm::normalize(t.n0)), 0.99) << "the vertex normals agree with Ng";
    }
  }
  fs::remove_all(dir);
}

// ----- Materials --------------------------------------------------------------------------------

const char* const kMappingMtl =
    "newmtl plain\nKa 0.1 0.2 0.3\nKd 0.4 0.5 0.6\nKs 0.7 0.8 0.9\nNs 50\nNi 1.2\nillum 2\n"
    "newmtl mirror3\nKs 0.5 0.5 0.5\nillum 3\n"
    "newmtl glass4\nKs 0.1 0.1 0.1\nTf 0.8 0.9 1\nNi 1.33\nillum 4\n"
    "newmtl mirror5\nKs 1 1 1\nillum 5\n"
    "newmtl glass6\nKs 0.2 0.2 0.2\nTf 0.5 0.5 0.5\nillum 6\n"
    "newmtl glass7\nKs 0.3 0.3 0.3\nTf 0.1 0.1 0.1\nNi 2.5\nillum 7\n"
    "newmtl dissolve\nKd 1 1 1\nd 0.25\nillum 2\n"
    "newmtl dissolve_tf\nKd 1 1 1\nd 0.5\nTf 0.2 0.4 0.6\nillum 1\n"
    "newmtl tr\nTr 0.25\n"
    "newmtl bare\n"
    "newmtl bad\nKd -1 0.5 0.5\nNi 0\n";

TEST(MeshMaterials, MtlMapsOntoTheLecturesCoefficientsAsTheDocsTableSays) {
  const fs::path dir = temp_dir("mapping");
  write(dir / "m.mtl", kMappingMtl);
  std::string obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (const char* name : {"plain", "mirror3", "glass4", "mirror5", "glass6", "glass7", "dissolve", "dissolve_tf", "tr",
                           "bare", "bad"}) {
    obj += std::string("usemtl ") + name + "\nf 1 2 3\n";
  }
  write(dir / "m.obj", obj);
  const LoadResult r = load_in(dir, mesh_scene("m.obj"));
  ASSERT_TRUE(r.ok()) << r.error_text();
  const Scene& s = *r.scene;
  ASSERT_EQ(s.materials.size(), 11u);
  const auto mat = [&](const char* name) -> const Material& {
    const Material* m = material_named(s, std::string("m/") + name);
    EXPECT_NE(m, nullptr) << name;
    static const Material none;
    return m ? *m : none;
  };
  const Material& plain = mat("plain");
  expect_color(plain.ka, 0.1, 0.2, 0.3, "Ka -> ka");
  expect_color(plain.kd, 0.4, 0.5, 0.6, "Kd -> kd");
  expect_color(plain.ks, 0.7, 0.8, 0.9, "Ks -> ks");
  EXPECT_EQ(plain.n, 50);  // Ns -> n as it is
  EXPECT_DOUBLE_EQ(plain.ior, 1.2);
  expect_color(plain.kr, 0, 0, 0, "illum 2: no mirror");
  expect_color(plain.kt, 0, 0, 0, "illum 2: opaque");
  EXPECT_FALSE(plain.fresnel);

  expect_color(mat("mirror3").kr, 0.5, 0.5, 0.5, "illum 3: kr = Ks");
  EXPECT_FALSE(mat("mirror3").fresnel);
  expect_color(mat("glass4").kr, 0.1, 0.1, 0.1, "illum 4: kr = Ks");
  expect_color(mat("glass4").kt, 1 - 0.8, 1 - 0.9, 0, "illum 4: kt = 1 - Tf");
  EXPECT_DOUBLE_EQ(mat("glass4").ior, 1.33);
  EXPECT_FALSE(mat("glass4").fresnel);
  expect_color(mat("mirror5").kr, 1, 1, 1, "illum 5: kr = Ks");
  expect_color(mat("mirror5").kt, 0, 0, 0, "illum 5: opaque");
  EXPECT_TRUE(mat("mirror5").fresnel);
  expect_color(mat("glass6").kt, 0.5, 0.5, 0.5, "illum 6: kt = 1 - Tf");
  EXPECT_FALSE(mat("glass6").fresnel);
  expect_color(mat("glass7").kr, 1 - (1 - 0.1), 1 - (1 - 0.1), 1 - (1 - 0.1), "illum 7: kr = Ks, at most 1 - kt");
  expect_color(mat("glass7").kt, 1 - 0.1, 1 - 0.1, 1 - 0.1, "illum 7: kt = 1 - Tf");
  EXPECT_EQ(mat("glass7").ior, 2.5);
  EXPECT_TRUE(mat("glass7").fresnel);
  // d < 1: kt = 1 - d*Tf (Tf 1 without one); Tr is 1 - d.
  expect_color(mat("dissolve").kt, 0.75, 0.75, 0.75, "d 0.25");
  expect_color(mat("dissolve_tf").kt, 1 - 0.5 * 0.2, 1 - 0.5 * 0.4, 1 - 0.5 * 0.6, "d 0.5, Tf");
  expect_color(mat("dissolve_tf").kr, 0, 0, 0, "illum 1");
  expect_color(mat("tr").kt, 0.25, 0.25, 0.25, "Tr 0.25");
  // What tinyobjloader fills in for absent keys: Ns 1, Ni 1, colours 0.
  const Material& bare = mat("bare");
  EXPECT_EQ(bare.n, 1);
  EXPECT_EQ(bare.ior, 1);
  expect_color(bare.kd, 0, 0, 0, "bare.kd");
  // Negative coefficients become 0 with a warning at their line, the number as written; Ni <= 0 becomes 1.5.
  const std::string mtl = kMappingMtl;
  const int bad_line = 1 + static_cast<int>(std::count(mtl.begin(), mtl.begin() + static_cast<std::ptrdiff_t>(mtl.find("Kd -1")), '\n'));
  expect_color(mat("bad").kd, 0, 0.5, 0.5, "Kd -1");
  EXPECT_EQ(mat("bad").ior, 1.5);
  EXPECT_TRUE(contains(all_warnings(r), "m.mtl:" + std::to_string(bad_line) + ": material 'bad': Kd -1 must be >= 0; using 0"))
      << all_warnings(r);
  EXPECT_TRUE(contains(all_warnings(r), "m.mtl:" + std::to_string(bad_line + 1) + ": material 'bad': Ni 0 must be > 0; using 1.5"))
      << all_warnings(r);
  fs::remove_all(dir);
}

TEST(MeshMaterials, NsIsTakenAsItIsOrConvertedFromBlinnByDividingByFour) {
  const fs::path dir = temp_dir("ns");
  write(dir / "m.mtl", "newmtl shiny\nKs 1 1 1\nNs 100\nillum 2\n");
  write(dir / "m.obj", std::string("mtllib m.mtl\nusemtl shiny\n") + kUnitTriangleObj);
  for (const auto& [extra, n] : {std::pair<std::string, double>{"", 100}, {R"(, "ns": "as_is")", 100},
                                 {R"(, "ns": "blinn_to_phong")", 25}}) {
    SCOPED_TRACE(extra);
    const LoadResult r = load_in(dir, mesh_scene("m.obj", extra));
    ASSERT_TRUE(r.ok()) << r.error_text();
    EXPECT_EQ(r.scene->materials.at(0).n, n);
    EXPECT_EQ(r.scene->meshes[0].ns, n == 25 ? NsMapping::kBlinnToPhong : NsMapping::kAsIs);
  }
  fs::remove_all(dir);
}

TEST(MeshMaterials, AnOverrideReplacesEveryFacesMaterialAndAddsNoMtlMaterials) {
  const fs::path dir = temp_dir("override");
  write(dir / "m.mtl", "newmtl a\nKd 1 0 0\nillum 2\nnewmtl b\nKd 0 1 0\nillum 2\n");
  write(dir / "m.obj", std::string("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n") +
                           "usemtl a\nf 1 2 3\nusemtl b\nf 2 4 3\ng nomaterial\nusemtl\nf 1 2 4\n");
  const LoadResult r = load_in(dir, R"({"materials": {"first": {"kd": 0.1}, "gold": {"kd": [1, 0.8, 0.2]}},
      "objects": [{"type": "mesh", "file": "m.obj", "material": "gold"}]})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  const Scene& s = *r.scene;
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[1].name, "gold");
  EXPECT_EQ(s.meshes[0].material_override, "gold");
  ASSERT_EQ(geometry(s).triangles.size(), 3u);
  for (const Triangle& t : geometry(s).triangles) EXPECT_EQ(t.material, 1);
  // Without it: the MTL's two, after the scene's own, plus the default for the third face.
  const LoadResult own = load_in(dir, R"({"materials": {"first": {"kd": 0.1}}, "objects": [{"type": "mesh", "file": "m.obj"}]})");
  ASSERT_TRUE(own.ok()) << own.error_text();
  std::vector<std::string> names;
  for (const Material& m : own.scene->materials) names.push_back(m.name);
  EXPECT_EQ(names, (std::vector<std::string>{"first", "m/a", "m/b", "m/default"}));
  // An unknown override is the usual unknown-material error.
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("m.obj", R"(, "material": "glod")")).error_text(),
                       "objects[0].material:"));
  fs::remove_all(dir);
}

// ----- Saving -----------------------------------------------------------------------------------

TEST(MeshSave, SceneToJsonWritesTheMeshObjectButNotItsMtlMaterialsAndReloadsTheSameTriangles) {
  const fs::path dir = temp_dir("save");
  write(dir / "meshes" / "m.mtl", "newmtl shiny\nKd 0.5 0.5 0.5\nKs 1 1 1\nNs 100\nillum 3\n");
  write(dir / "meshes" / "m.obj",
        "mtllib m.mtl\nusemtl shiny\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.5\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n");
  const LoadResult r = load_in(dir, R"({"materials": {"gold": {"kd": [1, 0.8, 0.2]}}, "objects": [
      {"type": "mesh", "file": "meshes/m.obj", "material": "gold",
       "transform": {"scale": [2, 1, 0.5], "rotate_deg": [10, 20, 30.5], "translate": [1, -2, 0.1]}},
      {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "gold"},
      {"type": "mesh", "file": "meshes/m.obj", "ns": "blinn_to_phong", "transform": {"scale": 3}}]})");
  ASSERT_TRUE(r.ok()) << r.error_text();
  const Scene& s = *r.scene;
  ASSERT_EQ(s.materials.size(), 2u);  // gold, and m/shiny from the second mesh
  EXPECT_EQ(s.materials[1].n, 25);
  const std::string json = scene_to_json(s);
  EXPECT_TRUE(contains(json, R"({"type": "mesh", "file": "meshes/m.obj", "material": "gold", )"
                             R"("transform": {"scale": [2, 1, 0.5], "rotate_deg": [10, 20, 30.5], "translate": [1, -2, 0.1]}})"))
      << json;
  EXPECT_TRUE(contains(json, R"({"type": "mesh", "file": "meshes/m.obj", "transform": {"scale": [3, 3, 3], )"
                             R"("rotate_deg": [0, 0, 0], "translate": [0, 0, 0]}, "ns": "blinn_to_phong"})"))
      << json;
  EXPECT_FALSE(contains(json, "shiny")) << "the MTL holds it: " << json;
  write(dir / "saved.json", json);
  const LoadResult back = load_scene_file((dir / "saved.json").string());
  ASSERT_TRUE(back.ok()) << back.error_text();
  const Scene& b = *back.scene;
  ASSERT_EQ(b.meshes.size(), 2u);
  EXPECT_EQ(b.mesh_object, s.mesh_object);
  EXPECT_EQ(b.sphere_object, s.sphere_object);
  for (std::size_t i = 0; i < 2; ++i) {
    SCOPED_TRACE(i);
    expect_same_triangles(geometry(b, i), geometry(s, i));
    EXPECT_EQ(b.meshes[i].file, s.meshes[i].file);
    EXPECT_EQ(b.meshes[i].material_override, s.meshes[i].material_override);
    EXPECT_EQ(b.meshes[i].ns, s.meshes[i].ns);
  }
  ASSERT_EQ(b.materials.size(), s.materials.size());
  for (std::size_t i = 0; i < b.materials.size(); ++i) {
    EXPECT_EQ(b.materials[i].name, s.materials[i].name);
    EXPECT_EQ(b.materials[i].n, s.materials[i].n);
    EXPECT_EQ(b.materials[i].source, s.materials[i].source);
  }
  // An edit to an MTL material is not saved: the reload has the MTL's value again.
  Scene edited = s;
  edited.materials[1].kd = Color(0, 0, 1);
  write(dir / "edited.json", scene_to_json(edited));
  const LoadResult e = load_scene_file((dir / "edited.json").string());
  ASSERT_TRUE(e.ok()) << e.error_text();
  expect_color(e.scene->materials[1].kd, 0.5, 0.5, 0.5, "MTL value after reload");
  fs::remove_all(dir);
}

// ----- An OBJ on its own ------------------------------------------------------------------------

// A unit cube centred on (3, 4, 5), wound outward, without normals or MTL.
const char* const kCubeObj =
    "v 2.5 3.5 4.5\nv 3.5 3.5 4.5\nv 3.5 4.5 4.5\nv 2.5 4.5 4.5\n"
    "v 2.5 3.5 5.5\nv 3.5 3.5 5.5\nv 3.5 4.5 5.5\nv 2.5 4.5 5.5\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

TEST(MeshOpenedAlone, AnObjGetsACameraThatFramesItAndALightThatLightsIt) {
  const fs::path dir = temp_dir("alone");
  write(dir / "cube.obj", kCubeObj);
  const LoadResult r = load_scene_file((dir / "cube.obj").string());
  ASSERT_TRUE(r.ok()) << r.error_text();
  const PreparedScene p(*r.scene);
  const Scene& s = p.scene();
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].file, "cube.obj");
  EXPECT_EQ(geometry(s).triangles.size(), 12u);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "cube/default");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::kPoint);
  // The ray through the image centre hits the mesh...
  const CameraFrame frame = make_camera_frame(s.camera, s.width, s.height);
  const Ray centre = camera_ray(frame, s.width / 2, s.height / 2, 0, 0);
  const auto hit = intersect(p, centre);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->object.kind, ObjectRef::Kind::kMesh);
  // ... every vertex is in view ...
  for (const Triangle& t : geometry(s).triangles) {
    for (const Vec3& v : {t.v0, t.v1, t.v2}) {
      const Vec3 d = v - frame.origin;
      const double depth = glm::dot(d, frame.forward);
      ASSERT_GT(depth, 0);
      EXPECT_LT(std::abs(glm::dot(d, frame.right) / glm::dot(frame.right, frame.right)), depth);
      EXPECT_LT(std::abs(glm::dot(d, frame.up) / glm::dot(frame.up, frame.up)), depth);
    }
  }
  // ... and the centre pixel is lit by the light (diffuse > 0).
  const PixelProbe probe = probe_pixel(p, s.width, s.height, s.width / 2, s.height / 2);
  ASSERT_TRUE(probe.root.hit);
  EXPECT_GT(probe.root.terms.diffuse.x, 0);
  fs::remove_all(dir);
}

TEST(MeshOpenedAlone, TheCornellObjOpensWithItsMtlAndItsEmitterHint) {
  const LoadResult r = load_scene_file(std::string(PHONGLAB_SOURCE_DIR) + "/assets/scenes/cornell/CornellBox-Original.obj");
  ASSERT_TRUE(r.ok()) << r.error_text();
  const PreparedScene p(*r.scene);
  const Scene& s = p.scene();
  EXPECT_EQ(s.materials.size(), 8u);
  EXPECT_NE(material_named(s, "CornellBox-Original/leftWall"), nullptr);
  EXPECT_TRUE(hinted_light(all_warnings(r)).has_value());
  const CameraFrame frame = make_camera_frame(s.camera, s.width, s.height);
  EXPECT_TRUE(intersect(p, camera_ray(frame, s.width / 2, s.height / 2, 0, 0)));
  // A broken OBJ opened alone names its line too.
  const fs::path dir = temp_dir("alone_bad");
  write(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 inf\nf 1 2 3\n");
  const LoadResult bad = load_scene_file((dir / "bad.obj").string());
  ASSERT_FALSE(bad.ok());
  EXPECT_TRUE(contains(bad.error_text(), "bad.obj:3: vertex coordinate 3 must be a finite number (got 'inf')"))
      << bad.error_text();
  fs::remove_all(dir);
}

// ----- Probe names ------------------------------------------------------------------------------

TEST(MeshProbe, AMeshHitIsNamedByItsObjectAndTheObjsFaceNumber) {
  const fs::path dir = temp_dir("probe");
  // Three faces side by side along x; the third (a quad, two triangles) is at x in [4, 5].
  write(dir / "three.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"
        "v 2 0 0\nv 3 0 0\nv 2 1 0\nf 4 5 6\n"
        "v 4 -1 0\nv 6 -1 0\nv 6 1 0\nv 4 1 0\nf 7 8 9 10\n");
  const PreparedScene p = prepared(load_in(dir, R"({
      "camera": {"position": [5, 0, 5], "look_at": [5, 0, 0], "fov_y": 10},
      "image": {"width": 32, "height": 32},
      "materials": {"m": {"kd": 0.5}},
      "lights": [{"type": "point", "position": [5, 0, 3]}],
      "objects": [{"type": "sphere", "center": [-10, 0, 0], "radius": 1, "material": "m"},
                  {"type": "mesh", "file": "three.obj"}]})"));
  const Scene& s = p.scene();
  // Faces count from 1 in file order, as OBJ indices and the loader's messages do.
  for (const double y : {-0.5, 0.5}) {  // either triangle of the quad
    const auto hit = shoot(p, {4.5 + std::abs(y), y, 1}, {0, 0, -1});
    ASSERT_TRUE(hit);
    EXPECT_EQ(object_name(s, hit->object), "objects[1] face 3");
  }
  EXPECT_EQ(object_name(s, shoot(p, {0.2, 0.2, 1}, {0, 0, -1})->object), "objects[1] face 1");
  const PixelProbe probe = probe_pixel(p, 32, 32, 16, 16);
  ASSERT_TRUE(probe.root.hit);
  EXPECT_TRUE(contains(probe_to_json(s, probe), R"("object": "objects[1] face 3")")) << probe_to_json(s, probe);
  EXPECT_TRUE(contains(probe_to_text(s, probe), "hits objects[1] face 3 (material \"three/default\")"))
      << probe_to_text(s, probe);
  fs::remove_all(dir);
}

// ----- The BVH answers as brute force does -------------------------------------------------------

std::uint64_t test_seed() {
  if (const char* env = std::getenv("PHONGLAB_TEST_SEED")) return std::strtoull(env, nullptr, 10);
  return 20240611;
}

Vec3 random_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 d(g(rng), g(rng), g(rng));
    const double len = glm::length(d);
    if (len > 1e-6) return d / len;
  }
}

// Nearest hits and shadow queries of `rays` random rays through the accelerator equal the
// brute-force ones: the same primitive, t bit for bit.
void expect_bvh_equals_brute_force(const PreparedScene& p, const Vec3& lo, const Vec3& hi, int rays, std::uint64_t seed) {
  const Scene& s = p.scene();
  ASSERT_NE(p.accel(), nullptr);
  SCOPED_TRACE("seed " + std::to_string(seed) + " (rerun with PHONGLAB_TEST_SEED=" + std::to_string(seed) + ")");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z), u01(0, 1);
  int hits = 0;
  for (int i = 0; i < rays; ++i) {
    const Ray ray = make_ray({ux(rng), uy(rng), uz(rng)}, random_direction(rng));
    const auto a = intersect(p, ray);
    const auto b = intersect_all(s, ray);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << i;
    if (a) {
      ++hits;
      ASSERT_EQ(a->t, b->t) << "ray " << i;
      ASSERT_EQ(a->object.kind, b->object.kind) << "ray " << i;
      ASSERT_EQ(a->object.index, b->object.index) << "ray " << i;
      ASSERT_EQ(a->object.prim, b->object.prim) << "ray " << i;
      ASSERT_TRUE(same_bits(a->p, b->p) && same_bits(a->ns, b->ns)) << "ray " << i;
      const double t_max = a->t * u01(rng) * 1.5;
      ASSERT_EQ(occluded(p, ray, t_max), occluded_all(s, ray, t_max)) << "ray " << i << " t_max " << t_max;
    } else {
      ASSERT_FALSE(occluded(p, ray, 1e30)) << "ray " << i;
    }
  }
  EXPECT_GT(hits, rays / 5);  // the rest leave through open sides or start outside
}

TEST(MeshAccel, TheCornellSphereBoxThroughTheBvhEqualsBruteForceForRandomRays) {
  const PreparedScene p = prepared(load_scene_arg("cornell-sphere"));
  expect_bvh_equals_brute_force(p, {-1.5, -0.5, -1.5}, {1.5, 2.5, 4}, 20000, test_seed());
}

TEST(MeshAccel, TransformedMeshesAmongOtherObjectsThroughTheBvhEqualBruteForce) {
  const std::uint64_t seed = test_seed() + 1;
  SCOPED_TRACE("seed " + std::to_string(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::string obj;
  for (int i = 0; i < 600; ++i) {
    const Vec3 c(u(rng), u(rng), u(rng));
    for (int k = 0; k < 3; ++k) {
      const Vec3 v = c + 0.15 * Vec3(u(rng), u(rng), u(rng));
      char line[128];
      std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", v.x, v.y, v.z);
      obj += line;
    }
    obj += "f -3 -2 -1\n";
  }
  const fs::path dir = temp_dir("soup");
  write(dir / "soup.obj", obj);
  const PreparedScene p = prepared(load_in(dir, R"({"materials": {"m": {"kd": 0.5}}, "objects": [
      {"type": "mesh", "file": "soup.obj", "transform": {"scale": [1, 2, 0.5], "rotate_deg": [10, 20, 30], "translate": [0.5, 0, 0]}},
      {"type": "sphere", "center": [0, 0, 0], "radius": 0.4, "material": "m"},
      {"type": "mesh", "file": "soup.obj", "transform": {"scale": -0.7, "translate": [-1, 1, 0]}},
      {"type": "triangle", "vertices": [[-2, -2, -2], [2, -2, -2], [0, 2, -2]], "material": "m"},
      {"type": "plane", "point": [0, -3, 0], "normal": [0, 1, 0], "material": "m"}]})"));
  fs::remove_all(dir);
  expect_bvh_equals_brute_force(p, {-2.5, -2.5, -2.5}, {2.5, 2.5, 2.5}, 20000, seed);
}

}  // namespace
}  // namespace phonglab

// ----- Regressions found by hand and by fuzzing (issue 18) -------------------------------------

namespace phonglab {
namespace {

TEST(MeshRegressions, AnIndexBeyondIntIsReportedAsWrittenNotWrapped) {
  const fs::path dir = temp_dir("huge_index");
  write(dir / "big.obj", std::string(kThreeVertices) + "f 1 2 99999999999\n");  // line 7
  const LoadResult r = load_in(dir, mesh_scene("big.obj"));
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(contains(r.error_text(), "big.obj:7: vertex index 99999999999 is out of range (the file has 3 vertices)"))
      << r.error_text();
  write(dir / "big.obj", std::string(kThreeVertices) + "f 1//1 2//1 3//4294967297\n");
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("big.obj")).error_text(),
                       "big.obj:7: normal index 4294967297 is out of range (the file has 1 normal)"));
  fs::remove_all(dir);
}

TEST(MeshRegressions, EveryReplacedMtlValueIsAWarningWithTheNumberAsWritten) {
  const fs::path dir = temp_dir("mtl_values");
  write(dir / "m.mtl", "newmtl red\nKd nan 1 1\nKs -0.5 0 1e999\nNi 0\nd 1.5\nNs -3\nKa 0.10 0.2 0.3\n");
  write(dir / "m.obj", std::string("mtllib m.mtl\nusemtl red\n") + kThreeVertices + "f 1 2 3\n");
  const LoadResult r = load_in(dir, mesh_scene("m.obj"));
  ASSERT_TRUE(r.ok()) << r.error_text();
  const std::string w = all_warnings(r);
  for (const char* expected : {"m.mtl:2: material 'red': Kd nan is not a finite number; using 0",
                               "m.mtl:3: material 'red': Ks -0.5 must be >= 0; using 0",
                               "m.mtl:3: material 'red': Ks 1e999 is not a finite number; using 0",
                               "m.mtl:4: material 'red': Ni 0 must be > 0; using 1.5",
                               "m.mtl:5: material 'red': d 1.5 must be in 0..1; using the nearest of 0 and 1",
                               "m.mtl:6: material 'red': Ns -3 must be >= 0; using 0"}) {
    EXPECT_TRUE(contains(w, expected)) << expected << "\n" << w;
  }
  EXPECT_FALSE(contains(w, "Ka")) << "a value in range is not warned about";
  const Material& red = r.scene->materials.back();
  EXPECT_EQ(red.kd, Color(0, 1, 1));
  EXPECT_EQ(red.ks, Color(0, 0, 0));
  EXPECT_EQ(red.ior, 1.5);
  fs::remove_all(dir);
}

// Found by phonglab_fuzz_obj (tests/fuzz/corpus/obj/regression-most-negative-index.txt): the
// most negative long as a relative index was negated to compare it (undefined behaviour).
TEST(MeshRegressions, TheMostNegativeIndexIsAnErrorNotAnOverflow) {
  const fs::path dir = temp_dir("most_negative");
  write(dir / "neg.obj", std::string(kThreeVertices) + "f 1 2 -9223372036854775808\n");  // line 7
  EXPECT_TRUE(contains(load_in(dir, mesh_scene("neg.obj")).error_text(),
                       "neg.obj:7: relative vertex index -9223372036854775808 reaches before the first vertex (3 read so far)"));
  write(dir / "neg.obj", std::string(kThreeVertices) + "f 1 2 -99999999999999999999\n");  // beyond long: strtol's verdict
  EXPECT_FALSE(load_in(dir, mesh_scene("neg.obj")).ok());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace phonglab
