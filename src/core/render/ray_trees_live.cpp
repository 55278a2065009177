// The live path of a slider: an edit the image is linear in is the trees' last exact image plus
// the edited coefficients' changes times the per-pixel sums they multiply (docs/speed.md,
// "Live re-shading"). For ka, kd or ks of material m the sum runs over m's hits of the pixel's
// tree, each weighted by the kr'/kt' chain above it: ka multiplies w·Iₐ, kd multiplies
// w·Σ_l vis_l·I_l·(N·L), ks multiplies w·Σ_l vis_l·I_l·spec_l. For Iₐ it is Σ w·ka; for a light's
// intensity Σ w·vis·(kd·(N·L) + ks·spec). The walk is TileShader::terms' with the coefficient
// taken out: the same stored cosines, visibilities, Fresnel factors and pruning.
#include <chrono>

#include "core/render/ray_trees.h"
#include "core/render/scene_changes.h"
#include "core/render/tile_work.h"

namespace phonglab {

namespace {

using Node = RayTrees::Node;
using Tile = RayTrees::Tile;

enum Coefficient : std::uint8_t { kKa, kKd, kKs, kAmbient, kIntensity };

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
    bn.fresnel = tile_.geometry[static_cast<std::size_t>(i)].fresnel;
    set_bounce_weights(m, bn);
    if (part != Term::kRefraction) child(bn.kr, w, weight, n.reflection, out);
    if (part != Term::kReflection && !is_zero(bn.kt)) child(bn.kt, w, weight, n.refraction, out);
  }

  void lights(std::int32_t i, const Material& m, bool mine, const Color& w, Term part, Color& out) {
    const bool diffuse = part != Term::kSpecular, specular = part != Term::kDiffuse;
    const std::size_t first = static_cast<std::size_t>(i) * lights_;
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

  const Scene& scene_;
  const Tile& tile_;
  Coefficient coefficient_;
  int index_;
  std::size_t lights_;
  bool complete_ = true;
};

}  // namespace

const RayTrees::Sums* RayTrees::sums_for(std::uint8_t coefficient, int index, Term term) const {
  for (const Sums& s : sums_) {
    if (s.coefficient == coefficient && s.index == index && s.term == term) return &s;
  }
  return nullptr;
}

bool RayTrees::recombines(const PreparedScene& scene, int width, int height, Term term,
                          const std::optional<Vec3>& shading_eye, bool term_images) const {
  if (!usable_ || !values_valid_ || sums_refused_ || term_images || width != width_ || height != height_ || term != values_term_ || !reshades(term) ||
      scene.experiment() || shading_eye != shading_eye_) {
    return false;
  }
  return changes_between(scene_->scene(), scene.scene()).linear() != Changes::Linear::kNone;
}

PassStats RayTrees::recombine(const PreparedScene& scene, Term term, int threads, Accumulator& accum,
                              const std::atomic<bool>* cancel, bool over_last) {
  const auto start = std::chrono::steady_clock::now();
  const Scene& base = scene_->scene();
  const std::vector<Delta> deltas = deltas_between(base, scene.scene(), changes_between(base, scene.scene()));
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
      stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return stats;  // cancelled: nothing kept, nothing written
    }
    if (incomplete.load()) {
      sums_refused_ = true;  // the exact re-shade traces what the trees lack
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
