#include "core/render/ray_trees.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <utility>

#include "core/packet/packet.h"
#include "core/render/scene_changes.h"
#include "core/render/shadow_rays.h"
#include "core/base/threads.h"
#include "core/render/tile_work.h"
#include "core/shading/experiment.h"

namespace phonglab {

namespace {

}  // namespace

EditScope edit_scope(const Scene& a, const Scene& b) { return changes_between(a, b).scope(); }

bool reshades(Term term) { return is_equation_term(term) && term != Term::kIndirect; }

void RayTrees::Geometry::push_back(const NodeGeometry& g) {
  if (count == px.size()) {
    for (std::vector<double>* v : {&px, &py, &pz, &nx, &ny, &nz, &gx, &gy, &gz, &vx, &vy, &vz, &offset, &fresnel}) {
      v->resize(std::max<std::size_t>(64, 2 * count));
    }
  }
  const std::size_t i = count++;
  px[i] = g.p.x, py[i] = g.p.y, pz[i] = g.p.z;
  nx[i] = g.n.x, ny[i] = g.n.y, nz[i] = g.n.z;
  gx[i] = g.ng.x, gy[i] = g.ng.y, gz[i] = g.ng.z;
  vx[i] = -g.dir.x, vy[i] = -g.dir.y, vz[i] = -g.dir.z;
  offset[i] = g.offset, fresnel[i] = g.fresnel;
}

void RayTrees::Geometry::pad() {
  for (std::vector<double>* v : {&px, &py, &pz, &nx, &ny, &nz, &gx, &gy, &gz, &vx, &vy, &vz, &offset, &fresnel}) {
    if (v->size() < lanes()) v->resize(lanes());
    std::fill(v->begin() + static_cast<std::ptrdiff_t>(count), v->begin() + static_cast<std::ptrdiff_t>(lanes()), 0.0);
  }
  same_normals = std::equal(nx.begin(), nx.begin() + static_cast<std::ptrdiff_t>(count), gx.begin()) &&
                 std::equal(ny.begin(), ny.begin() + static_cast<std::ptrdiff_t>(count), gy.begin()) &&
                 std::equal(nz.begin(), nz.begin() + static_cast<std::ptrdiff_t>(count), gz.begin());
}

namespace {

constexpr int kTile = 16;

using Node = RayTrees::Node;
using NodeLight = RayTrees::NodeLight;
using NodeGeometry = RayTrees::NodeGeometry;
using Tile = RayTrees::Tile;

// Keeps one tile's trees as the tracer reports them.
class TileRecorder final : public TraceRecorder {
 public:
  TileRecorder(Tile& tile, std::size_t lights) : tile_(tile), lights_(lights) {}

  std::int32_t root() const { return root_; }
  std::uint64_t reach() const { return reach_; }
  void ray_missed() override {
    reach_ |= RayTrees::kBackground;
    link(RayTrees::kMissed);
  }
  void begin_hit(const Ray& ray, const Hit& hit, const HitSide& side, double offset, int depth) override {
    const auto index = static_cast<std::int32_t>(tile_.nodes.size());
    reach_ |= RayTrees::reach_bit(hit.material);
    Node node;
    node.material = hit.material;
    node.depth = static_cast<std::int16_t>(depth);
    node.entering = side.entering;
    tile_.nodes.push_back(node);
    // No weight: a re-shade derives every weight afresh, from the root down.
    tile_.geometry.push_back(NodeGeometry{hit.p, side.n, side.ng, ray.dir, offset});
    tile_.lights.resize(tile_.lights.size() + lights_);
    tile_.seen.resize(tile_.seen.size() + lights_, LightSeen::kNoLight);
    tile_.cos_spec.resize(tile_.cos_spec.size() + lights_);
    link(index);
    open_.push_back(index);
  }
  void light(int index, LightSeen seen, double n_dot_l, double cos_spec, double spec) override {
    const std::size_t at = static_cast<std::size_t>(open_.back()) * lights_ + static_cast<std::size_t>(index);
    tile_.lights[at] = NodeLight{n_dot_l, spec};
    tile_.seen[at] = seen;
    tile_.cos_spec[at] = cos_spec;
  }
  void bounced(const Bounce& b) override { tile_.geometry.fresnel[static_cast<std::size_t>(open_.back())] = b.fresnel; }
  void begin_child(Child kind) override { child_ = kind; }
  void end_hit() override { open_.pop_back(); }

