#include "slicer/toolpath.h"

#include <gtest/gtest.h>

#include "slicer/units.h"

namespace strand::slicer {
namespace {

Stroke sample_stroke() {
  Stroke s;
  s.start_mm = {0, 0};
  s.segments = {line_to({2, 0}, Feature::Ligament), arc_to({3, 1}, {2, 1}, true, Feature::Node),
                line_to({3, 4}, Feature::Ligament)};
  return s;
}

TEST(Stroke, ReversingTwiceIsIdentity) {
  const Stroke s = sample_stroke();
  EXPECT_EQ(reversed(reversed(s)), s);
  EXPECT_EQ(reversed(s).start_mm, s.end_mm());
}

TEST(Stroke, LengthCountsArcsAlongTheCircle) {
  EXPECT_NEAR(stroke_length(sample_stroke()), 2.0 + kPi / 2 + 3.0, 1e-12);
}

TEST(Toolpath, BoundsIncludeArcBulge) {
  Toolpath t;
  Stroke s;
  s.start_mm = {1, 0};
  s.segments = {arc_to({-1, 0}, {0, 0}, true, Feature::Node)};  // upper half circle
  t.layers.push_back({0.5, 0.5, {s}});
  const auto [lo, hi] = bounds(t);
  EXPECT_NEAR(hi.y(), 1.0, 1e-12);
  EXPECT_NEAR(lo.y(), 0.0, 1e-12);
}

TEST(BeadArea, StadiumModel) {
  EXPECT_NEAR(bead_area_mm2(1.0, 1.0), kPi / 4, 1e-12);  // round bead
  EXPECT_NEAR(bead_area_mm2(1.0, 0.5), 0.25 + kPi * 0.0625, 1e-12);
}

}  // namespace
}  // namespace strand::slicer
