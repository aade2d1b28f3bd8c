#include "postprocess/inspect/crossings.h"

#include <gtest/gtest.h>

#include <random>

#include "postprocess/inspect/gcode_parser.h"

namespace strand::post {
namespace {

ContactReport contacts(const char* gcode) {
  return find_contacts(parse_gcode(gcode).program, 0.01, 1e-3);
}

TEST(Crossings, SelfCrossingInOneStrandIsFoundWithItsPoint) {
  const auto r = contacts("G0 X0 Y0 Z0.5\nG1 X10 Y10\nG1 X10 Y0\nG1 X0 Y10\n");
  ASSERT_EQ(r.crossings.size(), 1u);
  EXPECT_NEAR(r.crossings[0].at_mm.x(), 5.0, 1e-9);
  EXPECT_NEAR(r.crossings[0].at_mm.y(), 5.0, 1e-9);
}

TEST(Crossings, SerpentineHasNoContacts) {
  const auto r = contacts("G0 X0 Y0 Z0.5\nG1 X10\nG1 Y1\nG1 X0\nG1 Y2\nG1 X10\n");
  EXPECT_TRUE(r.crossings.empty());
  EXPECT_TRUE(r.touches.empty());
}

TEST(Crossings, DifferentLayersNeverCross) {
  const auto r = contacts(";LAYER:0\nG0 X0 Y5 Z0.5\nG1 X10 Y5\n;LAYER:1\nG0 X5 Y0 Z1\nG1 X5 Y10\n");
  EXPECT_TRUE(r.crossings.empty());
}

TEST(Crossings, EndingOnAFilamentIsATouch) {
  const auto r = contacts("G0 X0 Y0 Z0.5\nG1 X10\nG0 X5 Y5\nG1 X5 Y0\n");
  EXPECT_TRUE(r.crossings.empty());
  ASSERT_EQ(r.touches.size(), 1u);
  EXPECT_NEAR(r.touches[0].at_mm.x(), 5.0, 1e-9);
}

TEST(Crossings, ArcCrossingALineIsFound) {
  const auto r = contacts("G0 X-2 Y0 Z0.5\nG1 X2 Y0\nG0 X1 Y-1\nG3 X1 Y1 I-1 J1\n");
  EXPECT_EQ(r.crossings.size(), 1u);
}

// Separate one-segment strands (travels between them) so every pair is a candidate.
slicer::MotionProgram strands_of(const std::vector<std::pair<slicer::Vec2, slicer::Vec2>>& segs) {
  slicer::MotionProgram p;
  p.layers.push_back({0.5, 0.5});
  for (const auto& [a, b] : segs) {
    slicer::Move mv;
    mv.layer = 0;
    mv.end_mm = {a.x(), a.y(), 0.5};
    p.moves.push_back(mv);
    mv.kind = slicer::MoveKind::Deposit;
    mv.end_mm = {b.x(), b.y(), 0.5};
    p.moves.push_back(mv);
  }
  return p;
}

TEST(Crossings, GridAgreesWithAllPairsOnRandomSegmentsOfMixedLengths) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(0, 50), len(-0.5, 0.5), far(-40, 40);
  std::vector<std::pair<slicer::Vec2, slicer::Vec2>> segs;
  for (int i = 0; i < 600; ++i) {
    const slicer::Vec2 a(pos(rng), pos(rng));
    const slicer::Vec2 d = i % 50 == 0 ? slicer::Vec2(far(rng), far(rng)) : slicer::Vec2(len(rng), len(rng));
    segs.emplace_back(a, a + d);
  }
  std::size_t cross = 0, touch = 0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const auto c = slicer::segment_contact(segs[i].first, segs[i].second, segs[j].first, segs[j].second, 1e-3);
      cross += c == slicer::Contact::Crossing;
      touch += c == slicer::Contact::Touch;
    }
  }
  const auto r = find_contacts(strands_of(segs), 0.01, 1e-3);
  ASSERT_GT(cross, 20u) << "the sample must exercise crossings";
  EXPECT_EQ(r.crossings.size(), cross);
  EXPECT_EQ(r.touches.size(), touch);
}

TEST(Crossings, StarOfLinesThroughOnePointGivesEveryPair) {
  std::vector<std::pair<slicer::Vec2, slicer::Vec2>> segs;
  const int n = 40;  // a dense node: all lines share one cell
  for (int i = 0; i < n; ++i) {
    const double a = 3.14159265358979 * (i + 0.5) / n;
    const slicer::Vec2 d(std::cos(a), std::sin(a));
    segs.emplace_back(-10 * d, 10 * d);
  }
  EXPECT_EQ(find_contacts(strands_of(segs), 0.01, 1e-3).crossings.size(), static_cast<std::size_t>(n * (n - 1) / 2));
}

// Long rows 0.01 mm apart joined by U-turn links (the layer that made a uniform grid test
// every pair), crossed by one steep line: one crossing per row, no touches, no contacts
// between neighbouring rows or at the U-turn joints.
TEST(Crossings, LongRowSerpentineCrossedOnceGivesOneCrossingPerRow) {
  std::string g = "G0 X0 Y0 Z0.5\n";
  const int rows = 400;
  for (int r = 0; r < rows; ++r) {
    const double y = 0.01 * r;
    g += "G1 X" + std::to_string(r % 2 == 0 ? 100.0 : 0.0) + " Y" + std::to_string(y) + "\n";
    g += "G1 Y" + std::to_string(y + 0.01) + "\n";
  }
  g += "G0 X40.0 Y-1.0\nG1 X41.0 Y" + std::to_string(0.01 * rows + 1) + "\n";
  const auto r = contacts(g.c_str());
  EXPECT_EQ(r.crossings.size(), static_cast<std::size_t>(rows));
  EXPECT_TRUE(r.touches.empty());
}

}  // namespace
}  // namespace strand::post
