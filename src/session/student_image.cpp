#include "session/student_image.h"

#include <filesystem>

#include "core/scene/math.h"
#include "io/image_read.h"

namespace phonglab {

OpenedStudentImage open_student_image(const std::string& path, int view_width, int view_height, std::string_view hint) {
  OpenedStudentImage out;
  out.name = std::filesystem::path(path).filename().string();
  const std::optional<ReadImage> read = read_image_file(path, &out.error);
  if (!read) return out;
  if (read->width != view_width || read->height != view_height) {
    out.error = out.name + " is " + std::to_string(read->width) + "x" + std::to_string(read->height) +
                ", the view renders " + std::to_string(view_width) + "x" + std::to_string(view_height) +
                ": render yours at the view's size";
    if (!hint.empty()) out.error += " (" + std::string(hint) + ")";
    return out;
  }
  out.image = student_image(*read);
  return out;
}

ProgressiveFrame compare_frame(const StudentImage& image) {
  ProgressiveFrame a;
  a.width = image.width;
  a.height = image.height;
  a.spp = 1;
  a.pixels.resize(static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height));
  const bool codes = image.units == StudentImage::Units::kCodes8;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const auto at = [&](std::size_t c) {
      const double v = image.rgb[3 * i + c];
      return static_cast<float>(codes ? srgb_to_linear(v / 255) : v);
    };
    a.pixels[i] = glm::vec3(at(0), at(1), at(2));
  }
  return a;
}

}  // namespace phonglab
