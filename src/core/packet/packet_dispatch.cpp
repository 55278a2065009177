// The packet kernels' entry points (packet_kernel_list.h): each call goes to the instance of the
// one kernel source chosen for this CPU (packet_kernels.h), once at the first call, or by
// PHONGLAB_SIMD in the environment, or by set_packet_simd_target.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "core/packet/packet.h"
#include "core/packet/packet_kernels.h"

namespace phonglab {
namespace packet {

// The instances this build has (CMake builds them: src/core/CMakeLists.txt).
#if defined(PHONGLAB_PACKET_X86)
namespace avx2 {
#include "core/packet/packet_kernel_list.h"
}  // namespace avx2
namespace avx512 {
#include "core/packet/packet_kernel_list.h"
}  // namespace avx512
#elif defined(PHONGLAB_PACKET_WASM)
namespace simd128 {
#include "core/packet/packet_kernel_list.h"
}  // namespace simd128
#elif defined(PHONGLAB_PACKET_NEON)
namespace neon {
#include "core/packet/packet_kernel_list.h"
}  // namespace neon
#endif

namespace {

struct Kernels {
  decltype(&packet::nearest) nearest;
  decltype(&packet::occluded) occluded;
  decltype(&packet::hit_records) hit_records;
  decltype(&packet::triangle_records) triangle_records;
  decltype(&packet::camera_dirs) camera_dirs;
  decltype(&packet::light) light;
  decltype(&packet::add_light) add_light;
  decltype(&packet::specular_powers) specular_powers;
  decltype(&packet::hit_bounds) hit_bounds;
  decltype(&packet::sum_terms) sum_terms;
  decltype(&packet::ray_bounds) ray_bounds;
  decltype(&packet::bounce) bounce;
  decltype(&packet::hierarchy_nearest) hierarchy_nearest;
  decltype(&packet::hierarchy_occluded) hierarchy_occluded;
  decltype(&packet::triangles_nearest) triangles_nearest;
  decltype(&packet::triangles_occluded) triangles_occluded;
};

struct Instance {
  const char* key;   // as PHONGLAB_SIMD and set_packet_simd_target name it
  const char* name;  // as the bench and the page's status line show it
  int lanes;
  bool (*runs)();    // whether this CPU runs it
  bool fma;          // it has the whole powers' kernel (a fused multiply-add)
  Kernels k;
};

// An instance's kernels, in the order of Instance; POWERS: its specular_powers or nullptr.
#define PHONGLAB_KERNELS_OF(ns, powers)                                                                      \
  Kernels {                                                                                                  \
  &ns::nearest, &ns::occluded, &ns::hit_records, &ns::triangle_records, &ns::camera_dirs, &ns::light,        \
      &ns::add_light, powers, &ns::hit_bounds, &ns::sum_terms, &ns::ray_bounds, &ns::bounce,                \
      &ns::hierarchy_nearest, &ns::hierarchy_occluded, &ns::triangles_nearest, &ns::triangles_occluded      \
  }

// Best first.
const Instance kInstances[] = {
#if defined(PHONGLAB_PACKET_X86)
    {"avx512", "AVX-512", 8,
     [] {  // AVX-512 F and DQ (every such CPU has FMA too)
       return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
              __builtin_cpu_supports("fma");
     },
     true, PHONGLAB_KERNELS_OF(avx512, &avx512::specular_powers)},
    {"avx2", "AVX2", 4, [] { return __builtin_cpu_supports("avx2") != 0; }, true,
     PHONGLAB_KERNELS_OF(avx2, &avx2::specular_powers)},
#elif defined(PHONGLAB_PACKET_WASM)
    // Built with SIMD128, which the module needs to load at all; it has no fused multiply-add.
    {"simd128", "SIMD128", 4, [] { return true; }, false, PHONGLAB_KERNELS_OF(simd128, nullptr)},
#elif defined(PHONGLAB_PACKET_NEON)
    {"neon", "NEON", 4, [] { return true; }, true, PHONGLAB_KERNELS_OF(neon, &neon::specular_powers)},
#endif
    {"off", "", 0, [] { return true; }, false, Kernels{}},  // none: the scalar renderer serves
};
#undef PHONGLAB_KERNELS_OF

const Instance* find(std::string_view key) {
  for (const Instance& k : kInstances) {
    if (key == k.key) return k.runs() ? &k : nullptr;  // AVX2's powers kernel also needs FMA: packet_fma_supported
  }
  return nullptr;
}

const Instance* best() {
  for (const Instance& k : kInstances) {
    if (k.runs()) return &k;
  }
  return &kInstances[std::size(kInstances) - 1];
}

// PHONGLAB_SIMD's instance, or the best this CPU runs; an unknown or unusable key is said once,
// on stderr, with the keys that would do.
const Instance* first_choice() {
  const char* env = std::getenv("PHONGLAB_SIMD");
  if (env == nullptr || *env == '\0') return best();
  if (const Instance* k = find(env)) return k;
  std::string keys;
  for (const Instance& k : kInstances) {
    if (k.runs()) keys += std::string(keys.empty() ? "" : ", ") + k.key;
  }
  const Instance* chosen_here = best();
  std::fprintf(stderr, "phonglab: PHONGLAB_SIMD=%s: expected one of %s on this CPU; using %s\n", env, keys.c_str(),
               chosen_here->key);
  return chosen_here;
}

std::atomic<const Instance*> chosen{nullptr};

const Instance& active() {
  const Instance* k = chosen.load(std::memory_order_acquire);
  if (k == nullptr) {
    k = first_choice();
    chosen.store(k, std::memory_order_release);
  }
  return *k;
}

}  // namespace

void nearest(const Spheres& spheres, const Planes& planes, const Rays& rays, int lanes, double* t_best,
             std::int32_t* id) {
  active().k.nearest(spheres, planes, rays, lanes, t_best, id);
}
void occluded(const Spheres& spheres, const Planes& planes, const Rays& rays, const double* t_max, int lanes,
              std::uint8_t* occluded) {
  active().k.occluded(spheres, planes, rays, t_max, lanes, occluded);
}
void hit_records(const Spheres& spheres, const Planes& planes, const OffsetMargins& margins, const Rays& rays,
                 const double* t, const std::int32_t* id, int lanes, const HitRecords& out) {
  active().k.hit_records(spheres, planes, margins, rays, t, id, lanes, out);
}
void triangle_records(const TriangleRecords& tris, const OffsetMargins& margins, const Rays& rays, const double* t,
                      const std::int32_t* id, const double* b1, const double* b2, int lanes, const HitRecords& out) {
  active().k.triangle_records(tris, margins, rays, t, id, b1, b2, lanes, out);
}
void camera_dirs(const CameraIn& cam, const double* x_plus_u, const double* y_plus_v, int lanes, double* dx,
                 double* dy, double* dz) {
  active().k.camera_dirs(cam, x_plus_u, y_plus_v, lanes, dx, dy, dz);
}
ShadowCounts light(const LightIn& light, const ShadedPoints& pts, int lanes, const LightOut& out) {
  return active().k.light(light, pts, lanes, out);
}
void add_light(const ByMaterial& kd, const ByMaterial& ks, const std::int32_t* material, const std::uint8_t* seen,
               const double* n_dot_l, const double* spec, int lanes, const ColorLanes& diffuse,
               const ColorLanes& specular) {
  active().k.add_light(kd, ks, material, seen, n_dot_l, spec, lanes, diffuse, specular);
}
void specular_powers(const double* cos_spec, const std::int32_t* material, const int* power,
                     const std::uint8_t* seen, int lanes, double* spec, std::uint8_t* pending) {
  active().k.specular_powers(cos_spec, material, power, seen, lanes, spec, pending);
}
void hit_bounds(const double* px, const double* py, const double* pz, const double* offset, const std::int32_t* id,
                int live, double* out) {
  active().k.hit_bounds(px, py, pz, offset, id, live, out);
}
void sum_terms(const ByMaterial& ambient, const std::int32_t* material, const std::int32_t* id,
               const TermLanes& terms, int live, double* out) {
  active().k.sum_terms(ambient, material, id, terms, live, out);
}
void ray_bounds(const Rays& rays, const double* t_max, int live, double* out) {
  active().k.ray_bounds(rays, t_max, live, out);
}
void bounce(const BounceIn& in, int lanes, const BounceOut& out) { active().k.bounce(in, lanes, out); }
void hierarchy_nearest(const Hierarchy& h, const Rays& rays, int live, const NearestHits& out) {
  active().k.hierarchy_nearest(h, rays, live, out);
}
void hierarchy_occluded(const Hierarchy& h, const Rays& rays, const double* t_max, int lanes,
                        std::uint8_t* occluded) {
  active().k.hierarchy_occluded(h, rays, t_max, lanes, occluded);
}
void triangles_nearest(const LooseTriangles& tris, const Rays& rays, int live, const NearestHits& out) {
  active().k.triangles_nearest(tris, rays, live, out);
}
void triangles_occluded(const LooseTriangles& tris, const Rays& rays, const double* t_max, int lanes,
                        std::uint8_t* occluded) {
  active().k.triangles_occluded(tris, rays, t_max, lanes, occluded);
}

}  // namespace packet

bool packet_cpu_supported() { return packet::active().lanes > 0; }

bool packet_fma_supported() {
  const packet::Instance& k = packet::active();
#if defined(PHONGLAB_PACKET_X86)
  static const bool fma = __builtin_cpu_supports("fma") != 0;
  return k.fma && fma;
#else
  return k.fma;
#endif
}

const char* packet_simd_target() { return packet::active().name; }

const char* packet_simd_key() { return packet::active().key; }

int packet_simd_lanes() { return packet::active().lanes; }

std::vector<std::string> packet_simd_targets() {
  std::vector<std::string> keys;
  for (const packet::Instance& k : packet::kInstances) {
    if (k.runs()) keys.emplace_back(k.key);
  }
  return keys;
}

bool set_packet_simd_target(std::string_view key) {
  const packet::Instance* k = packet::find(key);
  if (k == nullptr) return false;
  packet::chosen.store(k, std::memory_order_release);
  return true;
}

}  // namespace phonglab
