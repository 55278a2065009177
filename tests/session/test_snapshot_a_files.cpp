// A of the compare from a student's image file (session/snapshot_a.h, SnapshotA::set_file_image, as
// FormulaShell::open_image sets it): compared with the live image whatever the samples, the
// caption names the image, one of another size says both sizes; closing the image goes back to
// the live image with no A.
#include <gtest/gtest.h>

#include "session/snapshot_a.h"

namespace phonglab {
namespace {

ProgressiveFrame frame(std::uint32_t spp, int width = 8, int height = 4) {
  ProgressiveFrame f;
  f.spp = spp;
  f.width = width;
  f.height = height;
  f.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), glm::vec3(0.25f));
  return f;
}

TEST(SnapshotAFromAFile, TheStudentsImageIsAOfTheCompareWhateverTheSamples) {
  SnapshotA a;
  a.request(3, false);  // an A asked of the renderer is replaced by the file's
  a.set_file_image(frame(1), "mine.png");
  EXPECT_EQ(a.file_name(), "mine.png");
  ASSERT_TRUE(a.has_image());
  EXPECT_FALSE(a.requested());
  EXPECT_TRUE(a.comparable(frame(64), CompareView::kDifference, true)) << "the student's samples are the pixel centres";
  EXPECT_EQ(a.caption(frame(64), CompareView::kDifference, true, 64, 4),
            "|live - A|: A, your image mine.png, against the live image");
  EXPECT_EQ(a.caption(frame(64), CompareView::kWipe, true, 64, 4), "wipe: A, your image mine.png, against the live image");
  EXPECT_EQ(a.target_spp(64, true, CompareView::kDifference, true), 64) << "the live image converges as usual";
}

TEST(SnapshotAFromAFile, AViewOfAnotherSizeSaysBothSizes) {
  SnapshotA a;
  a.set_file_image(frame(1, 8, 4), "mine.png");
  EXPECT_FALSE(a.comparable(frame(1, 16, 8), CompareView::kDifference, true));
  EXPECT_EQ(a.caption(frame(1, 16, 8), CompareView::kDifference, true, 64, 4),
            "A is your image 8x4, the view is now 16x8: open it at the view's size");
}

TEST(SnapshotAFromAFile, ClosingTheImageGoesBackToTheLiveImage) {
  SnapshotA a;
  a.set_file_image(frame(1), "mine.png");
  a.clear();  // FormulaShell::close_image: A was the file's
  EXPECT_EQ(a.file_name(), "");
  EXPECT_FALSE(a.has_image());
  EXPECT_EQ(a.caption(frame(64), CompareView::kWipe, true, 64, 4), "no A yet: Snapshot A keeps the finished image");
}

}  // namespace
}  // namespace phonglab
