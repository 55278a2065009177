// Reading images other programs wrote (src/io/image_read.h): the project's own PNG and PFM read
// back to the codes and floats written, hand-built PPM (P6, P3; 8 and 16 bit), PFM (both byte
// orders, grey) and PNG (RGBA, grey, grey + alpha, palette, 16 bit) to exact values, every
// refusal with its exact positioned message, and a seeded round trip through a small writer of
// this file's own.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <stb/stb_image_write.h>

#include "core/scene/display8.h"
#include "core/scene/math.h"
#include "io/image_io.h"
#include "io/image_read.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;
using Kind = ReadImage::Kind;

// read_image that must succeed.
ReadImage read_ok(const std::string& bytes, const std::string& name = "image") {
  std::string error;
  const auto image = read_image(bytes, name, &error);
  EXPECT_TRUE(image) << error;
  return image ? *image : ReadImage{};
}

// The message of a read_image that must fail.
std::string read_error(const std::string& bytes, const std::string& name = "mine.ppm") {
  std::string error;
  const auto image = read_image(bytes, name, &error);
  EXPECT_FALSE(image) << "read " << name << " though it should not";
  EXPECT_FALSE(error.empty());
  return error;
}

// --- little byte writers of this file's own ---

std::string be16(unsigned v) { return {static_cast<char>(v >> 8), static_cast<char>(v & 0xFF)}; }
std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>((v >> 16) & 0xFF), static_cast<char>((v >> 8) & 0xFF),
          static_cast<char>(v & 0xFF)};
}
std::string float_bytes(float f, bool little_endian) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  std::string out = be32(bits);
  if (little_endian) {
    std::swap(out[0], out[3]);
    std::swap(out[1], out[2]);
  }
  return out;
}

// A PNG of stored (uncompressed) deflate blocks: `scanlines` are the rows, each with its filter
// byte, as the PNG specification lays them out. CRCs and the Adler-32 are computed properly.
std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const char ch : bytes) {
    crc ^= static_cast<unsigned char>(ch);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}
std::string chunk(const std::string& type, const std::string& data) {
  return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(crc32(type + data));
}
std::string zlib_stored(const std::string& raw) {
  std::string out = "\x78\x01";
  std::size_t pos = 0;
  do {
    const std::size_t n = std::min<std::size_t>(raw.size() - pos, 65535);
    const bool last = pos + n == raw.size();
    out += static_cast<char>(last ? 1 : 0);
    out += static_cast<char>(n & 0xFF);
    out += static_cast<char>(n >> 8);
    out += static_cast<char>(~n & 0xFF);
    out += static_cast<char>((~n >> 8) & 0xFF);
    out += raw.substr(pos, n);
    pos += n;
  } while (pos < raw.size());
  std::uint32_t a = 1, b = 0;
  for (const char ch : raw) {
    a = (a + static_cast<unsigned char>(ch)) % 65521;
    b = (b + a) % 65521;
  }
  return out + be32(b << 16 | a);
}
std::string png(std::uint32_t width, std::uint32_t height, int depth, int colour_type, const std::string& scanlines,
                const std::string& before_data = "") {
  std::string ihdr = be32(width) + be32(height);
  ihdr += static_cast<char>(depth);
  ihdr += static_cast<char>(colour_type);
  ihdr += std::string(3, '\0');  // deflate, adaptive filtering, no interlace
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + before_data +
         chunk("IDAT", zlib_stored(scanlines)) + chunk("IEND", "");
}

// stb_image_write's PNG of 8-bit samples with `channels` channels (another writer than the project's).
std::string stb_png(int width, int height, int channels, const std::vector<unsigned char>& samples) {
  std::string out;
  auto append = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  EXPECT_TRUE(stbi_write_png_to_func(append, &out, width, height, channels, samples.data(), width * channels));
  return out;
}

