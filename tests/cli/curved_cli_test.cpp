// `strand <generator> --substrate cylinder ...` and `strand job` with a substrate: outputs,
// checks, and the bad-input rule (exit 2, one line naming the parameter, no file written).
// GCC 12 at -O3 reports a false -Wstringop-overflow in std::string::replace inlined into the
// tamper tests below (a bound past the maximum object size): not a defect of this code.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "patterns/registry.h"
#include "postprocess/preview/preview_scene.h"
#include "tests/support/cli_runner.h"
#include "tests/support/png_pixels.h"
#include "tests/support/sample_jobs.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

const std::string kMissingRib = "missing-rib --nozzle 1.2 --rib 6 --rows 4 --cols 8 --layers 3 ";
const std::string kRobot = " --machine kuka-iiwa14-wasp-cylinder";
const std::string kRotary = " --machine marlin-rotary-a";

std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string()[0] != '.';
  return n;
}

void expect_rejected(const std::string& args, const std::string& must_mention) {
  const auto dir = fresh_dir("curved-bad");
  const auto r = run_strand(args, dir);
  expect_input_error(r, must_mention);
  EXPECT_EQ(files_in(dir), 0u) << "no output file after: " << args;
}

TEST(CurvedCli, ThesisJobWritesTheRobotProgramsAndChecksClean) {
  const auto dir = fresh_dir("curved-job");
  const auto r = run_strand(
      "job '" + samples_dir() + "/missing-rib-cylinder.json' -o part.csv --report part.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f :
       {"part.csv", "Part.java", "part.src", "part.dat", "part.extruder.gcode", "part.json"}) {
    EXPECT_TRUE(exists(dir + "/" + f)) << f;
  }
  EXPECT_NE(r.out.find("laps           6 in 3 layers"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(dir + "/part.json"));
  EXPECT_EQ(report["laps"].size(), 6u);
  EXPECT_EQ(report["robot"]["joints"].size(), 7u);
  EXPECT_GT(report["programs"]["krl_lin_points"].get<int>(), 1000);
  const auto check = run_strand("check part.csv --machine kuka-iiwa14-wasp-cylinder", dir);
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("check: OK"), std::string::npos);
}

TEST(CurvedCli, RotaryMachineWritesFourAxisGcodeThatChecksClean) {
  const auto dir = fresh_dir("curved-rotary");
  const auto r =
      run_strand(kMissingRib + "--substrate cylinder --substrate-radius 25 --substrate-length 80" +
                     kRotary + " -o r.gcode",
                 dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(dir + "/r.gcode").find(";ROTARY_AXIS:A"), std::string::npos);
  const auto check = run_strand("check r.gcode --machine marlin-rotary-a --json", dir);
  EXPECT_EQ(check.exit_code, 0) << check.out;
  EXPECT_EQ(nlohmann::json::parse(check.out)["kind"], "rotary G-code");
}

// A move with bytes that are not UTF-8 (found by curved_fuzz): the finding quotes the line,
// and the JSON report stays valid instead of failing the whole check.
TEST(CurvedCli, ARotaryFileWithBinaryBytesStillGivesAJsonReport) {
  const auto dir = fresh_dir("curved-binary");
  ASSERT_EQ(run_strand(kMissingRib + "--substrate cylinder --substrate-radius 25 "
                                     "--substrate-length 80" + kRotary + " -o r.gcode",
                       dir)
                .exit_code,
            0);
  std::string text = slurp(dir + "/r.gcode");
  const auto move = text.find("\nG1 A");
  ASSERT_NE(move, std::string::npos);
  text.insert(text.find(" F", move) + 2, "\x9f");
  std::ofstream(dir + "/r.gcode", std::ios::binary) << text;
  const auto check = run_strand("check r.gcode --machine marlin-rotary-a --json", dir);
  EXPECT_NE(check.exit_code, 2) << check.err;
  const auto report = nlohmann::json::parse(check.out, nullptr, false);
  EXPECT_FALSE(report.is_discarded()) << check.out.substr(0, 200);
  EXPECT_EQ(report.value("kind", ""), "rotary G-code");
}

TEST(CurvedCli, ATamperedCsvFailsTheCheckWithExitOne) {
  const auto dir = fresh_dir("curved-tamper");
  ASSERT_EQ(
      run_strand("job '" + samples_dir() + "/missing-rib-cylinder.json' -o p.csv", dir).exit_code,
      0);
  std::string csv = slurp(dir + "/p.csv");
  const auto row = csv.find("\n100,");
  csv.replace(csv.find(',', csv.find(',', row + 1) + 1) + 1, 4, "9");  // x_mm of row 100
  std::ofstream(dir + "/p.csv") << csv;
  const auto check = run_strand("check p.csv --machine kuka-iiwa14-wasp-cylinder", dir);
  EXPECT_EQ(check.exit_code, 1) << check.out;
  EXPECT_NE(check.out.find("poses off the nozzle tip (1)"), std::string::npos) << check.out;
}

