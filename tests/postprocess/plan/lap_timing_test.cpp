// Lap timing with corner slowdowns (issue 20 item 2): the blended-corner speed, laps planned
// from rest to rest, a lap of sharp corners longer than distance / speed.
#include "postprocess/plan/lap_timing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "postprocess/plan/motion_time.h"
#include "slicer/units.h"

namespace strand::post {
namespace {

using slicer::Vec3;

// One lap through `corners` (contact points) at `speed`, all deposits.
slicer::PoseProgram lap_through(const std::vector<Vec3>& corners, double speed) {
  slicer::PoseProgram p;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    slicer::PosePoint pt;
    pt.contact_mm = corners[i];
    pt.extrude = i > 0;
    pt.speed_mm_per_s = i > 0 ? speed : 0.0;
    if (i > 0)
      pt.t_s = p.points.back().t_s + (corners[i] - corners[i - 1]).norm() / speed;
    p.points.push_back(pt);
  }
  p.laps.push_back({0, 1, 0, corners.size() - 1, 0.0, 0.0});
  p.layers.push_back({});
  return p;
}

// A zigzag of `n` legs of `leg_mm`, turning by `turn_deg` at each corner (alternating sides).
std::vector<Vec3> zigzag(int n, double leg_mm, double turn_deg) {
  std::vector<Vec3> pts = {Vec3::Zero()};
  const double half = slicer::deg_to_rad(turn_deg / 2.0);
  for (int i = 0; i < n; ++i) {
    const double side = i % 2 == 0 ? 1.0 : -1.0;
    pts.push_back(pts.back() + leg_mm * Vec3(std::cos(half), side * std::sin(half), 0.0));
  }
  return pts;
}

TEST(BlendedCornerSpeed, IsTheCentripetalLimitOnTheBlendArc) {
  const Vec3 x = Vec3::UnitX(), y = Vec3::UnitY();
  // 90 deg: the arc tangent 0.01 mm before and after the corner has radius 0.01 mm.
  EXPECT_NEAR(blended_corner_speed_mm_per_s(x, y, 100.0, 0.01), std::sqrt(100.0 * 0.01), 1e-9);
  // 60 deg: radius = blend / tan(30 deg).
  const Vec3 u(std::cos(slicer::kPi / 3), std::sin(slicer::kPi / 3), 0.0);
  EXPECT_NEAR(blended_corner_speed_mm_per_s(x, u, 500.0, 0.1),
              std::sqrt(500.0 * 0.1 / std::tan(slicer::kPi / 6)), 1e-9);
  EXPECT_EQ(blended_corner_speed_mm_per_s(x, x, 100.0, 0.01),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(blended_corner_speed_mm_per_s(x, -x, 100.0, 0.01), 0.0) << "a reversal stops";
  EXPECT_EQ(blended_corner_speed_mm_per_s(x, y, 100.0, 0.0), 0.0) << "no blending: exact stop";
  // A gentler turn is taken faster.
  EXPECT_GT(blended_corner_speed_mm_per_s(x, u, 100.0, 0.01),
            blended_corner_speed_mm_per_s(x, y, 100.0, 0.01));
}

TEST(RestToRestTimes, AStraightRunIsDistanceOverSpeedPlusTheRamps) {
  // 60 mm at 6 mm/s in three blocks, a = 100: each ramp costs v / (2a) = 0.03 s.
  const std::vector<PathBlock> blocks = {{20.0, 6.0, 1e9}, {20.0, 6.0, 1e9}, {20.0, 6.0, 1e9}};
  double total = 0.0;
  for (double t : rest_to_rest_times_s(blocks, 100.0)) total += t;
  EXPECT_NEAR(total, 10.0 + 2 * 0.03, 1e-9);
}

TEST(LapTiming, ALapWithManySharpCornersTakesLongerThanDistanceOverSpeed) {
  const CornerModel model{100.0, 0.01};
  const auto sharp = lap_through(zigzag(40, 1.0, 90.0), 6.0);
  const auto gentle = lap_through(zigzag(40, 1.0, 1.0), 6.0);
  const LapTiming s = time_laps(sharp, model), g = time_laps(gentle, model);
  ASSERT_EQ(s.planned_s.size(), 1u);
  EXPECT_NEAR(s.nominal_s[0], 40.0 / 6.0, 1e-9);
  EXPECT_NEAR(s.nominal_s[0], sharp.points.back().t_s, 1e-9) << "the CSV's time line";
  EXPECT_EQ(s.slowed_corners[0], 39);
  // Every 90 deg corner is taken at sqrt(a b) = 1 mm/s: each costs (6 - 1)^2 / (6 a) s.
  EXPECT_NEAR(s.planned_s[0] - s.nominal_s[0], 39 * 25.0 / 600.0 + 0.06, 1e-6);
  EXPECT_GT(s.planned_s[0], 1.2 * s.nominal_s[0]);
  // Gentle turns hardly slow it: only the start and the stop at the lap's end.
  EXPECT_NEAR(g.planned_s[0], g.nominal_s[0] + 0.06, 0.02);
  EXPECT_LT(g.planned_s[0], s.planned_s[0]);
  // The time line: monotonic, the lap's planned duration from its start to its end.
  for (std::size_t i = 1; i < s.t_s.size(); ++i) EXPECT_GT(s.t_s[i], s.t_s[i - 1]);
  EXPECT_NEAR(s.t_s.back(), s.planned_s[0], 1e-9);
  EXPECT_NEAR(s.planned_total_s, s.planned_s[0], 1e-12);
  const auto j = lap_timing_json(s);
  EXPECT_EQ(j.at("slowed_corners"), 39);
  EXPECT_EQ(j.at("text").get<std::string>().rfind("laps timed with corner slowdowns: +", 0), 0u)
      << j.dump();
}

TEST(LapTiming, EveryLapStartsAndEndsAtRestAndRepeatedPosesTakeNoTime) {
  auto corners = zigzag(10, 2.0, 30.0);
  corners.insert(corners.begin() + 5, corners[4]);  // a repeated pose
  auto p = lap_through(corners, 6.0);
  // Two laps: the second from point 6 on.
  for (std::size_t i = 6; i < p.points.size(); ++i) p.points[i].lap = 1;
  p.laps = {{0, 1, 0, 5, 0.0, 0.0}, {0, -1, 5, p.points.size() - 1, 0.0, 0.0}};
  const LapTiming t = time_laps(p, {100.0, 0.01});
  ASSERT_EQ(t.planned_s.size(), 2u);
  EXPECT_EQ(t.t_s[5], t.t_s[4]) << "no motion, no time";
  EXPECT_NEAR(t.t_s[5], t.planned_s[0], 1e-9);
  EXPECT_NEAR(t.t_s.back() - t.t_s[5], t.planned_s[1], 1e-9);
  // Each lap ramps up from and down to rest: longer than the same path run through.
  const LapTiming one = time_laps(lap_through(corners, 6.0), {100.0, 0.01});
  EXPECT_GT(t.planned_total_s, one.planned_total_s + 0.02);
  EXPECT_NEAR(t.nominal_total_s, one.nominal_total_s, 1e-9);
}

}  // namespace
}  // namespace strand::post
