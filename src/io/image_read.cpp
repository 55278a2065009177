#include "io/image_read.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <mutex>
#include <utility>

#include "core/scene/chars.h"
#include "core/scene/math.h"
#include "io/memory_budget.h"

// stb_image's PNG decoder, compiled here and private to this file (STB_IMAGE_STATIC): no other
// file of the project compiles it, so it cannot clash with a copy in a library the program links
// (Debian's libstb has one), and the fuzzer instruments the very decoder it attacks. This file is
// kept out of unity builds (src/io/CMakeLists.txt) so that the macros stay here.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO
#define STBI_NO_LINEAR
#define STBI_MAX_DIMENSIONS 16384
#include <stb_image.h>

namespace phonglab {

namespace {

constexpr int kMaxSide = 16384;  // the largest width or height read
static_assert(kMaxSide == STBI_MAX_DIMENSIONS);

const char* const kChannel[3] = {"red", "green", "blue"};

std::optional<ReadImage> fail(std::string* error, std::string message) {
  if (error) *error = std::move(message);
  return std::nullopt;
}

// Netpbm's whitespace: blank, tab, newline, carriage return, vertical tab, form feed.
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// The first `limit` bytes of `text` for a message, quoted: printable ASCII as it is, the rest
// escaped (\n, \r, \t, \xNN), "..." when cut.
std::string quoted(std::string_view text, std::size_t limit = 16) {
  std::string out = "\"";
  for (std::size_t i = 0; i < std::min(text.size(), limit); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      out += hex;
    }
  }
  if (text.size() > limit) out += "...";
  return out + "\"";
}

// Where sample `index` (from 0) of a width-wide RGB image is: "sample 14 of 36: the red of pixel (1, 1)".
std::string sample_place(std::size_t index, std::size_t count, int width) {
  const std::size_t pixel = index / 3;
  const auto w = static_cast<std::size_t>(width);
  return "sample " + std::to_string(index + 1) + " of " + std::to_string(count) + ": the " + kChannel[index % 3] +
         " of pixel (" + std::to_string(pixel % w) + ", " + std::to_string(pixel / w) + ")";
}

// "width 40 x height 30 x 3 samples": the size a header promises, for messages.
std::string size_text(int width, int height, int channels) {
  return "width " + std::to_string(width) + " x height " + std::to_string(height) + " x " + std::to_string(channels) +
         (channels == 1 ? " sample" : " samples");
}

// The text header of a PPM or PFM: tokens separated by whitespace (and, in a PPM, `#` comments
// to the end of the line), with the line each starts on.
class Header {
 public:
  Header(std::string_view bytes, std::size_t pos, bool comments) : bytes_(bytes), pos_(pos), comments_(comments) {}

