// The live path of a slider: an edit the image is linear in is the trees' last exact image plus
// the edited coefficients' changes times the per-pixel sums they multiply (docs/speed.md,
// "Live re-shading"). For ka, kd or ks of material m the sum runs over m's hits of the pixel's
// tree, each weighted by the kr'/kt' chain above it: ka multiplies w·Iₐ, kd multiplies
// w·Σ_l vis_l·I_l·(N·L), ks multiplies w·Σ_l vis_l·I_l·spec_l. For Iₐ it is Σ w·ka; for a light's
// intensity Σ w·vis·(kd·(N·L) + ks·spec). The walk is TileShader::terms' with the coefficient
// taken out: the same stored cosines, visibilities, Fresnel factors and pruning.
//
// A moved light (scene_changes.h's kMovedLight) is not linear in its position, but only its
// share changes: each pixel's value less the light's old share (its intensity times the sum
// above) is kept, and the light's new share is summed over the stored hits the walk reaches,
// their N.L, specular cosine and shadow ray taken again four wide from the hits as structure of
// arrays, in place; only the hits facing the light cast a shadow ray, only visible ones with ks
// take a power.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/packet/packet.h"
#include "core/packet/packet_kernels.h"
#include "core/render/ray_trees.h"
#include "core/render/scene_changes.h"
#include "core/render/shadow_rays.h"
#include "core/render/tile_work.h"

namespace phonglab {

namespace {

using Node = RayTrees::Node;
using Tile = RayTrees::Tile;

enum Coefficient : std::uint8_t { kKa, kKd, kKs, kAmbient, kIntensity };

constexpr std::uint32_t kDiffuseBit = 1u << 8, kSpecularBit = 1u << 9;  // LightHits::tag

// One coefficient whose change the live image adds, with the change.
struct Delta {
  Coefficient coefficient;
  int index;  // the material's or the light's
  Color change;
};

Color effective_intensity(const Light& light) { return light.enabled ? light.intensity : Color(0); }

// The edited coefficients between the trees' scene `a` and `b`, for the linear family.
std::vector<Delta> deltas_between(const Scene& a, const Scene& b, const Changes& c) {
  std::vector<Delta> out;
  for (std::size_t i = 0; i < c.coefficients.size(); ++i) {
    if (!c.coefficients[i]) continue;
    const Material& x = a.materials[i];
    const Material& y = b.materials[i];
    const int m = static_cast<int>(i);
    if (x.ka != y.ka) out.push_back({kKa, m, y.ka - x.ka});
    if (x.kd != y.kd) out.push_back({kKd, m, y.kd - x.kd});
    if (x.ks != y.ks) out.push_back({kKs, m, y.ks - x.ks});
  }
  if (c.ambient_changed) out.push_back({kAmbient, 0, b.ambient - a.ambient});
  for (std::size_t l = 0; l < c.light_shading.size(); ++l) {
    if (c.light_shading[l]) {
      out.push_back({kIntensity, static_cast<int>(l), effective_intensity(b.lights[l]) - effective_intensity(a.lights[l])});
    }
  }
  return out;
}

// The sum that multiplies one coefficient in one pixel's value, over the stored tree.
class SumWalker {
 public:
  SumWalker(const Scene& scene, const Tile& tile, Coefficient coefficient, int index)
      : scene_(scene), tile_(tile), coefficient_(coefficient), index_(index), lights_(scene.lights.size()) {}

  // For kIntensity: also mark in `hits` every hit whose light loop the walk reaches (whatever
  // its stored visibility), with its weights, for the live path of light `index` moved.
  void keep_hits(RayTrees::LightHits* hits) { hits_ = hits; }
  void at_pixel(std::size_t pixel) { pixel_ = pixel; }

  // The pixel whose tree starts at `root`, for `term` (the root's own part of the equation, or
  // its child's whole subtree); false when a needed child ray is not stored (the exact re-shade
  // traced it: the sum cannot be taken from the tree).
  bool pixel(std::int32_t root, Term term, Color& out) {
    out = Color(0);
    complete_ = true;
    if (root >= 0) node(root, Color(1), 1.0, term, out);
    return complete_;
  }