TEST(CurvedCli, AnInterruptedOutputSetFailsTheCheckUntilTheNextRunCompletesIt) {
  const auto dir = fresh_dir("curved-journal");
  const std::string job = "job '" + samples_dir() + "/missing-rib-cylinder.json' -o p.csv";
  ASSERT_EQ(run_strand(job, dir).exit_code, 0);
  // What a kill between two renames leaves: the journal and the set's remaining temps.
  const std::string dat = slurp(dir + "/p.dat");
  std::ofstream(dir + "/p.dat.strand-tmp") << dat;
  std::ofstream(dir + "/p.dat") << "&ACCESS RVP\nDEFDAT p\nENDDAT\n";  // an older .dat
  std::ofstream(dir + "/p.csv.strand-commit")
      << "strand output set v1\n"
      << dir << "/p.dat.strand-tmp\t" << dir << "/p.dat\n";
  const auto check = run_strand("check p.csv --machine kuka-iiwa14-wasp-cylinder", dir);
  EXPECT_EQ(check.exit_code, 1);
  EXPECT_NE(check.out.find("interrupted"), std::string::npos) << check.out;
  ASSERT_EQ(run_strand(job, dir).exit_code, 0);
  EXPECT_FALSE(exists(dir + "/p.csv.strand-commit"));
  EXPECT_FALSE(exists(dir + "/p.dat.strand-tmp"));
  EXPECT_EQ(slurp(dir + "/p.dat"), dat);
  EXPECT_EQ(run_strand("check p.csv --machine kuka-iiwa14-wasp-cylinder", dir).exit_code, 0);
}

TEST(CurvedCli, BadInputIsOneLineWithoutOutput) {
  const std::string cyl = "--substrate cylinder --substrate-length 80 ";
  expect_rejected(kMissingRib + cyl + "--substrate-radius 0" + kRobot + " -o p.csv",
                  "substrate.radius = 0: must be in (0, 10000] (mm)");
  expect_rejected(kMissingRib + cyl + "--substrate-radius 15" + kRobot + " -o p.csv",
                  "substrate.wrap = patch: the pattern is 102.687 around");
  expect_rejected(kMissingRib + cyl + "--substrate-radius 20 -o p.gcode", "prints on a flat bed");
  expect_rejected(kMissingRib + kRobot + " -o p.csv",
                  "prints on a cylinder; give --substrate cylinder");
  expect_rejected(kMissingRib + cyl + "--substrate-radius 17" + kRobot + " -o p.csv",
                  "A7 allows 340.0 deg");
  expect_rejected(kMissingRib + cyl + "--substrate-radius 800" + kRobot + " -o p.csv",
                  "out of the robot's reach");
  expect_rejected(kMissingRib + cyl + "--substrate-radius 60" + kRotary + " -o p.gcode",
                  "substrate.radius = 60: must be <= 55");
  expect_rejected(kMissingRib + "--substrate cylinder --substrate-radius 20 --substrate-length 40" +
                      kRobot + " -o p.csv",
                  "substrate.length = 40: must be >= the pattern's 57.582");
  expect_rejected(kMissingRib + cyl + "--substrate-radius 20" + kRobot + " -o p.gcode",
                  "give a .csv name");
  expect_rejected(kMissingRib + "--wrap full -o p.gcode", "substrate.type: missing");
  expect_rejected(
      kMissingRib + cyl + "--substrate-radius 20 --arc-length-at middle" + kRobot + " -o p.csv",
      "substrate.arc-length-at = middle: must be one of surface, deposition");
  expect_rejected("check nothing.csv", "input = nothing.csv");
}

// Every design as a sleeve on the rotary axis (--wrap full, the sample's parameters): one
// strand per layer that closes across the seam without crossing itself there; a design
// without a periodic variant is refused by name.
TEST(CurvedCli, EveryDesignWrapsAroundTheRotaryAxisWithOneStrandPerLayer) {
  for (const auto& g : patterns::generators()) {
    SCOPED_TRACE(g.name);
    const auto it = sample_params().find(g.name);
    ASSERT_NE(it, sample_params().end());
    nlohmann::json job = {
        {"generator", g.name},
        {"machine", "marlin-rotary-a"},
        {"params", it->second},
        {"substrate", {{"type", "cylinder"}, {"radius", 30}, {"length", 150}, {"wrap", "full"}}}};
    const auto dir = fresh_dir("curved-wrap");
    std::ofstream(dir + "/job.json") << job.dump();
    const auto r = run_strand("job job.json -o w.gcode", dir);
    if (g.generate_wrapped == nullptr) {
      expect_input_error(r, "substrate.wrap = full: not supported for " + g.name);
      continue;
    }
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(" cells of "), std::string::npos) << "the adjusted cell: " << r.out;
    const auto check = run_strand("check w.gcode --machine marlin-rotary-a --json", dir);
    const auto report = nlohmann::json::parse(check.out);
    EXPECT_TRUE(report["ok"].get<bool>()) << check.out.substr(0, 2000);
    EXPECT_EQ(report["crossings"], 0);
    for (const auto& layer : report["layers"])
      EXPECT_EQ(layer["strands"], 1) << "layer " << layer["layer"];
  }
}