  // The next token, empty at the end of the bytes; token_line() is the line it starts on.
  std::string_view next() {
    skip_space_and_comments();
    token_line_ = line_;
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_]) && !(comments_ && bytes_[pos_] == '#')) ++pos_;
    return bytes_.substr(start, pos_ - start);
  }

  // Skips a comment that starts here, up to (not over) the carriage return or newline ending it.
  void skip_comment() {
    if (!comments_ || pos_ >= bytes_.size() || bytes_[pos_] != '#') return;
    while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && bytes_[pos_] != '\r') ++pos_;
  }

  // Steps over the one whitespace character that ends a binary header (none at the end).
  void skip_one_space() {
    if (pos_ < bytes_.size()) {
      if (bytes_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  std::size_t pos() const { return pos_; }
  int line() const { return line_; }
  int token_line() const { return token_line_; }
  std::string at_line() const { return "line " + std::to_string(token_line_) + ": "; }

 private:
  void skip_space_and_comments() {
    while (pos_ < bytes_.size()) {
      const char c = bytes_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (is_space(c)) {
        ++pos_;
      } else if (comments_ && c == '#') {
        skip_comment();
      } else {
        break;
      }
    }
  }

  std::string_view bytes_;
  std::size_t pos_;
  bool comments_;
  int line_ = 1;
  int token_line_ = 1;
};

// A token of decimal digits as a number; values past 10^12 stay at 10^12 (messages show the
// digits as written). nullopt when the token holds anything but digits.
std::optional<std::uint64_t> whole_number(std::string_view token) {
  constexpr std::uint64_t kCap = 1'000'000'000'000;
  if (token.empty()) return std::nullopt;
  std::uint64_t value = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    value = std::min(kCap, value * 10 + static_cast<std::uint64_t>(c - '0'));
  }
  return value;
}

// Reads the header's next field, a whole number 1..max, named `what` ("width", "maxval").
std::optional<int> header_number(Header& header, const char* what, int max, const std::string& name,
                                 std::string* error) {
  const std::string_view token = header.next();
  if (token.empty()) {
    fail(error, name + ": line " + std::to_string(header.line()) + ": the header ends before the " + what);
    return std::nullopt;
  }
  const auto value = whole_number(token);
  if (!value) {
    fail(error, name + ": " + header.at_line() + "the " + what + " " + quoted(token) + " is not a whole number");
    return std::nullopt;
  }
  if (*value == 0) {
    fail(error, name + ": " + header.at_line() + what + " 0 is not positive");
    return std::nullopt;
  }
  if (*value > static_cast<std::uint64_t>(max)) {
    fail(error, name + ": " + header.at_line() + what + " " + std::string(token) + " is over " + std::to_string(max));
    return std::nullopt;
  }
  return static_cast<int>(*value);
}

// "" when the doubles of a width x height image fit in the memory left, else the refusal.
std::string refuse_pixels(int width, int height, std::size_t extra_bytes, const std::string& name) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  return refuse_if_too_large(pixels * 3 * sizeof(double) + extra_bytes, name + ": reading the image",
                             std::to_string(width) + " x " + std::to_string(height) + " pixels");
}

// Whether the magic number (two bytes) ends where a header's whitespace or comment starts.
bool magic_ends(std::string_view bytes, bool comments) {
  return bytes.size() == 2 || is_space(bytes[2]) || (comments && bytes[2] == '#');
}

// --- PPM ---------------------------------------------------------------------------------------

