#include "check/check.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <optional>

#include "core/render/render.h"
#include "core/base/threads.h"
#include "core/scene/camera.h"
#include "core/scene/display8.h"

namespace phonglab {

namespace {

constexpr double kFormulaTolerance = 1e-9;      // relative to max(1, |reference|)
constexpr double kLinearImageTolerance = 1e-3;  // absolute and relative
constexpr double kCodeTolerance = 1;            // 8-bit codes

// What a check compares at a pixel: the full value and (formula checks) the local terms.
struct Sample {
  Color full{0};
  std::array<Color, kFormulaSlots> slots{};  // ambient, diffuse, specular
};

// kLinearUnit: a linear image that holds [0, 1] only (a 16-bit PPM or PNG), compared with the
// reference clamped as its file would hold it.
// Yours per pixel: the full value, and (formula checks) the local terms.
struct Yours {
  std::vector<Color> full;
  std::vector<std::array<Color, kFormulaSlots>> slots;  // empty for an image
  std::size_t size() const { return full.size(); }
  Sample at(std::size_t i) const {
    Sample s;
    s.full = full[i];
    if (!slots.empty()) s.slots = slots[i];
    return s;
  }
};

// sRGB codes to linear values, once for the 256 codes.
const std::array<double, 256>& srgb_decode() {
  static const std::array<double, 256> table = [] {
    std::array<double, 256> t{};
    for (int c = 0; c < 256; ++c) t[static_cast<std::size_t>(c)] = srgb_to_linear(c / 255.0);
    return t;
  }();
  return table;
}

enum class Tolerance : std::uint8_t { kCodes8, kLinearImage, kLinearUnit, kFormula };

bool channel_differs(Tolerance tol, double yours, double reference) {
  // A mistake's image that is NaN (or the same infinity) where yours is explains it there.
  if (yours == reference || (std::isnan(yours) && std::isnan(reference))) return false;
  const double d = std::abs(yours - reference);
  switch (tol) {
    case Tolerance::kCodes8: return !(d <= kCodeTolerance);
    case Tolerance::kLinearImage:
    case Tolerance::kLinearUnit: return !(d <= kLinearImageTolerance + kLinearImageTolerance * std::abs(reference));
    case Tolerance::kFormula: return !(d <= kFormulaTolerance * std::max(1.0, std::abs(reference)));
  }
  return true;
}

bool colour_differs(Tolerance tol, const Color& yours, const Color& reference) {
  return channel_differs(tol, yours.x, reference.x) || channel_differs(tol, yours.y, reference.y) ||
         channel_differs(tol, yours.z, reference.z);
}

// The 8-bit codes `render` writes to a PNG for a linear value: through float, as its images hold
// them (Display8Encoder gives linear_to_srgb8 of the float exactly, without a pow per channel).
Color to_codes(const Color& linear, bool srgb) {
  const Display8Encoder& encode = srgb ? Display8Encoder::srgb() : Display8Encoder::linear();
  const auto code = [&](double c) { return static_cast<double>(encode(static_cast<float>(c))); };
  return {code(linear.x), code(linear.y), code(linear.z)};
}

// Runs fn(i) for i in [0, n) over the threads, in chunks.
template <class Fn>
void parallel_for(std::size_t n, int threads, Fn&& fn) {
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> next{0};
  const int workers = std::max(1, std::min(resolve_thread_count(threads), static_cast<int>((n + kChunk - 1) / kChunk)));
  run_workers(workers, [&](int) {
    for (;;) {
      const std::size_t begin = next.fetch_add(kChunk);
      if (begin >= n) return;
      const std::size_t end = std::min(n, begin + kChunk);
      for (std::size_t i = begin; i < end; ++i) fn(i);
    }
  });
}

PixelShade shade_pixel_in(const PreparedScene& prepared, const CameraFrame& frame, int x, int y, int spp,
                          bool corner) {
  const Scene& scene = prepared.scene();
  const TraceLimits limits{scene.max_depth, scene.min_weight};
  PixelShade out;
  RayCounts counts;
  for (int i = 0; i < spp; ++i) {
    double u = 0, v = 0;
    sample_offset(x, y, static_cast<std::uint32_t>(i), u, v);
    if (corner) {
      u -= 0.5;
      v -= 0.5;
    }
    const Ray ray = camera_ray(frame, x, y, u, v);
    const std::optional<Hit> hit = intersect(prepared, ray);
    if (!hit) {
      out.value += scene.background;
      continue;
    }
    const Terms t = shade(prepared, limits, ray, *hit, 0, 1.0, counts);
    const Color c = t.sum();
    out.finite = out.finite && all_finite(c);
    out.value += c;
    out.terms.ambient += t.ambient;
    out.terms.diffuse += t.diffuse;
    out.terms.specular += t.specular;
    out.terms.reflection += t.reflection;
    out.terms.refraction += t.refraction;
  }
  const double n = static_cast<double>(spp);
  out.value /= n;
  out.terms.ambient /= n;
  out.terms.diffuse /= n;
  out.terms.specular /= n;
  out.terms.reflection /= n;
  out.terms.refraction /= n;
  return out;
}

// One image the student's is compared with: the reference, or the reference with mistakes.
class Candidate {
 public:
  Candidate(const MistakeVariant& variant, const Scene& scene, const PreparedScene& reference_prepared,
            const Accumulator& reference, const CheckOptions& options, Tolerance tol)
      : variant_(variant), reference_(reference), options_(options), tol_(tol) {
    const bool traced = variant.rules.any() || variant.depth_change != 0 || variant.pixel_corner ||
                        variant.fov_horizontal;
    if (traced) {
      prepared_.emplace(prepare_with_rules(variant.scene_of(scene), reference_prepared, variant.rules));
      frame_ = make_camera_frame(prepared_->scene().camera, reference.width, reference.height);
    }
  }
  const MistakeVariant& variant() const { return variant_; }

