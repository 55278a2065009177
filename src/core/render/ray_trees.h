// The ray trees of an image's first sample, kept so that an edit which changes no ray is
// re-shaded instead of re-traced (docs/speed.md, "Re-shading"). A change of ka, kd, ks, n, Ia,
// the background, a light's intensity or mute, or the specular model leaves every ray, every hit
// and every shadow ray's answer as it was: the image is a sum over stored values. A moved light
// changes only the shadow rays towards it, which are cast again from the stored hit points.
// The re-shaded image is the one render_pass gives for the new scene, bit for bit.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/packet/packet_lanes.h"
#include "core/accel/prepared_scene.h"
#include "core/render/render.h"
#include "core/shading/shading.h"

namespace phonglab {

// What an edit between two snapshots of a scene invalidates.
enum class EditScope : std::uint8_t {
  kNothing,  // the same image
  kShading,  // ka, kd, ks, n, Ia, background, light intensity or mute, specular model
  kLights,   // a light moved or turned (and perhaps shading): the shadow rays towards it
  kBounces,  // kr, kt, ior, Fresnel, max depth, min weight (and perhaps the above): the rays
             // that stay are reused, those that become needed or change direction are traced
  kRetrace,  // camera, geometry, lights added or removed, another material table
};
EditScope edit_scope(const Scene& before, const Scene& after);

// Whether a term can be re-shaded from stored trees: the full image and its five terms.
bool reshades(Term term);

class RayTrees {
 public:
  // Traces the centre ray (sample 0) of every pixel of a width x height image of `scene`, with
  // `shading_eye` as RenderOptions has it, keeping every tree. Null when the trees would need
  // more than `budget_bytes`, when cancelled, or for a scene with an experiment that changes rays.
  // A scene whose experiment changes the local terms alone (a student's formulas) gets the trees
  // of its production twin: its rays are the same, and a re-shade gives the experiment's terms.
  // Traced in packets where the packet tracer serves the scene (`allow_packets`; the same trees
  // either way).
  // `recycled`: trees no longer wanted, whose memory the new ones take over (no page faults).
  static std::unique_ptr<RayTrees> record(std::shared_ptr<const PreparedScene> scene, int width, int height,
                                          const std::optional<Vec3>& shading_eye, int threads,
                                          std::size_t budget_bytes, const std::atomic<bool>* cancel = nullptr,
                                          bool allow_packets = true, std::unique_ptr<RayTrees> recycled = nullptr);

  // What re-shading `scene` at this size and eye would need (kRetrace: it cannot be). Another
  // eye ("move your head") is a shading edit: V changes at the primary hits only; so are other
  // local terms (an experiment's that changes them alone: every pixel is shaded again).
  EditScope scope_for(const PreparedScene& scene, int width, int height, const std::optional<Vec3>& shading_eye) const;

  // Sample 0 of `scene` for `term` (reshades(term)) into `accum`, which must be empty at this
  // size; the trees then describe `scene`. Only for a scope below kRetrace. Shadow rays towards
  // moved lights are cast again; a child ray that is not stored (it became needed, or its
  // direction changed with ior) is traced, and not stored; cancelled midway, the trees are no
  // longer usable (usable()). With accum.has_terms(), the five term images too: every pixel is
  // then shaded whole, none keeps its value from the last re-shade.
  PassStats reshade(std::shared_ptr<const PreparedScene> scene, Term term, const std::optional<Vec3>& shading_eye,
                    int threads, Accumulator& accum, const std::atomic<bool>* cancel = nullptr);

