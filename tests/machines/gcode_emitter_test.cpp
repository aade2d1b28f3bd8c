#include "machines/gcode_emitter.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>

#include "machines/gcode_format.h"

namespace strand::machines {
namespace {

slicer::MotionProgram two_moves() {
  slicer::MotionProgram p;
  p.layers = {{0.5, 0.5}};
  slicer::Move t;
  t.kind = slicer::MoveKind::Travel;
  t.end_mm = {0, 0, 0.5};
  t.feed_mm_per_min = 1000;
  t.layer = 0;
  slicer::Move d = t;
  d.kind = slicer::MoveKind::Deposit;
  d.end_mm = {10, 0, 0.5};
  d.feed_mm_per_min = 250;
  d.volume_mm3 = 4.0;
  d.width_mm = 0.8;
  d.feature = slicer::Feature::Node;
  p.moves = {t, d};
  return p;
}

MachineProfile e_machine(bool relative) {
  MachineProfile m;
  m.name.assign(1, 't');  // not = "t": GCC 12 -Wstringop-overflow false positive once inlined
  m.deposition.model = DepositionModel::EVolumetric;
  m.deposition.mm3_per_e = 2.0;
  m.deposition.relative_e = relative;
  return m;
}

TEST(GcodeFormat, FixedDigitsAndNoNegativeZero) {
  EXPECT_EQ(fmt_xyz(1.23456), "1.235");
  EXPECT_EQ(fmt_xyz(-0.0001), "0.000");
  EXPECT_EQ(fmt_e(0.123456789), "0.12346");
  EXPECT_EQ(fmt_feed(274.9999), "275");
}

TEST(GcodeEmitter, TravelIsG0DepositIsG1WithVolumetricE) {
  const std::string g = emit_gcode(two_moves(), e_machine(true), {});
  EXPECT_NE(g.find("G0 X0.000 Y0.000 Z0.500 F1000\n"), std::string::npos) << g;
  EXPECT_NE(g.find("G1 X10.000 E2.00000 F250\n"), std::string::npos) << g;
}

// A deposit shorter than the output's 0.001 mm steps (a sliver left where a clipped pattern
// meets its boundary) writes no line of its own: no "G1 E0.00003" residue, the E total kept.
TEST(GcodeEmitter, SubMicronDepositIsMergedIntoTheNextOneKeepingE) {
  slicer::MotionProgram p = two_moves();
  slicer::Move sliver = p.moves[1];
  sliver.end_mm = {10.0002, 0, 0.5};
  sliver.volume_mm3 = 0.2;
  slicer::Move next = p.moves[1];
  next.end_mm = {20, 0, 0.5};
  p.moves.push_back(sliver);
  p.moves.push_back(next);
  const std::string g = emit_gcode(p, e_machine(true), {});
  std::istringstream in(g);
  double e_total = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("G1", 0) != 0) continue;
    EXPECT_TRUE(line.find(" X") != std::string::npos || line.find(" Y") != std::string::npos ||
                line.find(" Z") != std::string::npos)
        << "a move without an axis word: " << line;
    const auto e = line.find(" E");
    if (e != std::string::npos) e_total += std::stod(line.substr(e + 2));
  }
  EXPECT_NEAR(e_total, (4.0 + 0.2 + 4.0) / 2.0, 1e-5) << g;
  EXPECT_NE(g.find("G1 X20.000 E2.10000"), std::string::npos) << g;
}

TEST(GcodeEmitter, ExtrusionModeComesAfterG90) {
  const std::string g = emit_gcode(two_moves(), e_machine(true), {});
  EXPECT_LT(g.find("G90"), g.find("M83"));
}

TEST(GcodeEmitter, LayerAndFeatureCommentsForViewers) {
  const std::string g = emit_gcode(two_moves(), e_machine(false), {});
  EXPECT_NE(g.find(";LAYER_CHANGE\n;Z:0.500\n;HEIGHT:0.500\n;LAYER:0\n"), std::string::npos) << g;
  EXPECT_NE(g.find(";TYPE:Perimeter\n;FEATURE:node\n;WIDTH:0.800\n"), std::string::npos) << g;
}

TEST(GcodeEmitter, ViewerRolesArePrusaSlicerRolesAndNoneOverstates) {
  // PrusaSlicer 2.5's extrusion roles (GCodeProcessor): an unknown name is dropped by its viewer.
  const std::set<std::string> roles = {"Perimeter",
                                       "External perimeter",
                                       "Overhang perimeter",
                                       "Internal infill",
                                       "Solid infill",
                                       "Top solid infill",
                                       "Ironing",
                                       "Bridge infill",
                                       "Gap fill",
                                       "Skirt/Brim",
                                       "Support material",
                                       "Support material interface",
                                       "Wipe tower",
                                       "Custom"};
  for (int f = 0; f <= static_cast<int>(slicer::Feature::Pen); ++f) {
    const std::string role = viewer_role(static_cast<slicer::Feature>(f));
    EXPECT_TRUE(roles.count(role)) << role;
    // Strand cannot know what is a top surface, an overhang or a bridge.
    for (const char* claim : {"Top", "Overhang", "Bridge", "Support", "Custom"})
      EXPECT_EQ(role.find(claim), std::string::npos) << role;
  }
  EXPECT_EQ(viewer_role(slicer::Feature::Frame), "External perimeter");  // the outer border
  EXPECT_NE(viewer_role(slicer::Feature::Node), "External perimeter");   // inside the lattice
  EXPECT_NE(viewer_role(slicer::Feature::Grip), viewer_role(slicer::Feature::Frame));
}

