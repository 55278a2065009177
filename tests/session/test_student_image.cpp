// A student's image file opened for the check (session/student_image.h), as the previewer's drop
// and the page's file field open it: refused with both sizes when it is not the view's, unreadable
// files said as such, and as A of the compare its 8-bit codes decoded to the linear values a
// render of them shows.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/scene/math.h"
#include "session/student_image.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

struct OpeningAStudentImage : ::testing::Test {
  test::TestFolder temp{"phonglab-student-image"};
  const fs::path dir = temp.path();
  // A binary PPM (maxval 255) of w x h whose pixel i is codes (i, 2i, 3i) mod 256.
  std::string ppm(const std::string& name, int w, int h) const {
    const std::string path = (dir / name).string();
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << w << " " << h << "\n255\n";
    for (int i = 0; i < w * h; ++i) {
      out.put(static_cast<char>(i % 256)).put(static_cast<char>((2 * i) % 256)).put(static_cast<char>((3 * i) % 256));
    }
    return path;
  }
};

TEST_F(OpeningAStudentImage, AnImageOfAnotherSizeIsRefusedWithBothSizesAndTheClientsHint) {
  const std::string path = ppm("small.ppm", 64, 48);
  const OpenedStudentImage opened = open_student_image(path, 320, 180, "the Probe panel names it");
  EXPECT_FALSE(opened.image);
  EXPECT_EQ(opened.name, "small.ppm");
  EXPECT_EQ(opened.error, "small.ppm is 64x48, the view renders 320x180: render yours at the view's size "
                          "(the Probe panel names it)");
  EXPECT_EQ(open_student_image(path, 320, 180).error,
            "small.ppm is 64x48, the view renders 320x180: render yours at the view's size");
}

TEST_F(OpeningAStudentImage, AFileThatDoesNotReadSaysWhy) {
  const OpenedStudentImage opened = open_student_image((dir / "missing.png").string(), 8, 4);
  EXPECT_FALSE(opened.image);
  EXPECT_NE(opened.error.find("missing.png"), std::string::npos) << opened.error;
}

TEST_F(OpeningAStudentImage, AsAItsCodesAreTheLinearValuesTheyEncode) {
  const OpenedStudentImage opened = open_student_image(ppm("mine.ppm", 8, 4), 8, 4);
  ASSERT_TRUE(opened.image) << opened.error;
  EXPECT_EQ(opened.error, "");
  EXPECT_EQ(opened.image->units, StudentImage::Units::kCodes8);
  const ProgressiveFrame a = compare_frame(*opened.image);
  ASSERT_EQ(a.width, 8);
  ASSERT_EQ(a.height, 4);
  EXPECT_EQ(a.spp, 1U);
  ASSERT_EQ(a.pixels.size(), 32U);
  for (int i = 0; i < 32; ++i) {
    const glm::vec3& p = a.pixels[static_cast<std::size_t>(i)];
    EXPECT_EQ(p.x, static_cast<float>(srgb_to_linear((i % 256) / 255.0))) << i;
    EXPECT_EQ(p.y, static_cast<float>(srgb_to_linear(((2 * i) % 256) / 255.0))) << i;
    EXPECT_EQ(p.z, static_cast<float>(srgb_to_linear(((3 * i) % 256) / 255.0))) << i;
  }
}

}  // namespace
}  // namespace phonglab