  // The live path of a slider or a light's drag (ray_trees_live.cpp). Whether `scene` differs
  // from the trees' scene only by an edit the image is linear in (some materials' ka, kd, ks; or
  // Ia; or some lights' intensity or mute: scene_changes.h), or by one moved light, at this size
  // and eye, for the term of the trees' last image (no term images): then its image is that
  // image plus each edited coefficient's change times the per-pixel sum it multiplies; for a
  // moved light, each pixel's value without that light plus its share at the stored hits, whose
  // shadow rays towards it are cast again.
  bool recombines(const PreparedScene& scene, int width, int height, Term term, const std::optional<Vec3>& shading_eye,
                  bool term_images) const;
  // How a first sample of `scene` (this size, eye and what is shown) is made from these trees:
  // traced anew (kTrace: they cannot be re-shaded into it), re-shaded (kReshade), or, while the
  // hand is on and the image is linear in the edit, recombined (kLive; its exact re-shade follows
  // when the hand stops). The one rule the previewer's renderer and the page follow.
  enum class Route { kTrace, kReshade, kLive };
  Route route(const PreparedScene& scene, int width, int height, Term term, const std::optional<Vec3>& shading_eye,
              bool term_images, bool interacting) const {
    if (scope_for(scene, width, height, shading_eye) == EditScope::kRetrace) return Route::kTrace;
    return interacting && recombines(scene, width, height, term, shading_eye, term_images) ? Route::kLive : Route::kReshade;
  }
  // That image of `scene` (recombines()) into `accum`, empty at this size. The trees stay as
  // they are; the sums are computed on first use (one pass over the stored trees, like a
  // re-shade without shadow rays) and kept for the next edits of the same coefficients, so a
  // slider costs a few multiply-adds a pixel. Equal to the exact re-shade to rounding (about
  // 1e-15 relative), not bit for bit: it is shown while the hand moves, the exact image after.
  // `over_last`: accum holds the last image this call wrote (nothing else written since), so
  // only the pixels whose trees meet an edited material, now or then, are written again.
  PassStats recombine(const PreparedScene& scene, Term term, int threads, Accumulator& accum,
                      const std::atomic<bool>* cancel = nullptr, bool over_last = false);

  bool usable() const { return usable_; }
  // Whether the last re-shade had to trace rays for more than an eighth of the pixels (children
  // that became needed or turned): recording again would serve the next edits better.
  bool worn() const { return traced_pixels_ * 8 > static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_); }
  std::size_t memory_bytes() const;
  std::size_t node_count() const;
  double record_seconds() const { return record_seconds_; }

  // One traced ray that met something, as a re-shade reads it (the hot part, kept small: a
  // re-shade streams through every node and is bound by memory).
  struct Node {
    std::int32_t material = 0;
    std::int32_t reflection = kNone, refraction = kNone;  // child nodes, kMissed or kNone
    std::int16_t depth = 0;
    bool entering = false;
  };
  // The rest of it: read for mirrors and glass, moved lights and a new specular model.
  struct NodeGeometry {
    Vec3 p{0}, n{0}, ng{0}, dir{0};  // hit point, facing shading and geometric normals, ray direction
    double offset = 0;               // surface_offset of the hit
    double fresnel = 0;              // F at a mirror or glass hit (Bounce::fresnel)
  };
  // A tile's NodeGeometry, node by node, as structure of arrays that the packet tracer's
  // kernels read in place: P, N, the geometric normal, V = -D (the ray reversed,
  // exactly), the offset and F. The arrays are at least lanes() long (pad() zeroes the lanes
  // past the last node) and keep their length when cleared, so a tile recorded again over them
  // writes in place.
  struct Geometry {
    std::vector<double> px, py, pz, nx, ny, nz, gx, gy, gz, vx, vy, vz, offset, fresnel;
    std::size_t count = 0;      // nodes
    bool same_normals = false;  // after pad(): every node's geometric normal is its shading normal
    std::size_t lanes() const { return static_cast<std::size_t>(packet::padded_lanes(static_cast<int>(count))); }
    void push_back(const NodeGeometry& g);
    NodeGeometry operator[](std::size_t i) const {
      return {{px[i], py[i], pz[i]}, {nx[i], ny[i], nz[i]}, {gx[i], gy[i], gz[i]}, {-vx[i], -vy[i], -vz[i]}, offset[i],
              fresnel[i]};
    }
    void pad();
    void clear() { count = 0; }
    std::size_t bytes() const { return px.capacity() * 14 * sizeof(double); }
  };
  // One light at a node, for the trees' scene: N.L and the specular factor (hot), whether its
  // shadow ray got through, and the specular cosine the factor came from. A blocked light's
  // factor is never read (trees recorded in packets leave it 0; it is taken again when the light
  // moves, n or the model changes).
  struct NodeLight {
    double n_dot_l = 0, spec = 0;
  };
  static constexpr std::int32_t kNone = -1;    // no such ray was traced
  static constexpr std::int32_t kMissed = -2;  // the ray was traced and met nothing

