// Flow model against values worked out by hand from the textbook formulas.
#include "postprocess/plan/flow_model.h"

#include <gtest/gtest.h>

namespace strand::post {
namespace {

// Glycerol-like Newtonian ink mu = 1 Pa.s, 0.5 mm nozzle (r = 2.5e-4 m), L = 10 mm, 1 bar:
// Q = pi r^4 dP / (8 mu L) = pi * 3.90625e-15 * 1e5 / 0.08 = 1.53398e-8 m^3/s = 15.3398 mm3/s.
TEST(FlowModel, HagenPoiseuilleTextbookValue) {
  const Rheology ink{false, 1.0};
  const Nozzle nz{0.25, 10.0};
  EXPECT_NEAR(flow_mm3_per_s(ink, nz, 1e5), 15.3398, 1e-3);
  EXPECT_NEAR(pressure_pa_for(ink, nz, 15.3398), 1e5, 1.0);
}

// Shear-thinning paste K = 100 Pa.s^n, n = 0.5, same nozzle, 1 bar:
// r dP / (2 K L) = 2.5e-4 * 1e5 / (2 * 100 * 0.01) = 12.5 s^-0.5 -> ^(1/n) = 156.25;
// pi n r^3 / (3n+1) = pi * 0.5 * 1.5625e-11 / 2.5 = 9.8175e-12; Q = 1.53398e-9 m^3/s = 1.53398 mm3/s.
TEST(FlowModel, PowerLawTextbookValueAndInverse) {
  Rheology ink;
  ink.power_law = true;
  ink.k_pa_sn = 100.0;
  ink.n = 0.5;
  const Nozzle nz{0.25, 10.0};
  EXPECT_NEAR(flow_mm3_per_s(ink, nz, 1e5), 1.53398, 1e-4);
  EXPECT_NEAR(pressure_pa_for(ink, nz, 1.53398), 1e5, 5.0);
  // Shear thinning: doubling the pressure gives 2^(1/n) = 4 times the flow.
  EXPECT_NEAR(flow_mm3_per_s(ink, nz, 2e5) / flow_mm3_per_s(ink, nz, 1e5), 4.0, 1e-9);
}

TEST(FlowModel, PowerLawWithNOneIsNewtonian) {
  Rheology pl;
  pl.power_law = true;
  pl.k_pa_sn = 3.0;
  pl.n = 1.0;
  const Rheology nw{false, 3.0};
  const Nozzle nz{0.42, 12.7};
  EXPECT_NEAR(flow_mm3_per_s(pl, nz, 8e4), flow_mm3_per_s(nw, nz, 8e4), 1e-9);
}

// Bead 0.84 x 0.74 mm (stadium 0.5261 mm2) at 250 mm/min needs 250/60 * 0.5261 = 2.192 mm3/s.
TEST(FlowModel, SpeedAndFlowAreInverse) {
  EXPECT_NEAR(flow_for_speed_mm3_per_s(250.0, 0.5261), 2.19208, 1e-4);
  EXPECT_NEAR(speed_mm_per_min(2.19208, 0.5261), 250.0, 1e-3);
}

}  // namespace
}  // namespace strand::post