void expect_rgb(const ReadImage& image, const std::vector<double>& rgb) {
  ASSERT_EQ(image.rgb.size(), rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) EXPECT_EQ(image.rgb[i], rgb[i]) << "value " << i;
}

// --- the project's own writers ---

TEST(ImageReadRoundTrip, TheProjectsPngReadsBackAsTheCodesItWrote) {
  Image image;
  image.width = 3;
  image.height = 2;
  image.pixels = {{0, 0.5f, 1}, {0.2f, 2, -1}, {0.0031f, 0.04f, 0.9f}, {1, 1, 1}, {0.25f, 0.75f, 0.01f}, {0, 0, 0}};
  const ReadImage read = read_ok(encode_png_srgb(image), "render.png");
  EXPECT_EQ(read.format, "PNG");
  EXPECT_EQ(read.kind, Kind::kSrgb8);
  ASSERT_EQ(read.width, 3);
  ASSERT_EQ(read.height, 2);
  std::vector<double> expected;
  for (const glm::vec3& p : image.pixels) {
    for (int c = 0; c < 3; ++c) expected.push_back(linear_to_srgb8(p[c]));
  }
  expect_rgb(read, expected);
}

TEST(ImageReadRoundTrip, TheProjectsPfmReadsBackAsItsFloatsTopRowFirst) {
  Image image;
  image.width = 2;
  image.height = 3;
  for (int i = 0; i < 6; ++i) image.pixels.push_back({0.1f * float(i), -3.5f * float(i), 1e20f + float(i)});
  image.pixels[5].x = std::numeric_limits<float>::infinity();
  const ReadImage read = read_ok(encode_pfm(image), "render.pfm");
  EXPECT_EQ(read.format, "PFM");
  EXPECT_EQ(read.kind, Kind::kLinearFloat);
  ASSERT_EQ(read.width, 2);
  ASSERT_EQ(read.height, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 2; ++x) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(read.rgb[static_cast<std::size_t>((y * 2 + x) * 3 + c)], double(image.at(x, y)[c]))
            << "pixel (" << x << ", " << y << ") channel " << c;
      }
    }
  }
}

// --- PPM ---

TEST(ImageReadPpm, P6EightBitIsSrgbCodes) {
  const ReadImage read = read_ok("P6\n2 1\n255\n" + std::string("\x00\x7f\xff\x01\x02\x80", 6));
  EXPECT_EQ(read.format, "PPM (P6)");
  EXPECT_EQ(read.kind, Kind::kSrgb8);
  EXPECT_EQ(read.width, 2);
  EXPECT_EQ(read.height, 1);
  expect_rgb(read, {0, 127, 255, 1, 2, 128});
}

TEST(ImageReadPpm, P6SixteenBitIsBigEndianValueOverMaxval) {
  const ReadImage read =
      read_ok("P6 1 2 65535\n" + be16(0) + be16(1) + be16(65535) + be16(32768) + be16(256) + be16(12345));
  EXPECT_EQ(read.kind, Kind::kLinear16);
  expect_rgb(read, {0, 1 / 65535.0, 1, 32768 / 65535.0, 256 / 65535.0, 12345 / 65535.0});
  // maxval 1000 also takes two bytes a sample; maxval 15 one.
  expect_rgb(read_ok("P6 1 1 1000\n" + be16(1000) + be16(999) + be16(3)), {1, 999 / 1000.0, 3 / 1000.0});
  const ReadImage four_bit = read_ok("P6 1 1 15\n" + std::string("\x0f\x00\x07", 3));
  EXPECT_EQ(four_bit.kind, Kind::kLinear16);
  expect_rgb(four_bit, {1, 0, 7 / 15.0});
}

