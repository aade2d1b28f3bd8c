// Regions from contours: nesting by even-odd, offsets that shrink, split and vanish.
#include "slicer/region.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::slicer {
namespace {

Ring square(double x0, double y0, double side) {
  return {Vec2(x0, y0), Vec2(x0 + side, y0), Vec2(x0 + side, y0 + side), Vec2(x0, y0 + side)};
}

// A contour far beyond any machine (a hostile mesh's vertex at 1e15 mm) is refused in one
// line before its coordinates are cast to Clipper's integers (it threw from inside Clipper).
TEST(Region, ContourBeyondTheCoordinateRangeIsRefused) {
  const Ring far = {{0, 0}, {1e15, 0}, {1e15, 1}};
  EXPECT_THROW(region_from_oriented_loops({far}), InputError);
  EXPECT_THROW(region_from_contours({far}), InputError);
  const Ring near = {{0, 0}, {10, 0}, {10, 10}};
  EXPECT_EQ(region_from_oriented_loops({near}).size(), 1u);
}

TEST(Region, NestedContoursBecomeHolesAndIslands) {
  Ring outer = square(0, 0, 30), hole = square(5, 5, 20), island = square(10, 10, 10);
  std::reverse(outer.begin(), outer.end());  // orientation of the input does not matter
  const Region r = region_from_contours({island, outer, hole});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NEAR(area_mm2(r), 900 - 400 + 100, 1e-6);
  EXPECT_TRUE(contains(r, Vec2(15, 15)));
  EXPECT_FALSE(contains(r, Vec2(7, 7)));
}

TEST(Region, OffsetShrinksSplitsAndVanishes) {
  // Two 10 mm squares joined by a 1 mm neck.
  const Region r = region_from_contours(
      {{Vec2(0, 0), Vec2(10, 0), Vec2(10, 4.5), Vec2(12, 4.5), Vec2(12, 0), Vec2(22, 0),
        Vec2(22, 10), Vec2(12, 10), Vec2(12, 5.5), Vec2(10, 5.5), Vec2(10, 10), Vec2(0, 10)}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(offset_region(r, -0.6).size(), 2u) << "the neck pinches off";
  EXPECT_NEAR(area_mm2(offset_region(r, -1.0)), 2 * 64.0, 0.2)
      << "two 8 x 8 squares, rounded inner corners";
  EXPECT_TRUE(offset_region(r, -6.0).empty());
  const double lost = area_mm2(region_difference(r, offset_region(offset_region(r, -0.6), 0.6)));
  EXPECT_GT(lost, 2.0) << "opening loses the 1 x 2 mm neck";
  EXPECT_LT(lost, 2.0 + 12 * 0.36 * (1 - kPi / 4)) << "and a little at each convex corner";
}

}  // namespace
}  // namespace strand::slicer