 private:
  void link(std::int32_t to) {
    if (open_.empty()) {
      root_ = to;
      return;
    }
    Node& parent = tile_.nodes[static_cast<std::size_t>(open_.back())];
    (child_ == Child::kReflection ? parent.reflection : parent.refraction) = to;
  }

  Tile& tile_;
  std::size_t lights_;
  std::vector<std::int32_t> open_;  // the hits whose children are being traced, innermost last
  Child child_ = Child::kReflection;
  std::int32_t root_ = RayTrees::kMissed;
  std::uint64_t reach_ = 0;
};

// Keeps one tile's trees as the packet tracer reports them, level by level: the same nodes,
// lights and links TileRecorder keeps (in another order, which no re-shade depends on).
class PacketTileSink final : public PacketTreeSink {
 public:
  PacketTileSink(Tile& tile, std::size_t lights) : tile_(tile), lights_(lights) {
    const auto pixels = static_cast<std::size_t>((tile.x1 - tile.x0) * (tile.y1 - tile.y0));
    tile.roots.assign(pixels, RayTrees::kMissed);
    tile.reach.assign(pixels, 0);
  }
  void missed(int pixel, std::int32_t parent, TraceRecorder::Child kind) override {
    tile_.reach[static_cast<std::size_t>(pixel)] |= RayTrees::kBackground;
    link(pixel, parent, kind, RayTrees::kMissed);
  }
  std::int32_t hit(int pixel, std::int32_t parent, TraceRecorder::Child kind, int depth, int material, bool entering,
                   const Vec3& p, const Vec3& n, const Vec3& ng, const Vec3& dir, double offset) override {
    const auto index = static_cast<std::int32_t>(tile_.nodes.size());
    tile_.reach[static_cast<std::size_t>(pixel)] |= RayTrees::reach_bit(material);
    Node node;
    node.material = material;
    node.depth = static_cast<std::int16_t>(depth);
    node.entering = entering;
    tile_.nodes.push_back(node);
    tile_.geometry.push_back(NodeGeometry{p, n, ng, dir, offset});
    tile_.lights.resize(tile_.lights.size() + lights_);
    tile_.seen.resize(tile_.seen.size() + lights_, LightSeen::kNoLight);
    tile_.cos_spec.resize(tile_.cos_spec.size() + lights_);
    link(pixel, parent, kind, index);
    return index;
  }
  void light(std::int32_t node, int index, LightSeen seen, double n_dot_l, double cos_spec, double spec) override {
    const std::size_t at = static_cast<std::size_t>(node) * lights_ + static_cast<std::size_t>(index);
    tile_.lights[at] = NodeLight{n_dot_l, spec};
    tile_.seen[at] = seen;
    tile_.cos_spec[at] = cos_spec;
  }
  void bounced(std::int32_t node, double fresnel) override { tile_.geometry.fresnel[static_cast<std::size_t>(node)] = fresnel; }

 private:
  void link(int pixel, std::int32_t parent, TraceRecorder::Child kind, std::int32_t to) {
    if (parent < 0) {
      tile_.roots[static_cast<std::size_t>(pixel)] = to;
      return;
    }
    Node& p = tile_.nodes[static_cast<std::size_t>(parent)];
    (kind == TraceRecorder::Child::kReflection ? p.reflection : p.refraction) = to;
  }

