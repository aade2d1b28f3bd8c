#include "postprocess/inspect/gcode_parser.h"

#include <gtest/gtest.h>

namespace strand::post {
namespace {

TEST(GcodeParser, EGrowthMarksDepositsInRelativeAndAbsoluteModes) {
  const auto r = parse_gcode("G90\nM82\nG1 X1 Y0 Z0.2 E0.5\nG1 X2 E0.5\nG1 X3 E1.0\nM83\nG1 X4 E0.2\n");
  ASSERT_EQ(r.program.moves.size(), 4u);
  EXPECT_EQ(r.program.moves[0].kind, slicer::MoveKind::Deposit);
  EXPECT_EQ(r.program.moves[1].kind, slicer::MoveKind::Travel);  // E unchanged
  EXPECT_EQ(r.program.moves[2].kind, slicer::MoveKind::Deposit);
  EXPECT_EQ(r.program.moves[3].kind, slicer::MoveKind::Deposit);
}

TEST(GcodeParser, WithoutEWordsG1DepositsAndG0Travels) {
  const auto r = parse_gcode("G0 X0 Y0 Z1\nG1 X5\nG0 X6\n");
  EXPECT_FALSE(r.has_e);
  EXPECT_EQ(r.program.moves[1].kind, slicer::MoveKind::Deposit);
  EXPECT_EQ(r.program.moves[2].kind, slicer::MoveKind::Travel);
}

TEST(GcodeParser, LayerMarkersDefineLayers) {
  const auto r = parse_gcode(";LAYER_CHANGE\n;Z:0.3\n;LAYER:0\nG1 X1 Z0.3\n;LAYER_CHANGE\n;Z:0.6\n;LAYER:1\nG1 X2 Z0.6\n");
  ASSERT_EQ(r.program.layers.size(), 2u);
  EXPECT_DOUBLE_EQ(r.program.layers[1].z_mm, 0.6);
  EXPECT_EQ(r.program.moves[1].layer, 1);
}

TEST(GcodeParser, InchesAreConvertedAndReported) {
  const auto r = parse_gcode("G20\nG1 X1 Y0\n");
  EXPECT_TRUE(r.inches);
  EXPECT_DOUBLE_EQ(r.program.moves[0].end_mm.x(), 25.4);
  EXPECT_FALSE(r.issues.empty());
}

TEST(GcodeParser, NonFiniteNumberIsAnIssue) {
  const auto r = parse_gcode("G1 X1\nG1 Xnan Y2\n");
  ASSERT_EQ(r.issues.size(), 1u);
  EXPECT_EQ(r.issues[0].line, 2);
}

TEST(GcodeParser, ArcCentreFromIJ) {
  const auto r = parse_gcode("G0 X1 Y0\nG3 X0 Y1 I-1 J0\n");
  ASSERT_EQ(r.arc_lines.size(), 1u);
  EXPECT_TRUE(r.program.moves[1].is_arc);
  EXPECT_EQ(r.program.moves[1].center_mm, slicer::Vec2(0, 0));
}

TEST(GcodeParser, RotaryAWordsFollowTheMoves) {
  // A turn with no XYZ is still a move (a deposit when E grows); moves before the first A
  // word are at A = 0, and G92 sets it.
  const auto r = parse_gcode("G1 X1 E1\nG1 A90 E2\nG0 Z5\nG92 A10\nG1 X2 A20 E3\n");
  ASSERT_EQ(r.program.moves.size(), 4u);
  EXPECT_EQ(r.a_deg, (std::vector<double>{0.0, 90.0, 90.0, 20.0}));
  EXPECT_EQ(r.program.moves[1].kind, slicer::MoveKind::Deposit);
  EXPECT_TRUE(parse_gcode("G1 X1 E1\n").a_deg.empty()) << "no A words, no A column";
}

}  // namespace
}  // namespace strand::post

namespace strand::post {
namespace {

TEST(GcodeParserBounds, AbsurdArcRadiiAreReadAsStraightMovesAndReported) {
  for (const char* g : {"G0 X0 Y0\nG2 X0 Y0 I1e12 J0\n", "G0 X0 Y0\nG2 X0 Y0 I1e-9 J0\n"}) {
    const ParsedGcode p = parse_gcode(g);
    ASSERT_EQ(p.program.moves.size(), 2u);
    EXPECT_FALSE(p.program.moves[1].is_arc) << g;
    ASSERT_EQ(p.issues.size(), 1u) << g;
    EXPECT_NE(p.issues[0].what.find("arc radius"), std::string::npos) << p.issues[0].what;
  }
}

TEST(GcodeParserBounds, TheChordsOfAllArcsAreBounded) {
  // Full circles of 1 km radius need about 70,000 chords each at 0.001 mm: within the budget
  // for a few, refused after about 700.
  std::string g = "G0 X0 Y0\n";
  for (int i = 0; i < 1000; ++i) g += "G2 X0 Y0 I1000000 J0\n";
  const ParsedGcode p = parse_gcode(g);
  std::size_t arcs = 0;
  for (const auto& m : p.program.moves) arcs += m.is_arc ? 1 : 0;
  EXPECT_GT(arcs, 100u);
  EXPECT_LT(arcs, 1000u);
  EXPECT_FALSE(p.issues.empty());
}

}  // namespace
}  // namespace strand::post
