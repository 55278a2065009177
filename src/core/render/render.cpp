#include "core/render/render.h"

#include <array>
#include <chrono>

#include "core/packet/packet.h"

namespace phonglab {

namespace {
// The sampler of one (pixel, sample) under indirect light, else nothing.
std::optional<IndirectSampler> sampler_for(const Scene& scene, Ambient ambient, int x, int y,
                                           std::uint32_t sample_index, std::uint32_t seed) {
  if (ambient != Ambient::kIndirect) return std::nullopt;
  return IndirectSampler(scene.indirect_bounces, indirect_pixel_key(x, y, seed), sample_index);
}
IndirectSampler* pointer(std::optional<IndirectSampler>& sampler) { return sampler ? &*sampler : nullptr; }
}  // namespace



void Accumulator::reset(int w, int h, bool with_terms) {
  width = w;
  height = h;
  samples = 0;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  sum.assign(n, Color(0));
  if (with_terms) {
    terms.assign(n, Terms{});
  } else {
    terms.clear();
  }
}

void Accumulator::reset_for_first_pass(int w, int h, bool with_terms) {
  width = w;
  height = h;
  samples = 0;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  sum.resize(n);
  terms.resize(with_terms ? n : 0);
}

void add_terms(Terms& sum, const Terms& sample) {
  // A term that is NaN or Inf adds 0, as render_pass does with such a sample of a term image.
  const auto add = [](Color& to, const Color& c) { to += all_finite(c) ? c : Color(0); };
  add(sum.ambient, sample.ambient);
  add(sum.diffuse, sample.diffuse);
  add(sum.specular, sample.specular);
  add(sum.reflection, sample.reflection);
  add(sum.refraction, sample.refraction);
}

Color Accumulator::mean(int x, int y) const {
  if (samples == 0) return Color(0);
  return sum[static_cast<std::size_t>(y) * width + x] / static_cast<double>(samples);
}

Color render_sample(const PreparedScene& prepared, const CameraFrame& frame, Term term, int x, int y,
                    std::uint32_t sample_index, RayCounts& counts, std::uint32_t seed,
                    const Vec3* shading_eye, Ambient ambient) {
  double u, v;
  sample_offset(x, y, sample_index, u, v, seed);
  const Ray ray = camera_ray(frame, x, y, u, v);
  ++counts.primary;
  const Scene& scene = prepared.scene();
  const TraceLimits limits{scene.max_depth, scene.min_weight};
  std::optional<IndirectSampler> sampler = sampler_for(scene, ambient_for(term, ambient), x, y, sample_index, seed);
  if (term == Term::kFull) return trace(prepared, limits, ray, 0, 1.0, counts, nullptr, shading_eye, pointer(sampler));
  if (term == Term::kRays) {
    const std::uint64_t before = counts.total() - 1;
    trace(prepared, limits, ray, 0, 1.0, counts, nullptr, shading_eye, pointer(sampler));
    return Color(static_cast<double>(counts.total() - before));
  }
  const std::optional<Hit> hit = intersect(prepared, ray);
  if (!hit) return miss_value(scene, term);
  switch (term) {
    case Term::kNormal: {
      const Vec3 n = glm::dot(hit->ns, ray.dir) < 0 ? hit->ns : -hit->ns;
      return 0.5 * n + 0.5;
    }
    case Term::kDepth:
      return Color(hit->t);
    default:
      break;
  }
  return term_value(
      shade(prepared, limits, ray, *hit, 0, 1.0, counts, nullptr, shading_eye, terms_wanted(term), pointer(sampler)),
      term);
}

Color render_sample_terms(const PreparedScene& prepared, const CameraFrame& frame, Term term, int x, int y,
                          std::uint32_t sample_index, RayCounts& counts, Terms& terms, std::uint32_t seed,
                          const Vec3* shading_eye, Ambient ambient) {
  const Scene& scene = prepared.scene();
  // A debug view is not read off the terms: its own value, then the terms' trace (uncounted twice).
  std::optional<Color> debug;
  if (!is_equation_term(term)) {
    RayCounts uncounted;
    debug = render_sample(prepared, frame, term, x, y, sample_index, uncounted, seed, shading_eye, ambient);
  }
  double u, v;
  sample_offset(x, y, sample_index, u, v, seed);
  const Ray ray = camera_ray(frame, x, y, u, v);
  ++counts.primary;
  const std::optional<Hit> hit = intersect(prepared, ray);
  if (!hit) {
    terms = Terms{};
    return debug ? *debug : miss_value(scene, term);
  }
  const TraceLimits limits{scene.max_depth, scene.min_weight};
  if (term == Term::kIndirect) {
    // The indirect term beside the lecture's five: the terms as §1 has them (ka·Ia), the value
    // the indirect term's estimate (the same gather render_sample takes: the tree's first).
    terms = shade(prepared, limits, ray, *hit, 0, 1.0, counts, nullptr, shading_eye, TermsWanted{});
    std::optional<IndirectSampler> sampler = sampler_for(scene, Ambient::kIndirect, x, y, sample_index, seed);
    return indirect_estimate(prepared, limits, scene.materials[static_cast<std::size_t>(hit->material)], hit->p,
                             hit_side(*hit, ray.dir), surface_offset(scene, *hit), counts, *sampler);
  }
  std::optional<IndirectSampler> sampler = sampler_for(scene, ambient, x, y, sample_index, seed);
  terms = shade(prepared, limits, ray, *hit, 0, 1.0, counts, nullptr, shading_eye, TermsWanted{}, pointer(sampler));
  return debug ? *debug : term_value(terms, term);
}




PassStats render_pass(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum,
                      const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  const Scene& scene = prepared.scene();
  const CameraFrame frame = make_camera_frame(scene.camera, accum.width, accum.height);
  const int tile = options.tile_size > 0 ? options.tile_size : 16;
  const int tiles_x = (accum.width + tile - 1) / tile;
  const int tiles_y = (accum.height + tile - 1) / tile;
  const int tile_count = tiles_x * tiles_y;
  const std::uint32_t sample_index = accum.samples;
  const int thread_count = std::max(1, std::min(resolve_thread_count(options.threads), tile_count));
  const Vec3* shading_eye = options.shading_eye ? &*options.shading_eye : nullptr;

  std::atomic<int> next_tile{0};
  std::atomic<bool> stopped{false};
  std::vector<PassStats> per_thread(static_cast<std::size_t>(thread_count));

  // Each tile is written by exactly one thread and each pixel's value depends only on
  // (x, y, sample_index), so the image is the same for any thread count or tile order.
  const Ambient ambient = ambient_for(options.term, options.ambient);
  const bool packets = options.packets && ambient == Ambient::kConstant && PacketTracer::draws(options.term) &&
                       packet_tracing_applies(prepared);
  const bool with_terms = accum.has_terms();
  auto worker = [&](PassStats& stats) {
    PacketTracer* tracer = packets ? &packet_tracer_for(prepared) : nullptr;
    std::vector<Color> tile_radiance;
    std::vector<Terms> tile_terms;
    if (packets) tile_radiance.resize(static_cast<std::size_t>(tile) * static_cast<std::size_t>(tile));
    if (packets && with_terms) tile_terms.resize(tile_radiance.size());
    // The first sample is written (0 + c, exactly what adding it to a cleared sum gives, -0
    // included), so the accumulator needs no clearing before it (reset_for_first_pass).
    const bool first = sample_index == 0;
    glm::vec3* const floats = first ? options.first_sample_image : nullptr;
    const auto add = [&](Color* row, int x, Color c) {
      if (!all_finite(c)) {
        ++stats.nan_count;
        c = Color(0);
      }
      row[x] = (first ? Color(0) : row[x]) + c;
      if (floats) floats[static_cast<std::size_t>(row - accum.sum.data()) + static_cast<std::size_t>(x)] = glm::vec3(row[x]);
    };
    const auto add_pixel_terms = [&](Terms& sum, const Terms& sample) {
      if (first) sum = Terms{};
      add_terms(sum, sample);
    };
    for (;;) {
      if (cancel && cancel->load(std::memory_order_relaxed)) {
        stopped.store(true, std::memory_order_relaxed);
        return;
      }
      const int t = next_tile.fetch_add(1, std::memory_order_relaxed);
      if (t >= tile_count) return;
      const int x0 = (t % tiles_x) * tile;
      const int y0 = (t / tiles_x) * tile;
      const int x1 = std::min(x0 + tile, accum.width);
      const int y1 = std::min(y0 + tile, accum.height);
      if (tracer) {
        tracer->render_tile(frame, x0, y0, x1, y1, sample_index, options.seed, tile_radiance.data(), stats.rays,
                            options.term, shading_eye, with_terms ? tile_terms.data() : nullptr);
        std::size_t i = 0;
        for (int y = y0; y < y1; ++y) {
          const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(accum.width);
          for (int x = x0; x < x1; ++x, ++i) {
            add(accum.sum.data() + row, x, tile_radiance[i]);
            if (with_terms) add_pixel_terms(accum.terms[row + static_cast<std::size_t>(x)], tile_terms[i]);
          }
        }
        continue;
      }
      for (int y = y0; y < y1; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(accum.width);
        for (int x = x0; x < x1; ++x) {
          if (!with_terms) {
            add(accum.sum.data() + row, x,
                render_sample(prepared, frame, options.term, x, y, sample_index, stats.rays, options.seed, shading_eye,
                              ambient));
            continue;
          }
          Terms terms;
          add(accum.sum.data() + row, x,
              render_sample_terms(prepared, frame, options.term, x, y, sample_index, stats.rays, terms, options.seed,
                                  shading_eye, ambient));
          add_pixel_terms(accum.terms[row + static_cast<std::size_t>(x)], terms);
        }
      }
    }
  };

  run_workers(thread_count, [&](int i) { worker(per_thread[static_cast<std::size_t>(i)]); });

  PassStats total;
  for (const PassStats& s : per_thread) {
    total.rays += s.rays;
    total.nan_count += s.nan_count;
  }
  total.completed = !stopped.load();
  total.packets = packets;
  if (total.completed) ++accum.samples;
  total.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return total;
}

PassStats render_passes(const PreparedScene& prepared, const RenderOptions& options, Accumulator& accum, int passes) {
  PassStats total;
  for (int i = 0; i < passes; ++i) {
    const PassStats pass = render_pass(prepared, options, accum);
    total.rays += pass.rays;
    total.nan_count += pass.nan_count;
    total.seconds += pass.seconds;
    total.packets = pass.packets;
  }
  return total;
}

}  // namespace phonglab

namespace phonglab {

PixelProbe probe_pixel(const PreparedScene& prepared, int width, int height, int x, int y,
                       const std::optional<Vec3>& shading_eye) {
  const Scene& scene = prepared.scene();
  PixelProbe probe;
  probe.x = x;
  probe.y = y;
  const CameraFrame frame = make_camera_frame(scene.camera, width, height);
  double u, v;
  sample_offset(x, y, 0, u, v);
  const Ray ray = camera_ray(frame, x, y, u, v);
  ++probe.rays.primary;
  trace(prepared, TraceLimits{scene.max_depth, scene.min_weight}, ray, 0, 1.0, probe.rays, &probe.root,
        shading_eye ? &*shading_eye : nullptr);
  return probe;
}

}  // namespace phonglab
