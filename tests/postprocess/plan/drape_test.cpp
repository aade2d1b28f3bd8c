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

}  // namespace
}  // namespace strand::post
