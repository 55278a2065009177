// Seeded random scenes that reach every branch of the equation (Phong and Blinn, point and
// directional lights, muted lights, lights on surfaces, mirrors, glass with and without Fresnel,
// the depth and weight limits, loose triangles, the camera inside a sphere, extreme scales), for
// the tests that compare two ways of computing the same image.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "core/accel/accel.h"
#include "core/accel/prepared_scene.h"
#include "core/scene/scene.h"

namespace phonglab {

inline Color random_color(std::mt19937& rng, double zero_chance, double hi) {
  std::uniform_real_distribution<double> u(0, 1);
  if (u(rng) < zero_chance) return Color(0);
  if (u(rng) < 0.5) return Color(u(rng) * hi);
  return Color(u(rng) * hi, u(rng) * hi, u(rng) * hi);
}

// Meshes and more spheres for a SceneBvh: a height field whose first rows are flat (rays through
// its shared edges meet two triangles at one t), sometimes with vertex normals; a closed box,
// sometimes of glass (rays enter and leave it); and up to ten more spheres.
inline void add_meshes(Scene& s, std::uint32_t seed, double scale) {
  std::mt19937 rng(seed * 7919u + 13u);
  std::uniform_real_distribution<double> u(0, 1), c(-3, 3);
  const int materials = static_cast<int>(s.materials.size());
  auto material = [&] { return std::uniform_int_distribution<int>(0, materials - 1)(rng); };
  const auto add = [&](std::vector<Triangle> tris) {
    Mesh mesh;
    mesh.file = "(test)";
    mesh.geometry = make_mesh_geometry(std::move(tris), {});
    s.meshes.push_back(std::move(mesh));
    s.mesh_object.push_back(static_cast<int>(s.mesh_object.size()));
  };
  const int n = std::uniform_int_distribution<int>(2, 24)(rng);
  const Vec3 corner = Vec3(c(rng), u(rng) - 0.5, c(rng) - 1) * scale;
  const double size = (1 + 3 * u(rng)) * scale;
  const bool normals = u(rng) < 0.5;
  const int field_material = material();
  std::vector<Vec3> grid;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const double h = j < n / 2 ? 0.0 : 0.2 * (u(rng) - 0.5) * size;
      grid.push_back(corner + Vec3(size * i / n, h, -size * j / n));
    }
  }
  std::vector<Triangle> field;
  const auto at_grid = [&](int i, int j) { return grid[static_cast<std::size_t>(j * (n + 1) + i)]; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Vec3 a = at_grid(i, j), b = at_grid(i + 1, j), cc = at_grid(i, j + 1), d = at_grid(i + 1, j + 1);
      const int m = u(rng) < 0.1 ? material() : field_material;
      for (Triangle t : {Triangle{a, b, d, m}, Triangle{a, d, cc, m}}) {
        if (normals) {
          t.has_vertex_normals = true;
          t.n0 = glm::normalize(Vec3(c(rng) * 0.2, 1, c(rng) * 0.2));
          t.n1 = glm::normalize(Vec3(c(rng) * 0.2, 1, c(rng) * 0.2));
          t.n2 = glm::normalize(Vec3(c(rng) * 0.2, 1, c(rng) * 0.2));
        }
        field.push_back(t);
      }
    }
  }
  add(std::move(field));
  if (u(rng) < 0.7) {  // an axis-aligned box of 12 triangles
    const Vec3 lo = Vec3(c(rng), u(rng), c(rng)) * scale;
    const Vec3 hi = lo + Vec3(0.2 + u(rng), 0.2 + u(rng), 0.2 + u(rng)) * scale;
    const int m = material();
    const auto corner_of = [&](int k) { return Vec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z); };
    const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    std::vector<Triangle> box;
    for (const auto& f : faces) {
      box.push_back(Triangle{corner_of(f[0]), corner_of(f[1]), corner_of(f[2]), m});
      box.push_back(Triangle{corner_of(f[0]), corner_of(f[2]), corner_of(f[3]), m});
    }
    add(std::move(box));
  }
  const int spheres = std::uniform_int_distribution<int>(0, 10)(rng);
  for (int i = 0; i < spheres; ++i) {
    s.spheres.push_back(Sphere{Vec3(c(rng), u(rng) * 2, c(rng)) * scale, (0.05 + 0.5 * u(rng)) * scale, material()});
    s.sphere_object.push_back(static_cast<int>(s.sphere_object.size()));
  }
}