  Tile& tile_;
  std::size_t lights_;
};

std::size_t tile_bytes(const Tile& t) {
  return t.nodes.capacity() * sizeof(Node) + t.geometry.bytes() +
         t.lights.capacity() * sizeof(NodeLight) + t.seen.capacity() * sizeof(LightSeen) +
         t.cos_spec.capacity() * sizeof(double) + t.roots.capacity() * sizeof(std::int32_t) +
         t.reach.capacity() * sizeof(std::uint64_t) + t.values.capacity() * sizeof(Color);
}

// work(tile, counts) for every tile (tile_work.h).
template <class Work>
bool for_each_tile(std::vector<Tile>& tiles, int threads, const std::atomic<bool>* cancel, std::atomic<bool>& stop,
                   std::vector<RayCounts>& counts, Work&& work) {
  return for_each_index(tiles.size(), threads, cancel, stop, counts,
                        [&](std::size_t i, RayCounts& rays) { work(tiles[i], rays); });
}

// The image's tiles, row by row.
std::vector<Tile> make_tiles(int width, int height) {
  std::vector<Tile> tiles;
  for (int y0 = 0; y0 < height; y0 += kTile) {
    for (int x0 = 0; x0 < width; x0 += kTile) {
      Tile t;
      t.x0 = x0;
      t.y0 = y0;
      t.x1 = std::min(x0 + kTile, width);
      t.y1 = std::min(y0 + kTile, height);
      tiles.push_back(std::move(t));
    }
  }
  return tiles;
}


// Sample 0's primary ray through pixel (x, y), as render_sample makes it.
Ray centre_ray(const CameraFrame& frame, int x, int y) {
  double u = 0, v = 0;
  sample_offset(x, y, 0, u, v, 0);
  return camera_ray(frame, x, y, u, v);
}

// Shadow rays waiting for their answers: a tile's at once, light by light, so the packet tracer
// tests only the spheres each bundle can meet.
struct ShadowBatch {
  struct Rays {
    ShadowRays rays;
    std::vector<std::size_t> at;  // where each answer goes (Tile::seen)
  };
  std::vector<Rays> lights;  // by light
  std::vector<std::uint8_t> blocked;

