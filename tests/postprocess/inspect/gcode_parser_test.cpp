#include "postprocess/inspect/gcode_parser.h"

#include <gtest/gtest.h>

#include "machines/profile.h"
#include "slicer/input_error.h"

namespace strand::post {
namespace {

TEST(GcodeParser, EGrowthMarksDepositsInRelativeAndAbsoluteModes) {
  const auto r =
      parse_gcode("G90\nM82\nG1 X1 Y0 Z0.2 E0.5\nG1 X2 E0.5\nG1 X3 E1.0\nM83\nG1 X4 E0.2\n");
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
  const auto r = parse_gcode(
      ";LAYER_CHANGE\n;Z:0.3\n;LAYER:0\nG1 X1 Z0.3\n;LAYER_CHANGE\n;Z:0.6\n;LAYER:1\nG1 X2 Z0.6\n");
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

// --- RS274NGC dialects (issue 19) ---

// A Vitaprint-style log-pile scaffold: no E, every G1 in XY deposits, and each layer is raised
// by an expression on the current position, G1 Z[#<_z> + #<layer_h>]. Layer k runs its 5 bars
// along X (k even) or Y (k odd) as one serpentine from where the layer below ended.
std::string log_pile(int layers) {
  std::string g = "%\n(log-pile, 5 bars of 8 mm, 2 mm pitch)\n#<layer_h> = 0.2\n#<pitch> = 2\n";
  g += "G92\tX0\tY0\nG1\tZ0.2\tF300\n";
  for (int k = 0; k < layers; ++k) {
    if (k > 0) g += "G1 Z[#<_z> + #<layer_h>] (next layer)\n";
    for (int j = 0; j < 5; ++j) {
      // even layers: bars along X at y = 2j; odd layers: bars along Y at x = 8 - 2j
      const bool out = j % 2 == 0;
      if (k % 2 == 0) {
        g += "G1 X" + std::string(out ? "[4 * #<pitch>]" : "0") + " Y[" + std::to_string(j) +
             " * #<pitch>]\n";
        if (j < 4) g += "G1 Y[#<_y> + #<pitch>]\n";
      } else {
        g += "G1 Y" + std::string(out ? "0" : "8") + " X[8 - " + std::to_string(j) +
             " * #<pitch>]\n";
        if (j < 4) g += "G1 X[#<_x> - #<pitch>]\n";
      }
    }
  }
  return g + "%\n";
}

TEST(GcodeDialects, AVitaprintLogPileReadsAsItsLayers) {
  const auto r = parse_gcode(log_pile(5));
  EXPECT_TRUE(r.issues.empty()) << r.issues[0].what;
  ASSERT_EQ(r.program.layers.size(), 5u);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(r.program.layers[k].z_mm, 0.2 * (k + 1), 1e-9);
  // Layer 1 runs along Y: its first bar ends at (8, 0), its second starts at x = 6.
  std::vector<slicer::Vec3> layer1;
  for (const auto& mv : r.program.moves)
    if (mv.layer == 1 && mv.kind == slicer::MoveKind::Deposit) layer1.push_back(mv.end_mm);
  ASSERT_GE(layer1.size(), 2u);
  EXPECT_NEAR(layer1[0].x(), 8.0, 1e-9);
  EXPECT_NEAR(layer1[0].y(), 0.0, 1e-9);
  EXPECT_NEAR(layer1[1].x(), 6.0, 1e-9);
}

TEST(GcodeDialects, ParametersAreSetAfterTheLineReadsThem) {
  // RS274NGC: every read on a line sees the values from before it.
  const auto r = parse_gcode("#1 = 5\n#1 = [#1 + 1] G1 X#1\nG1 X#1\n");
  ASSERT_EQ(r.program.moves.size(), 2u);
  EXPECT_DOUBLE_EQ(r.program.moves[0].end_mm.x(), 5.0);
  EXPECT_DOUBLE_EQ(r.program.moves[1].end_mm.x(), 6.0);
}

TEST(GcodeDialects, CurrentPositionFollowsUnits) {
  const auto r = parse_gcode("G20\nG1 X1\nG1 X[#<_x> + 1]\n");  // inches: _x is 1, not 25.4
  ASSERT_EQ(r.program.moves.size(), 2u);
  EXPECT_NEAR(r.program.moves[1].end_mm.x(), 50.8, 1e-9);
}

TEST(GcodeDialects, OWordSubroutinesAndLoopsRun) {
  const std::string g =
      "o100 sub\n"
      "  G1 X[#1] Y#2\n"
      "o100 endsub\n"
      "#<n> = 0\n"
      "o200 while [#<n> LT 3]\n"
      "  o100 call [#<n> * 10] [1]\n"
      "  #<n> = [#<n> + 1]\n"
      "o200 endwhile\n"
      "o300 repeat [2]\n"
      "  G1 Y[#<_y> + 1]\n"
      "o300 endrepeat\n"
      "o400 if [#<n> EQ 3]\n"
      "  G1 X99\n"
      "o400 else\n"
      "  G1 X-99\n"
      "o400 endif\n"
      "o500 do\n"
      "  #<n> = [#<n> - 1]\n"
      "  o510 if [#<n> EQ 1]\n"
      "    o500 break\n"
      "  o510 endif\n"
      "o500 while [#<n> GT 0]\n"
      "G1 X#<n>\n";
  const auto r = parse_gcode(g);
  ASSERT_TRUE(r.issues.empty()) << r.issues[0].what;
  std::vector<double> xs, ys;
  for (const auto& mv : r.program.moves) xs.push_back(mv.end_mm.x()), ys.push_back(mv.end_mm.y());
  EXPECT_EQ(xs, (std::vector<double>{0, 10, 20, 20, 20, 99, 1}));
  EXPECT_EQ(ys, (std::vector<double>{1, 1, 1, 2, 3, 3, 3}));
  EXPECT_EQ(r.move_lines[1], 2);  // the move's line is the subroutine's line
}

TEST(GcodeDialects, DivisionByZeroNamesItsLine) {
  try {
    parse_gcode("G1 X1\n#<h> = 0\nG1 Z[1 / #<h>]\n");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3: division by zero"), std::string::npos)
        << e.what();
  }
}

TEST(GcodeDialects, AnUnboundedLoopIsRefusedWithItsLine) {
  try {
    parse_gcode("G1 X0\no1 while [1]\nG1 X[#<_x> + 1]\no1 endwhile\n");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 2: this O-word loop"), std::string::npos)
        << e.what();
  }
  // Recursion without end is bounded by the call depth.
  EXPECT_THROW(parse_gcode("o1 sub\no1 call\no1 endsub\no1 call\n"), InputError);
  // Blocks that do not match are bad input too.
  EXPECT_THROW(parse_gcode("o1 while [1]\nG1 X1\n"), InputError);
  EXPECT_THROW(parse_gcode("o1 endif\n"), InputError);
}

TEST(GcodeDialects, WhatIsNotSupportedIsNamedOnceAndNothingAfterIsGuessed) {
  const auto r = parse_gcode("G1 X1 Z0.2\nG1 X2\no<purge> call\nG1 Z0.4\nG1 X3\nG1 X[#5399]\n");
  ASSERT_EQ(r.issues.size(), 1u);
  EXPECT_EQ(r.issues[0].line, 3);
  EXPECT_NE(r.issues[0].what.find("unsupported: O-word call of o<purge>"), std::string::npos)
      << r.issues[0].what;
  EXPECT_NE(r.issues[0].what.find("at line 3"), std::string::npos);
  EXPECT_EQ(r.program.moves.size(), 2u);
  EXPECT_EQ(r.program.layers.size(), 1u);
  const auto probe = parse_gcode("G1 X1\nG1 X[#5061]\nG1 X2\n");  // a probe result
  ASSERT_EQ(probe.issues.size(), 1u);
  EXPECT_NE(probe.issues[0].what.find("unsupported: system parameter #5061 at line 2"),
            std::string::npos);
}

TEST(GcodeDialects, VendorLinesWithBracketsStayAsTheyWere) {
  const auto r = parse_gcode(
      "EXCLUDE_OBJECT_DEFINE NAME=a CENTER=1,1 POLYGON=[[0,0],[1,1]]\nM117 [50%]\nG1 X1\n");
  EXPECT_TRUE(r.issues.empty());
  EXPECT_EQ(r.program.moves.size(), 1u);
  // Text that is not G-code (a job's JSON) is not read as expressions either.
  EXPECT_NO_THROW(parse_gcode("{\n  \"size\": [36, 36],\n  \"layers\": 3\n}\n"));
  // RepRapFirmware's own expressions stay a malformed number, as before (not exit 2).
  const auto rrf = parse_gcode("G1 X1\nG1 X{move.axes[0].max - 10}\n");
  ASSERT_EQ(rrf.issues.size(), 1u);
  EXPECT_EQ(rrf.issues[0].line, 2);
}

TEST(GcodeDialects, ValveOutputsDepositWhenTheProfileSwitchesThem) {
  auto m = machines::load_profile("bioprinter-xyz-reprap");
  m.deposition.on_gcode = {"M62 P2 ; valve open"};
  m.deposition.off_gcode = {"M63 P2 ; valve closed"};
  const std::string g = "G1 X1 Y0\nM62 P2\nG1 X5\nM63 P2\nG1 X9\nM62 P1\nG1 X12\n";
  const auto r = parse_gcode(g, pen_reading_from(m));
  ASSERT_EQ(r.program.moves.size(), 4u);
  EXPECT_EQ(r.program.moves[0].kind, slicer::MoveKind::Travel);   // closed at the start
  EXPECT_EQ(r.program.moves[1].kind, slicer::MoveKind::Deposit);  // M62 P2
  EXPECT_EQ(r.program.moves[2].kind, slicer::MoveKind::Travel);   // M63 P2
  EXPECT_EQ(r.program.moves[3].kind, slicer::MoveKind::Travel);   // another output
  // Without the profile every G1 deposits, as before.
  EXPECT_EQ(parse_gcode(g).program.moves[2].kind, slicer::MoveKind::Deposit);
}

TEST(GcodeDialects, AMillingProgramIsNamed) {
  const auto r = parse_gcode("G21\nM3 S12000\nG0 Z5\nG0 X10 Y10\nG1 Z-1.5 F100\nG1 X20\nM5\n");
  ASSERT_EQ(r.issues.size(), 1u);
  EXPECT_EQ(r.issues[0].line, 5);
  EXPECT_NE(r.issues[0].what.find("milling program"), std::string::npos);
  // A GRBL dispenser or laser (M3 S below 1000) or a pen pressing to Z -0.02 is not milling.
  EXPECT_TRUE(parse_gcode("M3 S255\nG1 X1 Z-1\n").issues.empty());
  EXPECT_TRUE(parse_gcode("M3 S12000\nG1 X1 Z-0.02\n").issues.empty());
}

}  // namespace
}  // namespace strand::post
