// `strand flow` from the outside: both directions, and bad input.
#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(FlowCli, PressureToSpeedAndSpeedToPressure) {
  // mu = 1 Pa.s, d 0.5 mm, L 10 mm, 1 bar -> 15.3398 mm3/s (see flow_model_test).
  const auto r = run_strand("flow --viscosity-pa-s 1 --nozzle-mm 0.5 --nozzle-length-mm 10 "
                            "--pressure-bar 1 --speed 250 --bead-width 0.5 --bead-height 0.4",
                            fresh_dir("flow"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("flow 15.3398 mm3/s"), std::string::npos) << r.out;
  // Bead 0.5 x 0.4: 0.1*0.4 + pi*0.16/4 = 0.165664 mm2; 15.3398/0.165664*60 = 5555.76 mm/min.
  EXPECT_NE(r.out.find("speed 5555.8 mm/min"), std::string::npos) << r.out;
  // 250 mm/min -> 0.690265 mm3/s -> 0.690265/15.3398 bar = 0.0450 bar.
  EXPECT_NE(r.out.find("pressure 0.0450 bar"), std::string::npos) << r.out;
}

TEST(FlowCli, NeedsExactlyOneRheology) {
  const auto r = run_strand("flow --viscosity-pa-s 1 --k-pa-sn 10 --n 0.5 --nozzle-mm 0.5 "
                            "--nozzle-length-mm 10 --pressure-bar 1", fresh_dir("flow"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("flow.viscosity-pa-s"), std::string::npos) << r.err;
}

TEST(FlowCli, NegativePressureIsNamed) {
  const auto r = run_strand("flow --viscosity-pa-s 1 --nozzle-mm 0.5 --nozzle-length-mm 10 --pressure-bar -1", fresh_dir("flow"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("flow.pressure-bar = -1: must be a finite number > 0 (bar)"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace strand::testing