std::optional<ReadImage> read_ppm(std::string_view bytes, const std::string& name, bool plain, std::string* error) {
  Header header(bytes, 2, true);
  const auto width = header_number(header, "width", kMaxSide, name, error);
  if (!width) return std::nullopt;
  const auto height = header_number(header, "height", kMaxSide, name, error);
  if (!height) return std::nullopt;
  const auto maxval = header_number(header, "maxval", 65535, name, error);
  if (!maxval) return std::nullopt;

  ReadImage image;
  image.width = *width;
  image.height = *height;
  image.format = plain ? "PPM (P3)" : "PPM (P6)";
  image.kind = *maxval == 255 ? ReadImage::Kind::kSrgb8 : ReadImage::Kind::kLinear16;
  // Codes as they are for 8-bit sRGB, else value / maxval (a division: exactly the nearest double).
  const double top = *maxval;
  const auto convert = [&](unsigned value) { return *maxval == 255 ? double(value) : value / top; };
  const std::size_t count = static_cast<std::size_t>(*width) * static_cast<std::size_t>(*height) * 3;

  if (!plain) {
    // One whitespace character (after a comment, the line end closing it) and then the samples.
    header.skip_comment();
    header.skip_one_space();
    const std::size_t start = header.pos();
    const std::string_view data = bytes.substr(start);
    const std::size_t sample_bytes = *maxval < 256 ? 1 : 2;
    const std::size_t need = count * sample_bytes;
    if (data.size() < need) {
      return fail(error, name + ": the data ends after " + std::to_string(data.size()) + " of " + std::to_string(need) +
                             " bytes (" + size_text(*width, *height, 3) + " x " +
                             (sample_bytes == 1 ? "1 byte)" : "2 bytes)"));
    }
    if (const std::string refusal = refuse_pixels(*width, *height, 0, name); !refusal.empty()) {
      return fail(error, refusal);
    }
    image.rgb.resize(count);
    const auto* p = reinterpret_cast<const unsigned char*>(data.data());
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned value = sample_bytes == 1 ? p[i] : (unsigned{p[2 * i]} << 8) | p[2 * i + 1];  // big-endian
      if (value > static_cast<unsigned>(*maxval)) {
        // The byte as counted from 1, like the lines.
        return fail(error, name + ": byte " + std::to_string(start + i * sample_bytes + 1) + ": sample " +
                               std::to_string(value) + " is over maxval " + std::to_string(*maxval) + " (" +
                               sample_place(i, count, *width) + ")");
      }
      image.rgb[i] = convert(value);
    }
    return image;
  }

  // P3: every sample needs a digit and a separator, so a file shorter than that is cut short;
  // it is read all the same (the vector grows with what is there) to say where it ends.
  const std::size_t rest = bytes.size() - std::min(bytes.size(), header.pos());
  if (rest >= 2 * count - 1) {
    if (const std::string refusal = refuse_pixels(*width, *height, 0, name); !refusal.empty()) {
      return fail(error, refusal);
    }
    image.rgb.reserve(count);
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::string_view token = header.next();
    if (token.empty()) {
      return fail(error, name + ": line " + std::to_string(header.line()) + ": the data ends after " +
                             std::to_string(i) + " of " + std::to_string(count) + " samples (" +
                             size_text(*width, *height, 3) + ")");
    }
    const auto value = whole_number(token);
    if (!value) {
      return fail(error, name + ": " + header.at_line() + quoted(token) + " is not a whole number (" +
                             sample_place(i, count, *width) + ")");
    }
    if (*value > static_cast<std::uint64_t>(*maxval)) {
      return fail(error, name + ": " + header.at_line() + "sample " + std::string(token) + " is over maxval " +
                             std::to_string(*maxval) + " (" + sample_place(i, count, *width) + ")");
    }
    image.rgb.push_back(convert(static_cast<unsigned>(*value)));
  }
  if (const std::string_view junk = header.next(); !junk.empty()) {
    return fail(error, name + ": " + header.at_line() + quoted(junk) + " after the image's " + std::to_string(count) +
                           " samples (" + size_text(*width, *height, 3) + ")");
  }
  return image;
}

// --- PFM ---------------------------------------------------------------------------------------

