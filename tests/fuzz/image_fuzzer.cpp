// libFuzzer target: any bytes as an image file (read_image tells PNG, PPM and PFM apart by their
// first bytes). A rejected image must say why, starting with the file's name; an accepted one
// must hold width x height x 3 values, each within its kind's range (8-bit codes: whole numbers
// 0..255; linear 16-bit: 0..1; a PFM's floats: anything), and every value is read.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "io/image_read.h"

using namespace phonglab;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::string error;
  const auto image = read_image(bytes, "fuzz.img", &error);
  if (!image) {
    if (error.rfind("fuzz.img: ", 0) != 0 || error.size() <= 10) std::abort();  // rejected without saying why
    return 0;
  }
  if (image->width < 1 || image->height < 1 || image->width > 16384 || image->height > 16384) std::abort();
  if (image->rgb.size() != static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height) * 3) {
    std::abort();
  }
  if (image->format.empty()) std::abort();
  double sum = 0;
  for (const double v : image->rgb) {
    switch (image->kind) {
      case ReadImage::Kind::kSrgb8:
        if (!(v >= 0 && v <= 255 && v == std::floor(v))) std::abort();
        break;
      case ReadImage::Kind::kLinear16:
        if (!(v >= 0 && v <= 1)) std::abort();
        break;
      case ReadImage::Kind::kLinearFloat:
        break;  // NaN and infinities are kept, for a checker to count
    }
    sum += v;
  }
  volatile double sink = sum;  // every value read
  (void)sink;
  return 0;
}
