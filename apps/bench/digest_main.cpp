// phonglab-digest: one line per image of every embedded scene (the full image, the five terms
// and the debug views, three passes each, by the packet and by the scalar tracer, the full image
// and the specular term also with "move your head"; the quad-shaded live rung, at the image's size and at an odd one;
// every numerics variant with its acne count; a probed pixel), each with
// its ray count and an FNV-1a hash of the accumulated sums. Run it before and after a change
// that must not change any image, and compare the two outputs:
//
//   build/bin/phonglab-digest > before.txt   (change, rebuild)   build/bin/phonglab-digest | diff before.txt -
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/render/quad_shading.h"
#include "core/render/render.h"
#include "experiments/numerics_variants.h"
#include "io/embedded_scenes.h"
#include "io/scene/scene_io.h"

namespace {

using namespace phonglab;

constexpr int kWidth = 160, kHeight = 90, kPasses = 3;

std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h = 1469598103934665603ull) {
  const auto* b = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i) {
    h ^= b[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::uint64_t hash(const Accumulator& a, std::uint64_t h) { return fnv1a(a.sum.data(), a.sum.size() * sizeof(Color), h); }

// The term and debug images, three passes each, both tracers, with and without a moved eye.
void term_images(const std::string& name, const PreparedScene& prepared) {
  for (int t = 0; t <= static_cast<int>(Term::kRays); ++t) {
    for (const bool packets : {false, true}) {
      for (const bool head : {false, true}) {
        const Term term = static_cast<Term>(t);
        if (head && term != Term::kFull && term != Term::kSpecular) continue;
        RenderOptions options;
        options.term = term;
        options.threads = 2;
        options.packets = packets;
        if (head) options.shading_eye = Vec3(0.7, 1.9, 5.5);
        Accumulator accum;
        accum.reset(kWidth, kHeight);
        std::uint64_t h = 1469598103934665603ull, rays = 0;
        for (int pass = 0; pass < kPasses; ++pass) {
          rays += render_pass(prepared, options, accum).rays.total();
          h = hash(accum, h);
        }
        std::printf("%s %s %s head=%d rays=%llu %016llx\n", name.c_str(), std::string(term_name(term)).c_str(),
                    packets ? "packets" : "scalar", head ? 1 : 0, static_cast<unsigned long long>(rays),
                    static_cast<unsigned long long>(h));
      }
    }
  }
}

// The quad-shaded live rung, both tracers, at the digest's size and at an odd one (quads cut
// by the image's edges).
void quad_rung(const std::string& name, const PreparedScene& prepared) {
  for (const bool packets : {false, true}) {
    for (const bool odd : {false, true}) {
      RenderOptions options;
      options.threads = 2;
      options.packets = packets;
      Accumulator accum;
      accum.reset(kWidth + (odd ? 7 : 0), kHeight + (odd ? 3 : 0));
      render_quad_shaded(prepared, options, accum);
      std::printf("%s quads %s %dx%d %016llx\n", name.c_str(), packets ? "packets" : "scalar", accum.width,
                  accum.height, static_cast<unsigned long long>(hash(accum, 1469598103934665603ull)));
    }
  }
}

// Every numerics variant and ablation of the bench: one pass and its acne count.
void variants(const std::string& name, const Scene& scene) {
  for (int v = 0; v < 8; ++v) {
    NumericsVariant variant;
    variant.float_geometry = v == 1;
    variant.textbook_sphere = v == 2;
    variant.fixed_offset = v == 3 ? 1e-3 : 0;
    variant.schlick_fresnel = v == 4;
    variant.nearest_hit_shadows = v == 5;
    variant.shadow_rays_behind = v == 6;
    variant.refraction_for_opaque = v == 7;
    const PreparedScene prepared = prepare_variant(scene, variant);
    RenderOptions options;
    options.threads = 2;
    options.packets = false;
    Accumulator accum;
    accum.reset(kWidth, kHeight);
    const PassStats stats = render_pass(prepared, options, accum);
    const AcneCount acne = count_acne(prepared, kWidth / 2, kHeight / 2, 2);
    std::printf("%s variant=%d rays=%llu acne=%llu/%llu %016llx\n", name.c_str(), v,
                static_cast<unsigned long long>(stats.rays.total()), static_cast<unsigned long long>(acne.pixels),
                static_cast<unsigned long long>(acne.rays), static_cast<unsigned long long>(hash(accum, 1469598103934665603ull)));
  }
}

}  // namespace

int main() {
  for (const EmbeddedScene& e : embedded_scenes()) {
    const std::string name(e.name);
    const LoadResult r = load_scene_arg(name);
    if (!r.ok()) {
      std::printf("%s: %s\n", name.c_str(), r.error_text().c_str());
      return 1;
    }
    const PreparedScene prepared(*r.scene);
    term_images(name, prepared);
    quad_rung(name, prepared);
    variants(name, *r.scene);
    const PixelProbe probe = probe_pixel(prepared, kWidth, kHeight, kWidth / 2, kHeight / 2);
    std::printf("%s probe %.17g %.17g %.17g\n", name.c_str(), probe.root.total.r, probe.root.total.g,
                probe.root.total.b);
  }
  return 0;
}