std::optional<ReadImage> read_pfm(std::string_view bytes, const std::string& name, bool grey, std::string* error) {
  Header header(bytes, 2, false);
  const auto width = header_number(header, "width", kMaxSide, name, error);
  if (!width) return std::nullopt;
  const auto height = header_number(header, "height", kMaxSide, name, error);
  if (!height) return std::nullopt;
  const std::string_view token = header.next();
  if (token.empty()) {
    return fail(error, name + ": line " + std::to_string(header.line()) + ": the header ends before the scale");
  }
  // The scale's sign is the byte order; a leading '+' is allowed (from_chars takes none).
  const std::string_view digits = token.size() > 1 && token[0] == '+' ? token.substr(1) : token;
  double scale = 0;
  const auto [end, ec] = double_from_chars(digits.data(), digits.data() + digits.size(), scale);
  if (ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(scale)) {
    return fail(error, name + ": " + header.at_line() + "the scale " + quoted(token) + " is not a finite number");
  }
  if (scale == 0) {
    return fail(error, name + ": " + header.at_line() + "the scale " + std::string(token) +
                           " is neither negative (little-endian) nor positive (big-endian)");
  }
  const bool little_endian = scale < 0;
  header.skip_one_space();

  const int channels = grey ? 1 : 3;
  const std::size_t pixels = static_cast<std::size_t>(*width) * static_cast<std::size_t>(*height);
  const std::size_t need = pixels * static_cast<std::size_t>(channels) * 4;
  const std::string_view data = bytes.substr(header.pos());
  if (data.size() < need) {
    return fail(error, name + ": the data ends after " + std::to_string(data.size()) + " of " + std::to_string(need) +
                           " bytes (" + size_text(*width, *height, channels) + " x 4 bytes)");
  }
  if (const std::string refusal = refuse_pixels(*width, *height, 0, name); !refusal.empty()) {
    return fail(error, refusal);
  }

  ReadImage image;
  image.width = *width;
  image.height = *height;
  image.kind = ReadImage::Kind::kLinearFloat;
  image.format = "PFM";
  image.rgb.resize(pixels * 3);
  const auto* p = reinterpret_cast<const unsigned char*>(data.data());
  for (int row = 0; row < *height; ++row) {  // the file's rows from the bottom
    const std::size_t y = static_cast<std::size_t>(*height - 1 - row);
    for (std::size_t x = 0; x < static_cast<std::size_t>(*width); ++x) {
      const std::size_t pixel = y * static_cast<std::size_t>(*width) + x;
      for (int c = 0; c < channels; ++c) {
        const unsigned char* b = p + 4 * ((static_cast<std::size_t>(row) * static_cast<std::size_t>(*width) + x) *
                                              static_cast<std::size_t>(channels) +
                                          static_cast<std::size_t>(c));
        const std::uint32_t bits =
            little_endian ? std::uint32_t{b[0]} | std::uint32_t{b[1]} << 8 | std::uint32_t{b[2]} << 16 |
                                std::uint32_t{b[3]} << 24
                          : std::uint32_t{b[3]} | std::uint32_t{b[2]} << 8 | std::uint32_t{b[1]} << 16 |
                                std::uint32_t{b[0]} << 24;
        float value;
        std::memcpy(&value, &bits, sizeof value);
        if (grey) {
          for (int k = 0; k < 3; ++k) image.rgb[pixel * 3 + static_cast<std::size_t>(k)] = value;
        } else {
          image.rgb[pixel * 3 + static_cast<std::size_t>(c)] = value;
        }
      }
    }
  }
  return image;
}

// --- PNG ---------------------------------------------------------------------------------------

std::uint32_t big_endian32(const unsigned char* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | std::uint32_t{p[3]};
}

// What a PNG's header chunk promises, how many compressed bytes its IDAT chunks hold, where its
// empty IDAT chunks are, and where the file ends inside one.
struct PngLayout {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int channels = 0;  // of the stored samples: 1 grey or palette, 2 grey + alpha, 3 RGB, 4 RGBA
  int depth = 0;     // bits a sample
  std::size_t compressed = 0;
  std::vector<std::size_t> empty_idat;  // offsets of IDAT chunks of no data (12 bytes, the last maybe cut)
  std::optional<std::size_t> cut_idat;  // the offset of an IDAT chunk whose data the file ends in
  std::size_t cut_length = 0;           // its length, and how many of its bytes the file holds
  std::size_t cut_have = 0;
};

// Reads the IHDR chunk and walks the chunks as the decoder does, up to IEND or a chunk the file
// ends in; nullopt when there is no IHDR of a known colour type first (stb_image then says what
// is wrong).
std::optional<PngLayout> png_layout(std::string_view bytes) {
  const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
  if (bytes.size() < 8 + 8 + 13 || std::memcmp(p + 12, "IHDR", 4) != 0 || big_endian32(p + 8) != 13) {
    return std::nullopt;
  }
  PngLayout layout;
  layout.width = big_endian32(p + 16);
  layout.height = big_endian32(p + 20);
  layout.depth = p[24];
  switch (p[25]) {
    case 0: layout.channels = 1; break;
    case 2: layout.channels = 3; break;
    case 3: layout.channels = 1; break;
    case 4: layout.channels = 2; break;
    case 6: layout.channels = 4; break;
    default: return std::nullopt;
  }
  std::size_t pos = 8;
  while (bytes.size() - pos >= 8) {  // a chunk: length, type, data, CRC
    const std::size_t length = big_endian32(p + pos);
    const std::size_t room = bytes.size() - pos - 8;  // what follows the length and type
    const bool idat = std::memcmp(p + pos + 4, "IDAT", 4) == 0;
    if (idat && length > room) {
      layout.cut_idat = pos;
      layout.cut_length = length;
      layout.cut_have = room;
      break;
    }
    if (idat) {
      layout.compressed += length;
      if (length == 0) layout.empty_idat.push_back(pos);  // perhaps without its CRC, at the end
    }
    if (std::memcmp(p + pos + 4, "IEND", 4) == 0 || length + 4 > room) break;  // the end, or a cut chunk
    pos += 12 + length;
  }
  return layout;
}

