// Reading PFM images back (the tests check what the CLI wrote; nothing in the programs reads PFM).
#pragma once

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "io/image_io.h"

namespace phonglab {

// Parses a colour PFM ("PF", either byte order); an empty Image and `error` when it cannot.
inline Image decode_pfm(const std::string& bytes, std::string* error = nullptr) {
  std::istringstream in(bytes);
  std::string magic;
  int w = 0, h = 0;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  if (!in || magic != "PF" || w <= 0 || h <= 0 || scale == 0) {
    if (error) *error = "not a colour PFM file";
    return {};
  }
  in.get();  // the single whitespace character after the scale
  const std::size_t offset = static_cast<std::size_t>(in.tellg());
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3;
  if (bytes.size() < offset + count * 4) {
    if (error) *error = "PFM file is truncated";
    return {};
  }
  Image img;
  img.width = w;
  img.height = h;
  img.pixels.resize(static_cast<std::size_t>(w) * h);
  const bool little = scale < 0;
  std::size_t pos = offset;
  for (int y = h - 1; y >= 0; --y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        std::uint32_t bits = 0;
        for (int b = 0; b < 4; ++b) {
          const auto byte = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[pos + (little ? b : 3 - b)]));
          bits |= byte << (8 * b);
        }
        pos += 4;
        float f;
        std::memcpy(&f, &bits, sizeof f);
        img.at(x, y)[c] = f;
      }
    }
  }
  return img;
}

// decode_pfm of a file's bytes.
inline Image read_pfm(const std::string& path, std::string* error = nullptr) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (error) *error = "cannot open " + path;
    return {};
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  return decode_pfm(ss.str(), error);
}

}  // namespace phonglab
