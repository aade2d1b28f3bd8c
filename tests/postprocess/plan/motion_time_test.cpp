// Trapezoidal time against moves timed by hand.
#include "postprocess/plan/motion_time.h"

#include <gtest/gtest.h>

#include <cmath>

namespace strand::post {
namespace {

slicer::Move line(double x, double y, double feed, slicer::MoveKind kind = slicer::MoveKind::Deposit) {
  slicer::Move m;
  m.kind = kind;
  m.end_mm = {x, y, 0.0};
  m.feed_mm_per_min = feed;
  m.layer = 0;
  return m;
}

slicer::MotionProgram program(std::vector<slicer::Move> moves) {
  slicer::MotionProgram p;
  p.layers = {{0.0, 0.5}};
  p.moves.assign(moves.begin(), moves.end());
  return p;
}

TimeOptions options(double accel) {
  TimeOptions o;
  o.acceleration_mm_per_s2 = accel;
  o.junction_deviation_mm = 0.05;
  o.max_feed_mm_per_min = 100000;
  return o;
}

TEST(MotionTime, OneLongMoveAcceleratesCruisesAndBrakes) {
  // 100 mm at 100 mm/s, a = 1000 mm/s^2: 5 mm and 0.1 s to reach speed, 5 mm and 0.1 s to
  // stop, 90 mm cruise in 0.9 s -> 1.1 s (naive: 1.0 s).
  const auto t = trapezoid_time(program({line(100, 0, 6000)}), options(1000));
  EXPECT_NEAR(t.total_s, 1.1, 1e-9);
  EXPECT_NEAR(t.layer_s.at(0), 1.1, 1e-9);
}

TEST(MotionTime, SquareSlowsAtEachSharpCorner) {
  // 10 mm square at 50 mm/s, a = 1000, jd = 0.05. 90 deg corners: sin(theta/2) = sqrt(0.5),
  // v_j = sqrt(1000 * 0.05 * 0.70711 / 0.29289) = 10.9868 mm/s.
  // First and last side (0 <-> 50 <-> 10.9868): 0.05 s + 0.039013 s + 7.5604 mm / 50 = 0.240220 s.
  // Middle sides (10.9868 -> 50 -> 10.9868): 2 * 0.039013 + 7.6207 mm / 50 = 0.230441 s.
  // Total 2 * 0.240220 + 2 * 0.230441 = 0.941322 s (naive 0.8 s).
  const auto t = trapezoid_time(
      program({line(10, 0, 3000), line(10, 10, 3000), line(0, 10, 3000), line(0, 0, 3000)}),
      options(1000));
  EXPECT_NEAR(junction_speed_mm_per_s({1, 0, 0}, {0, 1, 0}, 1000, 0.05), 10.98684, 1e-4);
  EXPECT_NEAR(t.total_s, 0.941322, 1e-5);
}

TEST(MotionTime, FineZigZagIsDominatedByAcceleration) {
  // 20 segments of 1 mm turning 90 deg each time, asked at 100 mm/s with a = 500:
  // v_j = sqrt(500 * 0.05 * 2.41421) = 7.76887 mm/s; no segment reaches cruise.
  // Middle segment: peak sqrt((2*500*1 + 2*7.76887^2)/2) = 23.6718 mm/s, 2*(23.6718-7.76887)/500
  // = 0.0636118 s. End segments (0 <-> v_j): peak sqrt((1000 + 60.355)/2) = 23.0260 mm/s,
  // 23.0260/500 + (23.0260-7.76887)/500 = 0.0765646 s. Total 2*0.0765646 + 18*0.0636118
  // = 1.298142 s, six times the naive 0.2 s.
  std::vector<slicer::Move> moves;
  for (int i = 1; i <= 20; ++i) moves.push_back(line(std::ceil(i / 2.0), std::floor(i / 2.0), 6000));
  const auto t = trapezoid_time(program(moves), options(500));
  EXPECT_NEAR(t.total_s, 1.298142, 1e-5);
}

TEST(MotionTime, ReversalStopsAndStraightOnKeepsSpeed) {
  EXPECT_EQ(junction_speed_mm_per_s({1, 0, 0}, {-1, 0, 0}, 1000, 0.05), 0.0);
  EXPECT_TRUE(std::isinf(junction_speed_mm_per_s({1, 0, 0}, {1, 0, 0}, 1000, 0.05)));
  // Two collinear 50 mm halves time like one 100 mm move.
  const auto t = trapezoid_time(program({line(50, 0, 6000), line(100, 0, 6000)}), options(1000));
  EXPECT_NEAR(t.total_s, 1.1, 1e-9);
}

TEST(MotionTime, ValveMachinesStopWhereFlowChangesAndDwellForLead) {
  // Travel then deposit, collinear: without the stop it is one 1.1 s move; with M400 at the
  // valve each 50 mm half starts and ends at rest: 2 * (0.1 + 0.1 + 40/100) = 1.2 s, plus
  // the 0.5 s lead dwell.
  auto o = options(1000);
  o.stop_at_flow_change = true;
  o.strand_start_dwell_s = 0.5;
  const auto t = trapezoid_time(
      program({line(50, 0, 6000, slicer::MoveKind::Travel), line(100, 0, 6000)}), o);
  EXPECT_NEAR(t.total_s, 1.7, 1e-9);
}

TEST(MotionTime, BlockTimeTriangleWhenTooShortToCruise) {
  // 1 mm from rest to rest at a = 1000 asking 100 mm/s: peak sqrt(1000) = 31.62 mm/s,
  // t = 2 * 31.62 / 1000 = 0.063246 s.
  EXPECT_NEAR(block_time_s(1.0, 0, 100, 0, 1000), 0.0632456, 1e-6);
}


// The planner as one backward and one forward pass over every block of the program (what
// trapezoid_time did before it streamed between cut blocks): the reference to match exactly.
double whole_program_time(const slicer::MotionProgram& p, const TimeOptions& o) {
  struct B {
    double len, v;
    slicer::Vec3 unit;
    bool stop;
    double entry;
  };
  std::vector<B> b;
  slicer::Vec3 at = p.start_mm;
  bool stop = true;
  for (const auto& mv : p.moves) {
    const double len = (mv.end_mm - at).norm();
    const double v = std::min(mv.feed_mm_per_min, o.max_feed_mm_per_min) / 60.0;
    if (len < 1e-9 || v <= 0) continue;
    b.push_back({len, v, (mv.end_mm - at) / len, stop, 0.0});
    stop = false;
    at = mv.end_mm;
  }
  const double a = o.acceleration_mm_per_s2;
  for (std::size_t i = 1; i < b.size(); ++i) {
    if (!b[i].stop) {
      b[i].entry = std::min({b[i - 1].v, b[i].v,
                             junction_speed_mm_per_s(b[i - 1].unit, b[i].unit, a, o.junction_deviation_mm)});
    }
  }
  double exit = 0.0;
  for (std::size_t k = b.size(); k-- > 0;) {
    b[k].entry = std::min(b[k].entry, std::sqrt(exit * exit + 2 * a * b[k].len));
    exit = b[k].entry;
  }
  for (std::size_t i = 1; i < b.size(); ++i) {
    b[i].entry = std::min(b[i].entry, std::sqrt(b[i - 1].entry * b[i - 1].entry + 2 * a * b[i - 1].len));
  }
  double total = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    total += block_time_s(b[i].len, b[i].entry, b[i].v, i + 1 < b.size() ? b[i + 1].entry : 0.0, a);
  }
  return total;
}

TEST(MotionTime, StreamingBetweenCutBlocksEqualsOnePassOverTheWholeProgram) {
  // Long rows (cut blocks), runs of tiny zig-zags (no cut for many blocks) and reversals.
  std::vector<slicer::Move> moves;
  double x = 0.0, y = 0.0;
  for (int row = 0; row < 40; ++row) {
    x = row % 2 == 0 ? 50.0 : 0.0;
    moves.push_back(line(x, y, 1500));
    for (int k = 0; k < 200; ++k) moves.push_back(line(x + (k % 2 ? 0.01 : 0.0), y += 0.003, 3000 + 10 * k));
    moves.push_back(line(x, y -= 0.2, 600));  // reversal
  }
  const auto p = program(moves);
  for (double accel : {50.0, 500.0, 5000.0}) {
    const double streamed = trapezoid_time(p, options(accel)).total_s;
    EXPECT_EQ(streamed, whole_program_time(p, options(accel))) << accel;  // bit for bit
  }
}

}  // namespace
}  // namespace strand::post
