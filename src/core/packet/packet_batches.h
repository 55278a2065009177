// The packet driver's batch buffers (internal to src/core/packet): a batch of rays and one
// recursion level's hits, lights, children and terms, as structure of arrays with room for a
// multiple of packet::kBatchLanes lanes; what the light loop needs of a material.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/packet/packet_kernels.h"
#include "core/scene/math.h"
#include "core/shading/shading.h"

namespace phonglab::packet_driver {

constexpr double kInf = std::numeric_limits<double>::infinity();

inline int padded(int n) { return packet::padded_lanes(n); }

// Grows v to at least n elements (never shrinks, never clears: lanes past the live ones keep
// old but initialised values, which the kernels compute on and the driver ignores).
template <class T>
void fit(std::vector<T>& v, int n) {
  if (v.size() < static_cast<std::size_t>(n)) v.resize(static_cast<std::size_t>(n));
}

inline std::size_t at(int i) { return static_cast<std::size_t>(i); }

// Rays of one batch as structure of arrays, with room for a multiple of kBatchLanes lanes.
struct RayBatch {
  std::vector<double> ox, oy, oz, dx, dy, dz;
  std::vector<double> weight;  // path weight from the camera
  // While recording trees: each ray's pixel in the tile and the node it is a child of (-1: none).
  std::vector<int> pixel;
  std::vector<std::int32_t> parent;
  int n = 0;

  void reserve_lanes(int count) {
    const int size = padded(count);
    for (std::vector<double>* v : {&ox, &oy, &oz, &dx, &dy, &dz, &weight}) fit(*v, size);
  }
  void tag_last(int pixel_of, std::int32_t parent_node) {
    fit(pixel, n);
    fit(parent, n);
    pixel[at(n - 1)] = pixel_of;
    parent[at(n - 1)] = parent_node;
  }
  void push(const Vec3& o, const Vec3& d, double w) {
    const std::size_t i = at(n);
    ox[i] = o.x, oy[i] = o.y, oz[i] = o.z;
    dx[i] = d.x, dy[i] = d.y, dz[i] = d.z;
    weight[i] = w;
    ++n;
  }
  Vec3 origin(int i) const { return {ox[at(i)], oy[at(i)], oz[at(i)]}; }
  Vec3 dir(int i) const { return {dx[at(i)], dy[at(i)], dz[at(i)]}; }
  packet::Rays view() const { return {ox.data(), oy.data(), oz.data(), dx.data(), dy.data(), dz.data()}; }
};

// A colour per lane as structure of arrays (the kernels' ColorLanes).
struct ColorArrays {
  std::vector<double> r, g, b;

