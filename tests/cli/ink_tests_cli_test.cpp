// The pore, fusion and collapse tests through the `strand` binary: generated for every flat
// printer, each passes `strand check` without a crossing; their sample photos measured and
// calibrated; and their one-line refusals.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "machines/profile.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(InkTestsCli, PoreFusionAndCollapsePassCheckOnEveryFlatPrinter) {
  int checked = 0;
  for (const auto& [name, description] : machines::list_profiles()) {
    const auto m = machines::load_profile(name);
    if (m.plotter.enabled || m.robot.enabled || m.rotary.enabled) continue;
    for (const std::string test : {"pore-test", "fusion-test", "collapse-test"}) {
      SCOPED_TRACE(test + " on " + name);
      const auto dir = fresh_dir("ink-tests-check");
      const auto r = run_strand(test + " --nozzle 0.6 --machine " + name + " -o t.gcode", dir);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const auto c = run_strand("check t.gcode --machine " + name + " --json", dir);
      const auto j = nlohmann::json::parse(c.out);
      EXPECT_TRUE(j["ok"].get<bool>()) << c.out.substr(0, 2000);
      EXPECT_EQ(j["crossings"], 0);
      ++checked;
    }
  }
  EXPECT_GE(checked, 12);
}

// The sample photos (synthetic: pores drawn with Pr 1, 0.908, 0.842, 0.801 and 0.785; the
// meander's beads 1 mm wide) measured through the binary, and the fusion result in the profile.
TEST(InkTestsCli, SamplePhotosMeasuredAndTheFusionSpacingCalibrated) {
  const auto dir = fresh_dir("ink-tests-measure");
  const std::string ink = std::string(STRAND_SOURCE_DIR) + "/samples/ink/";
  ASSERT_EQ(run_strand("pore-test --nozzle 0.6 --report pt.json -o pt.gcode", dir).exit_code, 0);
  auto r = run_strand("measure " + ink + "pore-test-photo.jpg --test pore --job pt.json -o pm.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("16 pores"), std::string::npos) << r.out;
  EXPECT_TRUE(exists(dir + "/pm.png"));
  const auto pm = nlohmann::json::parse(slurp(dir + "/pm.json"));
  const double truth_mean = (4 * 1.0 + 3 * (0.9078 + 0.8421 + 0.8007 + 0.7854)) / 16;
  EXPECT_NEAR(pm["mean_pr"].get<double>(), truth_mean, 0.03 * truth_mean);

  ASSERT_EQ(run_strand("fusion-test --nozzle 0.6 --report ft.json -o ft.gcode", dir).exit_code, 0);
  r = run_strand("measure " + ink + "fusion-test-photo.jpg --test fusion --job ft.json -o fm.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(run_strand("line-matrix --nozzle 0.6 --report lm.json -o lm.gcode", dir).exit_code, 0);
  ASSERT_EQ(run_strand("measure " + ink + "line-matrix-photo.jpg --test lines --job lm.json -o lm-m.json", dir).exit_code, 0);
  r = run_strand("calibrate lm-m.json fm.json -o ink.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto profile = nlohmann::json::parse(slurp(dir + "/ink.json"));
  EXPECT_DOUBLE_EQ(profile["min_spacing_without_fusion_mm"].get<double>(), 1.2);
  EXPECT_EQ(profile["measurements"], nlohmann::json::array({"lm-m.json", "fm.json"}));
  expect_input_error(run_strand("calibrate fm.json -o ink2.json", dir), "needs at least one `strand measure --test lines` output");
}

// The collapse sample photo (a synthetic side view, sags of 0, 0.05, 0.2, 1.2 and 20 mm drawn:
// Cf 100, 98.6, 94.4, 66.7 and 3.1 %) measured through the binary, and the gap it spans in
// the profile; a photo from above refused.
TEST(InkTestsCli, CollapseSamplePhotoMeasuredAndTheSpannedGapCalibrated) {
  const auto dir = fresh_dir("ink-tests-collapse");
  const std::string ink = std::string(STRAND_SOURCE_DIR) + "/samples/ink/";
  ASSERT_EQ(run_strand("collapse-test --nozzle 0.6 --report ct.json -o ct.gcode", dir).exit_code, 0);
  auto r = run_strand("measure " + ink + "collapse-test-photo.jpg --test collapse --job ct.json -o cm.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("5 gaps"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("widest spanned gap 4.000 mm"), std::string::npos) << r.out;
  EXPECT_TRUE(exists(dir + "/cm.png"));
  const auto cm = nlohmann::json::parse(slurp(dir + "/cm.json"));
  const double truth[] = {100.0, 98.6, 94.4, 66.7, 3.1};
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(cm["gaps"][k]["collapse_area_factor_pct"].get<double>(), truth[k], 2.0) << k;
  }
  EXPECT_EQ(cm["widest_spanned_gap_mm"], 4.0);

  ASSERT_EQ(run_strand("line-matrix --nozzle 0.6 --report lm.json -o lm.gcode", dir).exit_code, 0);
  ASSERT_EQ(run_strand("measure " + ink + "line-matrix-photo.jpg --test lines --job lm.json -o lm-m.json", dir).exit_code, 0);
  r = run_strand("calibrate lm-m.json cm.json -o ink.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("spans gaps up to 4 mm without collapse"), std::string::npos) << r.out;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(slurp(dir + "/ink.json"))["min_gap_without_collapse_mm"].get<double>(), 4.0);
  expect_input_error(run_strand("measure " + ink + "line-matrix-photo.jpg --test collapse --job ct.json -o x.json", dir),
                     "a view from above");
  EXPECT_FALSE(exists(dir + "/x.json"));
}

TEST(InkTestsCli, BadInputIsOneLineAndWritesNothing) {
  const auto dir = fresh_dir("ink-tests-bad");
  expect_input_error(run_strand("pore-test --nozzle 0.6 --layers 1 -o p.gcode", dir), "pore-test.layers = 1");
  expect_input_error(run_strand("fusion-test --nozzle 0.6 --spacing-end 0.2 -o f.gcode", dir),
                     "fusion-test.spacing-end = 0.2: must be >= nozzle = 0.6");
  expect_input_error(run_strand("collapse-test --nozzle 0.6 --gaps 2,-1 -o c.gcode", dir), "collapse-test.gaps");
  for (const char* f : {"p.gcode", "f.gcode", "c.gcode"}) EXPECT_FALSE(exists(dir + "/" + f)) << f;
}

}  // namespace
}  // namespace strand::testing
