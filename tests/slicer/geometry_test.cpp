#include "slicer/geometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/units.h"

namespace strand::slicer {
namespace {

TEST(SegmentContact, ProperCrossingIsCrossing) {
  EXPECT_EQ(segment_contact({0, 0}, {2, 2}, {0, 2}, {2, 0}, 1e-6), Contact::Crossing);
  const Vec2 p = crossing_point({0, 0}, {2, 2}, {0, 2}, {2, 0});
  EXPECT_NEAR(p.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.y(), 1.0, 1e-12);
}

TEST(SegmentContact, EndOnSegmentIsTouchNotCrossing) {
  EXPECT_EQ(segment_contact({0, 0}, {2, 0}, {1, 0}, {1, 1}, 1e-6), Contact::Touch);
}

TEST(SegmentContact, ParallelApartIsNone) {
  EXPECT_EQ(segment_contact({0, 0}, {2, 0}, {0, 0.5}, {2, 0.5}, 1e-3), Contact::None);
}

TEST(SegmentContact, CollinearOverlapIsTouch) {
  EXPECT_EQ(segment_contact({0, 0}, {2, 0}, {1, 0}, {3, 0}, 1e-6), Contact::Touch);
}

TEST(ArcSweep, CcwQuarterIsPositiveAndCwIsNegative) {
  EXPECT_NEAR(arc_sweep({0, 0}, {1, 0}, {0, 1}, true), kPi / 2, 1e-12);
  EXPECT_NEAR(arc_sweep({0, 0}, {1, 0}, {0, 1}, false), -3 * kPi / 2, 1e-12);
}

TEST(ArcSweep, SameStartAndEndIsFullCircle) {
  EXPECT_NEAR(arc_sweep({0, 0}, {1, 0}, {1, 0}, true), 2 * kPi, 1e-12);
}

TEST(WrapPeriod, MapsIntoHalfOpenRange) {
  EXPECT_NEAR(wrap_period(-kPi / 2, 2 * kPi), 3 * kPi / 2, 1e-12);
  EXPECT_NEAR(wrap_period(5 * kPi, 2 * kPi), kPi, 1e-12);
  EXPECT_EQ(wrap_period(-4.0, 4.0), 0.0);
  EXPECT_NEAR(wrap_period(7.5, 4.0), 3.5, 1e-12);
}

// The shortcut for values within one period either side gives fmod's bits exactly (outputs
// of every generator depend on it), and zero keeps its sign convention.
TEST(WrapPeriod, ShortcutGivesFmodsBits) {
  const double period = 4.0 * kPi / 3.0;
  for (int i = -2000; i <= 2000; ++i) {
    const double v = i * period / 997.0 + 1e-7 * i;
    double expected = std::fmod(v, period);
    if (expected < 0) expected += period;
    EXPECT_EQ(wrap_period(v, period), expected) << v;
  }
  EXPECT_FALSE(std::signbit(wrap_period(0.0, period)));
  EXPECT_EQ(wrap_period(-period, period), std::fmod(-period, period));
}

}  // namespace
}  // namespace strand::slicer