  Sample at(int x, int y) const {
    const int sy = variant_.flipped_y ? reference_.height - 1 - y : y;
    Sample s;
    if (prepared_) {
      const PixelShade p = shade_pixel_in(*prepared_, frame_, x, sy, options_.spp, variant_.pixel_corner);
      s.full = p.value;
      s.slots = {p.terms.ambient, p.terms.diffuse, p.terms.specular};
    } else {
      s = reference_sample(reference_, x, sy);
    }
    if (tol_ == Tolerance::kCodes8) s.full = to_codes(s.full, !variant_.linear_png);
    if (tol_ == Tolerance::kLinearUnit) s.full = glm::clamp(s.full, Color(0), Color(1));
    return s;
  }

  static Sample reference_sample(const Accumulator& accum, int x, int y) {
    Sample s;
    s.full = accum.mean(x, y);
    if (accum.has_terms()) {
      const Terms& t = accum.terms[static_cast<std::size_t>(y) * accum.width + x];
      const double n = static_cast<double>(accum.samples);
      s.slots = {t.ambient / n, t.diffuse / n, t.specular / n};
    }
    return s;
  }

 private:
  MistakeVariant variant_;
  const Accumulator& reference_;
  const CheckOptions& options_;
  Tolerance tol_;
  std::optional<PreparedScene> prepared_;
  CameraFrame frame_{};
};

// The comparison both checks share, once yours and the reference are known per pixel.
class Comparison {
 public:
  Comparison(const Scene& scene, const PreparedScene& prepared, const Accumulator& reference,
             const CheckOptions& options, Tolerance tol, std::array<bool, kFormulaSlots> slots)
      : scene_(scene), prepared_(prepared), reference_(reference), options_(options), tol_(tol), slots_(slots) {}

  bool differs(const Sample& yours, const Sample& ref) const {
    if (colour_differs(tol_, yours.full, ref.full)) return true;
    for (int s = 0; s < kFormulaSlots; ++s) {
      if (slots_[static_cast<std::size_t>(s)] && colour_differs(tol_, yours.slots[static_cast<std::size_t>(s)],
                                                                 ref.slots[static_cast<std::size_t>(s)])) {
        return true;
      }
    }
    return false;
  }

