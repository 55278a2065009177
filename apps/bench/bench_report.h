// `phonglab-cli bench`: the speed-versus-error report (report.md, CSV files, SVG plots).
#pragma once

#include <string>

namespace phonglab {

struct BenchReportOptions {
  std::string out_dir = "bench-out";  // where report.md, *.csv and *.svg go
  bool quick = false;                 // small images and few samples: under a minute, for CI
  int threads = 0;                    // 0: all hardware threads
};

// Runs every measurement and writes the report. Returns a process exit code (0, or 1 when a
// file cannot be written); progress goes to stdout.
int run_bench_report(const BenchReportOptions& options);

}  // namespace phonglab
