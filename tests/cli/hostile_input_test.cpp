// Issue 10's reproducers from the outside: hostile or malformed input never crashes, hangs
// or leaves a file behind; it ends in exit code 2 and one line naming what is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Every file in `dir` (names only), hidden runner files excluded.
std::set<std::string> files_in(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != ".stdout" && name != ".stderr") names.insert(name);
  }
  return names;
}

struct JobCase {
  const char* name;
  const char* job;           // content of job.json
  const char* must_mention;  // in the one error line
};

class HostileJob : public ::testing::TestWithParam<JobCase> {};

TEST_P(HostileJob, ExitTwoOneLineAndOnlyTheJobFileRemains) {
  const auto dir = fresh_dir("hostile-job");
  write(dir + "/job.json", GetParam().job);
  const auto r = run_strand("job job.json", dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_EQ(files_in(dir), std::set<std::string>{"job.json"});
}

INSTANTIATE_TEST_SUITE_P(
    Reproducers, HostileJob,
    ::testing::Values(
        JobCase{"generator_not_text", R"({"generator": 5})", "job.generator = 5: must be text"},
        JobCase{"machine_not_text", R"({"generator": "scaffold", "machine": [1]})",
                "job.machine = [1]: must be text"},
        JobCase{"output_not_text", R"({"generator": "scaffold", "output": {}})",
                "job.output = {}: must be text"},
        JobCase{"report_not_text", R"({"generator": "scaffold", "report": 3})",
                "job.report = 3: must be text"},
        JobCase{"description_not_text", R"({"generator": "scaffold", "description": false})",
                "job.description = false: must be text"},
        JobCase{"arc_tolerance_text", R"({"generator": "scaffold", "arc-tolerance": "x"})",
                "job.arc-tolerance = \"x\": must be a finite number"},
        JobCase{"params_not_object", R"({"generator": "scaffold", "params": [1, 2]})",
                "job.params: must be an object"},
        JobCase{"number_overflows", R"({"generator": "scaffold", "params": {"nozzle": 1e999}})",
                "job = job.json: unreadable JSON value"},
        JobCase{"malformed", R"({"generator": "scaffold",)", "job = job.json: malformed JSON at byte"},
        JobCase{"newline_in_a_key", "{\"generator\": \"scaffold\", \"a\\nb\": 1}",
                "job.a\\nb: unknown key"},
        JobCase{"newline_in_machine", R"({"generator": "scaffold", "machine": "x\ny"})",
                "machine = x\\ny: unknown machine"},
        JobCase{"plotter_for_a_generator",
                R"({"generator": "scaffold", "machine": "polargraph", "params": {"nozzle": 0.84,
                    "gap": 1.6, "size": "10x10", "layers": 2}})",
                "machine = polargraph: a pen plotter"},
        JobCase{"too_many_layers",
                R"({"generator": "tetrachiral", "params": {"nozzle": 0.5, "cell": 10, "cols": 2,
                    "rows": 3, "layers": 100000}})",
                "tetrachiral.layers = 100000: the specimen would have about"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Hostile, JsonNestedOneHundredThousandDeepIsRefusedNotOverflowed) {
  const auto dir = fresh_dir("hostile-deep");
  write(dir + "/job.json", std::string(100000, '[') + std::string(100000, ']'));
  expect_input_error(run_strand("job job.json", dir), "nested deeper than 64 levels");
  write(dir + "/sweep.json", std::string(100000, '{'));
  expect_input_error(run_strand("sweep sweep.json -o s", dir), "nested deeper than 64 levels");
  EXPECT_FALSE(exists(dir + "/s"));
}

TEST(Hostile, SweepWhereWithDeepNestingIsRefused) {
  const auto dir = fresh_dir("hostile-where");
  for (const std::string& where : {std::string(100000, '(') + "gap" + std::string(100000, ')') + " > 1",
                                  std::string(100000, '-') + "gap > 1",
                                  std::string(40, '(') + "gap" + std::string(40, ')') + " > 1"}) {
    write(dir + "/s.json", R"({"job": {"generator": "scaffold", "params": {"nozzle": 0.84,
        "size": "10x10", "layers": 2}}, "vary": {"gap": [1, 2]}, "where": [")" + where + "\"]}");
    const auto r = run_strand("sweep s.json -o out --no-previews", dir);
    expect_input_error(r, "sweep.where[0]");
    EXPECT_LT(r.err.size(), 400u) << "the error quotes a short prefix, not the whole input";
  }
}

TEST(Hostile, SweepModeOfTheWrongTypeIsNamed) {
  const auto dir = fresh_dir("hostile-mode");
  write(dir + "/s.json", R"({"job": {"generator": "scaffold"}, "vary": {"gap": [1]}, "mode": 3})");
  expect_input_error(run_strand("sweep s.json -o out --no-previews", dir), "sweep.mode = 3: must be text");
}

TEST(Hostile, AFailingReportLeavesNoGcodeBehind) {
  const auto dir = fresh_dir("hostile-report");
  const auto r = run_strand(
      "scaffold --nozzle 0.84 --gap 1.6 --size 10x10 --layers 2 -o x.gcode --report nodir/r.json "
      "--viewer-e",
      dir);
  expect_input_error(r, "output = nodir/r.json: cannot write here");
  EXPECT_TRUE(files_in(dir).empty()) << *files_in(dir).begin();
}

