// Idle printheads against the beads under them: a head riding 35 mm right of the depositing
// one at the same height meets this layer's beads where the part is wider than that; a lift,
// a narrow part or the layer below (where the depositing nozzle itself runs) are clear.
#include "postprocess/plan/idle_heads.h"

#include <gtest/gtest.h>

#include "machines/profile.h"

namespace strand::post {
namespace {

using slicer::Move;
using slicer::MoveKind;
using slicer::Vec3;

// Two heads, the second at (35, 0, dz) and held `lift` up while idle; 0.5 mm needles.
machines::MachineProfile two_heads(double lift, double dz = 0.0) {
  machines::MachineProfile m;
  m.name = "two";
  m.tools.resize(2);
  m.tools[1].offset_mm = Vec3(35, 0, dz);
  m.tools[0].nozzle_mm = m.tools[1].nozzle_mm = 0.5;
  m.tools[0].idle_lift_mm = m.tools[1].idle_lift_mm = lift;
  return m;
}

// One deposit of `tool` from a to b at height z in `layer` (0.4 mm layers, 0.5 mm beads).
void bead(IdleHeadCheck& c, int tool, const Vec3& a, const Vec3& b, int layer = 0) {
  Move mv;
  mv.kind = MoveKind::Deposit;
  mv.tool = static_cast<std::int16_t>(tool);
  mv.layer = layer;
  mv.width_mm = 0.5;
  mv.end_mm = b;
  c.add(a, b, mv, 0.4, 0, 7);
}

TEST(IdleHeads, AHeadAtTheSameHeightMeetsThisLayerWhereThePartIsWiderThanTheOffset) {
  IdleHeadCheck c(two_heads(0.0));
  ASSERT_TRUE(c.active());
  bead(c, 0, {0, 0, 0.4}, {50, 0, 0.4});      // a 50 mm row
  EXPECT_EQ(c.hit_count(), 0u) << "nothing was under the idle head yet";
  bead(c, 0, {0, 0.3, 0.4}, {10, 0.3, 0.4});  // the next row: head 2 rides over the first, 35 mm on
  ASSERT_EQ(c.hit_count(), 1u);
  const IdleHeadHit& h = c.hits().front();
  EXPECT_EQ(h.tool, 1);
  EXPECT_EQ(h.active_tool, 0);
  EXPECT_EQ(h.line, 7);
  EXPECT_NEAR(h.tip_mm.z(), 0.4, 1e-9);
  EXPECT_NEAR(h.bead_top_mm, 0.4, 1e-9);
  EXPECT_GE(h.tip_mm.x(), 35.0 - 1e-9);
  EXPECT_LE(h.tip_mm.x(), 45.0 + 1e-9);
  // Head 2 printing, head 1 idle 35 mm to its left over the same row.
  bead(c, 1, {40, 0.3, 0.4}, {45, 0.3, 0.4});
  EXPECT_EQ(c.hit_count(), 2u);
  EXPECT_EQ(c.hits().back().tool, 0);
}

TEST(IdleHeads, ALiftANarrowPartOrTheLayerBelowAreClear) {
  IdleHeadCheck lifted(two_heads(5.0));
  bead(lifted, 0, {0, 0, 0.4}, {50, 0, 0.4});
  bead(lifted, 0, {0, 0.3, 0.4}, {10, 0.3, 0.4});
  EXPECT_EQ(lifted.hit_count(), 0u);

  IdleHeadCheck narrow(two_heads(0.0));
  bead(narrow, 0, {0, 0, 0.4}, {30, 0, 0.4});  // 30 mm: head 2 starts at 35, beyond its bead
  bead(narrow, 0, {0, 0.3, 0.4}, {30, 0.3, 0.4});
  EXPECT_EQ(narrow.hit_count(), 0u);
  // 0.5 mm apart (the 0.25 mm tip radius and the 0.25 mm half bead): touching.
  bead(narrow, 0, {-4.5, 0.3, 0.4}, {-4.49, 0.3, 0.4});
  EXPECT_EQ(narrow.hit_count(), 0u);
  bead(narrow, 0, {-4.6, 0.3, 0.4}, {-4.59, 0.3, 0.4});
  EXPECT_EQ(narrow.hit_count(), 1u);

  // Over the layer below the idle tip is a layer height up, as the depositing one is.
  IdleHeadCheck below(two_heads(0.0));
  bead(below, 0, {0, 0, 0.4}, {50, 0, 0.4}, 0);
  bead(below, 0, {0, 0.3, 0.8}, {10, 0.3, 0.8}, 1);
  EXPECT_EQ(below.hit_count(), 0u);
}

TEST(IdleHeads, ALowerIdleNozzleMeetsTheLayerBelowAndAnEarlierTallerObject) {
  IdleHeadCheck lower(two_heads(0.0, -0.5));  // head 2's tip 0.5 mm below head 1's
  bead(lower, 0, {0, 0, 0.4}, {50, 0, 0.4}, 0);
  bead(lower, 0, {0, 0.3, 0.8}, {10, 0.3, 0.8}, 1);
  EXPECT_EQ(lower.hit_count(), 1u);
  EXPECT_NEAR(lower.hits().front().tip_mm.z(), 0.3, 1e-9);

  // Objects printed one after the other: the second's first layer under the first's top.
  IdleHeadCheck sequential(two_heads(1.0));
  bead(sequential, 0, {40, 0, 5.0}, {50, 0, 5.0}, 12);
  bead(sequential, 0, {41, 1, 0.4}, {42, 1, 0.4}, 0);  // newer and lower, in the same cell
  EXPECT_EQ(sequential.hit_count(), 0u);
  bead(sequential, 0, {0, 0, 0.4}, {10, 0, 0.4}, 0);
  EXPECT_EQ(sequential.hit_count(), 1u);
  EXPECT_NEAR(sequential.hits().front().bead_top_mm, 5.0, 1e-9);
}

TEST(IdleHeads, ARisingPrintDropsTheBeadsNoIdleTipComesDownToAndStillFindsTheLayerOn) {
  IdleHeadCheck c(two_heads(0.0, -0.5), 8);  // head 2 0.5 mm low: two layers down matter
  for (int k = 0; k < 30; ++k) {
    const double z = 0.4 * (k + 1);
    for (int row = 0; row < 4; ++row) bead(c, 1, {0, 3.0 * row, z}, {20, 3.0 * row, z}, k);
  }
  EXPECT_EQ(c.hit_count(), 0u);
  EXPECT_LE(c.beads_held(), 16u) << "two layers' rows, not thirty";
  bead(c, 0, {0, 0.3, 12.4}, {10, 0.3, 12.4}, 30);  // head 2 idle 35 mm on: nothing there
  EXPECT_EQ(c.hit_count(), 0u);
  bead(c, 0, {-30, 0.3, 12.4}, {-25, 0.3, 12.4}, 30);  // head 2 over layer 29's row, 0.1 mm into it
  EXPECT_EQ(c.hit_count(), 1u);
}

TEST(IdleHeads, OneHeadOrHeadsSharingANozzleAreNotChecked) {
  machines::MachineProfile one;
  EXPECT_FALSE(IdleHeadCheck(one).active());
  machines::MachineProfile shared = two_heads(0.0);
  shared.tools[1].offset_mm = Vec3::Zero();  // a multi-material single nozzle
  EXPECT_FALSE(IdleHeadCheck(shared).active());
}

}  // namespace
}  // namespace strand::post
