// `strand scaffold` from the outside: exit codes, messages, files, determinism.
#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kThesis = "scaffold --nozzle 0.84 --gap 1.6 --size 36x36 --height 13";

TEST(ScaffoldCli, ThesisSpecimenWritesGcodeReportAndSummary) {
  const auto dir = fresh_dir("ok");
  const auto r = run_strand(kThesis + " --machine deltawasp-2040-clay -o s.gcode --report s.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("35.000 x 35.000 mm"), std::string::npos) << r.out;
  EXPECT_NE(slurp(dir + "/s.gcode").find(";LAYER:17"), std::string::npos);
  EXPECT_NE(slurp(dir + "/s.json").find("\"ink_volume_ml\""), std::string::npos);
}

TEST(ScaffoldCli, SameInputGivesIdenticalBytes) {
  const auto dir = fresh_dir("det");
  ASSERT_EQ(run_strand(kThesis + " -o a.gcode --report a.json", dir).exit_code, 0);
  ASSERT_EQ(run_strand(kThesis + " -o b.gcode --report b.json", dir).exit_code, 0);
  EXPECT_EQ(slurp(dir + "/a.gcode"), slurp(dir + "/b.gcode"));
}

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

// Names the case in test listings instead of dumping its bytes.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class ScaffoldBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(ScaffoldBadInput, ExitTwoOneLineNoFile) {
  const auto dir = fresh_dir("bad");
  std::string args = GetParam().args;
  const auto r = run_strand(args + " -o out.gcode --report out.json", dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out.gcode"));
  EXPECT_FALSE(exists(dir + "/out.gcode.strand-tmp"));
  EXPECT_FALSE(exists(dir + "/out.json"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, ScaffoldBadInput,
    ::testing::Values(
        BadCase{"zero_nozzle", "scaffold --nozzle 0 --gap 1.6 --size 36x36 --height 13", "scaffold.nozzle = 0: must be in (0, 10] (mm)"},
        BadCase{"negative_size", "scaffold --nozzle 0.84 --gap 1.6 --size -36x36 --height 13", "scaffold.size"},
        BadCase{"missing_size", "scaffold --nozzle 0.84 --gap 1.6 --height 13", "scaffold.size: missing"},
        BadCase{"layer_height_low", "scaffold --nozzle 0.84 --gap 1.6 --size 36x36 --height 13 --layer-height 0.3", "[0.42, 0.84]"},
        BadCase{"layer_height_high", "scaffold --nozzle 0.84 --gap 1.6 --size 36x36 --height 13 --layer-height 0.9", "layer-height"},
        BadCase{"gap_and_pitch", "scaffold --nozzle 0.84 --gap 1.6 --pitch 2.44 --size 36x36 --height 13", "not both"},
        BadCase{"unknown_machine", "scaffold --nozzle 0.84 --gap 1.6 --size 36x36 --height 13 --machine nope", "machine = nope: unknown machine"},
        BadCase{"malformed_profile", "scaffold --nozzle 0.84 --gap 1.6 --size 36x36 --height 13 --machine " STRAND_SOURCE_DIR "/tests/machines/malformed.json", "malformed JSON"},
        BadCase{"does_not_fit", "scaffold --nozzle 0.84 --gap 1.6 --size 180x180 --height 13", "radius"},
        BadCase{"not_a_number", "scaffold --nozzle abc --gap 1.6 --size 36x36 --height 13", "scaffold.nozzle = abc"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(MachinesCli, ListsShippedProfilesOneLineEach) {
  const auto r = run_strand("machines");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("deltawasp-2040-clay  "), std::string::npos);
  EXPECT_NE(r.out.find("marlin-xyz-200  "), std::string::npos);
}

}  // namespace
}  // namespace strand::testing
