// Plotter kinematics: forward/inverse round trips, the R-theta document's worked example,
// cable tensions, the drawable area, and the bow bound after adaptive splitting.
#include "machines/plotter_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "machines/profile.h"
#include "slicer/geometry.h"

namespace strand::machines {
namespace {

class RoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(RoundTrip, ForwardThenInverseIsIdentityOverTheArea) {
  const MachineProfile m = load_profile(GetParam());
  const auto [lo, hi] = drawable_area(m.plotter);
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) {
      const Vec2 p = lo + Vec2((hi - lo).x() * i / 20, (hi - lo).y() * j / 20);
      EXPECT_LT((to_paper(m.plotter.setup, to_axes(m.plotter.setup, p)) - p).norm(), 1e-9) << p.transpose();
      const Vec2 a = to_axes(m.plotter.setup, p);
      EXPECT_LT((to_axes(m.plotter.setup, to_paper(m.plotter.setup, a)) - a).norm(), 1e-9);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Plotters, RoundTrip,
                         ::testing::Values("xy-plotter-servo", "polargraph", "polar-rtheta", "wall-drum-4pen"));

TEST(PlotterKinematics, RThetaMatchesTheDocumentsWorkedExample) {
  // P = (285, 195) -> P_R = 25260 steps, P_A = 32694 steps at 200 steps/mm.
  const MachineProfile m = load_profile("polar-rtheta");
  const Vec2 a = to_axes(m.plotter.setup, Vec2(285, 195)) * 200.0;
  EXPECT_NEAR(a.x(), 25260, 1.0);
  EXPECT_NEAR(a.y(), 32694, 1.0);
  EXPECT_LT(to_axes(m.plotter.setup, m.plotter.setup.home_mm).norm(), 1e-9);  // sheet centre = (0, 0)
}

TEST(PlotterKinematics, SymmetricTensionBelowTheMiddle) {
  const MachineProfile m = load_profile("polargraph");
  const auto [l, r] = cable_tension(m.plotter.setup, Vec2(750, 750));
  EXPECT_NEAR(l, r, 1e-12);
  EXPECT_NEAR(l, std::sqrt(2.0) / 2.0, 1e-12);  // 2 T cos 45° = W
}

TEST(PlotterKinematics, DrawableAreaHoldsLimitsAndRefusesTheMotorLine) {
  const MachineProfile m = load_profile("polargraph");
  const auto [lo, hi] = drawable_area(m.plotter);
  EXPECT_GT((hi - lo).x(), 300.0);
  EXPECT_GT((hi - lo).y(), 300.0);
  for (int i = 0; i <= 30; ++i) {
    for (int j = 0; j <= 30; ++j) {
      const Vec2 p = lo + Vec2((hi - lo).x() * i / 30, (hi - lo).y() * j / 30);
      EXPECT_FALSE(unreachable_reason(m.plotter, p).has_value()) << p.transpose();
    }
  }
  const auto why = unreachable_reason(m.plotter, Vec2(750, 20));
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("tension"), std::string::npos) << *why;
}

class BowBound : public ::testing::TestWithParam<const char*> {};

TEST_P(BowBound, AxisLinearMovesStayNearTheSegmentAfterSplitting) {
  const MachineProfile m = load_profile(GetParam());
  const auto [lo, hi] = drawable_area(m.plotter);
  const double tol = 0.02;
  const Vec2 a = lo + 0.05 * (hi - lo), b = lo + Vec2(0.95, 0.7).cwiseProduct(hi - lo);
  const auto pts = split_for_axes(m.plotter.setup, a, b, tol);
  EXPECT_GT(pts.size(), 1u);
  Vec2 from = a;
  double worst = 0.0;
  for (const Vec2& to : pts) {
    const Vec2 A = to_axes(m.plotter.setup, from), B = to_axes(m.plotter.setup, to);
    for (int k = 0; k <= 200; ++k) {
      const Vec2 q = to_paper(m.plotter.setup, A + (B - A) * (k / 200.0));
      worst = std::max(worst, slicer::point_segment_distance(q, a, b));
    }
    from = to;
  }
  EXPECT_LE(worst, tol);
  // One unsplit move would bow much further than the tolerance.
  const Vec2 A = to_axes(m.plotter.setup, a), B = to_axes(m.plotter.setup, b);
  EXPECT_GT(slicer::point_segment_distance(to_paper(m.plotter.setup, (A + B) / 2), a, b), 10 * tol);
}

INSTANTIATE_TEST_SUITE_P(Plotters, BowBound, ::testing::Values("polargraph", "polar-rtheta", "wall-drum-4pen"));

}  // namespace
}  // namespace strand::machines