  // How many of `pixels` (indices) the candidate's image matches yours at.
  std::size_t explained(const Candidate& c, const std::vector<std::size_t>& pixels,
                        const Yours& yours) const {
    std::atomic<std::size_t> count{0};
    parallel_for(pixels.size(), options_.threads, [&](std::size_t k) {
      const std::size_t i = pixels[k];
      const int x = static_cast<int>(i % static_cast<std::size_t>(reference_.width));
      const int y = static_cast<int>(i / static_cast<std::size_t>(reference_.width));
      if (!differs(yours.at(i), c.at(x, y))) count.fetch_add(1, std::memory_order_relaxed);
    });
    return count.load();
  }

  // The matches per pixel of `pixels`, as a bit string (to tell two mistakes' images apart).
  std::vector<bool> matches(const Candidate& c, const std::vector<std::size_t>& pixels,
                            const Yours& yours) const {
    std::vector<char> m(pixels.size(), 0);
    parallel_for(pixels.size(), options_.threads, [&](std::size_t k) {
      const std::size_t i = pixels[k];
      const int x = static_cast<int>(i % static_cast<std::size_t>(reference_.width));
      const int y = static_cast<int>(i / static_cast<std::size_t>(reference_.width));
      m[k] = differs(yours.at(i), c.at(x, y)) ? 0 : 1;
    });
    return std::vector<bool>(m.begin(), m.end());
  }

  // The nearest mistake (or pair) for the differing pixels, into `result`.
  void explain(const std::vector<std::size_t>& differing, const Yours& yours, bool formulas_only,
               CheckResult& result) const {
    if (differing.empty()) return;
    const std::vector<std::size_t> trial = spread(differing, options_.sample_pixels);
    const std::vector<Mistake> singles =
        applicable_mistakes(scene_, formulas_only, tol_ == Tolerance::kCodes8);
    struct Scored {
      std::vector<Mistake> mistakes;
      MistakeVariant variant;
      std::vector<bool> on_trial;
      std::size_t trial_count = 0;
    };
    std::vector<Scored> scored;
    for (const Mistake m : singles) {
      std::optional<Scored> best;
      for (const MistakeVariant& v : mistake_variants({m}, scene_)) {
        const Candidate c(v, scene_, prepared_, reference_, options_, tol_);
        Scored s{{m}, v, matches(c, trial, yours), 0};
        s.trial_count = static_cast<std::size_t>(std::count(s.on_trial.begin(), s.on_trial.end(), true));
        if (!best || s.trial_count > best->trial_count) best = std::move(s);
      }
      if (best && best->trial_count > 0) scored.push_back(std::move(*best));
    }
    if (name_best(scored, differing, trial, yours, " or ", result)) return;
    if (!options_.pairs) return;
    // No single mistake explains half: two at once (the catalogue is small).
    const std::vector<std::size_t> pair_trial = spread(differing, std::min<std::size_t>(options_.sample_pixels, 512));
    std::vector<Scored> pairs;
    for (std::size_t a = 0; a < singles.size(); ++a) {
      for (std::size_t b = a + 1; b < singles.size(); ++b) {
        std::optional<Scored> best;
        for (const MistakeVariant& v : mistake_variants({singles[a], singles[b]}, scene_)) {
          const Candidate c(v, scene_, prepared_, reference_, options_, tol_);
          Scored s{{singles[a], singles[b]}, v, matches(c, pair_trial, yours), 0};
          s.trial_count = static_cast<std::size_t>(std::count(s.on_trial.begin(), s.on_trial.end(), true));
          if (!best || s.trial_count > best->trial_count) best = std::move(s);
        }
        if (best && best->trial_count > 0) pairs.push_back(std::move(*best));
      }
    }
    name_best(pairs, differing, pair_trial, yours, " or ", result);
  }

 private:
  // Up to `limit` of the pixels not in `differing` (sorted), evenly spread through them.
  static std::vector<std::size_t> agreeing_pixels(const std::vector<std::size_t>& differing, std::size_t pixels,
                                                  std::size_t limit) {
    std::vector<std::size_t> all;
    all.reserve(pixels - differing.size());
    std::size_t d = 0;
    for (std::size_t i = 0; i < pixels; ++i) {
      if (d < differing.size() && differing[d] == i) {
        ++d;
        continue;
      }
      all.push_back(i);
    }
    return spread(all, limit);
  }