// A random scene the brute-force path traces (few spheres and triangles, no mesh); with
// `hierarchy`, the same one traced through a SceneBvh, with meshes and more spheres in it.
// Unprepared: random_scene prepares it.
inline Scene random_scene_data(std::uint32_t seed, bool hierarchy = false) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1), c(-3, 3);
  Scene s;
  const double scale = u(rng) < 0.2 ? std::pow(10.0, std::uniform_int_distribution<int>(-3, 4)(rng)) : 1.0;
  s.camera.position = Vec3(c(rng), 1 + 2 * u(rng), 5 + 3 * u(rng)) * scale;
  s.camera.look_at = Vec3(c(rng) * 0.3, c(rng) * 0.3, 0) * scale;
  s.camera.fov_y_deg = 20 + 100 * u(rng);
  s.background = random_color(rng, 0.3, 0.5);
  s.ambient = random_color(rng, 0.2, 1);
  s.max_depth = std::uniform_int_distribution<int>(0, 7)(rng);
  s.min_weight = u(rng) < 0.3 ? 0.0 : std::pow(10.0, -4 + 3 * u(rng));
  s.specular_model = u(rng) < 0.5 ? SpecularModel::kPhong : SpecularModel::kBlinn;
  const int materials = std::uniform_int_distribution<int>(1, 5)(rng);
  for (int i = 0; i < materials; ++i) {
    Material m;
    m.ka = random_color(rng, 0.3, 0.2);
    m.kd = random_color(rng, 0.3, 0.9);
    m.ks = random_color(rng, 0.3, 0.8);
    m.n = u(rng) < 0.1 ? 0.0 : (u(rng) < 0.2 ? 0.5 + u(rng) : std::pow(10.0, 3 * u(rng)));
    m.kr = random_color(rng, 0.6, 0.9);
    m.kt = random_color(rng, 0.6, 0.9);
    m.ior = 1 + u(rng);
    m.fresnel = u(rng) < 0.5;
    s.materials.push_back(m);
  }
  auto material = [&] { return std::uniform_int_distribution<int>(0, materials - 1)(rng); };
  const int spheres = std::uniform_int_distribution<int>(0, 6)(rng);
  for (int i = 0; i < spheres; ++i) {
    s.spheres.push_back(Sphere{Vec3(c(rng), u(rng) * 2, c(rng)) * scale, (0.1 + u(rng)) * scale, material()});
  }
  if (u(rng) < 0.15 && !s.spheres.empty()) {  // the camera inside a sphere
    s.spheres[0].center = s.camera.position;
    s.spheres[0].radius = 2 * scale;
  }
  const int planes = std::uniform_int_distribution<int>(0, 2)(rng);
  for (int i = 0; i < planes; ++i) {
    Vec3 n(c(rng) * 0.2, 1, c(rng) * 0.2);
    if (i == 1) n = Vec3(c(rng), c(rng), -3);  // a back wall, at any angle
    s.planes.push_back(Plane{Vec3(0, -u(rng), -4 * u(rng)) * scale, n, material()});
  }
  const int triangles = u(rng) < 0.3 ? std::uniform_int_distribution<int>(1, 2)(rng) : 0;
  for (int i = 0; i < triangles; ++i) {
    Triangle t;
    t.v0 = Vec3(c(rng), u(rng) * 2, c(rng)) * scale;
    t.v1 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
    t.v2 = t.v0 + Vec3(c(rng), c(rng), c(rng)) * scale;
    t.material = material();
    s.triangles.push_back(t);
  }
  const int lights = std::uniform_int_distribution<int>(0, 3)(rng);
  for (int i = 0; i < lights; ++i) {
    Light l;
    l.type = u(rng) < 0.6 ? LightType::kPoint : LightType::kDirectional;
    l.position = Vec3(c(rng), 1 + 4 * u(rng), c(rng)) * scale;
    l.direction = Vec3(c(rng), -1 - u(rng), c(rng));
    l.intensity = random_color(rng, 0.0, 1.0);
    l.enabled = u(rng) < 0.9;
    s.lights.push_back(l);
  }
  if (!s.lights.empty() && !s.spheres.empty() && u(rng) < 0.2) {  // a light lying on a sphere
    Light& l = s.lights[0];
    l.type = LightType::kPoint;
    l.position = s.spheres[0].center + Vec3(0, s.spheres[0].radius, 0);
  }
  if (hierarchy) add_meshes(s, seed, scale);
  return s;
}

inline PreparedScene random_scene(std::uint32_t seed, bool hierarchy = false) {
  return PreparedScene(random_scene_data(seed, hierarchy));
}

}  // namespace phonglab