TEST(ImageReadPpm, HeaderCommentsAndWhitespaceFollowNetpbm) {
  // Comments between any fields, tabs and CRLF; the raster starts after one whitespace character,
  // or after the line end that closes a comment right behind the maxval.
  expect_rgb(read_ok("P6# a comment\r\n#another\n 1\t1 # size\n255\n" + std::string("\x0a\x20\x0d", 3)), {10, 32, 13});
  expect_rgb(read_ok("P6 1 1 255#comment\n" + std::string("abc")), {'a', 'b', 'c'});
  // Bytes after the image are ignored.
  expect_rgb(read_ok("P6 1 1 255\nxyz\n\n trailing"), {'x', 'y', 'z'});
}

TEST(ImageReadPpm, P3EightAndSixteenBitWithComments) {
  const ReadImage read = read_ok(
      "P3\n# written by hand\n2 2 # width height\n255\n"
      "0 1 2   255 254 253\n"
      "# the second row\n"
      "10\t20\r\n30 40 50 60\n\n# the end\n");
  EXPECT_EQ(read.format, "PPM (P3)");
  EXPECT_EQ(read.kind, Kind::kSrgb8);
  expect_rgb(read, {0, 1, 2, 255, 254, 253, 10, 20, 30, 40, 50, 60});
  const ReadImage deep = read_ok("P3 2 1 65535 65535 0 1 32767 40000 7");
  EXPECT_EQ(deep.kind, Kind::kLinear16);
  expect_rgb(deep, {1, 0, 1 / 65535.0, 32767 / 65535.0, 40000 / 65535.0, 7 / 65535.0});
}

TEST(ImageReadPpmErrors, HeaderFieldsAreCheckedAtTheirLines) {
  EXPECT_EQ(read_error("P6\n# c\n40 30\n70000\n"), "mine.ppm: line 4: maxval 70000 is over 65535");
  EXPECT_EQ(read_error("P6\n40 30\n70000\n"), "mine.ppm: line 3: maxval 70000 is over 65535");
  EXPECT_EQ(read_error("P3\n40 30\n0\n"), "mine.ppm: line 3: maxval 0 is not positive");
  EXPECT_EQ(read_error("P6 40 30 99999999999999999999999\n"),
            "mine.ppm: line 1: maxval 99999999999999999999999 is over 65535");
  EXPECT_EQ(read_error("P6\n0 30\n255\n"), "mine.ppm: line 2: width 0 is not positive");
  EXPECT_EQ(read_error("P6\n40\n\n16385\n255\n"), "mine.ppm: line 4: height 16385 is over 16384");
  EXPECT_EQ(read_error("P6\n40 x30\n255\n"), "mine.ppm: line 2: the height \"x30\" is not a whole number");
  EXPECT_EQ(read_error("P6\n-4 3\n255\n"), "mine.ppm: line 2: the width \"-4\" is not a whole number");
  EXPECT_EQ(read_error("P6\n4 3\n"), "mine.ppm: line 3: the header ends before the maxval");
  EXPECT_EQ(read_error("P3"), "mine.ppm: line 1: the header ends before the width");
}

TEST(ImageReadPpmErrors, ACutP6NamesBothSizesWithoutAllocatingTheImage) {
  EXPECT_EQ(read_error("P6\n40 30\n255\n" + std::string(1234, 'x')),
            "mine.ppm: the data ends after 1234 of 3600 bytes (width 40 x height 30 x 3 samples x 1 byte)");
  EXPECT_EQ(read_error("P6 2 1 65535\n" + std::string(11, 'x')),
            "mine.ppm: the data ends after 11 of 12 bytes (width 2 x height 1 x 3 samples x 2 bytes)");
  EXPECT_EQ(read_error("P6 1 1 255"),
            "mine.ppm: the data ends after 0 of 3 bytes (width 1 x height 1 x 3 samples x 1 byte)");
  // The largest size claimed by a tiny file: refused from the sizes, nothing allocated.
  EXPECT_EQ(read_error("P6 16384 16384 65535\nabc"),
            "mine.ppm: the data ends after 3 of 1610612736 bytes (width 16384 x height 16384 x 3 samples x 2 bytes)");
  EXPECT_EQ(read_error("P3 16384 16384 255\n1 2 3"),
            "mine.ppm: line 2: the data ends after 3 of 805306368 samples (width 16384 x height 16384 x 3 samples)");
}

