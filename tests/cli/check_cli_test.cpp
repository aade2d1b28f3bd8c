// `strand check` from the outside: exit codes 0/1/2, text and JSON reports, the SVG view.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

const char* kCrossing = ";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 Y10\nG1 X10 Y0\nG1 X0 Y10\n";
const char* kClean =
    ";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10\nG1 Y1\nG1 X0\n;LAYER:1\nG0 X0 Y0 Z1\nG1 Y10\n";

TEST(CheckCli, ThesisScaffoldPassesWithOneStrandPerLayer) {
  const auto dir = fresh_dir("check-scaffold");
  ASSERT_EQ(run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 36x36 --height 13 -o s.gcode", dir)
                .exit_code,
            0);
  const auto r = run_strand("check s.gcode --machine deltawasp-2040-clay --json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["ok"].get<bool>());
  ASSERT_GT(j["layers"].size(), 10u);
  for (const auto& l : j["layers"]) EXPECT_EQ(l["strands"].get<int>(), 1) << l.dump();
}

TEST(CheckCli, CrossingExitsOneAndNamesThePointAndLines) {
  const auto dir = fresh_dir("check-cross");
  write(dir + "/x.gcode", kCrossing);
  const auto r = run_strand("check x.gcode", dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.out.find("crossing in layer 0 at (5.000, 5.000) mm: lines 3 and 5"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("check: FAILED"), std::string::npos);
}

TEST(CheckCli, ArcAndOutsideMoveFailOnTheDelta) {
  const auto dir = fresh_dir("check-machine");
  write(dir + "/a.gcode", "G0 X1 Y0 Z0.5\nG3 X0 Y1 I-1 J0\nG0 X150 Y0\n");
  const auto r = run_strand("check a.gcode --machine deltawasp-2040-clay --json", dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["arcs_forbidden"][0]["line"].get<int>(), 2);
  EXPECT_EQ(j["outside_volume"][0]["line"].get<int>(), 3);
  EXPECT_EQ(run_strand("check a.gcode", dir).exit_code, 0)
      << "without a machine neither is checked";
}

TEST(CheckCli, CleanFileExitsZeroAndWritesTheLayerSvg) {
  const auto dir = fresh_dir("check-svg");
  write(dir + "/c.gcode", kClean);
  const auto r = run_strand("check c.gcode --svg-layer 1 top.svg", dir);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(slurp(dir + "/top.svg").find("<svg"), std::string::npos);
  EXPECT_NE(r.out.find("check: OK"), std::string::npos);
}

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

class CheckBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(CheckBadInput, ExitTwoOneLineNoSvg) {
  const auto dir = fresh_dir("check-bad");
  write(dir + "/c.gcode", kClean);
  const auto r = run_strand(GetParam().args, dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out.svg"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CheckBadInput,
    ::testing::Values(BadCase{"missing_file", "check nope.gcode", "nope.gcode"},
                      BadCase{"unknown_machine", "check c.gcode --machine nope", "machine = nope"},
                      BadCase{"layer_out_of_range", "check c.gcode --svg-layer 2 out.svg",
                              "svg-layer = 2: must be in [0, 1]"},
                      BadCase{"layer_not_a_number", "check c.gcode --svg-layer x out.svg",
                              "svg-layer = x"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace strand::testing
