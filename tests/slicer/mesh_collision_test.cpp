#include "slicer/mesh_collision.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/units.h"

namespace strand::slicer {
namespace {

// A square of side 2 * half in the plane through `centre` spanned by a and b (unit), n x n
// cells.
Mesh square(const Vec3& centre, const Vec3& a, const Vec3& b, double half, int n) {
  Mesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      m.vertices_mm.push_back(centre + (-half + 2 * half * j / n) * a +
                              (-half + 2 * half * i / n) * b);
  auto id = [&](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      m.triangles.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
    }
  }
  return m;
}

const NozzleCone kCone{30.0, 25.0, 1.0};  // the shipped profiles' assumption

TEST(MeshProximity, ClosestPointWithItsTriangleAndWeights) {
  const MeshProximity p(square(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 10.0, 4));
  const MeshPoint m = p.closest(Vec3(1.25, -3.5, 2.0));
  EXPECT_NEAR(m.distance_mm, 2.0, 1e-12);
  EXPECT_TRUE(m.point_mm.isApprox(Vec3(1.25, -3.5, 0.0), 1e-12));
  EXPECT_GE(m.triangle, 0);
  EXPECT_NEAR(m.barycentric.sum(), 1.0, 1e-12);
  EXPECT_GE(m.barycentric.minCoeff(), 0.0);
  // Beside the square: its nearest edge point.
  EXPECT_TRUE(p.closest(Vec3(15.0, 0.0, 0.0)).point_mm.isApprox(Vec3(10.0, 0.0, 0.0), 1e-12));
}

TEST(MeshProximity, ASurfaceUnderTheTipIsClear) {
  // The substrate 1 mm under the tip, the nozzle pointing down at it (axis up = +z).
  const MeshProximity p(square(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 40.0, 8));
  EXPECT_FALSE(p.cone_hit(kCone, Vec3(0, 0, 1.0), Vec3::UnitZ()).has_value());
  // The same plane across the nozzle 10 mm up its axis: hit on the axis, inside the length.
  const auto hit = p.cone_hit(kCone, Vec3(0, 0, -10.0), Vec3::UnitZ());
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->z(), 0.0, 1e-9);
  // Beyond the cone's length it is not the nozzle's business.
  EXPECT_FALSE(p.cone_hit(kCone, Vec3(0, 0, -26.0), Vec3::UnitZ()).has_value());
}

// A wall parallel to the nozzle axis at distance d from it, 0..30 mm up: the frustum's radius
// at its far end is 1 + 25 tan 30 = 15.434 mm, so a wall at 15.4 is touched and one at 15.5
// is not, though no triangle corner is inside the cone either way.
TEST(MeshProximity, TheConeIsExactNotJustCorners) {
  const double r_end = 1.0 + 25.0 * std::tan(deg_to_rad(30.0));
  for (const double d : {5.0, 15.4, 15.5, 20.0}) {
    const MeshProximity p(square(Vec3(d, 0.0, 15.0), Vec3::UnitY(), Vec3::UnitZ(), 15.0, 1));
    const auto hit = p.cone_hit(kCone, Vec3::Zero(), Vec3::UnitZ());
    EXPECT_EQ(hit.has_value(), d < r_end) << "wall at " << d;
    if (hit) {
      EXPECT_NEAR(hit->x(), d, 1e-9);
      const double radial = std::hypot(hit->x(), hit->y());
      EXPECT_LE(radial, 1.0 + hit->z() * std::tan(deg_to_rad(30.0)) + 1e-6);
    }
  }
}

TEST(MeshProximity, TheAxisTiltsWithTheNozzle) {
  // A wall 16 mm beside a nozzle pointing along +x (beyond the frustum's 15.43 mm): clear
  // while the nozzle looks along the wall, touched once the axis leans 40 deg towards it.
  const MeshProximity p(square(Vec3(12.0, 16.0, 0.0), Vec3::UnitX(), Vec3::UnitZ(), 12.0, 2));
  EXPECT_FALSE(p.cone_hit(kCone, Vec3::Zero(), Vec3::UnitX()).has_value());
  const Vec3 lean(std::cos(deg_to_rad(40.0)), std::sin(deg_to_rad(40.0)), 0.0);
  EXPECT_TRUE(p.cone_hit(kCone, Vec3::Zero(), lean).has_value());
}

}  // namespace
}  // namespace strand::slicer
