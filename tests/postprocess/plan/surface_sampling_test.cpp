#include "postprocess/plan/surface_sampling.h"

#include <gtest/gtest.h>

#include "slicer/cylinder_surface.h"
#include "slicer/units.h"

namespace strand::post {
namespace {

using slicer::Vec3;

double chord_error(const slicer::Surface& s, const Vec2& a, const Vec2& b, double offset,
                   const std::function<Vec2(double)>& curve, double t0, double t1) {
  const Vec3 pa = s.frame_at(a, offset).point_mm, pb = s.frame_at(b, offset).point_mm;
  double worst = 0.0;
  for (int k = 1; k < 50; ++k) {
    const Vec3 q = s.frame_at(curve(t0 + (t1 - t0) * k / 50.0), offset).point_mm;
    const Vec3 ab = pb - pa;
    const double t = std::clamp((q - pa).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    worst = std::max(worst, (q - (pa + t * ab)).norm());
  }
  return worst;
}

TEST(SurfaceSampling, AStraightLineAroundTheCylinderIsCutIntoHelixChords) {
  const slicer::CylinderSurface c({10.0, 50.0});
  const Vec2 from(-20.0, 5.0), to(25.0, 30.0);
  const auto pts =
      sample_on_surface(c, from, slicer::line_to(to, slicer::Feature::Infill), 1.0, 0.01);
  ASSERT_GT(pts.size(), 10u) << "a line in (u, v) is a helix: never a single chord";
  EXPECT_EQ(pts.back(), to);
  auto line = [&](double t) { return Vec2(from + t * (to - from)); };
  Vec2 prev = from;
  double t_prev = 0.0;
  for (const Vec2& q : pts) {
    const double t = (q - from).norm() / (to - from).norm();
    EXPECT_LE(chord_error(c, prev, q, 1.0, line, t_prev, t), 0.01 + 1e-9);
    prev = q, t_prev = t;
  }
  EXPECT_LE(pts.size(),
            sample_bound(c, from, slicer::line_to(to, slicer::Feature::Infill), 1.0, 0.01));
}

TEST(SurfaceSampling, ALineAlongTheAxisIsOneChord) {
  const slicer::CylinderSurface c({10.0, 50.0});
  const auto pts = sample_on_surface(
      c, Vec2(3.0, 1.0), slicer::line_to(Vec2(3.0, 40.0), slicer::Feature::Infill), 0.0, 0.01);
  EXPECT_EQ(pts.size(), 1u);
}

TEST(SurfaceSampling, ArcsAreCutWithTheErrorMeasuredOnTheSurface) {
  const slicer::CylinderSurface c({8.0, 50.0});
  const Vec2 centre(2.0, 20.0), from(6.0, 20.0);
  const auto seg = slicer::arc_to(Vec2(2.0, 24.0), centre, true, slicer::Feature::Node);
  const double tol = 0.005;
  const auto pts = sample_on_surface(c, from, seg, 0.5, tol);
  auto arc = [&](double t) { return Vec2(slicer::on_circle(centre, 4.0, t)); };
  Vec2 prev = from;
  double a_prev = 0.0;
  for (const Vec2& q : pts) {
    const double a = slicer::angle_of(centre, q);
    EXPECT_LE(chord_error(c, prev, q, 0.5, arc, a_prev, a), tol + 1e-9);
    prev = q, a_prev = a;
  }
  EXPECT_NEAR(pts.back().x(), 2.0, 1e-12);
  EXPECT_NEAR(pts.back().y(), 24.0, 1e-12);
}

TEST(SurfaceSampling, TighterToleranceNeedsMorePoints) {
  const slicer::CylinderSurface c({10.0, 50.0});
  const auto seg = slicer::line_to(Vec2(30.0, 0.0), slicer::Feature::Infill);
  EXPECT_GT(sample_on_surface(c, Vec2(0, 0), seg, 0.0, 0.001).size(),
            sample_on_surface(c, Vec2(0, 0), seg, 0.0, 0.1).size());
}

}  // namespace
}  // namespace strand::post