TEST(Hostile, AJobNeverOverwritesItsOwnFile) {
  const auto dir = fresh_dir("hostile-self");
  const std::string job =
      R"({"generator": "scaffold", "params": {"nozzle": 0.84, "gap": 1.6, "size": "10x10",
          "layers": 2}, "output": "job.gcode", "report": "job.json"})";
  write(dir + "/job.json", job);
  expect_input_error(run_strand("job job.json", dir), "output = job.json: would overwrite the input");
  EXPECT_EQ(slurp(dir + "/job.json"), job);
  EXPECT_EQ(files_in(dir), std::set<std::string>{"job.json"});
}

TEST(Hostile, ANewlineInAProfileNameCannotInjectGcode) {
  const auto dir = fresh_dir("hostile-profile");
  write(dir + "/evil.json", R"({"name": "x\nG28 ; homed by the profile", "description": "d",
      "kinematics": {"type": "cartesian", "min_mm": [0, 0, 0], "max_mm": [100, 100, 100]},
      "firmware": {"flavour": "marlin", "arcs": false}, "deposition": {"model": "none"}})");
  const auto r = run_strand(
      "scaffold --nozzle 0.84 --gap 1.6 --size 10x10 --layers 2 --machine ./evil.json -o x.gcode", dir);
  expect_input_error(r, "name: must be one line of text without control characters");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
}

TEST(Hostile, NegativeStepsPerMmAreRefused) {
  const auto dir = fresh_dir("hostile-steps");
  const auto profile = slurp(std::string(STRAND_SOURCE_DIR) + "/machines/profiles/polar-rtheta.json");
  const auto at = profile.find("\"steps_per_mm\"");
  ASSERT_NE(at, std::string::npos);
  const auto open = profile.find('[', at), close = profile.find(']', at);
  write(dir + "/p.json", profile.substr(0, open) + "[-200, 200]" + profile.substr(close + 1));
  write(dir + "/x.gcode", "G0 X0 Y0\n");
  expect_input_error(run_strand("check x.gcode --machine ./p.json", dir),
                     "steps_per_mm = [-200,200]: must be in");
}

TEST(Hostile, CheckOfADirectoryIsBadInput) {
  const auto dir = fresh_dir("hostile-dir");
  fs::create_directories(dir + "/sub");
  expect_input_error(run_strand("check sub", dir), "input = sub: is a directory");
}

TEST(Hostile, FlowRefusesInfiniteSpeedAndATallBead) {
  const auto dir = fresh_dir("hostile-flow");
  const std::string ink = "flow --viscosity-pa-s 10 --nozzle-mm 0.84 --nozzle-length-mm 12 ";
  expect_input_error(run_strand(ink + "--speed inf", dir), "--speed = inf: must be a number, a speed (mm/min, mm/s)");
  expect_input_error(run_strand(ink + "--speed -5", dir), "flow.speed = -5: must be a finite number > 0");
  expect_input_error(run_strand(ink + "--speed 250 --bead-width 0.5 --bead-height 0.8", dir),
                     "flow.bead-height = 0.8: must be <= bead width 0.5");
}

TEST(Hostile, PreviewLayerMinusOneIsOutOfRange) {
  const auto dir = fresh_dir("hostile-preview");
  write(dir + "/x.gcode", ";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 Y0 E1\n");
  expect_input_error(run_strand("preview x.gcode -o x.png --layer -1", dir), "--layer");
  EXPECT_FALSE(exists(dir + "/x.png"));
}

}  // namespace
}  // namespace strand::testing

namespace strand::testing {
namespace {

TEST(Hostile, ArcsWhoseRoundedEndsMeetAreNotWrittenAsFullCircles) {
  const auto dir = fresh_dir("hostile-arc");
  const auto r = run_strand(
      "hexachiral --nozzle 0.87 --cell 14.2 --rows 3 --cols 5 --height 4.78 --machine marlin-xyz-200 "
      "-o h.gcode",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto check = run_strand("check h.gcode --machine marlin-xyz-200", dir);
  EXPECT_EQ(check.exit_code, 0) << check.out;
}

TEST(Hostile, AnArcToleranceThatMakesChordsCrossIsRefused) {
  const auto dir = fresh_dir("hostile-arc-tol");
  const auto r = run_strand(
      "tetrachiral --nozzle 0.451 --cell 9.11 --rows 7 --cols 5 --node-core 3.46 --layers 4 "
      "--layer-height 0.335 --arc-tolerance 0.499 -o t.gcode",
      dir);
  expect_input_error(r, "arc-tolerance = 0.499: the chords cross the strand");
  EXPECT_FALSE(exists(dir + "/t.gcode"));
}

TEST(Hostile, CheckJsonOfANonUtf8FileIsValidJson) {
  const auto dir = fresh_dir("hostile-utf8");
  std::ofstream(dir + "/x.gcode", std::ios::binary) << "G1 X\xb9\nG1 X10 Y0\n";
  const auto r = run_strand("check x.gcode --json", dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_TRUE(nlohmann::json::accept(r.out)) << r.out;
}

}  // namespace
}  // namespace strand::testing
