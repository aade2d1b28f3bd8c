#include "machines/gcode_emitter.h"

#include <gtest/gtest.h>

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
  m.name = "t";
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

TEST(GcodeEmitter, ExtrusionModeComesAfterG90) {
  const std::string g = emit_gcode(two_moves(), e_machine(true), {});
  EXPECT_LT(g.find("G90"), g.find("M83"));
}

TEST(GcodeEmitter, LayerAndFeatureCommentsForViewers) {
  const std::string g = emit_gcode(two_moves(), e_machine(false), {});
  EXPECT_NE(g.find(";LAYER_CHANGE\n;Z:0.500\n;HEIGHT:0.500\n;LAYER:0\n"), std::string::npos) << g;
  EXPECT_NE(g.find(";TYPE:External perimeter\n;FEATURE:node\n;WIDTH:0.800\n"), std::string::npos) << g;
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

}  // namespace
}  // namespace strand::machines