  // Up to `limit` of `all`, evenly spread through it.
  static std::vector<std::size_t> spread(const std::vector<std::size_t>& all, std::size_t limit) {
    if (all.size() <= limit) return all;
    std::vector<std::size_t> out;
    out.reserve(limit);
    for (std::size_t k = 0; k < limit; ++k) out.push_back(all[k * all.size() / limit]);
    return out;
  }

  // Names the best of `scored` when its share of all the differing pixels is at least half:
  // with the others whose images agree with it on every trial pixel and explain as many.
  template <class Scored>
  bool name_best(std::vector<Scored>& scored, const std::vector<std::size_t>& differing,
                 const std::vector<std::size_t>& trial, const Yours& yours, const char* joiner,
                 CheckResult& result) const {
    if (scored.empty()) return false;
    std::stable_sort(scored.begin(), scored.end(),
                     [](const Scored& a, const Scored& b) { return a.trial_count > b.trial_count; });
    // Mistakes that explain the same differing pixels: the ones whose images also keep the
    // student's pixels that are the reference's are the better explanation (an unclamped
    // specular term and the reversed R agree where R.V < 0, but the reversed R also loses the
    // highlight the student's image has); those that agree there too are named together.
    std::vector<std::size_t> tied = {0};
    for (std::size_t k = 1; k < scored.size(); ++k) {
      if (scored[k].trial_count == scored[0].trial_count && scored[k].on_trial == scored[0].on_trial) tied.push_back(k);
    }
    if (tied.size() > 1) {
      const std::vector<std::size_t> same = agreeing_pixels(differing, yours.size(), options_.sample_pixels);
      std::vector<std::size_t> misses(tied.size());
      for (std::size_t t = 0; t < tied.size(); ++t) {
        const Candidate c(scored[tied[t]].variant, scene_, prepared_, reference_, options_, tol_);
        misses[t] = same.size() - explained(c, same, yours);
      }
      const std::size_t fewest = *std::min_element(misses.begin(), misses.end());
      std::vector<std::size_t> kept;
      for (std::size_t t = 0; t < tied.size(); ++t) {
        if (misses[t] == fewest) kept.push_back(tied[t]);
      }
      tied = kept;
    }
    const Scored& best = scored[tied.front()];
    // The share is counted on every differing pixel (the trial may have been a spread of them).
    double count = static_cast<double>(best.trial_count);
    double counted = static_cast<double>(trial.size());
    if (trial.size() != differing.size()) {
      const Candidate c(best.variant, scene_, prepared_, reference_, options_, tol_);
      const std::vector<std::size_t> all = spread(differing, options_.count_pixels);
      count = static_cast<double>(explained(c, all, yours));
      counted = static_cast<double>(all.size());
    }
    const double percent = 100.0 * count / counted;
    if (percent < 50.0) return false;
    std::string name = best.variant.name();
    for (std::size_t t = 1; t < tied.size(); ++t) name += joiner + scored[tied[t]].variant.name();
    result.mistake = name;
    result.mistakes = best.mistakes;
    result.explained = percent;
    return true;
  }