  void push(std::size_t light, const Ray& ray, double t, std::size_t to) {
    if (lights.size() <= light) lights.resize(light + 1);
    Rays& r = lights[light];
    r.rays.push(ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z, t);
    r.at.push_back(to);
  }
  // Answers every ray into `tile.seen` and empties the batch.
  void resolve(const PreparedScene& prepared, Tile& tile, RayCounts& counts) {
    const bool packets = packet_tracing_applies(prepared);
    for (std::size_t li = 0; li < lights.size(); ++li) {
      Rays& r = lights[li];
      const std::size_t n = r.at.size();
      if (n == 0) continue;
      counts.shadow += n;
      answer_shadow_rays(prepared, prepared.scene().lights[li], packets, r.rays, blocked);
      for (std::size_t i = 0; i < n; ++i) tile.seen[r.at[i]] = blocked[i] ? LightSeen::kBlocked : LightSeen::kVisible;
      r.rays.clear();
      r.at.clear();
    }
  }
};

// Brings node i's stored lights up to `scene` (the same arithmetic as the tracer's light loop);
// the shadow rays towards moved lights go into `batch`.
void update_lights(const PreparedScene& prepared, const Changes& changes, Tile& tile, std::size_t i, const Vec3* eye,
                   ShadowBatch& batch) {
  const Scene& scene = prepared.scene();
  const std::size_t lights = scene.lights.size();
  const Node& node = tile.nodes[i];
  const Material& m = scene.materials[static_cast<std::size_t>(node.material)];
  std::optional<NodeGeometry> geometry;  // read from the arrays only for a light that needs it
  for (std::size_t li = 0; li < lights; ++li) {
    const std::size_t at = i * lights + li;
    NodeLight& nl = tile.lights[at];
    LightSeen& seen = tile.seen[at];
    const bool moved = changes.light_moved[li];
    if (!moved && !changes.model_changed && !(changes.eye_moved && node.depth == 0)) {
      if (changes.n_changed[static_cast<std::size_t>(node.material)] && seen != LightSeen::kNoLight) {
        nl.spec = specular_factor(tile.cos_spec[at], m.n);
      }
      continue;
    }
    if (!geometry) geometry = tile.geometry[i];
    const NodeGeometry& g = *geometry;
    const Light& light = scene.lights[li];
    Vec3 l;
    double dist = 0;
    const bool has_direction = light_direction(light, g.p, l, dist);
    const double n_dot_l = has_direction ? glm::dot(g.n, l) : 0;
    if (!(n_dot_l > 0)) {
      nl = NodeLight{n_dot_l, 0};
      seen = LightSeen::kNoLight;
      tile.cos_spec[at] = 0;
      continue;
    }
    Vec3 r;
    const Vec3 v = view_direction(g.p, g.dir, node.depth == 0 ? eye : nullptr);
    tile.cos_spec[at] = specular_cosine(scene.specular_model, g.n, l, v, n_dot_l, r);
    nl = NodeLight{n_dot_l, specular_factor(tile.cos_spec[at], m.n)};
    if (!moved && seen != LightSeen::kNoLight) continue;  // the same shadow ray as before
    Ray ray;
    double t_max = 0;
    seen = LightSeen::kVisible;  // unless the batch finds a blocker
    if (shadow_ray(light, g.p, g.ng, l, g.offset, ray, t_max)) batch.push(li, ray, t_max, at);
  }
}

// Brings node i's Fresnel factor up to its material's kr, kt, ior and Fresnel switch (the
// tracer's bounce()); with another ior its refracted ray goes elsewhere and is traced again.
void update_bounce(const Scene& scene, const Changes& changes, Tile& tile, std::size_t i) {
  Node& node = tile.nodes[i];
  const auto material = static_cast<std::size_t>(node.material);
  // F is recorded only where the tracer bounced: a hit below the old depth limit had none.
  if (!changes.bounce_changed[material] && !changes.depth_grew) return;
  const NodeGeometry g = tile.geometry[i];
  tile.geometry.fresnel[i] = bounce(scene.materials[material], g.dir, g.n, node.entering).fresnel;
  if (changes.ior_changed[material]) node.refraction = RayTrees::kNone;
}

// The local terms an experiment gives at one tile's stored hits (one that changes them alone:
// Experiment::local_terms_only), asked for all at once so that a formula runs lane by lane: the
// ambient term per node, and per node and light the share of each enabled light its shadow ray
// reached, at the nodes of the materials the experiment lights.
struct LocalTerms {
  std::vector<Color> ambient;       // per node
  std::vector<LightShare> shares;   // per node and light, as Tile::lights (only those asked for)
  std::vector<std::uint8_t> lit;    // per material: Experiment::lit
  std::vector<LocalHit> hits;       // scratch
  std::vector<std::size_t> at;      // scratch: where each share goes
  std::vector<LightShare> batch;    // scratch
  std::vector<LocalHit> block;      // scratch