  // The trees of one tile of pixels, as structure of arrays (per node; per node and light, light
  // by light within a node).
  struct Tile {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    std::vector<Node> nodes;
    Geometry geometry;
    std::vector<NodeLight> lights;
    std::vector<LightSeen> seen;
    std::vector<double> cos_spec;
    std::vector<std::int32_t> roots;  // per pixel, row by row: node, or kMissed
    std::vector<std::uint64_t> reach;  // per pixel: reach_bit of every material in its tree, kBackground
    std::vector<Color> values;         // per pixel: its value as last computed (for values_term_)
  };
  // The stored hits a moved light reaches in the walk of the trees' term, for the live path of
  // its drag: one tile's, node by node beside Tile::geometry (which the packet light and
  // shadow kernels read in place), and each pixel's value without the light's share.
  struct LightHits {
    std::vector<std::uint8_t> active;  // 1 for a node the walk reaches with a part the light lights, padded
    std::vector<Color> w;              // the kr'/kt' chain above the node
    std::vector<std::uint32_t> tag;    // the pixel within the tile (bits 0-7, as Tile::roots), whether the
                                       // term takes the hit's diffuse (bit 8) and specular (bit 9) part, the material (16-31)
    std::vector<Color> rest;           // per pixel: its value less the light's share
    std::size_t reached = 0;           // nodes with active set
    std::size_t bytes() const {
      return active.capacity() + (w.capacity() + rest.capacity()) * sizeof(Color) + tag.capacity() * sizeof(std::uint32_t);
    }
  };
  // A pixel whose tree meets none of the materials an edit changed (and no background, when
  // that changed) keeps its value: material i is bit i mod 63; bit 63 is a ray that met nothing.
  static constexpr std::uint64_t kBackground = std::uint64_t{1} << 63;
  static std::uint64_t reach_bit(int material) { return std::uint64_t{1} << (static_cast<unsigned>(material) % 63u); }

 private:
  RayTrees() = default;
  std::shared_ptr<const PreparedScene> scene_;  // the scene the stored values describe
  int width_ = 0, height_ = 0;
  std::optional<Vec3> shading_eye_;
  std::vector<Tile> tiles_;
  Term values_term_ = Term::kFull;
  bool values_valid_ = true;  // false after a cancelled re-shade: Tile::values are partly another scene's
  bool sums_refused_ = false; // a sum the trees cannot give (a child ray not stored): no live path for scene_
  bool usable_ = true;
  std::size_t budget_bytes_ = 0;  // what record() was given: the live path's arrays stay within it too
  bool moved_over_budget_ = false; // a moved light's arrays would not fit it: no live path for scene_
  std::size_t traced_pixels_ = 0;  // pixels the last re-shade traced rays for
  double record_seconds_ = 0;
  // The per-pixel sums of the live path, for scene_ (dropped when it changes): tile by tile,
  // pixel by pixel as Tile::roots.
  struct Sums {
    std::uint8_t coefficient = 0;  // ka, kd, ks of material `index`, Ia, or light `index`'s intensity
    int index = 0;
    Term term = Term::kFull;
    std::vector<std::vector<Color>> tiles;
  };
  std::vector<Sums> sums_;
  // The live path of a moved light, for scene_ (dropped with the sums): the light's hits.
  struct MovedLight {
    int light = -1;  // none: `tiles` are only memory to reuse
    Term term = Term::kFull;
    std::vector<LightHits> tiles;
  };
  MovedLight moved_;
  bool gather_light_hits(int light, Term term, int threads, const std::atomic<bool>* cancel, std::vector<RayCounts>& counts);
  PassStats recombine_moved(const PreparedScene& scene, int light, Term term, int threads, Accumulator& accum,
                            const std::atomic<bool>* cancel);
  std::uint64_t live_reach_ = ~std::uint64_t{0};  // the reach bits of the pixels the last recombine changed
  const Sums* sums_for(std::uint8_t coefficient, int index, Term term) const;
  void drop_sums() {
    sums_.clear();
    moved_.light = -1;  // its arrays' memory stays for the next one
    moved_over_budget_ = false;
    sums_refused_ = false;
  }
};

}  // namespace phonglab
