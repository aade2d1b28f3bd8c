// Draping on a 3-axis machine: deposits follow the substrate raised by the layer height,
// travels clear it, steep substrates and patterns bigger than the patch are refused.
#include "postprocess/plan/drape.h"

#include <gtest/gtest.h>

#include "patterns/registry.h"
#include "slicer/input_error.h"
#include "slicer/mesh_surface.h"
#include "tests/support/mesh_shapes.h"

namespace strand::post {
namespace {

slicer::Toolpath scaffold(const std::string& size) {
  const auto* g = patterns::find_generator("scaffold");
  return g->generate(slicer::resolve_params(
      g->table(), {{"nozzle", 0.6}, {"gap", 1.0}, {"size", size}, {"layers", 2}}));
}

std::string error_of(const slicer::Toolpath& t, const slicer::Surface& s,
                     const machines::MachineProfile& m) {
  try {
    plan_draped(t, s, m, plan_options_from(t, 0.01));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Drape, DepositsFollowTheSubstrateAndTravelsClearIt) {
  const slicer::Mesh plate = testing::plate_mesh(60, 40, 3, 60, 40);
  const slicer::MeshSurface s(plate, "plate");
  const auto m = machines::load_profile("marlin-xyz-200");
  const slicer::Toolpath t = scaffold("30x20");
  const slicer::MotionProgram p = plan_draped(t, s, m, plan_options_from(t, 0.01));
  const slicer::Vec2 c = m.volume.part_center_mm;
  int deposits = 0;
  slicer::Vec3 at = p.start_mm;
  for (const auto& mv : p.moves) {
    const bool sideways = (mv.end_mm - at).head<2>().norm() > 1e-9;
    if (mv.kind == slicer::MoveKind::Travel && sideways) {
      EXPECT_GE(at.z(), 3.0 + 1.0) << "travels cross above the substrate's top plus the lift";
      EXPECT_GE(mv.end_mm.z(), 3.0 + 1.0);
    }
    at = mv.end_mm;
    if (mv.kind == slicer::MoveKind::Deposit) {
      ++deposits;
      const double x = mv.end_mm.x() - c.x(), y = mv.end_mm.y() - c.y();
      const double surface = 3.0 * (1.0 - 2.0 * (x * x + y * y) / (3600.0 + 1600.0));
      EXPECT_NEAR(mv.end_mm.z() - surface, p.layers[mv.layer].z_mm, 0.01);
    }
  }
  EXPECT_GT(deposits, 100);
}

TEST(Drape, SteepSubstrateIsRefusedNamingTheSlope) {
  const slicer::MeshSurface s(testing::plate_mesh(60, 40, 25, 60, 40), "dome");
  const auto m = machines::load_profile("marlin-xyz-200");
  const std::string e = error_of(scaffold("50x30"), s, m);
  EXPECT_NE(e.find("onto: the substrate slopes "), std::string::npos) << e;
  EXPECT_NE(e.find("max_surface_slope_deg = 30 deg"), std::string::npos) << e;
}

TEST(Drape, PatternBiggerThanThePatchIsRefused) {
  const slicer::MeshSurface s(testing::plate_mesh(20, 20, 1, 20, 20), "small");
  const std::string e = error_of(scaffold("30x30"), s, machines::load_profile("marlin-xyz-200"));
  EXPECT_NE(e.find("leaves the substrate"), std::string::npos) << e;
}

// The shipped two-head machine (head 2 35 mm right of head 1) with each idle head held `lift`
// mm up.
machines::MachineProfile two_heads(double lift) {
  auto m = machines::load_profile("two-head-pneumatic");
  for (auto& t : m.tools) t.idle_lift_mm = lift;
  return m;
}

TEST(Drape, EachHeadsTipFollowsTheSubstrate) {
  // Layer 0 by head 1, layer 1 by head 2: the carriage moves by head 2's offset, and it is
  // head 2's tip that lies on the substrate raised by the layer's z (before, the carriage's
  // point was draped, 35 mm off).
  const slicer::MeshSurface s(testing::plate_mesh(60, 40, 3, 60, 40), "plate");
  const auto m = two_heads(5);
  const slicer::Toolpath t = scaffold("20x20");
  PlanOptions o = plan_options_from(t, 0.01);
  o.tools.by_layer = {0, 1};
  const slicer::MotionProgram p = plan_draped(t, s, m, o);
  const slicer::Vec2 c = m.volume.part_center_mm;
  int by_head[2] = {0, 0};
  for (const auto& mv : p.moves) {
    if (mv.kind != slicer::MoveKind::Deposit) continue;
    ASSERT_TRUE(mv.tool == 0 || mv.tool == 1);
    ++by_head[mv.tool];
    const slicer::Vec3 tip = mv.end_mm + machines::tool_offset(m, mv.tool);
    const double x = tip.x() - c.x(), y = tip.y() - c.y();
    EXPECT_LE(std::abs(x), 15.0) << "the tip stays over the pattern (and its lead-in), not 35 mm off";
    const double surface = 3.0 * (1.0 - 2.0 * (x * x + y * y) / (3600.0 + 1600.0));
    EXPECT_NEAR(tip.z() - surface, p.layers[mv.layer].z_mm, 0.01);
  }
  EXPECT_GT(by_head[0], 50);
  EXPECT_GT(by_head[1], 50);
}

TEST(Drape, AnIdleHeadTheSubstrateRisesUnderIsRefusedUnlessLifted) {
  // A bowl 100 x 40, 6 mm deep: 35 mm right of the print, under head 2, its side is about
  // 1.3 mm higher than under head 1, more than the first layer is thick.
  slicer::Mesh bowl_mesh = testing::plate_mesh(100, 40, -6, 100, 40);
  for (auto& v : bowl_mesh.vertices_mm) v.z() += 7;  // on the bed
  const slicer::MeshSurface bowl(bowl_mesh, "bowl");
  const slicer::Toolpath t = scaffold("10x10");
  const std::string e = error_of(t, bowl, two_heads(0));
  EXPECT_NE(e.find("tools: head 2 (T1) would drag through the print: idle while head 1 (T0) deposits layer 0"),
            std::string::npos) << e;
  EXPECT_NE(e.find("mm into the substrate at ("), std::string::npos) << e;
  EXPECT_EQ(error_of(t, bowl, two_heads(3)), "");
  // A dome falls away under head 2: nothing to meet, even level.
  EXPECT_EQ(error_of(t, slicer::MeshSurface(testing::plate_mesh(100, 40, 6, 100, 40), "dome"), two_heads(0)), "");
}

}  // namespace
}  // namespace strand::post