TEST(ImageReadPpmErrors, ASampleOverMaxvalIsPlaced) {
  // P6: the byte (from 1) and the sample's pixel.
  EXPECT_EQ(read_error("P6 2 1 15\n" + std::string("\x01\x02\x03\x04\x10\x05", 6)),
            "mine.ppm: byte 15: sample 16 is over maxval 15 (sample 5 of 6: the green of pixel (1, 0))");
  EXPECT_EQ(read_error("P6 1 1 1000\n" + be16(5) + be16(1001) + be16(0)),
            "mine.ppm: byte 15: sample 1001 is over maxval 1000 (sample 2 of 3: the green of pixel (0, 0))");
  // P3: the line.
  EXPECT_EQ(read_error("P3\n# c\n2 2\n255\n1 2 3\n4 5 6\n300 8 9\n10 11 12\n"),
            "mine.ppm: line 7: sample 300 is over maxval 255 (sample 7 of 12: the red of pixel (0, 1))");
}

TEST(ImageReadPpmErrors, P3DataProblemsArePlaced) {
  EXPECT_EQ(read_error("P3\n2 1\n255\n1 2 3\n4 five 6\n"),
            "mine.ppm: line 5: \"five\" is not a whole number (sample 5 of 6: the green of pixel (1, 0))");
  EXPECT_EQ(read_error("P3\n2 1\n255\n1 2 3\n4\n\n"),
            "mine.ppm: line 7: the data ends after 4 of 6 samples (width 2 x height 1 x 3 samples)");
  EXPECT_EQ(read_error("P3\n1 1\n255\n1 2 3\n\n4\n"),
            "mine.ppm: line 6: \"4\" after the image's 3 samples (width 1 x height 1 x 3 samples)");
  EXPECT_EQ(read_error("P3 1 1 255 1 2 3 junk"),
            "mine.ppm: line 1: \"junk\" after the image's 3 samples (width 1 x height 1 x 3 samples)");
  // Whitespace and comments after the samples are fine.
  expect_rgb(read_ok("P3 1 1 255 1 2 3 \n\t# end\n\n"), {1, 2, 3});
}

// --- PFM ---

TEST(ImageReadPfm, LittleAndBigEndianRowsFromTheBottom) {
  // Two rows of one pixel: the file's first row is the image's bottom row.
  const std::vector<float> bottom = {1.5f, -2.0f, 1e-30f};
  const std::vector<float> top = {0.25f, 3e38f, -0.0f};
  for (const bool little : {true, false}) {
    std::string bytes = std::string("PF\n1 2\n") + (little ? "-1.0" : "1.0") + "\n";
    for (const float f : bottom) bytes += float_bytes(f, little);
    for (const float f : top) bytes += float_bytes(f, little);
    const ReadImage read = read_ok(bytes, "a.pfm");
    EXPECT_EQ(read.kind, Kind::kLinearFloat);
    expect_rgb(read, {0.25, double(3e38f), -0.0, 1.5, -2.0, double(1e-30f)});
    EXPECT_TRUE(std::signbit(read.rgb[2])) << "-0 stays -0";
  }
  // The scale's size is not applied; '+' is taken; bytes after the image are ignored.
  expect_rgb(read_ok("PF 1 1 +4.5\n" + float_bytes(2, false) + float_bytes(3, false) + float_bytes(4, false) + "\n"),
             {2, 3, 4});
}

