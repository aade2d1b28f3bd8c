#include "postprocess/inspect/check.h"

#include <gtest/gtest.h>

#include "machines/plotter_kinematics.h"
#include "machines/profile.h"
#include "patterns/registry.h"
#include "patterns/scaffold.h"
#include "postprocess/plan/produce.h"
#include "slicer/input_error.h"

namespace strand::post {
namespace {

CheckReport check(const std::string& gcode, const machines::MachineProfile* m = nullptr) {
  CheckOptions o;
  o.machine = m;
  return check_gcode(gcode, o);
}

const machines::MachineProfile& delta() {
  static const auto m = machines::load_profile("deltawasp-2040-clay");
  return m;
}

TEST(Check, CrossingIsAFailureWithItsPointAndLines) {
  const auto r = check(";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 Y10\nG1 X10 Y0\nG1 X0 Y10\n");
  ASSERT_EQ(r.layers.size(), 1u);
  ASSERT_EQ(r.layers[0].crossings.size(), 1u);
  const Contact& c = r.layers[0].crossings[0];
  EXPECT_NEAR(c.at_mm.x(), 5.0, 1e-9);
  EXPECT_NEAR(c.at_mm.y(), 5.0, 1e-9);
  EXPECT_EQ(r.line_of(c.move_a), 3);
  EXPECT_EQ(r.line_of(c.move_b), 5);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(to_text(r).find("at (5.000, 5.000) mm: lines 3 and 5"), std::string::npos)
      << to_text(r);
}

// Issue 33: strands of two printheads crossing in a layer (two inks on each other) are
// crossings, named with their heads; one head's own layers are not.
TEST(Check, CrossingBetweenTwoPrintheadsIsNamed) {
  const auto r = check("M83\n;LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 Y10 E1\nT1\nG0 X10 Y0\nG1 X0 Y10 E1\n"
                       ";LAYER:1\nG0 X0 Y5 Z1\nG1 X10 Y5 E1\nT0\nG0 X0 Y0\nG1 X10 Y0 E1\nG1 X0 Y1 E1\n");
  ASSERT_EQ(r.layers.size(), 2u);
  ASSERT_EQ(r.layers[0].crossings.size(), 1u);
  EXPECT_TRUE(r.layers[0].crossings[0].between_tools());
  EXPECT_EQ(r.layers[0].strands_by_tool, (std::vector<int>{1, 1}));
  EXPECT_EQ(r.crossings_between_tools(), 1u);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(to_text(r).find("lines 4 and 7 (T0 and T1: two inks)"), std::string::npos) << to_text(r);
  EXPECT_NE(to_text(r).find("of which between printheads (two inks): 1"), std::string::npos);
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j["crossings_between_tools"], 1);
  EXPECT_EQ(j["layers"][0]["crossings"][0]["tools"], nlohmann::json({0, 1}));
  // One head's files say nothing of heads.
  EXPECT_FALSE(to_json(check(";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 Y10 E1\n")).contains("crossings_between_tools"));
}

// Issue 29: a file that deposits nothing fails under the diw rules and is said under the
// others; a layer with moves but no deposit is counted apart, not as a layer.
TEST(Check, NoDepositFailsDiwAndTravelOnlyLayersAreCountedApart) {
  const auto empty = check("G28\nG0 X10 Y10 Z5\nG0 X0 Y0\n");
  EXPECT_EQ(empty.deposit_moves, 0u);
  EXPECT_FALSE(empty.ok());
  EXPECT_NE(to_text(empty).find("no deposit: not one of the 2 moves deposits"), std::string::npos)
      << to_text(empty);
  CheckOptions fdm;
  fdm.rules = RulesChoice{CheckRules::Fdm, "given"};
  const auto said = check_gcode("G0 X10 Y10 Z5\n", fdm);
  EXPECT_TRUE(said.ok());
  EXPECT_NE(to_text(said).find("(said, not failed, under fdm rules)"), std::string::npos);
  const auto r = check(";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 E1\n;LAYER:1\nG0 X0 Y0 Z1\nG1 Y10 E2\n"
                       ";LAYER:2\nG0 Z1.5\nG0 X50 Y50\n");
  ASSERT_EQ(r.layers.size(), 2u);
  EXPECT_EQ(r.layers[1].layer, 1);
  EXPECT_EQ(r.layers_without_deposit, 1u);
  EXPECT_EQ(r.layers_without_deposit_index, std::vector<int>{2});
  EXPECT_TRUE(r.ok());
  const std::string text = to_text(r);
  EXPECT_EQ(text.rfind("2 layers, ", 0), 0u) << text;
  EXPECT_NE(text.find("1 layer with moves but no deposit, not counted as a layer: 2"),
            std::string::npos)
      << text;
  EXPECT_EQ(to_json(r).at("layers_without_deposit").get<int>(), 1);
}

TEST(Check, TouchIsReportedButPasses) {
  const auto r = check("G0 X0 Y0 Z0.5\nG1 X10\nG0 X5 Y5\nG1 X5 Y0\n");
  ASSERT_EQ(r.layers.size(), 1u);
  EXPECT_EQ(r.layers[0].touches.size(), 1u);
  EXPECT_TRUE(r.layers[0].crossings.empty());
  EXPECT_EQ(r.layers[0].strands, 2);
  EXPECT_TRUE(r.ok());
}

TEST(Check, ArcIsForbiddenOnlyWhereTheMachineForbidsArcs) {
  const std::string g = "G0 X1 Y0 Z0.5\nG3 X0 Y1 I-1 J0\n";
  const auto on_delta = check(g, &delta());
  ASSERT_EQ(on_delta.arcs_forbidden.size(), 1u);
  EXPECT_EQ(on_delta.arcs_forbidden[0].line, 2);
  EXPECT_FALSE(on_delta.ok());
  const auto cartesian = machines::load_profile("marlin-xyz-200");
  EXPECT_TRUE(check("G0 X101 Y100 Z0.5\nG3 X100 Y101 I-1 J0\n", &cartesian).ok());
  EXPECT_TRUE(check(g).arcs_forbidden.empty()) << "no machine, no arc rule";
}

TEST(Check, MoveOutsideTheDeltaRadiusIsFound) {
  const auto r = check("G0 X0 Y0 Z0.5\nG1 X50 Y0\nG1 X120 Y0\n", &delta());
  ASSERT_EQ(r.outside_volume.size(), 1u);
  EXPECT_EQ(r.outside_volume[0].line, 3);
  EXPECT_NE(r.outside_volume[0].what.find("radius 120 mm"), std::string::npos)
      << r.outside_volume[0].what;
  EXPECT_FALSE(r.ok());
}

TEST(Check, LinesStayRightAfterADwell) {
  const auto r = check("G0 X0 Y0 Z0.5\nG4 P500\nG1 X50 Y0\nG1 X120 Y0\n", &delta());
  ASSERT_EQ(r.outside_volume.size(), 1u);
  EXPECT_EQ(r.outside_volume[0].line, 4);
}

TEST(Check, ArcBulgingOutOfTheVolumeIsFoundThoughItsEndsAreInside) {
  // Both ends at radius 83.8 mm; the ccw arc passes (105, 0), the cw arc (55, 0).
  const auto out = check("G0 X80 Y-25 Z0.5\nG3 X80 Y25 I0 J25\n", &delta());
  ASSERT_EQ(out.outside_volume.size(), 1u);
  EXPECT_NEAR(out.outside_volume[0].at_mm.x(), 105.0, 1e-9);
  EXPECT_TRUE(check("G0 X80 Y-25 Z0.5\nG2 X80 Y25 I0 J25\n", &delta()).outside_volume.empty());
}

TEST(Check, NonFiniteNumberFails) {
  const auto r = check("G0 X0 Y0 Z0.5\nG1 X1\nG1 Xnan Y2\n");
  ASSERT_EQ(r.parse_issues.size(), 1u);
  EXPECT_EQ(r.parse_issues[0].line, 3);
  EXPECT_FALSE(r.ok());
}

TEST(Check, InchUnitsAreConvertedAndNotedNotFailed) {
  const auto r = check("G20\nG0 X0 Y0 Z0.02\nG1 X1\n");
  EXPECT_TRUE(r.ok()) << to_text(r);
  EXPECT_NEAR(r.layers.at(0).z_mm, 0.508, 1e-12);
  EXPECT_NE(to_text(r).find("notes (1):\n  line 1: inch units (G20)"), std::string::npos)
      << to_text(r);
}

TEST(CheckRules, FdmLetsInfillCrossButNotTwoWalls) {
  const std::string cross = "G0 X0 Y0 Z0.3\nG1 X10 Y10 E1\nG0 X10 Y0\nG1 X0 Y10 E2\n";
  CheckOptions o;
  o.rules = RulesChoice{CheckRules::Fdm, "test"};
  const auto infill = check_gcode(";TYPE:Solid infill\n" + cross, o);
  EXPECT_EQ(infill.crossing_count(), 1u);
  EXPECT_EQ(infill.crossings_allowed, 1u);
  EXPECT_TRUE(infill.ok());
  const auto wall_and_fill = check_gcode(
      ";TYPE:Perimeter\nG0 X0 Y0 Z0.3\nG1 X10 Y10 E1\nG0 X10 Y0\n;TYPE:Gap fill\nG1 X0 Y10 E2\n",
      o);
  EXPECT_TRUE(wall_and_fill.ok());
  const auto walls = check_gcode(";TYPE:External perimeter\n" + cross, o);
  EXPECT_EQ(walls.crossings_allowed, 0u);
  EXPECT_FALSE(walls.ok());
  o.rules = RulesChoice{CheckRules::Diw, "test"};
  EXPECT_FALSE(check_gcode(";TYPE:Solid infill\n" + cross, o).ok());
}

TEST(CheckRules, WithoutAMachineAPenServoMakesADrawingButM3M5AloneDoNot) {
  // Two strokes that cross, the pen lifted between them.
  const std::string strokes = "G1 X10 Y10\n{up}\nG1 X10 Y0\n{down}\nG1 X0 Y10\n";
  auto with = [&](const std::string& down, const std::string& up) {
    std::string g = down + "\nG0 X0 Y0\n" + strokes;
    g.replace(g.find("{up}"), 4, up);
    g.replace(g.find("{down}"), 6, down);
    return check(g);
  };
  const auto servo = with("M280 P0 S30", "M280 P0 S90");
  EXPECT_EQ(servo.rules.rules, CheckRules::Plot);
  EXPECT_EQ(servo.crossing_count(), 1u);
  EXPECT_TRUE(servo.ok());
  const auto spindle = with("M3 S1000", "M5");
  EXPECT_EQ(spindle.rules.rules, CheckRules::Diw);
  EXPECT_EQ(spindle.layers.at(0).strands, 2) << "M5 still stops the deposit";
  EXPECT_FALSE(spindle.ok());
}

TEST(CheckRules, DefaultFromThePlotterProfileElseTheSlicerNamedInTheHeader) {
  const auto plotter = machines::load_profile("polargraph");
  EXPECT_EQ(default_rules(&plotter, "; generated by PrusaSlicer\n").rules, CheckRules::Plot);
  EXPECT_EQ(default_rules(&delta(), "; generated by PrusaSlicer 2.5.0\n").rules, CheckRules::Fdm);
  EXPECT_EQ(default_rules(nullptr, ";FLAVOR:Marlin\n;Generated with Cura_SteamEngine 5.0\n").rules,
            CheckRules::Fdm);
  EXPECT_EQ(default_rules(nullptr, "M117 PrusaSlicer\n").rules, CheckRules::Diw)
      << "a name outside a comment is not a header";
  EXPECT_EQ(default_rules(nullptr, std::string(5000, '\n') + "; generated by PrusaSlicer\n").rules,
            CheckRules::Diw)
      << "only the head of the file is searched";
  EXPECT_EQ(default_rules(&delta(), "G1 X1\n").rules, CheckRules::Diw);
  EXPECT_EQ(check_rules_from_string("plot"), CheckRules::Plot);
  EXPECT_THROW(check_rules_from_string("FDM"), InputError);
}

TEST(Check, TextMessagesAndBareAxisWordsAreNotMalformed) {
  EXPECT_TRUE(
      check("M117 Open the air valve now\nG28 X Y\nG0 X0 Y0 Z1\nG1 X5\n").parse_issues.empty());
  EXPECT_FALSE(check("G1 X1.0 Yabc\n").parse_issues.empty());
}

TEST(Check, CuraFileWithAbsoluteEIsReadLayerByLayer) {
  const std::string cura =
      ";FLAVOR:Marlin\n;LAYER_COUNT:2\nM82\nG92 E0\n;LAYER:0\nG0 F3000 X10 Y10 "
      "Z0.3\n;TYPE:WALL-OUTER\n"
      "G1 F1200 X20 Y10 E0.5\nG1 X20 Y20 E1.0\nG1 X10 Y20 E1.5\nG1 X10 Y10 E2.0\nG1 F2400 E1.2\n"
      "G0 X30 Y30\nG1 F2400 E2.0\n;TYPE:FILL\nG1 X40 Y30 E2.5\n"
      ";LAYER:1\nG0 X10 Y10 Z0.5\nG1 X20 Y10 E3.0\nG1 X10 Y12 E3.5\n";
  const auto r = check(cura);
  ASSERT_EQ(r.layers.size(), 2u);
  EXPECT_NEAR(r.layers[0].z_mm, 0.3, 1e-12);
  EXPECT_NEAR(r.layers[1].z_mm, 0.5, 1e-12);
  EXPECT_EQ(r.layers[0].strands, 2);          // the wall loop, then the fill line after a travel
  EXPECT_EQ(r.layers[0].touches.size(), 1u);  // the loop closes on its start
  EXPECT_EQ(r.layers[1].strands, 1);
  EXPECT_TRUE(r.ok()) << to_text(r);
  EXPECT_EQ(parse_gcode(cura).program.moves[1].feature, slicer::Feature::Wall);
}

TEST(Check, ThesisScaffoldPassesWithOneStrandPerLayer) {
  const auto values =
      slicer::resolve_params(patterns::scaffold_table(),
                             {{"nozzle", 0.84}, {"gap", 1.6}, {"size", "36x36"}, {"height", 13}});
  const auto t = patterns::find_generator("scaffold")->generate(values);
  const auto out = produce(t, delta(), plan_options_from(t, 0.01), "s.gcode");
  const auto r = check(out.gcode, &delta());
  EXPECT_TRUE(r.ok()) << to_text(r);
  ASSERT_EQ(r.layers.size(), t.layers.size());
  for (const auto& l : r.layers) EXPECT_EQ(l.strands, 1) << "layer " << l.layer;
}

TEST(Check, ContactsBeforeTheFirstLayerGetTheirOwnRow) {
  const auto r = check(
      "G0 X0 Y0 Z0.3\nG1 X10 Y10\nG1 X10 Y0\nG1 X0 Y10\n;LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10\nG0 X5 "
      "Y5\nG1 X5 Y0\n");
  ASSERT_EQ(r.layers.size(), 2u);
  EXPECT_EQ(r.layers[0].layer, -1);
  EXPECT_EQ(r.layers[0].crossings.size(), 1u);
  EXPECT_EQ(r.layers[1].layer, 0);
  EXPECT_EQ(r.layers[1].touches.size(), 1u);
  EXPECT_TRUE(r.layers[1].crossings.empty());
}

TEST(Check, JsonCarriesTheVerdictAndTheContacts) {
  const auto j = to_json(check(";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 Y10\nG1 X10 Y0\nG1 X0 Y10\n"));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["layers"][0]["crossings"][0]["line_b"].get<int>(), 5);
  EXPECT_EQ(j["crossings"].get<int>(), 1);
}


