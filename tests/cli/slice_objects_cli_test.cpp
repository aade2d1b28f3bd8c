// `strand slice` by objects through the binary (issue 33): a 3MF's objects and --part files,
// each in its printhead, read back by `strand check`; bad --part values exit 2 naming --part.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(SliceObjectsCli, ThreeMfObjectsInTwoHeadsAndTheRefusals) {
  const auto dir = fresh_dir("slice-objects-cli");
  const std::string boxes = std::string(STRAND_SOURCE_DIR) + "/samples/meshes/two-boxes.3mf";
  auto r = run_strand("slice " + boxes + " --tools objects=1,0 --machine two-head-pneumatic --nozzle 0.6 --gap 1"
                      " -o boxes.gcode --report boxes.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("two-boxes.3mf object 0 in T1, "), std::string::npos) << r.out;
  const auto check = nlohmann::json::parse(run_strand("check boxes.gcode --json", dir).out);
  EXPECT_TRUE(check["ok"].get<bool>());
  EXPECT_EQ(check["crossings_between_tools"], 0);
  for (const auto& layer : check["layers"]) EXPECT_EQ(layer["strands_by_tool"], nlohmann::json({1, 1}));

  for (const char* bad : {"--part a.stl", "--part a.stl:one", "--part a.stl:1 --part b.stl:99"}) {
    const auto b = run_strand(std::string("slice ") + bad + " -o x.gcode", dir);
    expect_input_error(b, "--part = ");
    EXPECT_NE(b.err.find("must be FILE:TOOL, TOOL a printhead 0 to 15 (e.g. --part a.stl:1)"), std::string::npos) << b.err;
  }
  expect_input_error(run_strand("slice " + boxes + " --part " + boxes + ":0 -o x.gcode", dir),
                     "--part: give every part as --part FILE:TOOL, without PART or --onto");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
}

}  // namespace
}  // namespace strand::testing
