#include "slicer/cylinder_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <map>

#include "slicer/units.h"

namespace strand::slicer {
namespace {

constexpr double kR = 20.0;
constexpr double kL = 80.0;

CylinderSurface cylinder(ArcLengthAt at = ArcLengthAt::Surface, double inset = 0.0) {
  return CylinderSurface({kR, kL, at, inset});
}

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-12) {
  EXPECT_NEAR((a - b).norm(), 0.0, tol) << a.transpose() << " vs " << b.transpose();
}

TEST(CylinderSurface, UZeroIsOnTheXAxisWithTheNormalAlongIt) {
  // Hand-computed: u = 0 is the line the nozzle faces at turn 0; offset 1 mm raises it.
  const SurfaceFrame f = cylinder().frame_at(Vec2(0.0, 30.0), 1.0);
  expect_near(f.point_mm, Vec3(21.0, 0.0, 30.0));
  expect_near(f.normal, Vec3(1.0, 0.0, 0.0));
}

TEST(CylinderSurface, QuarterCircumferenceIsNinetyDegreesAround) {
  // u = pi R / 2 is a quarter of the way around: on +y, normal +y.
  const SurfaceFrame f = cylinder().frame_at(Vec2(kPi * kR / 2.0, 10.0), 0.0);
  expect_near(f.point_mm, Vec3(0.0, kR, 10.0), 1e-12);
  expect_near(f.normal, Vec3(0.0, 1.0, 0.0), 1e-15);
}

TEST(CylinderSurface, DerivativeLengthsAreTheStretchAndMatchDifferences) {
  for (const auto& c : {cylinder(), cylinder(ArcLengthAt::Deposition, 0.4)}) {
    for (double offset : {0.0, 0.8, 2.4}) {
      const Vec2 uv(7.3, 12.0);
      const SurfaceFrame f = c.frame_at(uv, offset);
      EXPECT_NEAR(f.d_du.norm(), c.u_stretch(offset), 1e-12);
      EXPECT_NEAR(f.d_dv.norm(), 1.0, 1e-15);
      const double h = 1e-6;
      const Vec3 du = (c.frame_at(uv + Vec2(h, 0), offset).point_mm -
                       c.frame_at(uv - Vec2(h, 0), offset).point_mm) /
                      (2 * h);
      expect_near(du, f.d_du, 1e-7);
    }
  }
}

TEST(CylinderSurface, StretchIsOneOnTheMeasuredRadius) {
  EXPECT_NEAR(cylinder().u_stretch(0.0), 1.0, 1e-15);
  EXPECT_NEAR(cylinder().u_stretch(2.0), 22.0 / 20.0, 1e-15);
  // Deposition: u measured at the bead centre, 0.4 mm under a tip at offset 0.8.
  const auto dep = cylinder(ArcLengthAt::Deposition, 0.4);
  EXPECT_NEAR(dep.u_radius_mm(0.8), 20.4, 1e-12);
  EXPECT_NEAR(dep.u_stretch(0.8), 20.8 / 20.4, 1e-12);
  EXPECT_NEAR(*dep.u_period_mm(0.8), kTwoPi * 20.4, 1e-9);
}

TEST(CylinderSurface, FixedMeasureKeepsEveryLayerAtTheSameAngles) {
  const CylinderSurface c({kR, kL, ArcLengthAt::Deposition, 0.4, 0.8});
  EXPECT_NEAR(c.angle_rad(10.0, 0.8), c.angle_rad(10.0, 4.0), 1e-15);
  EXPECT_NEAR(*c.u_period_mm(4.0), kTwoPi * 20.4, 1e-9);
}

TEST(CylinderSurface, PatternSeenFromOutsideIsNotMirrored) {
  const SurfaceFrame f = cylinder().frame_at(Vec2(3.0, 4.0), 0.5);
  EXPECT_GT(f.d_du.cross(f.d_dv).dot(f.normal), 0.0);
}

TEST(CylinderSurface, UIsPeriodicAndVIsBounded) {
  const auto c = cylinder();
  expect_near(c.frame_at(Vec2(5.0, 1.0), 0.0).point_mm,
              c.frame_at(Vec2(5.0 + kTwoPi * kR, 1.0), 0.0).point_mm, 1e-12);
  EXPECT_TRUE(c.in_domain(Vec2(1e4, 0.0)));
  EXPECT_FALSE(c.in_domain(Vec2(0.0, kL + 1.0)));
  EXPECT_FALSE(c.in_domain(Vec2(0.0, -0.1)));
}

TEST(CylinderSurface, PreviewMeshIsClosedOutwardAndWithinTolerance) {
  const TriangleMesh m = cylinder().preview_mesh(0.05);
  std::map<std::pair<int, int>, int> edges;
  double volume = 0.0;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    volume += m.vertices_mm[t[0]].dot(m.vertices_mm[t[1]].cross(m.vertices_mm[t[2]])) / 6.0;
  }
  for (const auto& [e, n] : edges) {
    EXPECT_EQ(n, 1);
    EXPECT_EQ(edges.count({e.second, e.first}), 1u)
        << "every edge is shared, in opposite directions";
  }
  const double exact = kPi * kR * kR * kL;
  EXPECT_GT(volume, 0.0) << "outward normals give a positive volume";
  EXPECT_LT(exact - volume, exact * 0.01);
  // Chord sagitta within tolerance: facets around = ceil(2 pi / (2 acos(1 - tol / R))).
  EXPECT_LE(kR * (1 - std::cos(kPi / ((m.vertices_mm.size() - 2) / 2))), 0.05 + 1e-12);
}

}  // namespace
}  // namespace strand::slicer