TEST(ImageReadPfm, GreyIsRepeatedAndNanAndInfinityAreKept) {
  const float inf = std::numeric_limits<float>::infinity();
  std::string bytes = "Pf\n3 1\n-1\n";
  for (const float f : {0.5f, std::numeric_limits<float>::quiet_NaN(), -inf}) bytes += float_bytes(f, true);
  const ReadImage read = read_ok(bytes);
  EXPECT_EQ(read.format, "PFM");
  ASSERT_EQ(read.rgb.size(), 9U);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(read.rgb[static_cast<std::size_t>(c)], 0.5);
    EXPECT_TRUE(std::isnan(read.rgb[static_cast<std::size_t>(3 + c)]));
    EXPECT_EQ(read.rgb[static_cast<std::size_t>(6 + c)], -double(inf));
  }
}

TEST(ImageReadPfmErrors, HeaderAndSize) {
  EXPECT_EQ(read_error("PF\n2 2\n0\n", "a.pfm"),
            "a.pfm: line 3: the scale 0 is neither negative (little-endian) nor positive (big-endian)");
  EXPECT_EQ(read_error("PF\n2 2\n-1.0x\n", "a.pfm"), "a.pfm: line 3: the scale \"-1.0x\" is not a finite number");
  EXPECT_EQ(read_error("PF\n2 2\nnan\n", "a.pfm"), "a.pfm: line 3: the scale \"nan\" is not a finite number");
  EXPECT_EQ(read_error("PF\n2 2\n", "a.pfm"), "a.pfm: line 3: the header ends before the scale");
  EXPECT_EQ(read_error("PF\n# no comments in a PFM\n2 2\n-1\n", "a.pfm"),
            "a.pfm: line 2: the width \"#\" is not a whole number");
  EXPECT_EQ(read_error("PF\n40 30\n-1.0\n" + std::string(1000, '\0'), "a.pfm"),
            "a.pfm: the data ends after 1000 of 14400 bytes (width 40 x height 30 x 3 samples x 4 bytes)");
  EXPECT_EQ(read_error("Pf\n40 30\n-1.0\n" + std::string(1000, '\0'), "a.pfm"),
            "a.pfm: the data ends after 1000 of 4800 bytes (width 40 x height 30 x 1 sample x 4 bytes)");
  EXPECT_EQ(read_error("PF 16384 16384 -1\n", "a.pfm"),
            "a.pfm: the data ends after 0 of 3221225472 bytes (width 16384 x height 16384 x 3 samples x 4 bytes)");
}

// --- PNG ---

TEST(ImageReadPng, RgbaGreyAndGreyAlphaFromAnotherWriter) {
  const ReadImage rgba = read_ok(stb_png(2, 1, 4, {10, 20, 30, 0, 40, 50, 60, 255}));
  EXPECT_EQ(rgba.kind, Kind::kSrgb8);
  expect_rgb(rgba, {10, 20, 30, 40, 50, 60});  // alpha left out
  expect_rgb(read_ok(stb_png(3, 1, 1, {0, 128, 255})), {0, 0, 0, 128, 128, 128, 255, 255, 255});
  expect_rgb(read_ok(stb_png(1, 2, 2, {7, 0, 200, 99})), {7, 7, 7, 200, 200, 200});
}

TEST(ImageReadPng, PaletteAndLowBitDepthsAreEightBitCodes) {
  // A 2 x 1 palette image (indices 1, 0) and a 1-bit grey one (0 and 1 become 0 and 255).
  const std::string plte = chunk("PLTE", std::string("\x01\x02\x03\xfa\xfb\xfc", 6));
  expect_rgb(read_ok(png(2, 1, 8, 3, std::string("\x00\x01\x00", 3), plte)), {250, 251, 252, 1, 2, 3});
  expect_rgb(read_ok(png(2, 1, 1, 0, std::string("\x00\x40", 2))), {0, 0, 0, 255, 255, 255});
}