  const Scene& scene_;
  const PreparedScene& prepared_;
  const Accumulator& reference_;
  const CheckOptions& options_;
  Tolerance tol_;
  std::array<bool, kFormulaSlots> slots_;
};

// Fills the verdict, the figures and the per-pixel signs from yours and the reference.
std::vector<std::size_t> compare_all(const Comparison& cmp, const Accumulator& reference,
                                     const Yours& yours, const std::vector<bool>& nan,
                                     Tolerance tol, CheckResult& result) {
  const std::size_t n = yours.size();
  result.pixels = n;
  result.sign.assign(n, 0);
  std::vector<std::size_t> differing;
  double worst = -1;
  for (std::size_t i = 0; i < n; ++i) {
    const int x = static_cast<int>(i % static_cast<std::size_t>(reference.width));
    const int y = static_cast<int>(i / static_cast<std::size_t>(reference.width));
    Sample ref = Candidate::reference_sample(reference, x, y);
    if (tol == Tolerance::kCodes8) ref.full = to_codes(ref.full, true);
    if (tol == Tolerance::kLinearUnit) ref.full = glm::clamp(ref.full, Color(0), Color(1));
    if (nan[i]) ++result.nan;
    // The largest channel difference, over the full value (NaN counts as the largest).
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(yours.full[i][c] - ref.full[c]);
      const double score = std::isnan(d) ? std::numeric_limits<double>::infinity() : d;
      if (score > worst) {
        worst = score;
        result.max_difference = d;
        result.worst_x = x;
        result.worst_y = y;
        result.worst_yours = yours.full[i];
        result.worst_reference = ref.full;
      }
    }
    if (!cmp.differs(yours.at(i), ref)) continue;
    differing.push_back(i);
    const Color d = yours.full[i] - ref.full;
    result.sign[i] = nan[i] || !all_finite(yours.full[i]) ? 3 : (d.x + d.y + d.z >= 0 ? 1 : 2);
  }
  result.differing = differing.size();
  result.match = differing.empty();
  return differing;
}

Accumulator render_reference(const PreparedScene& prepared, const CheckOptions& options, bool with_terms) {
  Accumulator accum;
  accum.reset(prepared.scene().width, prepared.scene().height, with_terms);
  RenderOptions ro;
  ro.threads = options.threads;
  render_passes(prepared, ro, accum, std::max(1, options.spp));
  return accum;
}

// The reference's means, taken over from its sums once the check no longer needs them (no
// second image of the same size: a check's time is mostly its memory).
std::vector<Color> reference_image(Accumulator&& accum) {
  std::vector<Color> out = std::move(accum.sum);
  const double n = static_cast<double>(std::max(accum.samples, 1u));
  if (n != 1) {
    for (Color& c : out) c /= n;
  }
  return out;
}

std::string number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string triple(const Color& c, bool single) {
  if (single) return number(c.x);
  return "(" + number(c.x) + ", " + number(c.y) + ", " + number(c.z) + ")";
}

std::string percent_text(double p) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", p);
  std::string s = buf;
  if (s.size() > 2 && s.compare(s.size() - 2, 2, ".0") == 0) s.resize(s.size() - 2);
  return s;
}

}  // namespace

PixelShade shade_pixel(const PreparedScene& prepared, int x, int y, int spp, bool corner) {
  const Scene& scene = prepared.scene();
  return shade_pixel_in(prepared, make_camera_frame(scene.camera, scene.width, scene.height), x, y, spp, corner);
}

namespace {

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}
std::string short_value(const FormulaValue& v) {
  if (!v.triple) return short_number(v.x);
  return "(" + short_number(v.x) + ", " + short_number(v.y) + ", " + short_number(v.z) + ")";
}
std::string short_colour(const Color& c) { return short_value(FormulaValue{true, c.x, c.y, c.z}); }

// One slot's lines: yours and the reference, then each statement's value.
void slot_lines(std::string& out, const char* indent, FormulaSlot slot, const Formula& f, const LocalHit& h,
                const Color& yours, const Color& reference) {
  out += std::string(indent) + std::string(formula_slot_name(slot)) + ": yours " + short_colour(yours) + ", reference " +
         short_colour(reference) + "\n";
  for (const auto& [name, value] : f.trace(formula_inputs(h, slot))) {
    if (name == "=") continue;
    out += std::string(indent) + "  " + name + " = " + short_value(value) + "\n";
  }
}

}  // namespace

