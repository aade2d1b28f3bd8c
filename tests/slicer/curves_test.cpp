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

TEST_P(ChordBound, PointBoundHoldsWithoutFlattening) {
  const double tol = GetParam();
  for (const SubPath& s : {wavy_cubic(), skewed_arc()}) {
    const double bound = flatten_point_bound(s, tol);
    const double points = static_cast<double>(flatten(s, tol).size());
    EXPECT_GE(bound, points);
    EXPECT_LE(bound, 8 * points + 8) << "a bound so loose it would refuse real drawings";
  }
}

TEST(Curves, AbsurdControlPointsNeitherHangNorExplode) {
  // 1e308 once took 2.1 GB in 7 s; the split depth is now bounded by the proof, capped
  SubPath s = wavy_cubic();
  s.pieces[0].p[0] = Vec2(1e308, 0);
  EXPECT_EQ(max_abs_coordinate(s), 1e308);
  EXPECT_LE(flatten_point_bound(s, 0.001), std::ldexp(1.0, 40) + 1);
  s.pieces[0].p[1] = Vec2(NAN, 0);
  EXPECT_EQ(max_abs_coordinate(s), INFINITY);
  EXPECT_LE(flatten(s, 0.001).size(), 2u);  // a NaN control point splits nothing
}

TEST(Curves, BoundsAreExactForCubicsAndArcs) {
  const SubPath c = wavy_cubic();
  const auto [lo, hi] = curve_bounds(c);
  Vec2 slo(INFINITY, INFINITY), shi(-INFINITY, -INFINITY);
  for (int i = 0; i <= 100000; ++i) {
    const Vec2 p = cubic_point(c.start, c.pieces[0], i / 100000.0);
    slo = slo.cwiseMin(p);
    shi = shi.cwiseMax(p);
  }
  EXPECT_LT((slo - lo).norm(), 1e-6);
  EXPECT_LT((shi - hi).norm(), 1e-6);
  const SubPath a = skewed_arc();
  const auto [alo, ahi] = curve_bounds(a);
  slo = Vec2(INFINITY, INFINITY), shi = -slo;
  for (int i = 0; i <= 100000; ++i) {
    const Vec2 p = arc_point(a.pieces[0], 0.3 - 4.0 * i / 100000.0);
    slo = slo.cwiseMin(p);
    shi = shi.cwiseMax(p);
  }
  EXPECT_LT((slo - alo).norm(), 1e-6);
  EXPECT_LT((shi - ahi).norm(), 1e-6);
}

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