TEST(GcodeEmitter, ValveCommandsBracketDepositsWithM400) {
  MachineProfile m;
  m.deposition.model = DepositionModel::Valve;
  m.deposition.on_gcode = {"M42 P4 S255"};
  m.deposition.off_gcode = {"M42 P4 S0"};
  m.deposition.lead_s = 0.2;
  const std::string g = emit_gcode(two_moves(), m, {});
  const auto on = g.find("M400\nM42 P4 S255\nG4 P200\n");
  const auto dep = g.find("G1 X10.000");
  const auto off = g.find("M400\nM42 P4 S0\n");
  ASSERT_NE(on, std::string::npos) << g;
  ASSERT_NE(off, std::string::npos) << g;
  EXPECT_LT(on, dep);
  EXPECT_GT(off, dep);
  EXPECT_EQ(g.find(" E"), std::string::npos) << "no E words on a valve machine";
}

TEST(GcodeEmitter, GrblDwellsInSecondsCommentsInParenthesesSyncWithG4P0) {
  MachineProfile m;
  m.firmware = Firmware::Grbl;
  m.deposition.model = DepositionModel::Valve;
  m.deposition.on_gcode = {"M8"};
  m.deposition.off_gcode = {"M9"};
  m.deposition.lead_s = 0.25;
  EmitOptions o;
  o.header = {"Strand (test)"};
  const std::string g = emit_gcode(two_moves(), m, o);
  EXPECT_NE(g.find("(Strand [test])\n"), std::string::npos) << g;
  EXPECT_NE(g.find("G4 P0\nM8\nG4 P0.250\n"), std::string::npos) << g;
  EXPECT_EQ(g.find("M400"), std::string::npos) << g;
  EXPECT_EQ(g.find("M83"), std::string::npos) << g;
  EXPECT_EQ(g.find(" E"), std::string::npos) << g;
}

TEST(GcodeEmitter, MarlinDwellsInMilliseconds) {
  MachineProfile m;
  m.deposition.model = DepositionModel::Valve;
  m.deposition.on_gcode = {"M42 P6 S255"};
  m.deposition.off_gcode = {"M42 P6 S0"};
  m.deposition.lead_s = 0.25;
  EXPECT_NE(emit_gcode(two_moves(), m, {}).find("M42 P6 S255\nG4 P250\n"), std::string::npos);
}

TEST(GcodeEmitter, LongExtrusionsAreSplitBelowExtrudeMaxLength) {
  // 4 mm3 at 0.01 mm3/E = 400 E over a 10 mm move; max 150 per move -> 3 moves of 133.33.
  MachineProfile m = e_machine(true);
  m.deposition.mm3_per_e = 0.01;
  m.deposition.extrude_max_length = 150.0;
  m.deposition.prime_e = 320.0;  // E-only prime: 3 moves of 106.67
  const std::string g = emit_gcode(two_moves(), m, {});
  EXPECT_NE(g.find("G1 X3.333 E133.33333 F250\nG1 X6.667 E133.33333\nG1 X10.000 E133.33333\n"), std::string::npos) << g;
  EXPECT_NE(g.find("G1 E106.66667 F200 ; prime\nG1 E106.66667 F200 ; prime\nG1 E106.66667 F200 ; prime\n"), std::string::npos) << g;
  EXPECT_NE(g.find("M302 S0"), std::string::npos) << "cold paste on Marlin";
  EXPECT_LT(g.find("M302 S0"), g.find("; prime"));
}

TEST(GcodeEmitter, CoastMovesRunWithTheValveClosed) {
  MachineProfile m;
  m.deposition.model = DepositionModel::Valve;
  m.deposition.on_gcode = {"ON"};
  m.deposition.off_gcode = {"OFF"};
  auto p = two_moves();
  auto tail = p.moves.back();
  p.moves.back().end_mm.x() = 7.0;
  tail.coast = true;
  p.moves.push_back(tail);
  const std::string g = emit_gcode(p, m, {});
  EXPECT_NE(g.find("G1 X7.000 F250\nM400\nOFF\nG1 X10.000\n"), std::string::npos) << g;
}

slicer::MotionProgram quarter_arc() {
  auto p = two_moves();
  auto& d = p.moves.back();
  d.is_arc = true;
  d.ccw = true;
  d.center_mm = {0, 5};
  d.end_mm = {5, 5, 0.5};
  return p;
}

TEST(GcodeEmitter, ArcsAreG2G3OnlyWhereAllowed) {
  MachineProfile m = e_machine(true);
  m.arcs = true;
  EXPECT_NE(emit_gcode(quarter_arc(), m, {}).find("G3 X5.000 Y5.000 I0.000 J5.000"), std::string::npos);
  m.arcs = false;
  const std::string g = emit_gcode(quarter_arc(), m, {});
  EXPECT_EQ(g.find("\nG3 "), std::string::npos) << g;
  EXPECT_EQ(g.find("\nG2 "), std::string::npos) << g;
  EXPECT_NE(g.find("G1 X5.000 Y5.000"), std::string::npos) << g;
}

TEST(GcodeEmitter, ViewerCopySaysNotForPrintingAndAddsE) {
  MachineProfile m;
  m.deposition.model = DepositionModel::None;
  EmitOptions o;
  o.viewer_e = true;
  const std::string g = emit_gcode(two_moves(), m, o);
  EXPECT_EQ(g.find("; PREVIEW ONLY - NOT FOR PRINTING"), 0u) << g;
  EXPECT_NE(g.find("G1 X10.000 E4.00000 F250"), std::string::npos) << g;
}

}  // namespace
}  // namespace strand::machines
