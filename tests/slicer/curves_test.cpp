// Flattening keeps every point of the true curve within the tolerance of the polyline.
#include "slicer/curves.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/units.h"

namespace strand::slicer {
namespace {

double distance_to_polyline(const Vec2& p, const Polyline& pl) {
  double best = INFINITY;
  for (std::size_t i = 1; i < pl.size(); ++i) best = std::min(best, point_segment_distance(p, pl[i - 1], pl[i]));
  return best;
}

SubPath wavy_cubic() {
  CurvePiece c;
  c.kind = CurveKind::Cubic;
  c.p[0] = Vec2(30, 80);
  c.p[1] = Vec2(-20, -40);
  c.p[2] = Vec2(60, 5);
  return {Vec2(0, 0), {c}, false};
}

SubPath skewed_arc() {
  CurvePiece a;
  a.kind = CurveKind::Arc;
  a.center = Vec2(10, 5);
  a.axes << 40, 25, -5, 8;  // a sheared ellipse (the image of a circle under skew + scale)
  a.t0_rad = 0.3;
  a.sweep_rad = -4.0;
  return {arc_point(a, 0.3), {a}, false};
}

class ChordBound : public ::testing::TestWithParam<double> {};

TEST_P(ChordBound, DenseSamplesOfCubicStayWithinTolerance) {
  const double tol = GetParam();
  const SubPath s = wavy_cubic();
  const Polyline pl = flatten(s, tol);
  double worst = 0.0;
  for (int i = 0; i <= 20000; ++i) worst = std::max(worst, distance_to_polyline(cubic_point(s.start, s.pieces[0], i / 20000.0), pl));
  EXPECT_LE(worst, tol);
  EXPECT_GT(worst, tol / 20) << "flattening far finer than asked: " << pl.size() << " points";
}

TEST_P(ChordBound, DenseSamplesOfSkewedArcStayWithinTolerance) {
  const double tol = GetParam();
  const SubPath s = skewed_arc();
  const Polyline pl = flatten(s, tol);
  double worst = 0.0;
  for (int i = 0; i <= 20000; ++i) {
    worst = std::max(worst, distance_to_polyline(arc_point(s.pieces[0], 0.3 - 4.0 * i / 20000.0), pl));
  }
  EXPECT_LE(worst, tol);
}

INSTANTIATE_TEST_SUITE_P(Tolerances, ChordBound, ::testing::Values(0.5, 0.05, 0.005));

TEST(Curves, AffineTransformOfArcMatchesTransformedPoints) {
  const SubPath s = skewed_arc();
  Affine m;
  m.linear << 1.2, 0.4, -0.3, 0.9;
  m.offset = Vec2(7, -3);
  const SubPath t = transformed(s, m);
  for (double u : {0.0, 0.5, 1.0}) {
    const double th = 0.3 - 4.0 * u;
    EXPECT_LT((arc_point(t.pieces[0], th) - m.apply(arc_point(s.pieces[0], th))).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace strand::slicer
