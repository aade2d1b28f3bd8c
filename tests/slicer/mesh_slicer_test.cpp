// Slices of shapes with known sections: a cube's square, a cylinder's circle, a torus's
// two circles and a bored cylinder's hole, within 0.01 mm of the analytic contour.
#include "slicer/mesh_slicer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/units.h"
#include "tests/support/mesh_shapes.h"

namespace strand::slicer {
namespace {

constexpr double kContourTolMm = 0.01;

// Largest distance from a contour vertex, and from each edge midpoint, to the circle.
double worst_circle_error(const Ring& ring, double radius) {
  double worst = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 mid = (ring[i] + ring[(i + 1) % ring.size()]) / 2.0;
    worst = std::max({worst, std::abs(ring[i].norm() - radius), std::abs(mid.norm() - radius)});
  }
  return worst;
}

TEST(MeshSlicer, CubeGivesItsSquareAtEveryHeight) {
  const MeshSlicer s(testing::box_mesh(Vec3(10, 20, 30)));
  for (double z : {0.25, 15.0, 29.75}) {
    const auto contours = slice_at(s, z);
    ASSERT_EQ(contours.size(), 1u) << z;
    EXPECT_NEAR(std::abs(signed_area_mm2(contours[0])), 200.0, 1e-9);
    for (const Vec2& p : contours[0]) {
      const double to_edge =
          std::min({std::abs(p.x()), std::abs(p.x() - 10), std::abs(p.y()), std::abs(p.y() - 20)});
      EXPECT_LT(to_edge, 1e-9);
    }
  }
}

TEST(MeshSlicer, CylinderGivesItsCircle) {
  const MeshSlicer s(testing::tube_mesh(10.0, 0.0, 5.0, 720));
  const auto contours = slice_at(s, 2.5);
  ASSERT_EQ(contours.size(), 1u);
  EXPECT_LT(worst_circle_error(contours[0], 10.0), kContourTolMm);
}

TEST(MeshSlicer, PlaneThroughVerticesStillGivesOneClosedContour) {
  const MeshSlicer s(testing::box_mesh(Vec3(4, 4, 4)));
  EXPECT_EQ(slice_at(s, 4.0 - 1e-12).size(), 1u);
  EXPECT_EQ(slice_at(s, 0.0).size(), 1u) << "moved just above the bottom face";
}

TEST(MeshSlicer, TorusGivesItsTwoCircles) {
  const double R = 20.0, r = 5.0;
  const MeshSlicer s(testing::torus_mesh(R, r, 512, 256));
  for (double z : {1.0, 5.0, 8.5}) {
    const double half = std::sqrt(r * r - (z - r) * (z - r));
    const Region region = region_from_contours(slice_at(s, z));
    ASSERT_EQ(region.size(), 1u) << z;
    ASSERT_EQ(region[0].holes.size(), 1u) << "the torus' hole";
    EXPECT_LT(worst_circle_error(region[0].outer, R + half), kContourTolMm) << z;
    EXPECT_LT(worst_circle_error(region[0].holes[0], R - half), kContourTolMm) << z;
  }
}

TEST(MeshSlicer, BoredCylinderSlicesToARegionWithAHole) {
  const auto layers = slice_layers(testing::tube_mesh(10, 3, 2, 256), 0.5, 4);
  ASSERT_EQ(layers.size(), 4u);
  for (const Region& r : layers) {
    ASSERT_EQ(r.size(), 1u);
    ASSERT_EQ(r[0].holes.size(), 1u);
    EXPECT_GT(signed_area_mm2(r[0].outer), 0.0) << "outer counter-clockwise";
    EXPECT_LT(signed_area_mm2(r[0].holes[0]), 0.0) << "hole clockwise";
    EXPECT_NEAR(area_mm2(r), kPi * (100 - 9), 0.05 * kPi * 100 / 256);
    EXPECT_FALSE(contains(r, Vec2(0, 0)));
    EXPECT_TRUE(contains(r, Vec2(6, 0)));
  }
}

}  // namespace
}  // namespace strand::slicer
