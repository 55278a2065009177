// Reading an image another program wrote (a student's render, to be checked against phonglab's):
// PNG, PPM (P6 binary and P3 plain, 8 and 16 bit) and PFM, told apart by their first bytes.
// The values stay in the file's own units; a broken file is refused with a message that names
// the file and the line, byte or sample where it breaks.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "check/check.h"

namespace phonglab {

// An image as read from a file, in that file's units.
struct ReadImage {
  int width = 0;
  int height = 0;
  enum class Kind : std::uint8_t {
    kSrgb8,        // 8-bit sRGB codes 0..255, as `render` writes PNG: an 8-bit PNG, or a PPM of maxval 255
    kLinear16,     // linear values in [0, 1]: a PPM of any other maxval 1..65535 (value / maxval), or a
                   // 16-bit PNG (taken as sRGB-encoded like the 8-bit ones: code / 65535 through the
                   // inverse sRGB curve)
    kLinearFloat,  // linear floats of a PFM, unclamped (NaN and infinities kept as they are)
  };
  Kind kind = Kind::kSrgb8;
  std::vector<double> rgb;  // width x height x 3 values, rows from the top-left (a PFM's are flipped)
  std::string format;       // "PNG", "PPM (P6)", "PPM (P3)" or "PFM", for messages
};

// Reads `bytes` (a file's content) named `name` in messages. The format comes from the first
// bytes, not the name: "\x89PNG", "P6", "P3", "PF" (RGB) or "Pf" (grey, repeated into R, G, B).
//   PNG: 8-bit grey, grey + alpha, RGB, RGBA or palette (alpha ignored), or 16-bit, via stb_image.
//   PPM: Netpbm's rules: whitespace-separated width, height, maxval (1..65535) with `#` comments
//        to the end of a line; P6 samples are 1 byte (maxval < 256) or 2 bytes big-endian, after
//        exactly one whitespace character; P3 samples are decimal, separated by whitespace and
//        comments. Bytes after a P6 image are ignored, as is whitespace after a P3 one.
//   PFM: "PF"/"Pf", width, height, scale (negative: little-endian floats, positive: big-endian;
//        its size is not applied), one whitespace character, then rows from the bottom. Bytes
//        after the image are ignored.
// Width and height are 1..16384 each. On failure returns nullopt and sets *error to a message
// such as "mine.ppm: line 3: maxval 70000 is over 65535".
std::optional<ReadImage> read_image(std::string_view bytes, const std::string& name, std::string* error);

// The image as a check takes it (check/check.h): 8-bit codes, linear values in [0, 1] (16 bit),
// or unclamped linear values (PFM).
StudentImage student_image(const ReadImage& image);

// read_image of the file at `path`, or "path: cannot open (No such file or directory)" and the
// like when it cannot be read.
std::optional<ReadImage> read_image_file(const std::string& path, std::string* error);

}  // namespace phonglab
