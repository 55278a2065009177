// Ray-primitive intersection: exact answers and the robustness cases of docs/accuracy.md (S, O, T).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/geometry/geometry.h"
#include "tests/support/test_support.h"

using namespace phonglab;

TEST(SphereIntersection, HitsUnitSphereAtKnownDistance) {
  const Sphere s{{0, 0, -5}, 1, 0};
  const auto t = intersect_sphere(s, make_ray({0, 0, 0}, {0, 0, -1}));
  ASSERT_TRUE(t.has_value());
  EXPECT_DOUBLE_EQ(*t, 4.0);
}

TEST(SphereIntersection, FromInsideReturnsFarRoot) {
  const Sphere s{{0, 0, 0}, 2, 0};
  const auto t = intersect_sphere(s, make_ray({0, 0, 0}, {1, 0, 0}));
  ASSERT_TRUE(t.has_value());
  EXPECT_DOUBLE_EQ(*t, 2.0);
}
