#include "apps/bench/embree_accel.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "core/accel/accel.h"
#include "core/accel/bvh.h"
#include "core/base/threads.h"
#include "core/scene/camera.h"

namespace phonglab {
namespace {

using Clock = std::chrono::steady_clock;

// Triangle hits nearer than this fraction of the coordinates' size are the surface a secondary
// ray leaves, seen again through float rounding (vertices, origin and t each carry ~2^-24
// relative error): 2^-16 covers incidence up to about 88.6 degrees from the normal.
constexpr double kFloatSelfHitMargin = 0x1p-16;

float round_up(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

float round_down(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

void report_error(void*, RTCError code, const char* message) {
  std::fprintf(stderr, "embree error %d: %s\n", static_cast<int>(code), message ? message : "");
}

// Bytes a device holds: its memory monitor adds each allocation and subtracts each release.
struct MemoryCounter {
  std::atomic<std::int64_t> bytes{0};
};

bool count_memory(void* user, ssize_t bytes, bool /*post*/) {
  // Each allocation (bytes > 0) and release (< 0) is reported once; as nothing is ever
  // cancelled here, every report is accumulated (rtcSetDeviceMemoryMonitorFunction(3)).
  static_cast<MemoryCounter*>(user)->bytes += static_cast<std::int64_t>(bytes);
  return true;
}

// Owns one Embree device and one scene on it; releases the scene first.
class EmbreeHandle {
 public:
  explicit EmbreeHandle(int build_threads) : memory_(std::make_unique<MemoryCounter>()) {
    const std::string config = build_threads > 0 ? "threads=" + std::to_string(build_threads) : "";
    device_ = rtcNewDevice(config.c_str());
    if (!device_) {
      throw std::runtime_error("Embree: rtcNewDevice failed (error " + std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
    }
    rtcSetDeviceErrorFunction(device_, report_error, nullptr);
    rtcSetDeviceMemoryMonitorFunction(device_, count_memory, memory_.get());
    scene_ = rtcNewScene(device_);
  }
  ~EmbreeHandle() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  EmbreeHandle(const EmbreeHandle&) = delete;
  EmbreeHandle& operator=(const EmbreeHandle&) = delete;

  RTCDevice device() const { return device_; }
  RTCScene scene() const { return scene_; }
  std::size_t memory_bytes() const { return static_cast<std::size_t>(std::max<std::int64_t>(0, memory_->bytes.load())); }

  // Adds a triangle geometry holding `tris` (unshared float vertices) and returns its id.
  unsigned add_triangles(const std::vector<Triangle>& tris) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * tris.size()));
    auto* idx = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris.size()));
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const Vec3* corners[3] = {&tris[i].v0, &tris[i].v1, &tris[i].v2};
      for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) v[9 * i + 3 * c + a] = static_cast<float>((*corners[c])[a]);
        idx[3 * i + c] = static_cast<unsigned>(3 * i + c);
      }
    }
    return attach(g);
  }

  unsigned attach(RTCGeometry g) {
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);  // the scene holds it now
    return id;
  }

 private:
  std::unique_ptr<MemoryCounter> memory_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

