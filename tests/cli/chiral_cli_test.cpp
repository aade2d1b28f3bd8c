// `strand tetrachiral` / `strand hexachiral` from the outside: summary, determinism, bad
// input exits 2 with one line and writes no file, sample job files run.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kTetra =
    "tetrachiral --nozzle 0.5 --cell 10 --rows 6 --cols 2 --layers 3 --grip 10";
const std::string kHexa =
    "hexachiral --nozzle 0.4 --cell 5.3 --rows 10 --cols 4 --layers 3 --grip 10";

TEST(ChiralCli, SummaryShowsSizeNodesAndOneStrand) {
  const auto dir = fresh_dir("chiral");
  const auto r = run_strand(kTetra + " -o t.gcode --report t.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("at most 1 strand(s) per layer"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ring 1.300 mm vs ligament 0.500 mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("thesis formula"), std::string::npos) << r.out;
  EXPECT_NE(slurp(dir + "/t.gcode").find(";FEATURE:node"), std::string::npos);
}

TEST(ChiralCli, SameInputGivesIdenticalBytes) {
  const auto dir = fresh_dir("chiral-det");
  ASSERT_EQ(run_strand(kHexa + " -o a.gcode", dir).exit_code, 0);
  ASSERT_EQ(run_strand(kHexa + " -o b.gcode", dir).exit_code, 0);
  EXPECT_EQ(slurp(dir + "/a.gcode"), slurp(dir + "/b.gcode"));
}

TEST(ChiralCli, BadInputExitsTwoWithOneLineAndNoFile) {
  const struct {
    std::string args, mention;
  } cases[] = {
      {"tetrachiral --nozzle 0.5 --cell 3 --layers 2", "tetrachiral.cell = 3: must be >= "},
      {kHexa + " --node-passes 4", "hexachiral.node-passes = 4: must be odd"},
      {kTetra + " --ligament-speed-factor 0", "ligament-speed-factor"},
      {"tetrachiral --nozzle 0.5 --cell 10 --cols 30 --layers 2", "radius"},
  };
  for (const auto& c : cases) {
    const auto dir = fresh_dir("chiral-bad");
    const auto r = run_strand(c.args + " -o out.gcode --report out.json", dir);
    SCOPED_TRACE(c.args);
    expect_input_error(r, c.mention);
    EXPECT_FALSE(exists(dir + "/out.gcode"));
    EXPECT_FALSE(exists(dir + "/out.json"));
  }
}

TEST(ChiralCli, ThesisSampleJobsRun) {
  for (const char* name : {"tetrachiral-thesis", "hexachiral-thesis"}) {
    const auto dir = fresh_dir("chiral-job");
    const auto r =
        run_strand(std::string("job ") + STRAND_SOURCE_DIR + "/samples/" + name + ".json", dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(exists(dir + "/" + name + ".gcode"));
  }
}

}  // namespace
}  // namespace strand::testing
