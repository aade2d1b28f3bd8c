#include "postprocess/plan/arc_segmentation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/units.h"

namespace strand::post {
namespace {

// Largest distance between the true arc and the chords, sampled densely along each chord.
double max_chord_error(const Vec2& from, const Vec2& c, const std::vector<Vec2>& pts, double r) {
  double worst = 0;
  Vec2 a = from;
  for (const Vec2& b : pts) {
    for (int k = 0; k <= 50; ++k) {
      const Vec2 q = a + (b - a) * (k / 50.0);
      worst = std::max(worst, r - (q - c).norm());
    }
    a = b;
  }
  return worst;
}

struct ArcCase {
  const char* name;
  double radius_mm, sweep_deg, tolerance_mm;
  bool ccw;
};

// Names the case in test listings instead of dumping its bytes.
void PrintTo(const ArcCase& c, std::ostream* os) { *os << c.name; }

class ArcChordBound : public ::testing::TestWithParam<ArcCase> {};

TEST_P(ArcChordBound, EveryChordWithinTolerance) {
  const auto& c = GetParam();
  const Vec2 center(3, -2);
  const Vec2 from = center + Vec2(c.radius_mm, 0);
  const double end_angle = slicer::deg_to_rad(c.ccw ? c.sweep_deg : -c.sweep_deg);
  const Vec2 to = slicer::on_circle(center, c.radius_mm, end_angle);
  const auto pts = segment_arc(from, center, to, c.ccw, c.tolerance_mm);
  EXPECT_LE(max_chord_error(from, center, pts, c.radius_mm), c.tolerance_mm + 1e-12);
  EXPECT_EQ(pts.back(), to);
  // Not wastefully fine: one chord fewer would break the bound.
  const int n = static_cast<int>(pts.size());
  if (n > 1) {
    const double phi = slicer::deg_to_rad(c.sweep_deg) / (n - 1);
    EXPECT_GT(c.radius_mm * (1 - std::cos(phi / 2)), c.tolerance_mm * 0.999);
  }
}

INSTANTIATE_TEST_SUITE_P(Arcs, ArcChordBound,
                         ::testing::Values(ArcCase{"thesis_node_quarter", 1.6, 90, 0.01, true},
                                           ArcCase{"large_half_circle", 50, 180, 0.01, false},
                                           ArcCase{"tiny_radius_coarse_tolerance", 0.2, 270, 0.05,
                                                   true},
                                           ArcCase{"fine_tolerance", 5, 120, 0.001, false}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(ArcSegmentation, FullCircleWhenStartEqualsEnd) {
  const auto pts = segment_arc({1, 0}, {0, 0}, {1, 0}, true, 0.01);
  EXPECT_GT(pts.size(), 20u);
  EXPECT_NEAR(pts[pts.size() / 2].x(), -1.0, 0.02);
}

}  // namespace
}  // namespace strand::post