  void compute(const Experiment& e, const Scene& scene, const Tile& tile, const Vec3* eye) {
    const std::size_t nodes = tile.nodes.size(), lights = scene.lights.size();
    lit.resize(scene.materials.size());
    for (std::size_t m = 0; m < scene.materials.size(); ++m) lit[m] = e.lit(scene.materials[m]) ? 1 : 0;
    hits.resize(nodes);
    for (std::size_t i = 0; i < nodes; ++i) {
      const Node& node = tile.nodes[i];
      const NodeGeometry g = tile.geometry[i];
      hits[i] = LocalHit{&scene, &scene.materials[static_cast<std::size_t>(node.material)], nullptr, g.p, g.n, Vec3(0),
                         view_direction(g.p, g.dir, node.depth == 0 ? eye : nullptr), 0, 0};
    }
    ambient.resize(nodes);
    e.ambient_batch(hits.data(), nodes, ambient.data());
    // The lights: each node's hit again with every enabled light its shadow ray reached.
    at.clear();
    for (std::size_t i = 0; i < nodes; ++i) {
      if (!lit[static_cast<std::size_t>(tile.nodes[i].material)]) continue;
      for (std::size_t li = 0; li < lights; ++li) {
        const std::size_t k = i * lights + li;
        if (scene.lights[li].enabled && tile.seen[k] == LightSeen::kVisible) at.push_back(k);
      }
    }
    const std::size_t count = at.size();
    if (count == 0) return;
    shares.resize(nodes * lights);
    batch.resize(count);
    // In blocks, so the hits asked for stay in cache with their answers.
    constexpr std::size_t kBlock = 256;
    block.resize(std::min(count, kBlock));
    for (std::size_t first = 0; first < count; first += kBlock) {
      const std::size_t n = std::min(kBlock, count - first);
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t k = at[first + j];
        const std::size_t i = k / lights, li = k % lights;
        LocalHit h = hits[i];
        h.light = &scene.lights[li];
        double dist = 0;
        light_direction(*h.light, h.p, h.l, dist);
        h.n_dot_l = tile.lights[k].n_dot_l;
        h.spec = tile.lights[k].spec;
        block[j] = h;
      }
      e.light_share_batch(block.data(), n, batch.data() + first);
    }
    for (std::size_t j = 0; j < count; ++j) shares[at[j]] = batch[j];
  }
};

// The equation over one tile's stored trees, for `scene`; with kExperiment, its local terms are
// the experiment's, from `local` (computed for this tile and scene).
template <bool kExperiment>
class TileShader {
 public:
  TileShader(const PreparedScene& prepared, const Tile& tile, RayCounts& counts, const LocalTerms* local = nullptr)
      : prepared_(prepared), scene_(prepared.scene()), tile_(tile), counts_(counts),
        lights_(scene_.lights.size()), local_(local) {}

  // The terms of node i, as shade() gives them. Inlined where the pixel loop calls it for a root
  // (most nodes are roots); children go through child_terms.
  [[gnu::always_inline]] inline Terms terms(std::int32_t i, const TermsWanted& wanted, double weight) {
    const Node& node = tile_.nodes[static_cast<std::size_t>(i)];
    const Material& m = scene_.materials[static_cast<std::size_t>(node.material)];
    Terms t;
    if constexpr (kExperiment) {
      t.ambient = local_->ambient[static_cast<std::size_t>(i)];
      if (wanted.lights && local_->lit[static_cast<std::size_t>(node.material)]) {
        const std::size_t first = static_cast<std::size_t>(i) * lights_;
        const LightSeen* seen = tile_.seen.data() + first;
        for (std::size_t li = 0; li < lights_; ++li) {
          if (!scene_.lights[li].enabled || seen[li] != LightSeen::kVisible) continue;
          const LightShare& share = local_->shares[first + li];
          t.diffuse += share.diffuse;
          t.specular += share.specular;
        }
      }
    } else {
      t.ambient = m.ka * scene_.ambient;
      if (wanted.lights && is_lit(m)) {
        const bool has_specular = !is_zero(m.ks);
        const std::size_t first = static_cast<std::size_t>(i) * lights_;
        const NodeLight* lights = tile_.lights.data() + first;
        const LightSeen* seen = tile_.seen.data() + first;
        for (std::size_t li = 0; li < lights_; ++li) {
          const Light& light = scene_.lights[li];
          if (!light.enabled || seen[li] != LightSeen::kVisible) continue;
          add_light(light, m, lights[li].n_dot_l, has_specular ? lights[li].spec : 0.0, t.diffuse, t.specular);
        }
      }
    }
    if (!(node.depth < scene_.max_depth && has_children(m))) return t;
    // kr' and kt' from the stored F (the directions are needed only for a ray not stored).
    Bounce bn;
    bn.fresnel = tile_.geometry.fresnel[static_cast<std::size_t>(i)];
    set_bounce_weights(m, bn);
    if (wanted.reflection) t.reflection = child(node, i, bn.kr, weight, Child::kReflection, node.reflection);
    if (wanted.refraction && !is_zero(bn.kt)) {
      t.refraction = child(node, i, bn.kt, weight, Child::kRefraction, node.refraction);
    }
    return t;
  }