TEST(CurvedCli, PreviewDrawsPoseCsvsAndRotaryFilesOnTheirWorkpiece) {
  const auto dir = fresh_dir("curved-preview");
  ASSERT_EQ(
      run_strand("job '" + samples_dir() + "/missing-rib-cylinder.json' -o p.csv", dir).exit_code,
      0);
  ASSERT_EQ(run_strand("job '" + samples_dir() + "/scaffold-cylinder-rotary.json' -o r.gcode", dir)
                .exit_code,
            0);
  for (const char* f : {"p.csv", "r.gcode"}) {
    const auto r = run_strand(std::string("preview ") + f + " -o x.png --view iso", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(std::string(f) == "p.csv" ? "(3 layers" : "(4 layers"), std::string::npos)
        << r.out;
    EXPECT_GT(png_stats(slurp(dir + "/x.png")).drawn_fraction, 0.02) << f;
  }
  // The CSV's features come through: the missing-rib's nodes in the node colour.
  ASSERT_EQ(run_strand("preview p.csv -o n.png", dir).exit_code, 0);
  const auto node = post::feature_colour(slicer::Feature::Node);
  EXPECT_GT(colour_spot(slurp(dir + "/n.png"), int(node.r * 255), int(node.g * 255),
                        int(node.b * 255), 30)
                .count,
            100);
  expect_input_error(run_strand("preview p.csv -o m.png --marks", dir),
                     "marks: only for flat G-code");
}

TEST(CurvedCli, ExtrusionFlagAndJobKeyChooseWhatDrivesTheExtruder) {
  const std::string cylinder = "--substrate cylinder --substrate-radius 20 --substrate-length 80";
  for (const std::string mode : {"time", "volumetric"}) {
    const auto dir = fresh_dir("curved-extrusion");
    const auto r = run_strand(kMissingRib + cylinder + kRobot + " --extrusion " + mode +
                                  " -o p.csv --report p.json",
                              dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto report = nlohmann::json::parse(slurp(dir + "/p.json"));
    EXPECT_EQ(report["ink"]["extrusion"], mode);
    const double ratio = report["ink"]["extruder_to_bead_ratio"].get<double>();
    EXPECT_NE(r.out.find("mL from the extruder, beads"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("lap timing     laps timed with corner slowdowns: +"), std::string::npos)
        << r.out;
    ASSERT_TRUE(report.contains("lap_timing"));
    EXPECT_EQ(report["laps"].size(), 6u);
    for (const auto& lap : report["laps"])
      EXPECT_GT(lap["planned_time_s"].get<double>(), lap["nominal_time_s"].get<double>());
    if (mode == "volumetric") {
      EXPECT_NEAR(ratio, 1.0, 0.01);
      EXPECT_EQ(r.out.find("warning        the extruder delivers"), std::string::npos) << r.out;
    } else {
      EXPECT_LT(ratio, 0.9);
      EXPECT_NE(r.out.find("warning        the extruder delivers 0.34x"), std::string::npos)
          << r.out;
    }
  }
  // The job key sits with the substrate's.
  const auto dir = fresh_dir("curved-extrusion-job");
  auto job = nlohmann::json::parse(slurp(samples_dir() + "/missing-rib-cylinder.json"));
  job["substrate"]["extrusion"] = "volumetric";
  std::ofstream(dir + "/j.json") << job.dump();
  const auto r = run_strand("job j.json -o v.csv --report v.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/v.json"))["ink"]["extrusion"], "volumetric");
  expect_rejected(kMissingRib + cylinder + kRobot + " --extrusion screw -o p.csv",
                  "substrate.extrusion");
  expect_rejected("scaffold --nozzle 0.8 --gap 1.5 --size 20x20 --layers 1 --substrate cylinder "
                  "--substrate-radius 25 --substrate-length 60" + kRotary +
                      " --extrusion volumetric -o r.gcode",
                  "substrate.extrusion");
}

TEST(CurvedCli, HelpListsTheSubstrateFlags) {
  const auto r = run_strand("tetrachiral --help");
  for (const char* f :
       {"--substrate ", "--substrate-radius", "--substrate-length", "--wrap", "--arc-length-at",
        "--extrusion"}) {
    EXPECT_NE(r.out.find(f), std::string::npos) << f;
  }
}

}  // namespace
}  // namespace strand::testing
