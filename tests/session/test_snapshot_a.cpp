// Snapshot A of the A/B compare (src/session/snapshot_a.h): taken only from the image it names,
// dropped when an edit comes first, compared like with like, and a presented lesson's difference
// held at A's samples; A from a student's image file (FormulaShell::open_image), compared whatever
// the samples and closed back to the live image.
#include <gtest/gtest.h>

#include "session/snapshot_a.h"

namespace phonglab {
namespace {

ProgressiveFrame frame(std::uint64_t generation, int divisor, std::uint32_t spp, int width = 8, int height = 4) {
  ProgressiveFrame f;
  f.generation = generation;
  f.divisor = divisor;
  f.spp = spp;
  f.width = width;
  f.height = height;
  f.pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), glm::vec3(0.5f));
  return f;
}

TEST(SnapshotA, WaitsForTheFinishedImageOfItsGeneration) {
  SnapshotA a;
  a.request(7, false);
  EXPECT_FALSE(a.take_when_ready(7, frame(7, 1, 3), false));  // converging: not yet
  EXPECT_TRUE(a.requested());
  EXPECT_TRUE(a.take_when_ready(7, frame(7, 1, 64), true));
  EXPECT_FALSE(a.requested());
  ASSERT_TRUE(a.has_image());
  EXPECT_EQ(a.image().spp, 64U);
}

TEST(SnapshotA, AnEditBeforeTheImageIsDoneDropsIt) {
  SnapshotA a;
  a.request(7, false);
  EXPECT_FALSE(a.take_when_ready(8, frame(8, 1, 64), true));  // the renderer moved on
  EXPECT_TRUE(a.dropped());
  EXPECT_FALSE(a.requested());
  EXPECT_FALSE(a.has_image());
  EXPECT_EQ(a.caption(frame(8, 1, 64), CompareView::kWipe, true, 64, 4),
            "A was not taken: the view changed before the image was done");
}

TEST(SnapshotA, ALessonsATakesTheFirstFullResolutionImage) {
  SnapshotA a;
  a.request(3, true);
  EXPECT_FALSE(a.take_when_ready(3, frame(3, 2, 1), false));  // half resolution: not yet
  EXPECT_TRUE(a.take_when_ready(3, frame(3, 1, 1), false));   // full, one sample: taken, not final
  EXPECT_EQ(a.image().spp, 1U);
}

TEST(SnapshotA, TheDifferenceComparesOnlyTheSameSamples) {
  SnapshotA a;
  a.request(1, false);
  ASSERT_TRUE(a.take_when_ready(1, frame(1, 1, 16), true));
  EXPECT_TRUE(a.comparable(frame(2, 1, 4), CompareView::kWipe, true));
  EXPECT_FALSE(a.comparable(frame(2, 1, 4), CompareView::kDifference, true));
  EXPECT_TRUE(a.comparable(frame(2, 1, 16), CompareView::kDifference, true));
  EXPECT_TRUE(a.comparable(frame(2, 1, 4), CompareView::kDifference, false));  // against the indirect light
  EXPECT_FALSE(a.comparable(frame(2, 2, 16, 4, 2), CompareView::kWipe, true));   // another size
  EXPECT_EQ(a.caption(frame(2, 1, 4), CompareView::kDifference, true, 64, 4),
            "|live - A| shows when live has A's 16 spp (now 4)");
  EXPECT_EQ(a.caption(frame(2, 1, 16, 16, 8), CompareView::kWipe, true, 64, 4),
            "A is 8x4, the view is now 16x8: take A again to compare");
}

TEST(SnapshotA, APresentedLessonsDifferenceStaysAtASamples) {
  SnapshotA a;
  EXPECT_EQ(a.target_spp(64, true, CompareView::kDifference, true), 64);  // no A
  a.request(1, true);
  ASSERT_TRUE(a.take_when_ready(1, frame(1, 1, 1), false));
  EXPECT_EQ(a.target_spp(64, true, CompareView::kDifference, true), 1);
  EXPECT_EQ(a.target_spp(64, false, CompareView::kDifference, true), 64);  // exploring
  EXPECT_EQ(a.target_spp(64, true, CompareView::kWipe, true), 64);
  EXPECT_EQ(a.target_spp(64, true, CompareView::kDifference, false), 64);  // the indirect light settles with samples
  EXPECT_EQ(a.target_spp(0, false, CompareView::kNone, true), 1);
}

TEST(SnapshotA, ClearingForgetsAAndTheRequest) {
  SnapshotA a;
  a.request(1, false);
  ASSERT_TRUE(a.take_when_ready(1, frame(1, 1, 8), true));
  a.request(2, false);
  a.clear();
  EXPECT_FALSE(a.has_image());
  EXPECT_FALSE(a.requested());
  EXPECT_EQ(a.caption(frame(3, 1, 8), CompareView::kWipe, true, 64, 4), "no A yet: Snapshot A keeps the finished image");
}

// A from a file.
TEST(SnapshotAFromAFile, TheStudentsImageIsAOfTheCompareWhateverTheSamples) {
  SnapshotA a;
  a.request(3, false);  // an A asked of the renderer is replaced by the file's
  a.set_file_image(frame(0, 1, 1), "mine.png");
  EXPECT_EQ(a.file_name(), "mine.png");
  ASSERT_TRUE(a.has_image());
  EXPECT_FALSE(a.requested());
  EXPECT_TRUE(a.comparable(frame(0, 1, 64), CompareView::kDifference, true)) << "the student's samples are the pixel centres";
  EXPECT_EQ(a.caption(frame(0, 1, 64), CompareView::kDifference, true, 64, 4),
            "|live - A|: A, your image mine.png, against the live image");
  EXPECT_EQ(a.caption(frame(0, 1, 64), CompareView::kWipe, true, 64, 4), "wipe: A, your image mine.png, against the live image");
  EXPECT_EQ(a.target_spp(64, true, CompareView::kDifference, true), 64) << "the live image converges as usual";
}

TEST(SnapshotAFromAFile, AViewOfAnotherSizeSaysBothSizes) {
  SnapshotA a;
  a.set_file_image(frame(0, 1, 1, 8, 4), "mine.png");
  EXPECT_FALSE(a.comparable(frame(0, 1, 1, 16, 8), CompareView::kDifference, true));
  EXPECT_EQ(a.caption(frame(0, 1, 1, 16, 8), CompareView::kDifference, true, 64, 4),
            "A is your image 8x4, the view is now 16x8: open it at the view's size");
}

TEST(SnapshotAFromAFile, ClosingTheImageGoesBackToTheLiveImage) {
  SnapshotA a;
  a.set_file_image(frame(0, 1, 1), "mine.png");
  a.clear();  // FormulaShell::close_image: A was the file's
  EXPECT_EQ(a.file_name(), "");
  EXPECT_FALSE(a.has_image());
  EXPECT_EQ(a.caption(frame(0, 1, 64), CompareView::kWipe, true, 64, 4), "no A yet: Snapshot A keeps the finished image");
}

}  // namespace
}  // namespace phonglab
