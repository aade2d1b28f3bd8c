// Planner speed rules (feature factors from job or profile, volumetric cap) and valve lag.
#include "postprocess/plan/planner.h"

#include <gtest/gtest.h>

namespace strand::post {
namespace {

using slicer::Feature;

slicer::Toolpath one_node_stroke() {
  slicer::Toolpath t;
  t.generator = "test";
  t.parameters = {{"speed", 600.0}};
  slicer::Stroke s;
  s.start_mm = {0, 0};
  s.segments = {slicer::line_to({20, 0}, Feature::Node)};
  s.width_mm = 0.8;
  s.height_mm = 0.6;
  t.layers = {{0.6, 0.6, {s}}};
  return t;
}

machines::MachineProfile machine(const char* model) {
  nlohmann::json j = {
      {"name", "t"}, {"description", "d"},
      {"kinematics", {{"type", "cartesian"}, {"min_mm", {-50, -50, 0}}, {"max_mm", {50, 50, 50}}, {"part_center_mm", {0, 0}}}},
      {"firmware", {{"flavour", "marlin"}, {"arcs", false}}},
      {"deposition", {{"model", model}}},
      {"speed_factors", {{"node", 1.1}}}};
  if (std::string(model) == "e-volumetric") j["deposition"]["mm3_per_e"] = 1.0;
  if (std::string(model) == "valve") {
    j["deposition"]["on_gcode"] = {"M42 P6 S255"};
    j["deposition"]["off_gcode"] = {"M42 P6 S0"};
    j["deposition"]["lag_s"] = 0.5;
  }
  return machines::profile_from_json(j, "test");
}

std::vector<slicer::Move> deposits(const slicer::MotionProgram& p) {
  std::vector<slicer::Move> out;
  for (const auto& m : p.moves) {
    if (m.kind == slicer::MoveKind::Deposit) out.push_back(m);
  }
  return out;
}

TEST(Planner, ProfileSpeedFactorAppliesWhenTheJobGivesNone) {
  const auto t = one_node_stroke();
  const auto d = deposits(plan(t, machine("none"), plan_options_from(t, 0.01)));
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR(d[0].feed_mm_per_min, 660.0, 1e-9);
}

TEST(Planner, JobSpeedFactorWinsOverProfile) {
  auto t = one_node_stroke();
  t.parameters["node-speed-factor"] = 0.5;
  const auto d = deposits(plan(t, machine("none"), plan_options_from(t, 0.01)));
  EXPECT_NEAR(d.at(0).feed_mm_per_min, 300.0, 1e-9);
}

TEST(Planner, EDrivenFeedIsCappedByVolumetricFlow) {
  const auto t = one_node_stroke();
  auto m = machine("e-volumetric");
  m.limits.max_volumetric_flow_mm3_per_s = 1.0;
  // Bead 0.8 x 0.6: (0.8 - 0.6) * 0.6 + pi * 0.36 / 4 = 0.402743 mm2; 1 mm3/s -> 148.98 mm/min.
  const auto d = deposits(plan(t, m, plan_options_from(t, 0.01)));
  EXPECT_NEAR(d.at(0).feed_mm_per_min, 60.0 / 0.402743, 1e-2);
  EXPECT_NEAR(d.at(0).volume_mm3, 20 * 0.402743, 1e-5);
}

TEST(Planner, ValveLagClosesBeforeTheStrandEnds) {
  // 20 mm at 660 mm/min (11 mm/s); lag 0.5 s -> the valve closes 5.5 mm before the end.
  const auto t = one_node_stroke();
  const auto d = deposits(plan(t, machine("valve"), plan_options_from(t, 0.01)));
  ASSERT_EQ(d.size(), 2u);
  EXPECT_FALSE(d[0].coast);
  EXPECT_TRUE(d[1].coast);
  EXPECT_NEAR(d[0].end_mm.x(), 14.5, 1e-9);
  EXPECT_NEAR(d[0].volume_mm3 + d[1].volume_mm3, 20 * 0.402743, 1e-5);
}

}  // namespace
}  // namespace strand::post
