// Deposition options from the outside: the preview copy and user profiles checked by schema.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kSmall = "scaffold --nozzle 0.84 --gap 1.6 --size 10x10 --layers 2";

TEST(DepositionCli, ViewerEWritesAPreviewCopyBesideThePrintableFile) {
  const auto dir = fresh_dir("viewer");
  const auto r = run_strand(kSmall + " --machine deltawasp-2040-clay-valve -o s.gcode --viewer-e", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/s.gcode").find(" E"), std::string::npos);
  const std::string preview = slurp(dir + "/s.viewer-e.gcode");
  EXPECT_EQ(preview.find("; PREVIEW ONLY - NOT FOR PRINTING"), 0u);
  EXPECT_NE(preview.find(" E"), std::string::npos);
}

TEST(DepositionCli, UserProfileWithABadKeyExitsTwoNamingThePath) {
  const auto dir = fresh_dir("profile");
  std::ofstream(dir + "/mine.json") << R"({"name": "mine", "description": "d",
    "kinematics": {"type": "cartesian", "min_mm": [0,0,0], "max_mm": [100,100,100]},
    "firmware": {"flavour": "klipper", "arcs": true},
    "deposition": {"model": "valve", "on_gcode": ["SET_PIN PIN=valve VALUE=1"], "off_gcode": ["SET_PIN PIN=valve VALUE=0"], "lag_s": 90}})";
  const auto r = run_strand(kSmall + " --machine mine.json -o s.gcode", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("deposition.lag_s = 90: must be in [0, 60]"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(dir + "/s.gcode"));
}

TEST(DepositionCli, KlipperUserProfileRuns) {
  const auto dir = fresh_dir("klipper");
  std::ofstream(dir + "/k.json") << R"({"name": "k", "description": "d",
    "kinematics": {"type": "cartesian", "min_mm": [0,0,0], "max_mm": [100,100,100]},
    "firmware": {"flavour": "klipper", "arcs": true},
    "deposition": {"model": "valve", "on_gcode": ["SET_PIN PIN=valve VALUE=1"], "off_gcode": ["SET_PIN PIN=valve VALUE=0"]}})";
  const auto r = run_strand(kSmall + " --machine k.json -o s.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(dir + "/s.gcode").find("M400\nSET_PIN PIN=valve VALUE=1\n"), std::string::npos);
}

}  // namespace
}  // namespace strand::testing