using slicer::Vec2;

// Pen drawings: a plotter profile makes check read the machine's axes back to paper.
std::string polargraph_gcode(const machines::MachineProfile& m, const std::vector<Vec2>& paper) {
  std::string g = "G21\nG90\n";
  bool first = true;
  for (const Vec2& p : paper) {
    const Vec2 a = machines::to_axes(m.plotter.setup, p);
    g += std::string(first ? "G0" : "G1") + " X" + std::to_string(a.x()) + " Y" + std::to_string(a.y()) + "\n";
    first = false;
  }
  return g;
}

TEST(CheckPen, CrossingStrokesAreListedButDoNotFailADrawing) {
  const auto m = machines::load_profile("polargraph");
  const auto [lo, hi] = machines::drawable_area(m.plotter);
  const Vec2 c = (lo + hi) / 2;
  const auto r = check_gcode(polargraph_gcode(m, {c + Vec2(-20, -20), c + Vec2(20, 20), c + Vec2(20, -20), c + Vec2(-20, 20)}),
                             {0.01, 1e-3, &m});
  EXPECT_TRUE(r.pen_drawing);
  EXPECT_EQ(r.crossing_count(), 1u) << "the X is found on the paper, not in cable-length space";
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r.outside_volume.empty());
}

TEST(CheckPen, PointOutsideThePolargraphTensionAreaIsAProblem) {
  const auto m = machines::load_profile("polargraph");
  const double mid = m.plotter.setup.motor_distance_mm / 2;
  // Just below the line between the motors the cables pull almost horizontally: the
  // tension far exceeds the allowed maximum.
  const auto r = check_gcode(polargraph_gcode(m, {Vec2(mid, 600), Vec2(mid, 8)}), {0.01, 1e-3, &m});
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(r.outside_volume.size(), 1u);
  EXPECT_NE(r.outside_volume[0].what.find("tension"), std::string::npos) << r.outside_volume[0].what;
  EXPECT_NEAR(r.outside_volume[0].at_mm.y(), 8.0, 0.01) << "reported in paper mm";
}

}  // namespace
}  // namespace strand::post