  // Whether a ray was traced because it was not stored since the last call (then the pixel's
  // value depends on what its stored tree does not show).
  bool traced_fresh() { return std::exchange(traced_fresh_, false); }

 private:
  // kw times what the child ray brings back (the Equation's child()).
  [[gnu::noinline]] Terms child_terms(std::int32_t i, double weight) { return terms(i, TermsWanted{}, weight); }

  using Child = TraceRecorder::Child;
  Color child(const Node& node, std::int32_t i, const Color& kw, double weight, Child kind, std::int32_t stored) {
    const std::optional<double> w = child_weight(kw, weight, scene_.min_weight);
    if (!w) return Color(0);
    if (stored == RayTrees::kMissed) return kw * scene_.background;
    if (stored >= 0) return kw * child_terms(stored, *w).sum();
    traced_fresh_ = true;
    // Not stored (it cannot happen below kRetrace): traced as the tracer would.
    const Material& m = scene_.materials[static_cast<std::size_t>(node.material)];
    const NodeGeometry g = tile_.geometry[static_cast<std::size_t>(i)];
    const Bounce bn = bounce(m, g.dir, g.n, node.entering);
    const Vec3& dir = kind == Child::kReflection ? bn.mirror : bn.refracted;
    const Ray ray = make_ray(offset_origin(g.p, g.ng, dir, g.offset), dir);
    return kw * trace(prepared_, TraceLimits{scene_.max_depth, scene_.min_weight}, ray, node.depth + 1, *w, counts_);
  }

  const PreparedScene& prepared_;
  const Scene& scene_;
  const Tile& tile_;
  RayCounts& counts_;
  std::size_t lights_;
  const LocalTerms* local_;
  bool traced_fresh_ = false;
};

}  // namespace