// An Embree ray for `ray` up to tfar, starting a float self-hit margin of the coordinates
// (|origin| + the scene's `scale`) along it; no hit yet.
RTCRayHit rtc_ray(const Ray& ray, double scale, float tfar) {
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(ray.origin.x);
  rh.ray.org_y = static_cast<float>(ray.origin.y);
  rh.ray.org_z = static_cast<float>(ray.origin.z);
  rh.ray.dir_x = static_cast<float>(ray.dir.x);
  rh.ray.dir_y = static_cast<float>(ray.dir.y);
  rh.ray.dir_z = static_cast<float>(ray.dir.z);
  rh.ray.tnear = static_cast<float>(kFloatSelfHitMargin * (max_abs(ray.origin) + scale));
  rh.ray.tfar = tfar;
  rh.ray.mask = ~0u;
  rh.ray.time = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// The query state the sphere callbacks see: Embree hands them the context pointer, and the
// context is this struct's first member, so the double ray and the nearest sphere travel along.
struct SphereQuery {
  RTCIntersectContext context;
  const Ray* ray = nullptr;
  const Sphere* spheres = nullptr;
  double t_max = 0;  // nearest sphere hit so far (exact), else the query's own t_max
  int sphere = -1;   // index of that sphere
};
static_assert(std::is_standard_layout_v<SphereQuery>, "the context must sit at the start");

SphereQuery& query_of(RTCIntersectContext* context) { return *reinterpret_cast<SphereQuery*>(context); }

// A query context for `ray` over `spheres`, with no sphere hit before t_max.
SphereQuery make_sphere_query(const Ray& ray, const Sphere* spheres, double t_max) {
  SphereQuery q;
  rtcInitIntersectContext(&q.context);
  q.ray = &ray;
  q.spheres = spheres;
  q.t_max = t_max;
  return q;
}

void sphere_bounds_fn(const RTCBoundsFunctionArguments* args) {
  const auto* spheres = static_cast<const Sphere*>(args->geometryUserPtr);
  const Aabb b = sphere_bounds(spheres[args->primID]);
  RTCBounds* o = args->bounds_o;
  o->lower_x = round_down(b.lo.x);
  o->lower_y = round_down(b.lo.y);
  o->lower_z = round_down(b.lo.z);
  o->upper_x = round_up(b.hi.x);
  o->upper_y = round_up(b.hi.y);
  o->upper_z = round_up(b.hi.z);
}

void sphere_intersect_fn(const RTCIntersectFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;  // single-ray queries only
  SphereQuery& q = query_of(args->context);
  auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  // Bounded by the nearest sphere so far (exact) and by any nearer triangle Embree found.
  const double limit = std::min(q.t_max, static_cast<double>(rh->ray.tfar));
  const double t = sphere_root(q.spheres[args->primID], q.ray->origin, q.ray->dir, 0, limit);
  if (!(t > 0)) return;
  q.t_max = t;
  q.sphere = static_cast<int>(args->primID);
  rh->ray.tfar = round_up(t);
  rh->hit.u = 0;
  rh->hit.v = 0;
  rh->hit.Ng_x = rh->hit.Ng_y = rh->hit.Ng_z = 0;  // the renderer recomputes the normal
  rh->hit.primID = args->primID;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
}

void sphere_occluded_fn(const RTCOccludedFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  SphereQuery& q = query_of(args->context);
  auto* ray = reinterpret_cast<RTCRay*>(args->ray);
  if (sphere_root(q.spheres[args->primID], q.ray->origin, q.ray->dir, 0, q.t_max) > 0) {
    ray->tfar = -std::numeric_limits<float>::infinity();  // Embree's "occluded" mark
  }
}

// Largest coordinate magnitude of everything but planes (sets the float rounding margin).
double scene_scale(const Scene& scene) {
  const Aabb b = scene_bounds(scene);
  return b.empty() ? 0.0 : std::max(max_abs(b.lo), max_abs(b.hi));
}

class EmbreeAccel final : public Accelerator {
 public:
  EmbreeAccel(const Scene& scene, const EmbreeOptions& options, EmbreeBuildStats* stats)
      : spheres_(scene.spheres), triangles_(scene.triangles), scale_(scene_scale(scene)),
        embree_(options.build_threads) {
    const auto t0 = Clock::now();
    for (const Mesh& m : scene.meshes) meshes_.push_back(m.geometry.get());
    if (!spheres_.empty()) {
      RTCGeometry g = rtcNewGeometry(embree_.device(), RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(g, static_cast<unsigned>(spheres_.size()));
      rtcSetGeometryUserData(g, spheres_.data());
      rtcSetGeometryBoundsFunction(g, sphere_bounds_fn, spheres_.data());
      rtcSetGeometryIntersectFunction(g, sphere_intersect_fn);
      rtcSetGeometryOccludedFunction(g, sphere_occluded_fn);
      sphere_geometry_ = embree_.attach(g);
      map(sphere_geometry_, {ObjectRef::Kind::kSphere, -1});
    }
    if (!triangles_.empty()) map(embree_.add_triangles(triangles_), {ObjectRef::Kind::kTriangle, -1});
    for (std::size_t m = 0; m < meshes_.size(); ++m) {
      if (meshes_[m]->triangles.empty()) continue;
      map(embree_.add_triangles(meshes_[m]->triangles), {ObjectRef::Kind::kMesh, static_cast<int>(m)});
    }
    const auto t1 = Clock::now();
    rtcCommitScene(embree_.scene());
    const auto t2 = Clock::now();
    if (stats) {
      stats->commit_seconds = std::chrono::duration<double>(t2 - t1).count();
      stats->total_seconds = std::chrono::duration<double>(t2 - t0).count();
      stats->memory_bytes = embree_.memory_bytes();
    }
  }

  std::optional<Hit> intersect(const Scene& scene, const Ray& ray, double t_max) const override {
    double best = t_max;
    ObjectRef obj;
    if (const int i = nearest_plane(scene.planes, ray, best); i >= 0) obj = {ObjectRef::Kind::kPlane, i};
    SphereQuery q = make_sphere_query(ray, spheres_.data(), best);
    RTCRayHit rh = make_rtc_ray_hit(ray, best);
    rtcIntersect1(embree_.scene(), &q.context, &rh);
    double b1 = 0, b2 = 0;
    const unsigned geom = rh.hit.geomID;
    if (geom != RTC_INVALID_GEOMETRY_ID) {
      if (geom == sphere_geometry_ && q.sphere >= 0) {
        best = q.t_max;
        obj = {ObjectRef::Kind::kSphere, q.sphere};
      } else if (geom < geometries_.size() && static_cast<double>(rh.ray.tfar) < best) {
        const ObjectRef kind = geometries_[geom];
        best = static_cast<double>(rh.ray.tfar);
        b1 = static_cast<double>(rh.hit.u);
        b2 = static_cast<double>(rh.hit.v);
        const int prim = static_cast<int>(rh.hit.primID);
        obj = kind.kind == ObjectRef::Kind::kMesh ? ObjectRef{kind.kind, kind.index, prim}
                                                  : ObjectRef{kind.kind, prim};
      }
    }
    if (obj.kind == ObjectRef::Kind::kNone) return std::nullopt;
    return make_hit(scene, ray, obj, best, b1, b2);
  }

  bool occluded(const Scene& scene, const Ray& ray, double t_max) const override {
    if (any_plane(scene.planes, ray, t_max)) return true;
    SphereQuery q = make_sphere_query(ray, spheres_.data(), t_max);
    RTCRayHit rh = make_rtc_ray_hit(ray, t_max);
    rh.ray.tfar = round_down(t_max);  // never an occluder at or beyond the end of the segment
    rtcOccluded1(embree_.scene(), &q.context, &rh.ray);
    return rh.ray.tfar == -std::numeric_limits<float>::infinity();
  }

  bool matches(const Scene& scene) const override {
    if (scene.spheres.size() != spheres_.size() || scene.triangles.size() != triangles_.size() ||
        scene.meshes.size() != meshes_.size()) {
      return false;
    }
    for (std::size_t i = 0; i < spheres_.size(); ++i) {
      if (scene.spheres[i].center != spheres_[i].center || scene.spheres[i].radius != spheres_[i].radius) return false;
    }
    for (std::size_t i = 0; i < triangles_.size(); ++i) {
      const Triangle& a = scene.triangles[i];
      const Triangle& b = triangles_[i];
      if (a.v0 != b.v0 || a.v1 != b.v1 || a.v2 != b.v2) return false;
    }
    for (std::size_t i = 0; i < meshes_.size(); ++i) {
      if (scene.meshes[i].geometry.get() != meshes_[i]) return false;
    }
    return true;
  }

 private:
  void map(unsigned geometry, ObjectRef kind) {
    if (geometries_.size() <= geometry) geometries_.resize(geometry + 1);
    geometries_[geometry] = kind;
  }

  RTCRayHit make_rtc_ray_hit(const Ray& ray, double t_max) const { return rtc_ray(ray, scale_, round_up(t_max)); }

  std::vector<Sphere> spheres_;      // the user geometry's primitives (and matches())
  std::vector<Triangle> triangles_;  // for matches()
  std::vector<const MeshGeometry*> meshes_;
  double scale_ = 0;                 // largest coordinate of the scene's bounded primitives
  EmbreeHandle embree_;
  unsigned sphere_geometry_ = RTC_INVALID_GEOMETRY_ID;
  std::vector<ObjectRef> geometries_;  // by Embree geometry id: kind and mesh index
};

// The primary-ray packet scene: Embree's own primitives throughout.
void add_packet_primitives(EmbreeHandle& embree, const Scene& scene) {
  if (!scene.spheres.empty()) {
    RTCGeometry g = rtcNewGeometry(embree.device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                          4 * sizeof(float), scene.spheres.size()));
    for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
      const Sphere& s = scene.spheres[i];
      v[4 * i + 0] = static_cast<float>(s.center.x);
      v[4 * i + 1] = static_cast<float>(s.center.y);
      v[4 * i + 2] = static_cast<float>(s.center.z);
      v[4 * i + 3] = static_cast<float>(s.radius);
    }
    embree.attach(g);
  }
  std::vector<Triangle> tris = scene.triangles;
  for (const Mesh& m : scene.meshes) tris.insert(tris.end(), m.geometry->triangles.begin(), m.geometry->triangles.end());
  // An infinite plane becomes a square 1e4 times the scene's size around its point.
  const Aabb b = scene_bounds(scene);
  const double size = b.empty() ? 1.0 : std::max(1.0, max_abs(b.hi - b.lo));
  const double half = 1e4 * size;
  for (const Plane& pl : scene.planes) {
    const Vec3 n = glm::normalize(pl.normal);
    const Vec3 axis = std::abs(n.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    const Vec3 u = glm::normalize(glm::cross(n, axis)) * half;
    const Vec3 w = glm::cross(n, glm::normalize(u)) * half;
    const Vec3 c = pl.point;
    tris.push_back(Triangle{c - u - w, c + u - w, c + u + w, pl.material});
    tris.push_back(Triangle{c - u - w, c + u + w, c - u + w, pl.material});
  }
  if (!tris.empty()) embree.add_triangles(tris);
}

// Embree's own primitives behind the Accelerator interface (make_embree_native_accel).
class EmbreeNativeAccel final : public Accelerator {
 public:
  explicit EmbreeNativeAccel(const Scene& scene) : scale_(scene_scale(scene)), embree_(0) {
    add_packet_primitives(embree_, scene);
    sphere_geometry_ = scene.spheres.empty() ? RTC_INVALID_GEOMETRY_ID : 0;
    // add_packet_primitives' triangle order: loose triangles, each mesh's, two per plane.
    std::size_t first = scene.triangles.size();
    for (const Mesh& m : scene.meshes) {
      mesh_first_.push_back(first);
      first += m.geometry->triangles.size();
    }
    plane_first_ = first;
    rtcCommitScene(embree_.scene());
  }

  std::optional<Hit> intersect(const Scene& scene, const Ray& ray, double t_max) const override {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = ray_hit(ray, round_up(t_max));
    rtcIntersect1(embree_.scene(), &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return make_hit(scene, ray, object(rh.hit.geomID, rh.hit.primID), static_cast<double>(rh.ray.tfar),
                    static_cast<double>(rh.hit.u), static_cast<double>(rh.hit.v));
  }

  bool occluded(const Scene& /*scene*/, const Ray& ray, double t_max) const override {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh = ray_hit(ray, round_down(t_max));
    rtcOccluded1(embree_.scene(), &context, &rh.ray);
    return rh.ray.tfar == -std::numeric_limits<float>::infinity();
  }

  bool matches(const Scene& /*scene*/) const override { return false; }  // built per snapshot, never reused

 private:
  RTCRayHit ray_hit(const Ray& ray, float tfar) const { return rtc_ray(ray, scale_, tfar); }

  // The scene object Embree's (geometry, primitive) names.
  ObjectRef object(unsigned geometry, unsigned prim) const {
    if (geometry == sphere_geometry_) return {ObjectRef::Kind::kSphere, static_cast<int>(prim)};
    const std::size_t p = prim;
    if (p >= plane_first_) return {ObjectRef::Kind::kPlane, static_cast<int>((p - plane_first_) / 2)};
    for (std::size_t m = mesh_first_.size(); m-- > 0;) {
      if (p >= mesh_first_[m]) return {ObjectRef::Kind::kMesh, static_cast<int>(m), static_cast<int>(p - mesh_first_[m])};
    }
    return {ObjectRef::Kind::kTriangle, static_cast<int>(p)};
  }

  double scale_ = 0;
  EmbreeHandle embree_;
  unsigned sphere_geometry_ = RTC_INVALID_GEOMETRY_ID;
  std::vector<std::size_t> mesh_first_;
  std::size_t plane_first_ = 0;
};

}  // namespace

std::shared_ptr<const Accelerator> make_embree_accel(const Scene& scene, const EmbreeOptions& options,
                                                     EmbreeBuildStats* stats) {
  return std::make_shared<EmbreeAccel>(scene, options, stats);
}

std::shared_ptr<const Accelerator> make_embree_native_accel(const Scene& scene) {
  return std::make_shared<EmbreeNativeAccel>(scene);
}

std::vector<PacketCast> embree_cast_primary_packets(const Scene& scene, int width, int height, int threads,
                                                    int casts) {
  EmbreeHandle embree(threads);
  add_packet_primitives(embree, scene);
  rtcCommitScene(embree.scene());
  const CameraFrame frame = make_camera_frame(scene.camera, width, height);
  float org[3], fwd[3], right[3], up[3];
  for (int a = 0; a < 3; ++a) {
    org[a] = static_cast<float>(frame.origin[a]);
    fwd[a] = static_cast<float>(frame.forward[a]);
    right[a] = static_cast<float>(frame.right[a]);
    up[a] = static_cast<float>(frame.up[a]);
  }
  std::vector<float> screen_x(static_cast<std::size_t>(width)), screen_y(static_cast<std::size_t>(height));
  for (int x = 0; x < width; ++x) screen_x[static_cast<std::size_t>(x)] = static_cast<float>(2 * (x + 0.5) / width - 1);
  for (int y = 0; y < height; ++y) screen_y[static_cast<std::size_t>(y)] = static_cast<float>(1 - 2 * (y + 0.5) / height);
  constexpr int kSide = 4;  // 4 x 4 pixels per 16-wide packet
  const int blocks_x = (width + kSide - 1) / kSide;
  const int blocks = blocks_x * ((height + kSide - 1) / kSide);
  std::atomic<int> next{0};
  std::atomic<std::uint64_t> rays{0}, hits{0};
  const auto worker = [&] {
    std::uint64_t my_rays = 0, my_hits = 0;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    // Blocks of 16 rows are handed out as one unit so the atomic counter stays off the profile.
    constexpr int kBlocksPerTask = 16;
    for (;;) {
      const int first = next.fetch_add(kBlocksPerTask, std::memory_order_relaxed);
      if (first >= blocks) break;
      for (int blk = first; blk < std::min(blocks, first + kBlocksPerTask); ++blk) {
        const int x0 = (blk % blocks_x) * kSide, y0 = (blk / blocks_x) * kSide;
        alignas(64) int valid[16];
        alignas(64) RTCRayHit16 rh;  // every field Embree reads is set below
        // camera_ray's formula in float, with the screen coordinates of every column and row
        // computed once per frame; lane by lane loops the compiler turns into SIMD.
        alignas(64) float sx[16], sy[16];
        for (int k = 0; k < 16; ++k) {
          const int x = x0 + (k & 3), y = y0 + (k >> 2);
          valid[k] = x < width && y < height ? -1 : 0;
          sx[k] = screen_x[static_cast<std::size_t>(std::min(x, width - 1))];
          sy[k] = screen_y[static_cast<std::size_t>(std::min(y, height - 1))];
        }
        for (int k = 0; k < 16; ++k) {
          const float dx = fwd[0] + sx[k] * right[0] + sy[k] * up[0];
          const float dy = fwd[1] + sx[k] * right[1] + sy[k] * up[1];
          const float dz = fwd[2] + sx[k] * right[2] + sy[k] * up[2];
          const float inv_len = 1 / std::sqrt(dx * dx + dy * dy + dz * dz);
          rh.ray.dir_x[k] = dx * inv_len;
          rh.ray.dir_y[k] = dy * inv_len;
          rh.ray.dir_z[k] = dz * inv_len;
        }
        for (int k = 0; k < 16; ++k) {
          rh.ray.org_x[k] = org[0];
          rh.ray.org_y[k] = org[1];
          rh.ray.org_z[k] = org[2];
          rh.ray.tnear[k] = 0;
          rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
          rh.ray.time[k] = 0;
          rh.ray.mask[k] = ~0u;
          rh.ray.id[k] = 0;
          rh.ray.flags[k] = 0;
          rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect16(valid, embree.scene(), &context, &rh);
        for (int k = 0; k < 16; ++k) {
          if (!valid[k]) continue;
          ++my_rays;
          if (rh.hit.geomID[k] != RTC_INVALID_GEOMETRY_ID) ++my_hits;
        }
      }
    }
    rays += my_rays;
    hits += my_hits;
  };
  std::vector<PacketCast> out;
  for (int c = 0; c <= casts; ++c) {
    next = 0;
    rays = 0;
    hits = 0;
    const auto t0 = Clock::now();
    run_workers(threads, [&](int) { worker(); });
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (c > 0) out.push_back(PacketCast{seconds, rays.load(), hits.load()});
  }
  return out;
}

}  // namespace phonglab