TEST(ImageReadPng, SixteenBitIsSrgbEncodedAndReadAsLinear) {
  const unsigned codes[] = {0, 1, 65535, 32768, 1000, 50000};
  std::string row(1, '\0');
  for (const unsigned v : codes) row += be16(v);
  const ReadImage read = read_ok(png(2, 1, 16, 2, row));
  EXPECT_EQ(read.kind, Kind::kLinear16);
  std::vector<double> expected;
  for (const unsigned v : codes) expected.push_back(srgb_to_linear(v / 65535.0));
  expect_rgb(read, expected);
  EXPECT_EQ(read.rgb[2], 1.0);
  // 16-bit grey + alpha: grey repeated, alpha left out.
  expect_rgb(read_ok(png(1, 1, 16, 4, std::string(1, '\0') + be16(65535) + be16(0))), {1, 1, 1});
}

TEST(ImageReadPngErrors, BrokenAndOversizedPngsAreNamed) {
  EXPECT_EQ(read_error(std::string("\x89PNG\r\n\x1a\n", 8) + "garbage!", "a.png"),
            "a.png: not a readable PNG (stb_image: first not IHDR)");
  EXPECT_EQ(read_error(std::string("\x89PNG\n\x1a\n\0\0\0\x0dIHDR", 15), "a.png"),
            "a.png: not a readable PNG (its signature is \"\\x89PNG\\n\\x1A\\n\\x00...\", "
            "not \"\\x89PNG\\r\\n\\x1A\\n\")");
  std::string cut = png(4, 4, 8, 2, std::string(4 * 13, '\0'));
  cut.resize(cut.size() - 30);
  EXPECT_EQ(read_error(cut, "a.png"),
            "a.png: the data ends inside the IDAT chunk at byte 34: 49 of its 63 bytes are there");
  std::string header_only = png(1, 1, 8, 2, std::string(4, '\0'));
  header_only.resize(33 + 8);
  EXPECT_EQ(read_error(header_only, "a.png"),
            "a.png: the data ends inside the IDAT chunk at byte 34: 0 of its 15 bytes are there");
  EXPECT_EQ(read_error(png(1, 1, 8, 2, std::string(4, '\0'), chunk("ABCD", "x")), "a.png"),
            "a.png: not a readable PNG (stb_image: a critical chunk of unknown type \"ABCD\")");
  EXPECT_EQ(read_error(png(1, 1, 8, 2, std::string(4, '\0'), chunk(std::string(4, '\0'), "")), "a.png"),
            "a.png: not a readable PNG (stb_image: a critical chunk of unknown type)");
  EXPECT_EQ(read_error(png(16385, 1, 8, 2, ""), "a.png"), "a.png: the PNG's width 16385 is over 16384");
  EXPECT_EQ(read_error(png(1, 20000, 8, 2, ""), "a.png"), "a.png: the PNG's height 20000 is over 16384");
  // A header promising far more than its compressed bytes can hold is refused before decoding.
  EXPECT_EQ(read_error(png(16384, 16384, 16, 6, std::string(9, '\0')), "a.png"),
            "a.png: the PNG's image data is 20 bytes compressed, too few for width 16384 x height 16384 "
            "(2147500032 bytes unpacked)");
}

// An empty IDAT chunk before the data made stb_image copy nothing from a null buffer, which UBSan
// reports (the fuzzer's seed regression-empty-idat.png). Such chunks are legal and hold no data:
// the image reads as it would without them.
TEST(ImageReadRegressions, EmptyIdatChunksAroundTheDataAreSkipped) {
  const std::string row("\x00\x01\x02\x03\x04\x05\x06", 7);
  const std::string with_empty = png(2, 1, 8, 2, row, chunk("IDAT", ""));
  expect_rgb(read_ok(with_empty), {1, 2, 3, 4, 5, 6});
  // Empty ones after the data too; an image whose only IDAT is empty has no data.
  std::string after = with_empty;
  after.insert(after.size() - 12, chunk("IDAT", "") + chunk("IDAT", ""));
  expect_rgb(read_ok(after), {1, 2, 3, 4, 5, 6});
  const std::string none = std::string("\x89PNG\r\n\x1a\n", 8) +
                           chunk("IHDR", be32(1) + be32(1) + std::string("\x08\x02\0\0\0", 5)) + chunk("IDAT", "") +
                           chunk("IEND", "");
  EXPECT_EQ(read_error(none, "a.png"), "a.png: not a readable PNG (stb_image: no IDAT)");
  // An empty IDAT chunk the file ends in, without its CRC (the fuzzer's regression-empty-idat-cut.png).
  const std::string cut = none.substr(0, 33) + be32(0) + "IDAT";
  EXPECT_EQ(read_error(cut, "a.png"), "a.png: not a readable PNG (stb_image: a critical chunk of unknown type)");
}