std::unique_ptr<RayTrees> RayTrees::record(std::shared_ptr<const PreparedScene> scene, int width, int height,
                                           const std::optional<Vec3>& shading_eye, int threads,
                                           std::size_t budget_bytes, const std::atomic<bool>* cancel,
                                           bool allow_packets, std::unique_ptr<RayTrees> recycled) {
  if (!scene || width <= 0 || height <= 0) return nullptr;
  if (const Experiment* e = scene->experiment()) {
    if (!e->local_terms_only()) return nullptr;
    // Its rays are production's: the trees of the production twin (the same accelerator), which
    // a re-shade then shades with the experiment's local terms.
    scene = std::make_shared<const PreparedScene>(scene->without_experiment());
  }
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<RayTrees> trees(new RayTrees);
  trees->scene_ = scene;
  trees->width_ = width;
  trees->height_ = height;
  trees->shading_eye_ = shading_eye;
  trees->budget_bytes_ = budget_bytes;
  trees->tiles_ = make_tiles(width, height);
  if (recycled && recycled->tiles_.size() == trees->tiles_.size()) {
    // The old tiles' arrays, emptied: their memory is already the process's.
    for (std::size_t i = 0; i < trees->tiles_.size(); ++i) {
      Tile& old = recycled->tiles_[i];
      Tile& t = trees->tiles_[i];
      old.nodes.clear(), old.geometry.clear(), old.lights.clear(), old.seen.clear(), old.cos_spec.clear();
      old.roots.clear(), old.reach.clear(), old.values.clear();
      std::swap(t.nodes, old.nodes), std::swap(t.geometry, old.geometry), std::swap(t.lights, old.lights);
      std::swap(t.seen, old.seen), std::swap(t.cos_spec, old.cos_spec), std::swap(t.roots, old.roots);
      std::swap(t.reach, old.reach), std::swap(t.values, old.values);
    }
    trees->moved_.tiles = std::move(recycled->moved_.tiles);  // a moved light's arrays, likewise
  }
  recycled.reset();
  const Scene& s = scene->scene();
  const CameraFrame frame = make_camera_frame(s.camera, width, height);
  const TraceLimits limits{s.max_depth, s.min_weight};
  const Vec3* eye = shading_eye ? &*shading_eye : nullptr;
  std::atomic<std::size_t> bytes{0};
  std::atomic<bool> stop{false};
  std::vector<RayCounts> counts;
  // In packets where the packet tracer serves the scene: the same trees, a few times sooner.
  const bool packets = allow_packets && packet_tracing_applies(*scene);
  const bool done = for_each_tile(trees->tiles_, threads, cancel, stop, counts, [&](Tile& tile, RayCounts& rays) {
    const auto pixels = static_cast<std::size_t>((tile.x1 - tile.x0) * (tile.y1 - tile.y0));
    if (packets) {
      PacketTileSink sink(tile, s.lights.size());
      tile.values.resize(pixels);
      packet_tracer_for(*scene).record_tile(frame, tile.x0, tile.y0, tile.x1, tile.y1, eye, sink, tile.values.data(), rays);
      tile.geometry.pad();
      if (bytes.fetch_add(tile_bytes(tile)) + tile_bytes(tile) > budget_bytes) stop.store(true);
      return;
    }
    tile.roots.reserve(pixels);
    tile.reach.reserve(pixels);
    tile.values.reserve(pixels);
    for (int y = tile.y0; y < tile.y1; ++y) {
      for (int x = tile.x0; x < tile.x1; ++x) {
        TileRecorder recorder(tile, s.lights.size());
        tile.values.push_back(trace_recorded(*scene, limits, centre_ray(frame, x, y), rays, recorder, eye));
        tile.roots.push_back(recorder.root());
        tile.reach.push_back(recorder.reach());
      }
    }
    tile.geometry.pad();
    if (bytes.fetch_add(tile_bytes(tile)) + tile_bytes(tile) > budget_bytes) stop.store(true);
  });
  if (!done) return nullptr;
  trees->record_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trees;
}

EditScope RayTrees::scope_for(const PreparedScene& scene, int width, int height,
                              const std::optional<Vec3>& shading_eye) const {
  const Experiment* e = scene.experiment();
  if (!usable_ || width != width_ || height != height_ || (e != nullptr && !e->local_terms_only())) {
    return EditScope::kRetrace;
  }
  Changes changes = changes_between(scene_->scene(), scene.scene());
  changes.eye_moved = shading_eye != shading_eye_;
  const EditScope scope = changes.scope();
  // Other local terms (a formula typed, another mistake) are a shading edit of every pixel.
  return scope == EditScope::kNothing && e != scene_->experiment() ? EditScope::kShading : scope;
}