std::string formula_probe_text(const Scene& scene, const ProbeNode& node, const LocalRules& formulas) {
  if (!node.hit || node.material < 0 || static_cast<std::size_t>(node.material) >= scene.materials.size()) return "";
  const Formula* ambient = formulas.formulas[static_cast<std::size_t>(FormulaSlot::kAmbient)].get();
  const Formula* diffuse = formulas.formulas[static_cast<std::size_t>(FormulaSlot::kDiffuse)].get();
  const Formula* specular = formulas.formulas[static_cast<std::size_t>(FormulaSlot::kSpecular)].get();
  if (!ambient && !diffuse && !specular) return "";
  const Material& m = scene.materials[static_cast<std::size_t>(node.material)];
  std::string out = "at the primary hit (" + m.name + "):\n";
  LocalHit h{&scene, &m, nullptr, node.p, node.n, Vec3(0), node.v, 0, 0};
  if (ambient) {
    slot_lines(out, "", FormulaSlot::kAmbient, *ambient, h, ambient->evaluate(formula_inputs(h, FormulaSlot::kAmbient)),
               m.ka * scene.ambient);
  }
  if (!diffuse && !specular) return out;
  for (const ProbeLight& pl : node.lights) {
    if (pl.index < 0 || static_cast<std::size_t>(pl.index) >= scene.lights.size()) continue;
    const Light& light = scene.lights[static_cast<std::size_t>(pl.index)];
    out += "light " + std::to_string(pl.index) + " (N\xC2\xB7L " + short_number(pl.n_dot_l) + "): ";
    if (!pl.lit_side) {
      out += "behind the surface: no term\n";
      continue;
    }
    if (!pl.visible) {
      out += "in shadow: no term\n";
      continue;
    }
    out += "\n";
    LocalHit lh = h;
    lh.light = &light;
    lh.l = pl.l;
    lh.n_dot_l = pl.n_dot_l;
    Vec3 r;
    lh.spec = specular_factor(specular_cosine(scene.specular_model, node.n, pl.l, node.v, pl.n_dot_l, r), m.n);
    const LightShare reference = light_share(light, m, pl.n_dot_l, lh.spec);
    if (diffuse) {
      slot_lines(out, "  ", FormulaSlot::kDiffuse, *diffuse, lh,
                 light.intensity * diffuse->evaluate(formula_inputs(lh, FormulaSlot::kDiffuse)), reference.diffuse);
    }
    if (specular) {
      slot_lines(out, "  ", FormulaSlot::kSpecular, *specular, lh,
                 light.intensity * specular->evaluate(formula_inputs(lh, FormulaSlot::kSpecular)), reference.specular);
    }
  }
  return out;
}

CheckResult check_image(const Scene& scene_in, const StudentImage& image, const CheckOptions& options) {
  Scene scene = scene_in;
  scene.width = image.width;
  scene.height = image.height;
  const PreparedScene prepared(scene);
  const bool codes8 = image.units == StudentImage::Units::kCodes8;
  const Tolerance tol = codes8                                               ? Tolerance::kCodes8
                        : image.units == StudentImage::Units::kLinearUnit ? Tolerance::kLinearUnit
                                                                          : Tolerance::kLinearImage;
  Accumulator reference = render_reference(prepared, options, false);

  CheckResult result;
  result.codes8 = codes8;
  result.width = image.width;
  result.height = image.height;
  const std::size_t n = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  Yours yours;
  yours.full.resize(n);
  std::vector<bool> nan(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const Color c{image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]};
    yours.full[i] = c;
    nan[i] = !all_finite(c);
  }
  const Comparison cmp(scene, prepared, reference, options, tol, {false, false, false});
  const std::vector<std::size_t> differing = compare_all(cmp, reference, yours, nan, tol, result);
  cmp.explain(differing, yours, false, result);
  result.reference = reference_image(std::move(reference));
  // Yours as linear values (for the views), in place of the codes.
  result.yours = std::move(yours.full);
  if (codes8) {
    const std::array<double, 256>& decode = srgb_decode();
    const auto linear = [&](double code) { return decode[static_cast<std::size_t>(std::clamp(code, 0.0, 255.0))]; };
    for (Color& c : result.yours) c = Color(linear(c.x), linear(c.y), linear(c.z));
  }
  return result;
}