std::optional<ReadImage> read_png(std::string_view bytes, const std::string& name, std::string* error) {
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    return fail(error, name + ": the PNG is over 2 GiB, more than stb_image reads");
  }
  // A PNG moved as text (line ends converted) or cut short has a broken signature; stb_image
  // would only call it an unknown type.
  constexpr std::string_view kSignature("\x89PNG\r\n\x1a\n", 8);
  if (bytes.substr(0, 8) != kSignature) {
    return fail(error, name + ": not a readable PNG (its signature is " + quoted(bytes, 8) + ", not " +
                           quoted(kSignature) + ")");
  }
  // Checked before stb_image allocates the image the header promises: the size, and whether the
  // compressed data can hold it at all (deflate packs at most 1032 bytes into one).
  std::string without_empty_idat;
  if (const auto layout = png_layout(bytes)) {
    // stb_image would allocate what the chunk claims before finding the file too short.
    if (layout->cut_idat) {
      return fail(error, name + ": the data ends inside the IDAT chunk at byte " +
                             std::to_string(*layout->cut_idat + 1) + ": " + std::to_string(layout->cut_have) +
                             " of its " + std::to_string(layout->cut_length) + " bytes are there");
    }
    for (const auto& [what, side] : {std::pair{"width", layout->width}, std::pair{"height", layout->height}}) {
      if (side > static_cast<std::uint32_t>(kMaxSide)) {
        return fail(error, name + ": the PNG's " + what + " " + std::to_string(side) + " is over " +
                               std::to_string(kMaxSide));
      }
    }
    const std::size_t row_bytes =
        (std::size_t{layout->width} * static_cast<std::size_t>(layout->channels * layout->depth) + 7) / 8;
    const std::size_t unpacked = std::size_t{layout->height} * (1 + row_bytes);  // a filter byte a row
    if (layout->width > 0 && layout->height > 0 && unpacked > 1032 * layout->compressed + 1032) {
      return fail(error, name + ": the PNG's image data is " + std::to_string(layout->compressed) +
                             " bytes compressed, too few for width " + std::to_string(layout->width) + " x height " +
                             std::to_string(layout->height) + " (" + std::to_string(unpacked) + " bytes unpacked)");
    }
    if (layout->width > 0 && layout->height > 0) {
      const std::string refusal = refuse_pixels(static_cast<int>(layout->width), static_cast<int>(layout->height),
                                                2 * unpacked, name);
      if (!refusal.empty()) return fail(error, refusal);
    }
    // An IDAT chunk of no data is allowed, but stb_image copies its nothing into a buffer not yet
    // allocated (memcpy from a null pointer: undefined behaviour, reported by UBSan); holding no
    // data, such chunks are left out of what it decodes.
    if (!layout->empty_idat.empty()) {
      std::size_t from = 0;
      for (const std::size_t at : layout->empty_idat) {
        without_empty_idat.append(bytes.substr(from, at - from));
        from = std::min(at + 12, bytes.size());
      }
      without_empty_idat.append(bytes.substr(from));
      bytes = without_empty_idat;
    }
  }

  // One decode at a time: stb_image writes the name of an unknown chunk into a static buffer.
  static std::mutex decoding;
  const std::lock_guard<std::mutex> lock(decoding);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int length = static_cast<int>(bytes.size());
  const bool sixteen = stbi_is_16_bit_from_memory(data, length) != 0;
  int width = 0;
  int height = 0;
  int channels = 0;
  void* pixels = sixteen ? static_cast<void*>(stbi_load_16_from_memory(data, length, &width, &height, &channels, 0))
                         : static_cast<void*>(stbi_load_from_memory(data, length, &width, &height, &channels, 0));
  if (!pixels) {
    std::string reason = stbi_failure_reason() ? stbi_failure_reason() : "";
    // "XXXX PNG chunk not known", the type's four bytes as they are (a NUL among them cuts it).
    constexpr std::string_view kUnknownChunk = " PNG chunk not known";
    if (const std::size_t at = reason.find(kUnknownChunk); at != std::string::npos || reason.empty()) {
      reason = "a critical chunk of unknown type" +
               (at != std::string::npos && at == 4 ? " " + quoted(std::string_view(reason).substr(0, 4)) : "");
    }
    return fail(error, name + ": not a readable PNG (stb_image: " + reason + ")");
  }
  ReadImage image;
  image.width = width;
  image.height = height;
  image.format = "PNG";
  image.kind = sixteen ? ReadImage::Kind::kLinear16 : ReadImage::Kind::kSrgb8;
  const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  image.rgb.resize(count * 3);
  const auto stride = static_cast<std::size_t>(channels);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t c = 0; c < 3; ++c) {
      // Grey (with or without alpha) repeats its one channel; alpha is left out.
      const std::size_t from = i * stride + (stride < 3 ? 0 : c);
      image.rgb[i * 3 + c] = sixteen ? srgb_to_linear(static_cast<const stbi_us*>(pixels)[from] / 65535.0)
                                     : double(static_cast<const stbi_uc*>(pixels)[from]);
    }
  }
  stbi_image_free(pixels);
  return image;
}

}  // namespace

