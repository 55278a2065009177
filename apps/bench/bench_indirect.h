// The bench's indirect light section: the estimator's convergence against a long reference run of
// itself (RMSE against samples per pixel, with the 1/sqrt(spp) line), and its Mrays/s beside the
// Whitted image's on the Cornell box, side by side.
#pragma once

#include <sstream>
#include <string>

#include "apps/bench/bench_common.h"

namespace phonglab::bench {

struct IndirectBenchResult {
  std::string markdown;
  std::string csv;         // indirect.csv: scene, spp, seed, rmse
  std::string plot_svg;    // indirect_spp.svg
  double rmse_slope = 0;   // fitted log-log slope of RMSE against spp
  double mrays_ratio = 0;  // indirect view's Mrays/s over the Whitted image's (medians)
};

IndirectBenchResult run_indirect_bench(bool quick, int threads);

// `phonglab-cli bench --only indirect`: the section alone, as DIR/indirect.md with its files.
int write_indirect_report(bool quick, int threads, const std::string& out_dir);

}  // namespace phonglab::bench
