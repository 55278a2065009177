// The bench's yardsticks beside the acceleration section: what users compare against first. A
// plain float brute-force Whitted loop (float_loop.h) and Embree single-ray queries, on
// `lecture` and on the same scene with its floor as two triangles, contenders alternating frame
// by frame in one run.
#pragma once

#include <string>

namespace phonglab {

struct YardstickResult {
  std::string markdown;       // a "## Against the yardsticks" section
  std::string csv;            // yardsticks.csv
  bool checks_passed = true;  // false after a "CHECK FAILED" line
};

YardstickResult run_yardsticks(bool quick, int threads);

}  // namespace phonglab
