// A student's work checked against the reference (docs/checking.md): an image their own ray
// tracer rendered of a scene, or formulas typed in for the local terms. Both get a verdict, the
// pixels that differ, the largest difference, and, where one explains the difference, the name
// of the known mistake (src/check/mistakes.h) that gives the student's pixels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "check/mistakes.h"
#include "check/rules.h"
#include "core/accel/prepared_scene.h"
#include "core/scene/scene.h"

namespace phonglab {

// An image another program rendered, in its file's units.
struct StudentImage {
  enum class Units : std::uint8_t {
    kCodes8,  // 8-bit sRGB codes 0..255 (PNG, PPM with maxval 255): 1 code of tolerance
    kLinear,      // linear values, unclamped (PFM): 1e-3 + 1e-3 |reference| of tolerance
    kLinearUnit,  // linear values in [0, 1] (a PPM of maxval other than 255, a 16-bit PNG): the
                  // same tolerance, against the reference clamped to [0, 1] as the file holds it
  };
  int width = 0, height = 0;
  Units units = Units::kCodes8;
  std::vector<double> rgb;  // width * height * 3, rows from the top
};

struct CheckOptions {
  int spp = 1;          // samples per pixel of the reference (1: the pixel centres)
  int threads = 0;      // 0: all hardware threads
  bool pairs = true;    // try two mistakes at once when no single one explains half
  // Differing pixels a mistake is first tried on (an even stride through them); the named
  // mistake's share is then counted on up to `count_pixels` of them (all, in most checks).
  std::size_t sample_pixels = 1024;
  std::size_t count_pixels = 16384;
};

struct CheckResult {
  bool match = true;
  bool formulas = false;          // a formula check (else an image's)
  bool codes8 = false;            // differences in 8-bit codes (else linear values)
  int width = 0, height = 0;
  std::size_t pixels = 0, differing = 0;
  std::size_t nan = 0;            // pixels where yours is NaN or infinite
  double max_difference = 0;      // the largest channel difference, in the image's units
  int worst_x = 0, worst_y = 0;
  Color worst_yours{0}, worst_reference{0};  // at the worst pixel, in the image's units
  std::string mistake;            // "" (none), "no-shadows", "reflect-sign or view-reversed", "a and b"
  std::vector<Mistake> mistakes;  // the first named (one, or a pair)
  double explained = 0;           // percent of the differing pixels the named mistake explains
  // Per pixel: 0 the same, 1 yours brighter, 2 darker, 3 NaN (the difference view, --diff).
  std::vector<std::uint8_t> sign;
  std::vector<Color> reference;   // the reference image, linear
  std::vector<Color> yours;       // yours, linear (an 8-bit image decoded), NaN kept
};

// Checks `image` against `scene` rendered at the image's size. The image must have the size
// the caller renders at (scene.width x scene.height is set from it).
CheckResult check_image(const Scene& scene, const StudentImage& image, const CheckOptions& options = {});

// Checks the scene rendered with `formulas` (only the formulas are used) against the reference
// at scene.width x scene.height: the full image and each replaced term.
CheckResult check_formulas(const Scene& scene, const LocalRules& formulas, const CheckOptions& options = {});

// The verdict as text (docs/checking.md): "match"/"differs", "pixels N differing M", "max
// difference X at (x, y): yours Y, reference Z", "nan K" (formulas), "nearest mistake: ...".
std::string check_report_text(const CheckResult& result);
// One line for a student: the verdict and the nearest mistake in words.
std::string check_summary(const CheckResult& result);
// The difference view: the reference dimmed, yours brighter orange, darker blue, NaN magenta.
std::vector<Color> check_difference_image(const CheckResult& result);

// Yours against the reference at a probed pixel's primary hit, slot by slot and light by light,
// with the values of your statements there (the Formula panel's probe). "" when the ray met
// nothing or no formula is given.
std::string formula_probe_text(const Scene& scene, const ProbeNode& hit, const LocalRules& formulas);

// The value of one pixel (mean over `spp` samples) of `prepared`, for the full image and its
// five terms; `corner`: through (x, y) + the sample offset - 0.5 (the pixel-corner mistake).
struct PixelShade {
  Color value{0};
  Terms terms;
  bool finite = true;
};
PixelShade shade_pixel(const PreparedScene& prepared, int x, int y, int spp, bool corner = false);

}  // namespace phonglab
