// Pinned output: a small valve-machine scaffold must come out byte for byte as reviewed in
// tests/golden/. A deliberate format change regenerates the file (command below) and the
// diff is reviewed in the commit.
#include <gtest/gtest.h>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(Golden, SmallScaffoldOnTheValveDeltaIsByteIdentical) {
  const std::string args =
      "scaffold --nozzle 0.84 --gap 1.6 --size 5x5 --layers 2 --machine deltawasp-2040-clay-valve";
  const auto dir = fresh_dir("golden");
  const auto r = run_strand(args + " -o out.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string golden = slurp(std::string(STRAND_SOURCE_DIR) + "/tests/golden/scaffold_5x5_valve.gcode");
  ASSERT_FALSE(golden.empty());
  EXPECT_EQ(slurp(dir + "/out.gcode"), golden)
      << "output changed; if intended: strand " << args << " -o tests/golden/scaffold_5x5_valve.gcode";
}

}  // namespace
}  // namespace strand::testing