 private:
  void node(std::int32_t i, const Color& w, double weight, Term part, Color& out) {
    const Node& n = tile_.nodes[static_cast<std::size_t>(i)];
    const Material& m = scene_.materials[static_cast<std::size_t>(n.material)];
    const bool mine = n.material == index_;
    if (part == Term::kFull || part == Term::kAmbient) {
      if (coefficient_ == kKa && mine) out += w * scene_.ambient;
      if (coefficient_ == kAmbient) out += w * m.ka;
    }
    if (part == Term::kFull || part == Term::kDiffuse || part == Term::kSpecular) lights(i, m, mine, w, part, out);
    if (part != Term::kFull && part != Term::kReflection && part != Term::kRefraction) return;
    if (!(n.depth < scene_.max_depth && has_children(m))) return;
    Bounce bn;
    bn.fresnel = tile_.geometry.fresnel[static_cast<std::size_t>(i)];
    set_bounce_weights(m, bn);
    if (part != Term::kRefraction) child(bn.kr, w, weight, n.reflection, out);
    if (part != Term::kReflection && !is_zero(bn.kt)) child(bn.kt, w, weight, n.refraction, out);
  }

  void lights(std::int32_t i, const Material& m, bool mine, const Color& w, Term part, Color& out) {
    const bool diffuse = part != Term::kSpecular, specular = part != Term::kDiffuse;
    const std::size_t first = static_cast<std::size_t>(i) * lights_;
    if (hits_ != nullptr && is_lit(m)) keep(i, m, w, diffuse, specular);
    for (std::size_t l = 0; l < lights_; ++l) {
      if (tile_.seen[first + l] != LightSeen::kVisible) continue;
      const Light& light = scene_.lights[l];
      const RayTrees::NodeLight& nl = tile_.lights[first + l];
      if (coefficient_ == kIntensity) {
        if (static_cast<int>(l) != index_) continue;
        if (diffuse) out += w * (m.kd * nl.n_dot_l);
        if (specular) out += w * (m.ks * nl.spec);
      } else if (light.enabled && mine) {
        if (coefficient_ == kKd && diffuse) out += w * (light.intensity * nl.n_dot_l);
        if (coefficient_ == kKs && specular) out += w * (light.intensity * nl.spec);
      }
    }
  }

  void child(const Color& kw, const Color& w, double weight, std::int32_t stored, Color& out) {
    const std::optional<double> cw = child_weight(kw, weight, scene_.min_weight);
    if (!cw || stored == RayTrees::kMissed) return;  // the background: no coefficient in it
    if (stored < 0) {
      complete_ = false;
      return;
    }
    node(stored, w * kw, *cw, Term::kFull, out);
  }

  // Hit i, seen through the chain w, as the moved light's kernels read it.
  void keep(std::int32_t i, const Material& m, const Color& w, bool diffuse, bool specular) {
    diffuse = diffuse && !is_zero(m.kd);
    specular = specular && !is_zero(m.ks);
    if (!diffuse && !specular) return;
    const auto at = static_cast<std::size_t>(i);
    const auto material = static_cast<std::uint32_t>(tile_.nodes[at].material);
    if (material > 0xffffu) complete_ = false;  // no room in the tag: no live path
    RayTrees::LightHits& h = *hits_;
    h.active[at] = 1;
    h.w[at] = w;
    h.tag[at] = static_cast<std::uint32_t>(pixel_) | (diffuse ? kDiffuseBit : 0u) | (specular ? kSpecularBit : 0u) |
                material << 16;
    ++h.reached;
  }

