#include "apps/bench/bench_indirect.h"

#include <cmath>

namespace phonglab::bench {

namespace {

// Mean of `passes` passes of the indirect view (the full image with indirect light).
std::vector<Color> indirect_image(const PreparedScene& scene, int w, int h, int passes, int threads, std::uint32_t seed) {
  return means(render(scene, w, h, passes, threads, seed, true, Ambient::kIndirect).accum);
}

// The Whitted image's and the indirect view's Mrays/s: one pass each, alternating, `rounds` times.
struct Speeds {
  std::vector<double> whitted, indirect;
};
Speeds alternate_speeds(const PreparedScene& scene, int w, int h, int rounds, int threads) {
  Speeds s;
  for (int r = 0; r < rounds; ++r) {
    for (const Ambient ambient : {Ambient::kConstant, Ambient::kIndirect}) {
      const PassStats pass = render(scene, w, h, 1, threads, 0, true, ambient).stats;
      const double mrays = static_cast<double>(pass.rays.total()) / pass.seconds * 1e-6;
      (ambient == Ambient::kConstant ? s.whitted : s.indirect).push_back(mrays);
    }
  }
  return s;
}

}  // namespace

IndirectBenchResult run_indirect_bench(bool quick, int threads) {
  IndirectBenchResult result;
  // The reference's noise must be 10x below the smallest RMSE plotted: RMSE(N) is about
  // 0.13/sqrt(N) here, so the reference needs about 100 N samples a pixel.
  const int w = quick ? 64 : 96, h = quick ? 36 : 54;
  const int half_spp = quick ? 1024 : 16384;
  const int max_spp = quick ? 16 : 128;
  const int seeds = 4;
  const Scene scene = load_embedded("cornell");
  const PreparedScene prepared(scene);
  std::printf("indirect: cornell %dx%d, reference 2 x %d spp, %d seeds up to %d spp\n", w, h, half_spp, seeds, max_spp);
  // The reference: two independent halves (other seeds); their difference measures its noise.
  const std::vector<Color> a = indirect_image(prepared, w, h, half_spp, threads, 1000);
  const std::vector<Color> b = indirect_image(prepared, w, h, half_spp, threads, 2000);
  std::vector<Color> ref(a.size());
  for (std::size_t i = 0; i < ref.size(); ++i) ref[i] = 0.5 * (a[i] + b[i]);
  const double ref_noise = rmse(a, b) / 2;  // each half's RMSE is rmse(a, b) / sqrt(2); their mean's half that
  std::vector<double> spps, mean_rmse;
  for (int spp = 1; spp <= max_spp; spp *= 2) spps.push_back(spp);
  mean_rmse.assign(spps.size(), 0);
  result.csv = "scene,spp,seed,rmse\n";
  for (int seed = 0; seed < seeds; ++seed) {
    RenderOptions options;
    options.ambient = Ambient::kIndirect;
    options.threads = threads;
    options.seed = static_cast<std::uint32_t>(seed);
    Accumulator accum;
    accum.reset(w, h);
    std::size_t k = 0;
    for (int spp = 1; spp <= max_spp; ++spp) {
      render_pass(prepared, options, accum);
      if (k < spps.size() && spp == static_cast<int>(spps[k])) {
        const double e = rmse(means(accum), ref);
        mean_rmse[k] += e / seeds;
        result.csv += "cornell," + std::to_string(spp) + "," + std::to_string(seed) + "," + fmt("%.6e", e) + "\n";
        ++k;
      }
    }
  }
  result.rmse_slope = loglog_slope(spps, mean_rmse);
  std::vector<double> line(spps.size());
  for (std::size_t i = 0; i < spps.size(); ++i) line[i] = mean_rmse[0] / std::sqrt(spps[i]);
  result.plot_svg = loglog_svg("Indirect view on cornell: RMSE against samples per pixel (mean of 4 seeds)",
                               "samples per pixel", "RMSE", {{"indirect view", spps, mean_rmse}, {"1/sqrt(spp) from 1 spp", spps, line}},
                               {-0.5});
  const int sw = quick ? 320 : 640, sh = quick ? 180 : 360, rounds = quick ? 3 : 7;
  const Speeds speeds = alternate_speeds(prepared, sw, sh, rounds, threads);
  const double whitted = median(speeds.whitted), indirect = median(speeds.indirect);
  result.mrays_ratio = indirect / whitted;
  std::ostringstream md;
  md << "\n## Indirect light: what the ambient term stands in for\n\n"
     << "The full image with indirect light on `cornell` (" << w << "x" << h << ", the scene's " << scene.indirect_bounces
     << " bounces) against a long run of the same estimator (two halves of " << half_spp << " spp with other seeds; "
     << "their difference puts its own RMSE at " << fmt("%.2g", ref_noise) << "), mean RMSE over " << seeds << " seeds:\n\n"
     << "| spp | RMSE | RMSE x sqrt(spp) |\n|---|---|---|\n";
  for (std::size_t i = 0; i < spps.size(); ++i) {
    md << "| " << spps[i] << " | " << fmt("%.4g", mean_rmse[i]) << " | " << fmt("%.4g", mean_rmse[i] * std::sqrt(spps[i]))
       << " |\n";
  }
  md << "\nFitted slope " << fmt("%.3f", result.rmse_slope) << " (1/sqrt(spp) is -0.5; the reference's noise is "
     << (ref_noise * 10 <= mean_rmse.back() ? "10x below" : "**not** 10x below") << " the smallest RMSE).\n\n"
     << "![RMSE against spp](indirect_spp.svg)\n\n"
     << "Speed, " << sw << "x" << sh << ", 1 spp a pass, " << rounds << " passes each, alternating, medians: the Whitted "
     << "image (packet tracer) " << fmt("%.1f", whitted) << " Mrays/s, the indirect view (scalar tracer, gather rays "
     << "counted) " << fmt("%.1f", indirect) << " Mrays/s: **" << fmt("%.2f", result.mrays_ratio) << "x**.\n";
  result.markdown = md.str();
  if (ref_noise * 10 > mean_rmse.back()) std::printf("CHECK FAILED: the indirect reference's noise is not 10x below\n");
  std::printf("  slope %.3f, Mrays/s whitted %.1f indirect %.1f (%.2fx)\n", result.rmse_slope, whitted, indirect,
              result.mrays_ratio);
  return result;
}

int write_indirect_report(bool quick, int threads, const std::string& out_dir) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  Writer out{out_dir};
  const IndirectBenchResult r = run_indirect_bench(quick, resolve_thread_count(threads));
  out.write("indirect.md", "# phonglab: the indirect light's convergence and speed\n\nMade by `phonglab-cli bench --only indirect" +
                               std::string(quick ? " --quick" : "") + "` on " + cpu_model() + ".\n" + r.markdown);
  out.write("indirect.csv", r.csv);
  out.write("indirect_spp.svg", r.plot_svg);
  std::printf("wrote %s/indirect.md\n", out_dir.c_str());
  return out.ok ? 0 : 1;
}

}  // namespace phonglab::bench
