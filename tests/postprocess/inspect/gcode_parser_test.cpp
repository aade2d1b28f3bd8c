#include "postprocess/inspect/gcode_parser.h"

#include <gtest/gtest.h>

#include "machines/profile.h"

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

TEST(GcodeParser, InchesAreConvertedAndNotedNotAnIssue) {
  const auto r = parse_gcode("G20\nG1 X1 Y0\nG21\nG1 X30\n");
  EXPECT_TRUE(r.inches);
  EXPECT_DOUBLE_EQ(r.program.moves[0].end_mm.x(), 25.4);
  EXPECT_DOUBLE_EQ(r.program.moves[1].end_mm.x(), 30.0);  // G21: millimetres again
  EXPECT_TRUE(r.issues.empty());
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0].line, 1);
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

TEST(GcodeParserBounds, CommandNumbersBeyondAnyCommandAreIgnored) {
  // Found by gcode_fuzz: the number did not fit an int (undefined behaviour).
  const ParsedGcode p = parse_gcode("M1111111111300 S30\nG1111111111 X1\nG1e12 X2\nM-5\nG1 X3\n");
  ASSERT_EQ(p.program.moves.size(), 1u);
  EXPECT_EQ(p.program.moves[0].end_mm.x(), 3.0);
  EXPECT_EQ(p.pen_commands, 0);
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

namespace strand::post {
namespace {

using slicer::MoveKind;

std::vector<MoveKind> kinds(const ParsedGcode& p) {
  std::vector<MoveKind> k;
  for (const auto& m : p.program.moves) k.push_back(m.kind);
  return k;
}

constexpr MoveKind kInk = MoveKind::Deposit, kAir = MoveKind::Travel;

TEST(GcodeParserPen, M300ByTheUnicornConventionLiftsThePenForG1Travels) {
  const auto p = parse_gcode("M300 S50\nG1 X1\nM300 S30\nG1 X2\nM300 S50.0\nG1 X3\n");
  EXPECT_EQ(kinds(p), (std::vector<MoveKind>{kAir, kInk, kAir}));
  EXPECT_EQ(p.pen_commands, 3);
  ASSERT_EQ(p.notes.size(), 1u);
  EXPECT_NE(p.notes[0].what.find("Unicorn"), std::string::npos) << p.notes[0].what;
}

TEST(GcodeParserPen, AMarlinBeepOrAnotherServoSaysNothingAboutThePen) {
  EXPECT_EQ(kinds(parse_gcode("M300 S50\nM300 S30 P200\nG1 X1\n")), (std::vector<MoveKind>{kAir}));
  const auto servo = machines::load_profile("xy-plotter-servo");
  const auto p =
      parse_gcode("M280 P0 S90\nM280 P1 S30\nG1 X1\nM280 P0 S30\nG1 X2\n", pen_reading_from(servo));
  EXPECT_EQ(kinds(p), (std::vector<MoveKind>{kAir, kInk}));
  EXPECT_NE(p.notes[0].what.find("xy-plotter-servo"), std::string::npos) << p.notes[0].what;
}

TEST(GcodeParserPen, ProfileValuesOverrideTheConvention) {
  PenReading r;  // a servo mounted the other way round: 120 down, 20 up
  r.down_value = 120;
  r.up_value = 20;
  EXPECT_EQ(kinds(parse_gcode("M280 S20\nG1 X1\nM280 S120\nG1 X2\n", r)),
            (std::vector<MoveKind>{kAir, kInk}));
  EXPECT_EQ(kinds(parse_gcode("M280 S20\nG1 X1\nM280 S120\nG1 X2\n")),
            (std::vector<MoveKind>{kInk, kAir}));  // Makelangelo's convention: small is down
}

TEST(GcodeParserPen, GrblSpindleM3DownM5Up) {
  EXPECT_EQ(kinds(parse_gcode("M5\nG1 X1\nM3 S1000\nG1 X2\nM3 S0\nG1 X3\nM3\nG1 X4\n")),
            (std::vector<MoveKind>{kAir, kInk, kAir, kInk}));
}

TEST(GcodeParserPen, GrblServoProfileReadsItsSpindleValues) {
  // xy-plotter-grbl: M3 S50 up, M3 S30 down; without the profile both are "spindle on".
  const char* g = "M3 S50\nG1 X1\nM3 S30\nG1 X2\nM5\nG1 X3\n";
  EXPECT_EQ(kinds(parse_gcode(g, pen_reading_from(machines::load_profile("xy-plotter-grbl")))),
            (std::vector<MoveKind>{kAir, kInk, kAir}));
  EXPECT_EQ(kinds(parse_gcode(g)), (std::vector<MoveKind>{kInk, kInk, kAir}));
}

TEST(GcodeParserPen, FilesWithEIgnorePenCommands) {
  EXPECT_EQ(kinds(parse_gcode("M300 S50\nG1 X1 E1\nM5\nG1 X2 E2\n")),
            (std::vector<MoveKind>{kInk, kInk}));
}

TEST(GcodeParserPen, ZLiftDrawingsReadFromTheFileOrTheProfile) {
  const char* g = "G0 Z2\nG1 X1\nG1 Z0\nG1 X2\nG1 Y2\nG0 Z2\nG1 X0 Y0\n";
  EXPECT_EQ(kinds(parse_gcode(g)),
            (std::vector<MoveKind>{kAir, kInk, kAir, kInk, kInk, kAir, kInk}));
  const auto drawing = parse_drawing(g, {});
  EXPECT_EQ(kinds(drawing), (std::vector<MoveKind>{kAir, kAir, kAir, kInk, kInk, kAir, kAir}));
  ASSERT_EQ(drawing.notes.size(), 1u);
  EXPECT_NE(drawing.notes[0].what.find("above z 0.2 mm"), std::string::npos)
      << drawing.notes[0].what;
  const auto z = machines::load_profile("xy-plotter-z");
  EXPECT_EQ(kinds(parse_drawing(g, pen_reading_from(z))), kinds(drawing));
}

}  // namespace
}  // namespace strand::post