// stb_image grows its buffer to what an IDAT chunk claims before it finds the file shorter: 2 GiB
// for a 100-byte file (the fuzzer's seed regression-idat-claims-more.png). The reader refuses the
// chunk first, with both sizes.
TEST(ImageReadRegressions, AnIdatChunkLongerThanTheFileIsRefusedBeforeDecoding) {
  std::string claims = png(1, 1, 8, 2, std::string(4, '\0'));
  claims.replace(33, 4, be32(0x7fff0000));
  EXPECT_EQ(read_error(claims, "a.png"),
            "a.png: the data ends inside the IDAT chunk at byte 34: 31 of its 2147418112 bytes are there");
}

// --- memory ---

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

// Reads `bytes` with 16 MiB of address space to spare (of which the memory budget counts half),
// prints the error (or "read it") on stderr and exits.
[[noreturn]] void read_with_16_mib_to_spare(const std::string& bytes) {
  std::size_t pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  struct rlimit limit {};
  limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(pages * 4096 + (std::size_t{16} << 20));
  setrlimit(RLIMIT_AS, &limit);
  std::string error;
  const auto image = read_image(bytes, "big.ppm", &error);
  std::fprintf(stderr, "%s\n", image ? "read it" : error.c_str());
  std::exit(0);
}

TEST(ImageReadMemory, AnImageTooLargeForTheMemoryLeftIsRefusedWithItsSize) {
  if (kAddressSanitizer) GTEST_SKIP() << "ASan reserves terabytes of address space: no RLIMIT_AS under it";
  // The suite's process has the renderer's helper threads by now: the child re-executes the
  // test alone rather than forking them mid-flight.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  // 1024 x 1024 pixels, whose doubles need 24 MiB.
  const std::string bytes = "P6 1024 1024 255\n" + std::string(std::size_t{3} << 20, '\x80');
  EXPECT_EXIT(read_with_16_mib_to_spare(bytes), testing::ExitedWithCode(0),
              "big.ppm: reading the image would need about 24.0 MiB \\(1024 x 1024 pixels\\) but about "
              "[0-9.]+ MiB are available");
}

// --- detection and files ---

TEST(ImageReadFormat, TheFormatComesFromTheBytesNotTheName) {
  EXPECT_EQ(read_ok("P3 1 1 255 1 2 3", "looks.png").format, "PPM (P3)");
  EXPECT_EQ(read_error(std::string("GIF89a\x01\x00\x01\x00", 10), "x.gif"),
            "x.gif: not a PNG, PPM (P3/P6) or PFM image (starts with \"GIF89a\\x01\\x00...\")");
  EXPECT_EQ(read_error("P5\n1 1\n255\n\x01", "grey.pgm"),
            "grey.pgm: not a PNG, PPM (P3/P6) or PFM image (starts with \"P5\\n1 1\\n2...\")");
  EXPECT_EQ(read_error("Pfizer", "notes.txt"),
            "notes.txt: not a PNG, PPM (P3/P6) or PFM image (starts with \"Pfizer\")");
  EXPECT_EQ(read_error("", "empty.ppm"), "empty.ppm: the file is empty, not a PNG, PPM (P3/P6) or PFM image");
}

