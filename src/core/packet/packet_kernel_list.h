// The packet tracer's kernels, declared (no include guard: packet_kernels.h includes this list once
// in namespace phonglab::packet, the program's entry points, and once in the namespace of each
// instance of the one kernel source). What each kernel does is written beside its data in
// packet_kernels.h, under the kernel's name. Lane counts are multiples of kBatchLanes.

// Nearest sphere or plane with t in (0, t_best) for each lane, in the order of intersect_all
// (spheres, then planes). On entry t_best holds each lane's limit (+inf for a plain query); on
// return the nearest t, and id the sphere index, spheres.count + the plane index, or is left
// unchanged when nothing is nearer.
void nearest(const Spheres& spheres, const Planes& planes, const Rays& rays, int lanes, double* t_best,
             std::int32_t* id);

// Any sphere or plane with t in (0, t_max) (occluded_all): sets occluded[i] = 1 for those
// lanes and leaves the others as they are. Lanes whose t_max is not > 0 hold no ray.
void occluded(const Spheres& spheres, const Planes& planes, const Rays& rays, const double* t_max, int lanes,
              std::uint8_t* occluded);

void hit_records(const Spheres& spheres, const Planes& planes, const OffsetMargins& margins, const Rays& rays,
                 const double* t, const std::int32_t* id, int lanes, const HitRecords& out);

void triangle_records(const TriangleRecords& tris, const OffsetMargins& margins, const Rays& rays, const double* t,
                      const std::int32_t* id, const double* b1, const double* b2, int lanes, const HitRecords& out);

void camera_dirs(const CameraIn& cam, const double* x_plus_u, const double* y_plus_v, int lanes, double* dx,
                 double* dy, double* dz);

ShadowCounts light(const LightIn& light, const ShadedPoints& pts, int lanes, const LightOut& out);

// One light's terms added where it is seen (shade()'s light loop after the shadow query): for
// the lanes with seen[i] set, diffuse += (I_l kd) N.L and specular += (I_l ks) spec, with I_l kd
// and I_l ks of the lane's material. Other lanes, and their material entries, are not read.
void add_light(const ByMaterial& kd, const ByMaterial& ks, const std::int32_t* material, const std::uint8_t* seen,
               const double* n_dot_l, const double* spec, int lanes, const ColorLanes& diffuse,
               const ColorLanes& specular);

// The specular factor (specular_factor: max(0, cos)^n) of the lanes where `seen` is set, by
// material: power[m] is a whole n in [1, 4096] that this kernel raises to, 0 for a material
// without ks (factor 0), or -1 (std::pow). Writes spec where the value is certainly std::pow's
// double (packet_kernels_powers.cpp says why) and sets pending[i] = 1 on the seen lanes left to the
// caller's std::pow (about one in five of a whole n's, every lane of -1, and lanes of mixed
// materials), 0 elsewhere. Only an instance with a fused multiply-add has it: call only where packet_fma_supported().
void specular_powers(const double* cos_spec, const std::int32_t* material, const int* power,
                     const std::uint8_t* seen, int lanes, double* spec, std::uint8_t* pending);

// The box of the hit points (lanes [0, live) whose id is >= 0; a NaN coordinate is passed
// over) and their largest offset: out = lo x, y, z, hi x, y, z, the offset (+inf, -inf and 0
// with no hit).
void hit_bounds(const double* px, const double* py, const double* pz, const double* offset, const std::int32_t* id,
                int live, double* out);

void sum_terms(const ByMaterial& ambient, const std::int32_t* material, const std::int32_t* id,
               const TermLanes& terms, int live, double* out);

// The box of the origins, and of the directions, of the rays in lanes [0, live) whose t_max is
// > 0 (every one when t_max is null): out = lo x, y, z, hi x, y, z of the origins, then of the
// directions. With no such ray, lo is +inf and hi -inf.
void ray_bounds(const Rays& rays, const double* t_max, int live, double* out);

void bounce(const BounceIn& in, int lanes, const BounceOut& out);

void hierarchy_nearest(const Hierarchy& h, const Rays& rays, int live, const NearestHits& out);

// SceneBvh::occluded without its planes: sets occluded[i] = 1 for the lanes that anything blocks
// within (0, t_max). Lanes whose t_max is not > 0, or that are occluded already, are skipped.
void hierarchy_occluded(const Hierarchy& h, const Rays& rays, const double* t_max, int lanes,
                        std::uint8_t* occluded);

// nearest_triangle for lanes [0, live): where a triangle is strictly nearer than t (ties go to
// what came first: spheres, planes, then triangles in order), t, id (first_id + k), b1 and b2
// are replaced; prim is left alone.
void triangles_nearest(const LooseTriangles& tris, const Rays& rays, int live, const NearestHits& out);

// any_triangle within (0, t_max): sets occluded[i] = 1 for the lanes a triangle blocks. Lanes
// whose t_max is not > 0, or that are occluded already, are skipped.
void triangles_occluded(const LooseTriangles& tris, const Rays& rays, const double* t_max, int lanes,
                        std::uint8_t* occluded);