  const Scene& scene_;
  const Tile& tile_;
  Coefficient coefficient_;
  int index_;
  std::size_t lights_;
  bool complete_ = true;
  RayTrees::LightHits* hits_ = nullptr;
  std::size_t pixel_ = 0;
};

using LightHits = RayTrees::LightHits;
using Geometry = RayTrees::Geometry;

// A material as the moved light's share reads it: the light's products with its kd and ks
// (light_products, as both tracers form them) and its exponent.
struct LiveMaterial {
  LightProducts products;
  double n = 0;
};

// The specular factor for the live image, within a few ulps of specular_factor: an integer
// exponent (the usual n) by repeated squaring, at most 2·log2(n) roundings, instead of pow.
double live_specular_factor(double cos_spec, double n) {
  if (!(n >= 1 && n <= 65536 && n == std::floor(n))) return specular_factor(cos_spec, n);
  double base = clamp_positive(clamp_unit(cos_spec)), result = 1;
  for (auto k = static_cast<std::uint32_t>(n); k != 0; k >>= 1, base *= base) {
    result *= (k & 1u) != 0 ? base : 1.0;  // a select, not a branch the bits would mispredict
  }
  return result;
}

// One thread's scratch for a tile: V where the trees' eye moved the primary hits', the light
// loop's geometry at each node, the shadow rays that need a test, their answers, and the light's
// share per pixel.
struct LightScratch {
  std::vector<double> vx, vy, vz;
  std::vector<double> n_dot_l, cos_spec, ox, oy, oz, dx, dy, dz, t_max;
  ShadowRays shadow;                // those that need a test
  std::vector<std::size_t> tested;  // the node of each shadow ray
  std::vector<std::uint8_t> blocked;
  std::vector<Color> share;
};

// V at every node: the stored -D, but towards `eye` at the primary hits when the trees have one
// (view_direction, as the tracer takes it).
struct Views {
  const double *x, *y, *z;
};
Views views(const Tile& tile, const Vec3* eye, LightScratch& s) {
  const Geometry& g = tile.geometry;
  if (eye == nullptr) return {g.vx.data(), g.vy.data(), g.vz.data()};
  s.vx.assign(g.vx.begin(), g.vx.begin() + static_cast<std::ptrdiff_t>(g.lanes()));
  s.vy.assign(g.vy.begin(), g.vy.begin() + static_cast<std::ptrdiff_t>(g.lanes()));
  s.vz.assign(g.vz.begin(), g.vz.begin() + static_cast<std::ptrdiff_t>(g.lanes()));
  for (std::size_t i = 0; i < g.count; ++i) {
    if (tile.nodes[i].depth != 0) continue;
    const Vec3 v = view_direction(Vec3(g.px[i], g.py[i], g.pz[i]), Vec3(-g.vx[i], -g.vy[i], -g.vz[i]), eye);
    s.vx[i] = v.x, s.vy[i] = v.y, s.vz[i] = v.z;
  }
  return {s.vx.data(), s.vy.data(), s.vz.data()};
}

// N.L, the specular cosine and the shadow ray at every node the walk reached: the packet
// tracer's light kernel over the tile's geometry in place, or node by node through the same
// rules (shading.h) without packet kernels.
void light_geometry(const Scene& scene, const Light& light, const Tile& tile, const LightHits& h, const Views& v,
                    bool packets, LightScratch& s) {
  const Geometry& g = tile.geometry;
  const std::size_t lanes = g.lanes();
  // The geometric normals are the shading ones on spheres and planes: read those instead.
  const double* gx = g.same_normals ? g.nx.data() : g.gx.data();
  const double* gy = g.same_normals ? g.ny.data() : g.gy.data();
  const double* gz = g.same_normals ? g.nz.data() : g.gz.data();
  for (std::vector<double>* a : {&s.n_dot_l, &s.cos_spec, &s.ox, &s.oy, &s.oz, &s.dx, &s.dy, &s.dz, &s.t_max}) {
    a->resize(lanes);
  }
  if (packets) {
    packet::LightIn in{};
    in.point = light.type == LightType::kPoint;
    const Vec3 l = in.point ? light.position : -light.direction;
    in.x = l.x, in.y = l.y, in.z = l.z;
    in.shrink = in.point ? surface_offset(light.position, 0) : 0.0;
    in.blinn = scene.specular_model == SpecularModel::kBlinn;
    const packet::ShadedPoints pts{g.px.data(), g.py.data(), g.pz.data(), g.nx.data(),     g.ny.data(),
                                   g.nz.data(), gx,          gy,          gz,              v.x,
                                   v.y,         v.z,         g.offset.data(), h.active.data()};
    const packet::LightOut out{s.n_dot_l.data(), s.cos_spec.data(), s.ox.data(), s.oy.data(), s.oz.data(),
                               s.dx.data(),      s.dy.data(),       s.dz.data(), s.t_max.data()};
    packet::light(in, pts, static_cast<int>(lanes), out);
    return;
  }
  for (std::size_t i = 0; i < g.count; ++i) {
    if (!h.active[i]) continue;
    const Vec3 p(g.px[i], g.py[i], g.pz[i]), n(g.nx[i], g.ny[i], g.nz[i]);
    Vec3 l;
    double dist = 0;
    s.n_dot_l[i] = light_direction(light, p, l, dist) ? glm::dot(n, l) : std::numeric_limits<double>::quiet_NaN();
    if (!(s.n_dot_l[i] > 0)) continue;
    Vec3 r;
    s.cos_spec[i] = specular_cosine(scene.specular_model, n, l, Vec3(v.x[i], v.y[i], v.z[i]), s.n_dot_l[i], r);
    Ray ray{};
    double t_max = 0;
    if (!shadow_ray(light, p, Vec3(gx[i], gy[i], gz[i]), l, g.offset[i], ray, t_max)) t_max = 0;
    s.ox[i] = ray.origin.x, s.oy[i] = ray.origin.y, s.oz[i] = ray.origin.z;
    s.dx[i] = ray.dir.x, s.dy[i] = ray.dir.y, s.dz[i] = ray.dir.z;
    s.t_max[i] = t_max;
  }
}

// The moved light's share in each pixel of one tile (s.share): I·(w·kd·N.L + w·ks·spec) over
// the nodes the walk reached that see it.
void light_share_tile(const PreparedScene& prepared, const Light& light, const std::vector<LiveMaterial>& materials,
                      const Tile& tile, const LightHits& h, const Vec3* eye, bool packets, LightScratch& s,
                      RayCounts& rays) {
  light_geometry(prepared.scene(), light, tile, h, views(tile, eye, s), packets, s);
  const std::size_t count = tile.geometry.count;
  s.shadow.clear();
  s.tested.clear();
  for (std::size_t i = 0; i < count; ++i) {
    if (!h.active[i] || !(s.n_dot_l[i] > 0)) continue;
    ++rays.shadow;
    if (!(s.t_max[i] > 0)) continue;  // the light within rounding distance: seen, no ray
    s.shadow.push(s.ox[i], s.oy[i], s.oz[i], s.dx[i], s.dy[i], s.dz[i], s.t_max[i]);
    s.tested.push_back(i);
  }
  answer_shadow_rays(prepared, light, packets, s.shadow, s.blocked);
  std::size_t next = 0;  // the next tested node
  for (std::size_t i = 0; i < count; ++i) {
    if (!h.active[i] || !(s.n_dot_l[i] > 0)) continue;
    const bool tested = next < s.tested.size() && s.tested[next] == i;
    if (tested && s.blocked[next++]) continue;
    const std::uint32_t tag = h.tag[i];
    const LiveMaterial& m = materials[tag >> 16];
    Color c = tag & kDiffuseBit ? m.products.kd * s.n_dot_l[i] : Color(0);
    if (tag & kSpecularBit) c += m.products.ks * live_specular_factor(s.cos_spec[i], m.n);
    s.share[tag & 0xffu] += h.w[i] * c;
  }
}

}  // namespace

bool RayTrees::gather_light_hits(int light, Term term, int threads, const std::atomic<bool>* cancel,
                                 std::vector<RayCounts>& counts) {
  // Per node a lane flag, its chain and tag, and a rest per pixel, within the trees' budget
  // beside them; over it, the exact re-shade.
  std::size_t arrays = 0, kept = 0;
  for (const Tile& tile : tiles_) {
    arrays += tile.geometry.lanes() * (1 + sizeof(Color) + sizeof(std::uint32_t)) + tile.roots.size() * sizeof(Color);
  }
  for (const LightHits& h : moved_.tiles) kept += h.bytes();
  if (memory_bytes() - kept + arrays > budget_bytes_) {
    moved_over_budget_ = true;
    return false;
  }
  moved_.light = light;
  moved_.term = term;
  moved_.tiles.resize(tiles_.size());  // the arrays of the last one are overwritten, their memory kept
  const Scene& base = scene_->scene();
  const Color before = effective_intensity(base.lights[static_cast<std::size_t>(light)]);
  std::atomic<bool> stop{false}, incomplete{false};
  const bool done = for_each_index(tiles_.size(), threads, cancel, stop, counts, [&](std::size_t t, RayCounts&) {
    const Tile& tile = tiles_[t];
    LightHits& hits = moved_.tiles[t];
    const std::size_t lanes = tile.geometry.lanes();
    hits.active.assign(lanes, 0);
    hits.w.resize(lanes);
    hits.tag.resize(lanes);
    hits.reached = 0;
    hits.rest.resize(tile.roots.size());
    SumWalker walker(base, tile, kIntensity, light);
    walker.keep_hits(&hits);
    for (std::size_t p = 0; p < tile.roots.size(); ++p) {
      walker.at_pixel(p);
      Color sum;
      if (!walker.pixel(tile.roots[p], term, sum)) incomplete.store(true, std::memory_order_relaxed);
      hits.rest[p] = tile.values[p] - before * sum;
    }
  });
  if (done && !incomplete.load()) return true;
  moved_.light = -1;
  if (done) sums_refused_ = true;  // a child ray not stored: the exact re-shade traces it
  return false;
}

PassStats RayTrees::recombine_moved(const PreparedScene& scene, int light, Term term, int threads, Accumulator& accum,
                                    const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  PassStats stats;
  std::vector<RayCounts> counts;
  if ((moved_.light != light || moved_.term != term) && !gather_light_hits(light, term, threads, cancel, counts)) {
    stats.completed = false;  // cancelled, or over the budget: nothing written
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return stats;
  }
  const Light& moved = scene.scene().lights[static_cast<std::size_t>(light)];
  const bool packets = packet_tracing_applies(scene);
  std::vector<LiveMaterial> materials;
  for (const Material& m : scene.scene().materials) materials.push_back({light_products(moved, m), m.n});
  const Vec3* eye = shading_eye_ ? &*shading_eye_ : nullptr;
  std::atomic<std::uint64_t> nan_count{0};
  std::atomic<bool> stop{false};
  const bool done = for_each_index(tiles_.size(), threads, cancel, stop, counts, [&](std::size_t t, RayCounts& rays) {
    const Tile& tile = tiles_[t];
    const LightHits& hits = moved_.tiles[t];
    thread_local LightScratch scratch;
    scratch.share.assign(tile.roots.size(), Color(0));
    if (moved.enabled && hits.reached > 0) {  // muted: no share
      light_share_tile(scene, moved, materials, tile, hits, eye, packets, scratch, rays);
    }
    std::size_t p = 0;
    for (int y = tile.y0; y < tile.y1; ++y) {
      Color* row = accum.sum.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(accum.width);
      for (int x = tile.x0; x < tile.x1; ++x, ++p) {
        Color c = hits.rest[p] + scratch.share[p];
        if (!all_finite(c)) {  // as render_pass replaces them
          c = Color(0);
          nan_count.fetch_add(1, std::memory_order_relaxed);
        }
        row[x] = c;
      }
    }
  });
  for (const RayCounts& c : counts) stats.rays += c;
  stats.completed = done;
  live_reach_ = ~std::uint64_t{0};  // every pixel may have changed
  stats.nan_count = nan_count.load();
  if (done) ++accum.samples;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

const RayTrees::Sums* RayTrees::sums_for(std::uint8_t coefficient, int index, Term term) const {
  for (const Sums& s : sums_) {
    if (s.coefficient == coefficient && s.index == index && s.term == term) return &s;
  }
  return nullptr;
}

bool RayTrees::recombines(const PreparedScene& scene, int width, int height, Term term,
                          const std::optional<Vec3>& shading_eye, bool term_images) const {
  if (!usable_ || !values_valid_ || sums_refused_ || term_images || width != width_ || height != height_ || term != values_term_ || !reshades(term) ||
      scene.experiment() || scene_->experiment() || shading_eye != shading_eye_) {
    return false;
  }
  const Changes::Linear family = changes_between(scene_->scene(), scene.scene()).linear();
  return family != Changes::Linear::kNone && !(family == Changes::Linear::kMovedLight && moved_over_budget_);
}

PassStats RayTrees::recombine(const PreparedScene& scene, Term term, int threads, Accumulator& accum,
                              const std::atomic<bool>* cancel, bool over_last) {
  const auto start = std::chrono::steady_clock::now();
  const Scene& base = scene_->scene();
  const Changes changes = changes_between(base, scene.scene());
  if (changes.linear() == Changes::Linear::kMovedLight) {
    const auto moved = std::find(changes.light_moved.begin(), changes.light_moved.end(), true);
    return recombine_moved(scene, static_cast<int>(moved - changes.light_moved.begin()), term, threads, accum, cancel);
  }
  const std::vector<Delta> deltas = deltas_between(base, scene.scene(), changes);
  PassStats stats;
  std::vector<RayCounts> counts;
  // The sums not kept yet, in one pass over the trees; kept only when every one is whole.
  std::vector<Sums> fresh;
  for (const Delta& d : deltas) {
    if (sums_for(d.coefficient, d.index, term) == nullptr) fresh.push_back(Sums{d.coefficient, d.index, term, {}});
  }
  if (!fresh.empty()) {
    for (Sums& s : fresh) s.tiles.resize(tiles_.size());
    std::atomic<bool> stop{false}, incomplete{false};
    const bool done = for_each_index(tiles_.size(), threads, cancel, stop, counts, [&](std::size_t t, RayCounts&) {
      const Tile& tile = tiles_[t];
      for (Sums& s : fresh) {
        SumWalker walker(base, tile, static_cast<Coefficient>(s.coefficient), s.index);
        std::vector<Color>& out = s.tiles[t];
        out.resize(tile.roots.size());
        for (std::size_t p = 0; p < tile.roots.size(); ++p) {
          if (!walker.pixel(tile.roots[p], term, out[p])) incomplete.store(true, std::memory_order_relaxed);
        }
      }
    });
    if (!done) {
      stats.completed = false;
      stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return stats;  // cancelled: nothing kept, nothing written
    }
    if (incomplete.load()) {
      sums_refused_ = true;  // the exact re-shade traces what the trees lack
      stats.completed = false;
      stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return stats;
    }
    constexpr std::size_t kKept = 6;  // a few sliders' worth; the oldest go first
    for (Sums& s : fresh) sums_.push_back(std::move(s));
    while (sums_.size() > kKept) sums_.erase(sums_.begin());
  }
  std::vector<const Sums*> used;
  for (const Delta& d : deltas) used.push_back(sums_for(d.coefficient, d.index, term));
  // The pixels whose value differs from the trees' own: those meeting an edited material (the
  // sums of the others are 0), every pixel for Ia and the lights. Over the last image, those it
  // changed too (they return to the trees' value); the rest already hold it.
  std::uint64_t reach = 0;
  for (const Delta& d : deltas) reach |= d.coefficient <= kKs ? reach_bit(d.index) : ~std::uint64_t{0};
  const std::uint64_t written = over_last ? reach | live_reach_ : ~std::uint64_t{0};
  std::atomic<std::uint64_t> nan_count{0};
  std::atomic<bool> stop{false};
  const bool done = for_each_index(tiles_.size(), threads, cancel, stop, counts, [&](std::size_t t, RayCounts&) {
    const Tile& tile = tiles_[t];
    thread_local std::vector<const Color*> tile_sums;
    tile_sums.clear();
    for (const Sums* sums : used) tile_sums.push_back(sums->tiles[t].data());
    std::size_t p = 0;
    for (int y = tile.y0; y < tile.y1; ++y) {
      Color* row = accum.sum.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(accum.width);
      for (int x = tile.x0; x < tile.x1; ++x, ++p) {
        if ((tile.reach[p] & written) == 0) continue;
        Color c = tile.values[p];
        for (std::size_t k = 0; k < deltas.size(); ++k) c += deltas[k].change * tile_sums[k][p];
        if (!all_finite(c)) {  // as render_pass replaces them
          c = Color(0);
          nan_count.fetch_add(1, std::memory_order_relaxed);
        }
        row[x] = c;
      }
    }
  });
  stats.completed = done;
  live_reach_ = done ? reach : ~std::uint64_t{0};
  stats.nan_count = nan_count.load();
  if (stats.completed) ++accum.samples;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace phonglab
