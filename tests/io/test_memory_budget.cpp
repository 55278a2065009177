// The memory estimate's arithmetic and its message (the limits themselves: tests/robustness).
#include <gtest/gtest.h>

#include "io/memory_budget.h"

namespace phonglab {
namespace {

TEST(MemoryBudget, RefusesOnlyWhatDoesNotFitAndSaysHowMuchItNeeds) {
  EXPECT_EQ(memory_refusal(100, 200, "the mesh", "x"), "");
  EXPECT_EQ(memory_refusal(100, 100, "the mesh", "x"), "") << "exactly fitting fits";
  EXPECT_EQ(memory_refusal(std::size_t{1} << 40, std::nullopt, "the mesh", "x"), "") << "unknown: allowed";
  EXPECT_EQ(memory_refusal(std::size_t{3} << 30, std::size_t{1} << 30, "the mesh", "9 triangles"),
            "the mesh would need about 3.0 GiB (9 triangles) but about 1.0 GiB are available");
  EXPECT_EQ(byte_size(512 * 1024), "512 KiB");
  EXPECT_EQ(byte_size(std::size_t{12} << 20), "12.0 MiB");
  EXPECT_GT(mesh_bytes_needed(0, 0, 2), mesh_bytes_needed(0, 0, 1));
  EXPECT_EQ(json_bytes_needed(0), 0U);
  const auto available = available_memory();
  ASSERT_TRUE(available) << "Linux has /proc/meminfo";
  EXPECT_GT(*available, std::size_t{1} << 20);
}

}  // namespace
}  // namespace phonglab