  void fit_lanes(int size) {
    fit(r, size);
    fit(g, size);
    fit(b, size);
  }
  void zero(int lanes) {  // lanes: a multiple of kBatchLanes within the room
    for (std::vector<double>* v : {&r, &g, &b}) std::fill_n(v->begin(), lanes, 0.0);
  }
  packet::ColorLanes lanes() { return {r.data(), g.data(), b.data()}; }
  Color at_lane(int i) const { return {r[at(i)], g[at(i)], b[at(i)]}; }
  void set(int i, const Color& c) { r[at(i)] = c.r, g[at(i)] = c.g, b[at(i)] = c.b; }
};

// A shadow ray's fate for one light at one hit.
enum class Shadow : std::uint8_t { kNone = 0, kVisible = 1, kTest = 2 };

// Everything one recursion level keeps while its children are traced. All arrays are indexed
// by the level's ray (lane); lanes whose ray missed are skipped (their light kernel lanes are
// computed and ignored, and their shadow lanes are idle).
struct Level {
  // Nearest hits.
  std::vector<double> t, b1, b2;
  std::vector<std::int32_t> id;  // sphere k, spheres + plane k, spheres + planes + triangle k,
                                 // spheres + planes + triangles + mesh k; -1: miss
  std::vector<std::int32_t> prim;  // a mesh's triangle
  // Shading frame at the hit.
  std::vector<std::int32_t> material;
  std::vector<std::uint8_t> entering;
  std::vector<std::uint8_t> lit;  // a hit whose material has kd or ks: lights are evaluated there
  std::vector<std::uint8_t> active;  // the light kernel's lanes: lit, or every hit while recording
  std::vector<std::int32_t> node;    // while recording: the hit's node
  Vec3 lo{0}, hi{0};              // bounds of the hit points
  double max_offset = 0;          // the largest surface_offset among them
  std::vector<double> px, py, pz, nx, ny, nz, gx, gy, gz, vx, vy, vz, offset;
  // The terms of shade() but the ambient (the material's), summed light by light, and what the
  // children bring back (zero at lanes without them).
  ColorArrays diffuse, specular, reflection, refraction;
  // One light at those points, with its shadow rays (kernel output, tested in place), and where
  // it is seen with its specular factor.
  std::vector<double> n_dot_l, cos_spec, sox, soy, soz, sdx, sdy, sdz, st_max, spec;
  std::vector<Shadow> shadow;
  std::vector<std::uint8_t> blocked, seen, pending;  // pending: seen, its factor still to take
  // Children: the bounce at mirror and glass hits (kernel output), the level's reflected and
  // refracted rays, and what they bring back.
  std::vector<std::uint8_t> bounces, tir;
  std::vector<double> ior, eta, fresnel, mx, my, mz, tx, ty, tz;
  RayBatch reflected, refracted;
  std::vector<Color> kr, kt;  // kr', kt' of each hit
  std::vector<Color> reflected_radiance, refracted_radiance;
  std::vector<int> reflected_index, refracted_index;  // per lane: lane in the child batch, or -1

  void fit_lanes(int count) {
    const int size = padded(count);
    for (std::vector<double>* v : {&t, &b1, &b2, &px, &py, &pz, &nx, &ny, &nz, &gx, &gy, &gz, &vx, &vy, &vz, &offset,
                                   &n_dot_l, &cos_spec, &sox, &soy, &soz, &sdx, &sdy, &sdz, &st_max, &ior, &eta,
                                   &fresnel, &mx, &my, &mz, &tx, &ty, &tz, &spec}) {
      fit(*v, size);
    }
    fit(id, size);
    fit(prim, size);
    fit(material, size);
    fit(entering, size);
    fit(lit, size);
    fit(active, size);
    fit(node, size);
    fit(bounces, size);
    fit(tir, size);
    for (ColorArrays* c : {&diffuse, &specular, &reflection, &refraction}) c->fit_lanes(size);
    fit(shadow, size);
    fit(blocked, size);
    fit(seen, size);
    fit(pending, size);
    fit(kr, size);
    fit(kt, size);
    fit(reflected_index, size);
    fit(refracted_index, size);
  }
  packet::HitRecords records() {
    return {px.data(), py.data(), pz.data(), nx.data(), ny.data(), nz.data(), gx.data(),
            gy.data(), gz.data(), vx.data(), vy.data(), vz.data(), offset.data(), entering.data()};
  }
};

// A colour per material (or per light and material) as structure of arrays, for the kernels.
struct MaterialColors {
  std::vector<double> r, g, b;

  void push(const Color& c) {
    r.push_back(c.r);
    g.push_back(c.g);
    b.push_back(c.b);
  }
  // The colours from entry `first` on (a light's, when stored light by light).
  packet::ByMaterial from(std::size_t first) const { return {r.data() + first, g.data() + first, b.data() + first}; }
};

// What the light loop needs of a material, gathered once per scene.
struct MaterialInfo {
  bool lit = false;       // kd or ks non-zero: lights are evaluated
  bool specular = false;  // ks non-zero
  bool bounces = false;   // kr or kt non-zero: children may follow
  double n = 0;
  double ior = 1;
  Color ambient{0};       // ka * Ia, as shade() computes it
};

}  // namespace phonglab::packet_driver