std::optional<ReadImage> read_image(std::string_view bytes, const std::string& name, std::string* error) {
  if (bytes.size() >= 4 && bytes.substr(0, 4) == "\x89PNG") return read_png(bytes, name, error);
  if (bytes.size() >= 2 && bytes[0] == 'P') {
    switch (bytes[1]) {
      case '6':
        if (magic_ends(bytes, true)) return read_ppm(bytes, name, false, error);
        break;
      case '3':
        if (magic_ends(bytes, true)) return read_ppm(bytes, name, true, error);
        break;
      case 'F':
        if (magic_ends(bytes, false)) return read_pfm(bytes, name, false, error);
        break;
      case 'f':
        if (magic_ends(bytes, false)) return read_pfm(bytes, name, true, error);
        break;
      default: break;
    }
  }
  if (bytes.empty()) return fail(error, name + ": the file is empty, not a PNG, PPM (P3/P6) or PFM image");
  return fail(error, name + ": not a PNG, PPM (P3/P6) or PFM image (starts with " + quoted(bytes, 8) + ")");
}

std::optional<ReadImage> read_image_file(const std::string& path, std::string* error) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return fail(error, path + ": cannot open (" + std::strerror(errno) + ")");
  std::string bytes;
  char buffer[1 << 16];
  std::size_t got;
  while ((got = std::fread(buffer, 1, sizeof buffer, file)) > 0) bytes.append(buffer, got);
  const bool failed = std::ferror(file) != 0;
  const int read_errno = errno;
  std::fclose(file);
  if (failed) return fail(error, path + ": cannot read (" + std::strerror(read_errno) + ")");
  return read_image(bytes, path, error);
}

StudentImage student_image(const ReadImage& image) {
  StudentImage student;
  student.width = image.width;
  student.height = image.height;
  student.units = image.kind == ReadImage::Kind::kSrgb8      ? StudentImage::Units::kCodes8
                  : image.kind == ReadImage::Kind::kLinear16 ? StudentImage::Units::kLinearUnit
                                                             : StudentImage::Units::kLinear;
  student.rgb = image.rgb;
  return student;
}

}  // namespace phonglab
