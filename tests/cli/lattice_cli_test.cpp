// `strand missing-rib` and `strand reentrant` from the outside: exit codes, one-line
// messages, no partial files, identical bytes for identical input.
#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kMissingRib = "missing-rib --nozzle 0.6 --rib 5 --angle 20 --rows 6 --cols 6 --layers 3";
const std::string kReentrant = "reentrant --nozzle 0.84 --cell-width 8 --cell-height 8 --angle 20 --rows 6 --cols 5 --height 5";

TEST(LatticeCli, BothWriteGcodeReportAndSummaryWithOneStrandPerLayer) {
  for (const std::string& cmd : {kMissingRib, kReentrant}) {
    const auto dir = fresh_dir("ok");
    const auto r = run_strand(cmd + " -o l.gcode --report l.json", dir);
    ASSERT_EQ(r.exit_code, 0) << cmd << "\n" << r.err;
    EXPECT_NE(r.out.find("at most 1 strand(s) per layer"), std::string::npos) << r.out;
    EXPECT_NE(slurp(dir + "/l.gcode").find(";FEATURE:ligament"), std::string::npos);
    EXPECT_NE(slurp(dir + "/l.json").find("\"relative_density\""), std::string::npos);
  }
}

TEST(LatticeCli, SameInputGivesIdenticalBytes) {
  for (const std::string& cmd : {kMissingRib, kReentrant}) {
    const auto dir = fresh_dir("det");
    ASSERT_EQ(run_strand(cmd + " -o a.gcode", dir).exit_code, 0);
    ASSERT_EQ(run_strand(cmd + " -o b.gcode", dir).exit_code, 0);
    EXPECT_EQ(slurp(dir + "/a.gcode"), slurp(dir + "/b.gcode")) << cmd;
  }
}

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

class LatticeBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(LatticeBadInput, ExitTwoOneLineNoFile) {
  const auto dir = fresh_dir("bad");
  const auto r = run_strand(std::string(GetParam().args) + " -o out.gcode --report out.json", dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out.gcode"));
  EXPECT_FALSE(exists(dir + "/out.json"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, LatticeBadInput,
    ::testing::Values(
        BadCase{"rib_too_short", "missing-rib --nozzle 0.6 --rib 1 --layers 3", "missing-rib.rib = 1: must be >= 1.0628"},
        BadCase{"rib_angle_45", "missing-rib --nozzle 0.6 --rib 5 --angle 45 --layers 3", "missing-rib.angle = 45: must be in (0, 45)"},
        BadCase{"rib_rows_zero", "missing-rib --nozzle 0.6 --rib 5 --rows 0 --layers 3", "missing-rib.rows = 0"},
        BadCase{"rib_too_big", "missing-rib --nozzle 0.6 --rib 5 --rows 20 --cols 20 --layers 3", "radius"},
        BadCase{"reentrant_odd_rows", "reentrant --nozzle 0.84 --cell-width 8 --cell-height 8 --rows 5 --layers 3", "reentrant.rows = 5: must be even"},
        BadCase{"reentrant_narrow", "reentrant --nozzle 0.84 --cell-width 3 --cell-height 8 --layers 3", "reentrant.cell-width = 3: must be >= 4 * nozzle = 3.36"},
        BadCase{"reentrant_angle", "reentrant --nozzle 0.84 --cell-width 8 --cell-height 8 --angle 42 --layers 3", "reentrant.angle = 42: must be in (0, 41.8"},
        BadCase{"reentrant_missing_height", "reentrant --nozzle 0.84 --cell-width 8 --layers 3", "reentrant.cell-height: missing"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace strand::testing
