// Centre lines of narrow regions: along the middle of a rib, none in a rib narrower than the
// band or in a wide part, one connected chain through an L's corner and a T's fork with no
// spur to a corner.
#include "slicer/medial_axis.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace strand::slicer {
namespace {

// A nozzle of 0.6 mm: widths from half a bead to two beads, lines a nozzle long at least.
const MedialAxisLimits kBand{0.3, 1.2, 0.6};

Region box(double x0, double y0, double x1, double y1) {
  return {{{Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)}, {}}};
}

Region united(const Region& a, const Region& b) {
  std::vector<Ring> loops = rings_of(a);
  for (const Ring& r : rings_of(b)) loops.push_back(r);
  return region_from_oriented_loops(loops);
}

// Every point of every line, and the free ends (points on one line only, at a line's end).
std::vector<Vec2> free_ends(const std::vector<CentreLine>& lines) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    for (const Vec2& end : {lines[i].points.front(), lines[i].points.back()}) {
      bool shared = false;
      for (std::size_t j = 0; j < lines.size(); ++j) {
        if (j == i) continue;
        for (const Vec2& p : lines[j].points) shared = shared || (p - end).norm() < 1e-9;
      }
      if (!shared) out.push_back(end);
    }
  }
  return out;
}

double distance_to_boundary(const Region& r, const Vec2& p) {
  double best = 1e300;
  for (const Ring& ring : rings_of(r)) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      best = std::min(best, point_segment_distance(p, ring[i], ring[(i + 1) % ring.size()]));
    }
  }
  return best;
}

TEST(MedialAxis, ARibOfOneMillimetreHasOneLineAlongItsMiddle) {
  const auto lines = centre_lines(box(0, -0.5, 20, 0.5), kBand);
  ASSERT_EQ(lines.size(), 1u);
  for (const Vec2& p : lines[0].points) EXPECT_NEAR(p.y(), 0.0, 0.05) << p.transpose();
  // The axis stops where the corners' bisectors meet, half the width from each end.
  EXPECT_NEAR(polyline_length_mm(lines[0].points), 19.0, 0.05);
  for (const double w : lines[0].width_mm) EXPECT_NEAR(w, 1.0, 1e-6);
}

TEST(MedialAxis, NothingInARibNarrowerThanHalfABeadOrInAWidePart) {
  EXPECT_TRUE(centre_lines(box(0, -0.1, 20, 0.1), kBand).empty()) << "0.2 mm wide";
  EXPECT_TRUE(centre_lines(box(0, 0, 10, 10), kBand).empty()) << "the corners' bisectors alone";
}

TEST(MedialAxis, AnLShapedWallIsOneLineRoundTheCornerWithoutASpur) {
  // Arms 10 mm long and 1 mm wide, meeting at the origin's corner.
  const Region l = united(box(0, 0, 10, 1), box(0, 0, 1, 10));
  const auto lines = centre_lines(l, kBand);
  ASSERT_EQ(lines.size(), 1u);
  const auto ends = free_ends(lines);
  ASSERT_EQ(ends.size(), 2u);
  for (const Vec2& e : ends) EXPECT_GT(e.norm(), 9.0) << "an end near an arm's end, not a corner";
  for (const Vec2& p : lines[0].points) {
    EXPECT_GE(distance_to_boundary(l, p), 0.15 - 1e-9) << p.transpose();
    EXPECT_GT((p - Vec2(0, 0)).norm(), 0.5) << "no spur into the outer corner";
  }
}

TEST(MedialAxis, ATShapedWallGivesABarAndAStemMeetingAtTheFork) {
  // Bar 20 mm x 0.8 mm, stem 0.8 mm x 10 mm down from its middle.
  const Region t = united(box(-10, 0, 10, 0.8), box(-0.4, -10, 0.4, 0.8));
  const auto lines = centre_lines(t, kBand);
  ASSERT_EQ(lines.size(), 2u);
  const auto ends = free_ends(lines);
  ASSERT_EQ(ends.size(), 3u) << "the bar's two ends and the stem's foot; the stem's top is on the bar";
  std::vector<double> xs, ys;
  for (const Vec2& e : ends) {
    if (std::abs(e.y() - 0.4) < 0.05) xs.push_back(e.x());
    else ys.push_back(e.y());
  }
  ASSERT_EQ(xs.size(), 2u);
  EXPECT_LT(*std::min_element(xs.begin(), xs.end()), -9.0);
  EXPECT_GT(*std::max_element(xs.begin(), xs.end()), 9.0);
  ASSERT_EQ(ys.size(), 1u);
  EXPECT_LT(ys[0], -9.0);
  double length = 0.0;
  for (const auto& line : lines) length += polyline_length_mm(line.points);
  EXPECT_NEAR(length, 19.2 + 10.4 - 0.4, 0.3) << "bar and stem, each short of its ends by w/2";
}

TEST(MedialAxis, ARingNarrowerThanTwoBeadsIsOneClosedLine) {
  Ring outer, hole;
  for (int i = 0; i < 64; ++i) {
    const double a = 2 * 3.141592653589793 * i / 64;
    outer.push_back(5.0 * Vec2(std::cos(a), std::sin(a)));
    hole.push_back(4.2 * Vec2(std::cos(-a), std::sin(-a)));
  }
  const auto lines = centre_lines({{outer, {hole}}}, kBand);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].points.front(), lines[0].points.back());
  for (const Vec2& p : lines[0].points) EXPECT_NEAR(p.norm(), 4.6, 0.05);
}

TEST(MedialAxis, ARegionOverTheSegmentCapGivesNoLine) {
  Ring zigzag;
  for (int i = 0; i <= 100; ++i) zigzag.push_back(Vec2(0.2 * i, i % 2 ? 0.05 : 0.0));
  zigzag.push_back(Vec2(20, 1));
  zigzag.push_back(Vec2(0, 1));
  MedialAxisLimits capped = kBand;
  EXPECT_FALSE(centre_lines({{zigzag, {}}}, capped).empty());
  capped.max_segments = 50;
  EXPECT_TRUE(centre_lines({{zigzag, {}}}, capped).empty());
}

}  // namespace
}  // namespace strand::slicer
