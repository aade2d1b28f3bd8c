#include "postprocess/plan/laps.h"

#include <gtest/gtest.h>

#include "slicer/units.h"

namespace strand::post {
namespace {

std::vector<slicer::PosePoint> turns(const std::vector<double>& deg) {
  std::vector<slicer::PosePoint> pts;
  for (double d : deg) {
    slicer::PosePoint p;
    p.turn_rad = slicer::deg_to_rad(d);
    pts.push_back(p);
  }
  return pts;
}

TEST(Laps, OutAndBackIsAForwardAndAReturnLap) {
  const auto pts = turns({-100, -50, 0, 60, 120, 30, -40, -100});
  const auto laps = split_laps(pts, 0, pts.size() - 1, 0);
  ASSERT_EQ(laps.size(), 2u);
  EXPECT_EQ(laps[0].direction, 1);
  EXPECT_EQ(laps[0].last, 4u);
  EXPECT_EQ(laps[1].direction, -1);
  EXPECT_EQ(laps[1].first, 4u);
  EXPECT_EQ(laps[1].last, 7u);
  EXPECT_NEAR(slicer::rad_to_deg(laps[0].turn_max_rad - laps[0].turn_min_rad), 220.0, 1e-9);
}

TEST(Laps, WigglesWithinADegreeDoNotStartALap) {
  // A serpentine that creeps forward with half-degree back-steps is one forward lap.
  const auto pts = turns({0, 10, 9.5, 20, 19.6, 30, 29.5, 40});
  const auto laps = split_laps(pts, 0, pts.size() - 1, 0);
  ASSERT_EQ(laps.size(), 1u);
  EXPECT_EQ(laps[0].direction, 1);
}

TEST(Laps, ALapEndsAtTheLastTimeItReachesItsFarthestTurn) {
  // Reaches 90 twice: the lap runs to the second visit, then returns.
  const auto pts = turns({0, 90, 50, 90, 10, 0});
  const auto laps = split_laps(pts, 0, pts.size() - 1, 3);
  ASSERT_EQ(laps.size(), 2u);
  EXPECT_EQ(laps[0].last, 3u);
  EXPECT_EQ(laps[1].layer, 3);
}

TEST(Laps, APassAlongTheAxisHoldsItsTurnInOneLap) {
  const auto pts = turns({5, 5, 5, 5});
  const auto laps = split_laps(pts, 0, 3, 0);
  ASSERT_EQ(laps.size(), 1u);
  EXPECT_EQ(laps[0].first, 0u);
  EXPECT_EQ(laps[0].last, 3u);
}

TEST(Laps, AssignNumbersLapsAcrossLayersAndEveryPointHasOne) {
  auto pts = turns({0, 50, 100, 50, 0, 0, 80, 0});
  for (std::size_t i = 5; i < pts.size(); ++i) pts[i].layer = 1;
  slicer::PoseProgram p;
  p.points = pts;
  assign_laps(p);
  ASSERT_EQ(p.laps.size(), 4u);
  EXPECT_EQ(p.points[2].lap, 0);
  EXPECT_EQ(p.points[3].lap, 1);
  EXPECT_EQ(p.points[5].lap, 2) << "a layer's first point opens its first lap";
  EXPECT_EQ(p.points[7].lap, 3);
  const auto [lo, hi] = turn_range(p);
  EXPECT_NEAR(slicer::rad_to_deg(hi - lo), 100.0, 1e-9);
}

}  // namespace
}  // namespace strand::post
