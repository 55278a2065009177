// A student's own image of the view, read from its file and checked as the previewer checks one
// dropped on its window: rendered as
// phonglab-cli render writes it (1 spp, PNG) with the sign of R wrong, it differs and the mistake
// is named; the correct image, as an 8-bit PPM, matches at every pixel. (The previewer's path:
// read_image_file, student_image, check_image of the view's scene at the image's size.)
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "check/check.h"
#include "check/rules.h"
#include "core/render/render.h"
#include "io/image_io.h"
#include "io/image_read.h"
#include "io/scene/scene_io.h"
#include "tests/support/test_folder.h"

namespace phonglab {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 90;

struct StudentImageFiles : ::testing::Test {
  test::TestFolder temp{"phonglab-student-image-check"};
  const fs::path dir = temp.path();
  Scene lecture;
  void SetUp() override {
    LoadResult loaded = load_scene_arg("lecture");
    ASSERT_TRUE(loaded.ok()) << loaded.error_text();
    lecture = *loaded.scene;
    lecture.width = kWidth;
    lecture.height = kHeight;
  }
  // phonglab-cli render lecture --width W --height H --spp 1 [--formula 'specular=TEXT'] -o PATH.
  std::string render_png(const std::string& name, const std::string& specular) const {
    LocalRules rules;
    if (!specular.empty()) {
      FormulaError error;
      rules.formulas[static_cast<std::size_t>(FormulaSlot::kSpecular)] = Formula::compile(specular, &error);
      EXPECT_TRUE(rules.any()) << error.text();
    }
    const PreparedScene built(lecture);
    const PreparedScene prepared = rules.any() ? prepare_with_rules(lecture, built, rules) : built;
    Accumulator accum;
    accum.reset(kWidth, kHeight);
    render_passes(prepared, RenderOptions{}, accum, 1);
    const std::string path = (dir / name).string();
    EXPECT_EQ(write_image(path, mean_image(accum)), "");
    return path;
  }
  // The file as the previewer reads it.
  static StudentImage read(const std::string& path) {
    std::string error;
    const std::optional<ReadImage> image = read_image_file(path, &error);
    EXPECT_TRUE(image) << error;
    return image ? student_image(*image) : StudentImage{};
  }
};

TEST_F(StudentImageFiles, AnImageWithTheWrongSignOfRIsNamed) {
  const StudentImage mine = read(render_png("mine.png", "R = reflect(L, N); ks * pow(max(0, dot(R, V)), n)"));
  ASSERT_EQ(mine.width, kWidth);
  ASSERT_EQ(mine.height, kHeight);
  EXPECT_EQ(mine.units, StudentImage::Units::kCodes8);
  const CheckResult r = check_image(lecture, mine);
  EXPECT_FALSE(r.match);
  EXPECT_GT(r.differing, 0U);
  EXPECT_EQ(r.mistake, "reflect-sign or view-reversed") << check_report_text(r);
}

// convert right.png -depth 8 right.ppm: the same codes in a binary PPM of maxval 255.
TEST_F(StudentImageFiles, ACorrectImageAsAnEightBitPpmMatches) {
  const StudentImage png = read(render_png("right.png", ""));
  ASSERT_EQ(png.rgb.size(), static_cast<std::size_t>(kWidth) * kHeight * 3);
  const std::string ppm = (dir / "right.ppm").string();
  {
    std::ofstream out(ppm, std::ios::binary);
    out << "P6\n" << kWidth << " " << kHeight << "\n255\n";
    for (const double code : png.rgb) out.put(static_cast<char>(static_cast<unsigned char>(code)));
  }
  const StudentImage mine = read(ppm);
  EXPECT_EQ(mine.units, StudentImage::Units::kCodes8);
  EXPECT_EQ(mine.rgb, png.rgb);
  const CheckResult r = check_image(lecture, mine);
  EXPECT_TRUE(r.match) << check_report_text(r);
  EXPECT_EQ(r.differing, 0U);
}

}  // namespace
}  // namespace phonglab