PassStats RayTrees::reshade(std::shared_ptr<const PreparedScene> scene, Term term,
                            const std::optional<Vec3>& shading_eye, int threads, Accumulator& accum,
                            const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  const Scene& s = scene->scene();
  Changes changes = changes_between(scene_->scene(), s);
  changes.eye_moved = shading_eye != shading_eye_;
  const bool update = changes.stale_hits();
  const Vec3* eye = shading_eye ? &*shading_eye : nullptr;
  // With term images every pixel is shaded whole: only its value is kept from pass to pass.
  const bool with_terms = accum.has_terms();
  const TermsWanted wanted = with_terms ? TermsWanted{} : terms_wanted(term);
  // Local terms of an experiment, now or in the stored values: every pixel is shaded again.
  const Experiment* experiment = scene->experiment();
  const std::uint64_t dirty = with_terms || !values_valid_ || experiment || scene_->experiment()
                                  ? ~std::uint64_t{0}
                                  : changes.dirty_reach(term != values_term_);
  std::atomic<bool> stop{false};
  std::vector<RayCounts> counts;
  std::atomic<std::uint64_t> nan_count{0};
  std::atomic<std::size_t> traced_pixels{0};
  // One tile's pixels, by a shader of the production terms or of the experiment's.
  const auto shade_pixels = [&](Tile& tile, auto& shader) {
    std::size_t pixel = 0;
    for (int y = tile.y0; y < tile.y1; ++y) {
      const std::size_t row_start = static_cast<std::size_t>(y) * static_cast<std::size_t>(accum.width);
      Color* row = accum.sum.data() + row_start;
      for (int x = tile.x0; x < tile.x1; ++x, ++pixel) {
        if (tile.reach[pixel] & dirty) {
          const std::int32_t root = tile.roots[pixel];
          if (!with_terms) {
            tile.values[pixel] = root == kMissed ? miss_value(s, term)
                                 : term == Term::kFull ? shader.terms(root, wanted, 1.0).sum()
                                                       : term_value(shader.terms(root, wanted, 1.0), term);
          } else {
            const Terms t = root == kMissed ? Terms{} : shader.terms(root, wanted, 1.0);
            tile.values[pixel] = root == kMissed ? miss_value(s, term) : term_value(t, term);
            Terms& sums = accum.terms[row_start + static_cast<std::size_t>(x)];
            sums = Terms{};
            add_terms(sums, t);  // what render_pass adds to the empty sums
          }
          if (shader.traced_fresh()) {
            tile.reach[pixel] = ~std::uint64_t{0};  // any later edit re-shades it
            traced_pixels.fetch_add(1, std::memory_order_relaxed);
          }
        }
        Color c = tile.values[pixel];
        if (!all_finite(c)) {  // as render_pass replaces them
          c = Color(0);
          nan_count.fetch_add(1, std::memory_order_relaxed);
        }
        row[x] = Color(0) + c;  // what render_pass adds to the empty sum, without reading it
      }
    }
  };
  const bool done = for_each_tile(tiles_, threads, cancel, stop, counts, [&](Tile& tile, RayCounts& rays) {
    if (update) {
      thread_local ShadowBatch batch;
      for (std::size_t i = 0; i < tile.nodes.size(); ++i) {
        update_lights(*scene, changes, tile, i, eye, batch);
        update_bounce(s, changes, tile, i);
      }
      batch.resolve(*scene, tile, rays);
    }
    if (experiment) {
      thread_local LocalTerms local;
      local.compute(*experiment, s, tile, eye);
      TileShader<true> shader(*scene, tile, rays, &local);
      shade_pixels(tile, shader);
    } else {
      TileShader<false> shader(*scene, tile, rays);
      shade_pixels(tile, shader);
    }
  });
  PassStats stats;
  for (const RayCounts& c : counts) stats.rays += c;
  stats.nan_count = nan_count.load();
  traced_pixels_ = traced_pixels.load();
  stats.completed = done;
  if (done) {
    ++accum.samples;
    if (scene != scene_) drop_sums();  // they describe the trees' scene
    scene_ = std::move(scene);
    values_term_ = term;
    values_valid_ = true;
    shading_eye_ = shading_eye;
  } else if (update) {
    usable_ = false;  // some tiles describe the new scene, some the old
  } else {
    values_valid_ = false;  // only values changed, some of them: the next re-shade shades every pixel
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

std::size_t RayTrees::memory_bytes() const {
  std::size_t bytes = tiles_.capacity() * sizeof(Tile);
  for (const Tile& t : tiles_) bytes += tile_bytes(t);
  for (const Sums& sums : sums_) {
    for (const std::vector<Color>& t : sums.tiles) bytes += t.capacity() * sizeof(Color);
  }
  for (const LightHits& h : moved_.tiles) bytes += h.bytes();
  return bytes;
}

std::size_t RayTrees::node_count() const {
  std::size_t n = 0;
  for (const Tile& t : tiles_) n += t.nodes.size();
  return n;
}

}  // namespace phonglab