TEST(ImageReadFile, ReadsAFileAndNamesTheOnesItCannot) {
  const fs::path dir = fs::temp_directory_path() / ("phonglab_image_read_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "mine.ppm").string();
  std::ofstream(path, std::ios::binary) << "P6 1 1 255\n" << std::string("\x01\x02\x03", 3);
  std::string error;
  const auto image = read_image_file(path, &error);
  ASSERT_TRUE(image) << error;
  expect_rgb(*image, {1, 2, 3});
  EXPECT_FALSE(read_image_file((dir / "missing.png").string(), &error));
  EXPECT_EQ(error, (dir / "missing.png").string() + ": cannot open (No such file or directory)");
  EXPECT_FALSE(read_image_file(dir.string(), &error));
  EXPECT_EQ(error, dir.string() + ": cannot read (Is a directory)");
  std::ofstream(path, std::ios::binary) << "P6 1 1 256\n";
  EXPECT_FALSE(read_image_file(path, &error));
  EXPECT_EQ(error, path + ": the data ends after 0 of 6 bytes (width 1 x height 1 x 3 samples x 2 bytes)");
  fs::remove_all(dir);
}

// --- a seeded round trip through an independent writer ---

TEST(ImageReadProperty, RandomPpmAndPfmImagesReadBackExactly) {
  std::mt19937 rng(20261203);
  auto uniform = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const char* const spaces[] = {" ", "\n", "\t", "\r\n", "  \n ", "\n# a comment\n", " #c\n\t"};
  for (int round = 0; round < 300; ++round) {
    const int width = uniform(1, 9);
    const int height = uniform(1, 9);
    const int n = width * height * 3;
    const int format = uniform(0, 2);  // P6, P3, PFM
    std::string bytes;
    std::vector<double> expected(static_cast<std::size_t>(n));
    auto gap = [&](bool comments) { return std::string(spaces[uniform(0, comments ? 6 : 4)]); };
    if (format < 2) {
      const int maxval = uniform(0, 2) == 0 ? 255 : uniform(0, 1) ? uniform(1, 65535) : (uniform(0, 1) ? 65535 : 1);
      bytes = (format == 0 ? "P6" : "P3") + gap(true) + std::to_string(width) + gap(true) + std::to_string(height) +
              gap(true) + std::to_string(maxval) + (format == 0 ? "\n" : gap(true));
      for (int i = 0; i < n; ++i) {
        const int v = uniform(0, maxval);
        expected[static_cast<std::size_t>(i)] = maxval == 255 ? v : v / double(maxval);
        if (format == 1) bytes += std::to_string(v) + gap(true);
        else if (maxval < 256) bytes += static_cast<char>(v);
        else bytes += be16(static_cast<unsigned>(v));
      }
      if (format == 0 && uniform(0, 1)) bytes += "\n";
    } else {
      const bool little = uniform(0, 1) != 0;
      bytes = "PF" + gap(false) + std::to_string(width) + gap(false) + std::to_string(height) + gap(false) +
              (little ? "-1.0" : "1.0") + "\n";
      std::vector<float> values(static_cast<std::size_t>(n));
      for (float& f : values) {
        std::uint32_t bits = static_cast<std::uint32_t>(rng());
        std::memcpy(&f, &bits, sizeof f);
        if (std::isnan(f)) f = 0.125f;  // NaN compares unequal; kept NaNs are checked above
      }
      for (int row = height - 1; row >= 0; --row) {
        for (int k = 0; k < width * 3; ++k) {
          const float f = values[static_cast<std::size_t>(row * width * 3 + k)];
          bytes += float_bytes(f, little);
          expected[static_cast<std::size_t>(row * width * 3 + k)] = f;
        }
      }
    }
    std::string error;
    const auto read = read_image(bytes, "random", &error);
    ASSERT_TRUE(read) << "round " << round << ": " << error;
    ASSERT_EQ(read->width, width) << "round " << round;
    ASSERT_EQ(read->height, height) << "round " << round;
    ASSERT_EQ(read->rgb, expected) << "round " << round << ", format " << format;
  }
}

}  // namespace
}  // namespace phonglab