CheckResult check_formulas(const Scene& scene, const LocalRules& formulas, const CheckOptions& options) {
  const PreparedScene prepared(scene);
  Accumulator reference = render_reference(prepared, options, true);
  LocalRules only_formulas;
  only_formulas.formulas = formulas.formulas;
  const PreparedScene with_formulas = prepare_with_rules(scene, prepared, only_formulas);
  const CameraFrame frame = make_camera_frame(scene.camera, scene.width, scene.height);

  CheckResult result;
  result.formulas = true;
  result.width = scene.width;
  result.height = scene.height;
  const std::size_t n = static_cast<std::size_t>(scene.width) * static_cast<std::size_t>(scene.height);
  Yours yours;
  yours.full.resize(n);
  yours.slots.resize(n);
  std::vector<char> finite(n, 1);
  parallel_for(n, options.threads, [&](std::size_t i) {
    const int x = static_cast<int>(i % static_cast<std::size_t>(scene.width));
    const int y = static_cast<int>(i / static_cast<std::size_t>(scene.width));
    const PixelShade p = shade_pixel_in(with_formulas, frame, x, y, std::max(1, options.spp), false);
    yours.full[i] = p.value;
    yours.slots[i] = {p.terms.ambient, p.terms.diffuse, p.terms.specular};
    finite[i] = p.finite && all_finite(p.terms.ambient) && all_finite(p.terms.diffuse) && all_finite(p.terms.specular)
                    ? 1
                    : 0;
  });
  std::vector<bool> nan(n);
  result.yours.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    nan[i] = finite[i] == 0;
    result.yours[i] = yours.full[i];
  }
  std::array<bool, kFormulaSlots> slots{};
  for (int s = 0; s < kFormulaSlots; ++s) slots[static_cast<std::size_t>(s)] = formulas.formulas[static_cast<std::size_t>(s)] != nullptr;
  const Comparison cmp(scene, prepared, reference, options, Tolerance::kFormula, slots);
  const std::vector<std::size_t> differing = compare_all(cmp, reference, yours, nan, Tolerance::kFormula, result);
  // The formula mistakes are specular ones: tried when the specular term is the student's.
  if (slots[static_cast<std::size_t>(FormulaSlot::kSpecular)]) cmp.explain(differing, yours, true, result);
  result.reference = reference_image(std::move(reference));
  return result;
}

std::string check_report_text(const CheckResult& r) {
  std::string out = r.match ? "match\n" : "differs\n";
  out += "pixels " + std::to_string(r.pixels) + " differing " + std::to_string(r.differing) + "\n";
  out += "max difference " + number(r.max_difference) + " at (" + std::to_string(r.worst_x) + ", " +
         std::to_string(r.worst_y) + "): yours " + triple(r.worst_yours, false) + ", reference " +
         triple(r.worst_reference, false) + "\n";
  if (r.formulas || r.nan > 0) out += "nan " + std::to_string(r.nan) + "\n";
  if (!r.match) {
    if (r.mistake.empty()) {
      out += "nearest mistake: none\n";
    } else {
      out += "nearest mistake: " + r.mistake + " (explains " + percent_text(r.explained) +
             " % of the differing pixels)\n";
    }
  }
  return out;
}

std::string check_summary(const CheckResult& r) {
  if (r.match) return "match: every pixel is the reference's";
  std::string out = "differs: " + std::to_string(r.differing) + " of " + std::to_string(r.pixels) + " pixels";
  if (r.nan > 0) out += " (" + std::to_string(r.nan) + " NaN)";
  if (r.mistakes.empty()) return out + "; no known mistake explains them";
  out += "; " + std::string(mistake_info(r.mistakes.front()).words);
  if (r.mistakes.size() > 1) out += "; and " + std::string(mistake_info(r.mistakes[1]).words);
  return out + " (" + percent_text(r.explained) + " % of the differing pixels)";
}

std::vector<Color> check_difference_image(const CheckResult& r) {
  std::vector<Color> out(r.reference.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    switch (r.sign.empty() ? 0 : r.sign[i]) {
      case 1: out[i] = Color(1.0, 0.35, 0.0); break;   // yours brighter
      case 2: out[i] = Color(0.05, 0.35, 1.0); break;  // yours darker
      case 3: out[i] = Color(1.0, 0.0, 1.0); break;    // NaN or infinite
      default: {
        const Color c = glm::clamp(r.reference[i], Color(0), Color(1));
        out[i] = 0.2 * c;  // the reference, dimmed
      }
    }
  }
  return out;
}

}  // namespace phonglab
