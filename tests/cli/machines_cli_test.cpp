// `strand machines`: the list with origins, show, check, and a lab's own profiles found by name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

// strand with XDG_CONFIG_HOME set to `config` (an absolute path), in `dir`.
CliResult run_with_config(const std::string& config, const std::string& args,
                          const std::string& dir) {
  return run_in_shell("XDG_CONFIG_HOME='" + config + "' '" + std::string(STRAND_CLI) + "' " + args,
                      dir);
}

void write(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path) << text;
}

TEST(MachinesCli, ShowPrintsAProfileThatLoadsAsItself) {
  const auto dir = fresh_dir("machines-show");
  const auto shown = run_with_config(dir + "/cfg", "machines show deltawasp-2040-clay", dir);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  const auto j = nlohmann::json::parse(shown.out);
  EXPECT_EQ(j.at("name"), "deltawasp-2040-clay");
  // Copied to a file and named by path, it makes the same G-code as the shipped name.
  write(dir + "/copy.json", shown.out);
  const std::string job = "scaffold --nozzle 0.84 --gap 1.6 --size 12x12 --layers 2 ";
  ASSERT_EQ(run_with_config(dir + "/cfg", job + "--machine copy.json -o a.gcode", dir).exit_code,
            0);
  ASSERT_EQ(run_with_config(dir + "/cfg", job + "--machine deltawasp-2040-clay -o b.gcode", dir)
                .exit_code,
            0);
  EXPECT_EQ(slurp(dir + "/a.gcode").size(), slurp(dir + "/b.gcode").size());
  const auto unknown = run_with_config(dir + "/cfg", "machines show deltawasp", dir);
  expect_input_error(unknown, "machine = deltawasp: unknown machine");
}

TEST(MachinesCli, AUserProfileIsFoundByNameAndItsShadowingReported) {
  const auto dir = fresh_dir("machines-user");
  const auto cfg = dir + "/cfg";
  auto profile =
      nlohmann::json::parse(run_with_config(cfg, "machines show deltawasp-2040-clay", dir).out);
  profile["name"] = "lab-delta";
  profile["description"] = "our DeltaWASP with the 0.6 mm nozzle";
  write(cfg + "/strand/machines/lab-delta.json", profile.dump(2));
  profile["description"] = "recalibrated";
  write(cfg + "/strand/machines/deltawasp-2040-clay.json", profile.dump(2));

  const auto list = run_with_config(cfg, "machines", dir);
  ASSERT_EQ(list.exit_code, 0) << list.err;
  EXPECT_NE(list.out.find("lab-delta  our DeltaWASP with the 0.6 mm nozzle  [" + cfg +
                          "/strand/machines/lab-delta.json]"),
            std::string::npos)
      << list.out;
  EXPECT_NE(list.out.find("deltawasp-2040-clay  recalibrated  [" + cfg +
                          "/strand/machines/deltawasp-2040-clay.json, shadows the shipped one]"),
            std::string::npos)
      << list.out;
  const auto json = nlohmann::json::parse(run_with_config(cfg, "machines --json", dir).out);
  bool found = false;
  for (const auto& m : json) {
    if (m.at("name") == "deltawasp-2040-clay") {
      found = true;
      EXPECT_TRUE(m.at("shadows_shipped").get<bool>());
    }
    if (m.at("name") == "xy-plotter-servo") {
      EXPECT_EQ(m.at("origin"), "shipped");
    }
  }
  EXPECT_TRUE(found);
  const auto job = run_with_config(
      cfg,
      "scaffold --nozzle 0.84 --gap 1.6 --size 12x12 --layers 2 --machine lab-delta -o l.gcode",
      dir);
  EXPECT_EQ(job.exit_code, 0) << job.err;
  EXPECT_NE(slurp(dir + "/l.gcode").find("lab-delta"), std::string::npos);
}

TEST(MachinesCli, CheckListsEverySchemaProblemOnItsOwnLine) {
  const auto dir = fresh_dir("machines-check");
  auto profile = nlohmann::json::parse(run_strand("machines show marlin-xyz-200", dir).out);
  write(dir + "/good.json", profile.dump(2));
  const auto good = run_strand("machines check good.json", dir);
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_EQ(good.out.rfind("good.json: ok (", 0), 0u) << good.out;
  profile["travel_lift_mm"] = "high";
  profile["limits"]["max_feed_mm_per_min"] = -5;
  write(dir + "/bad.json", profile.dump(2));
  const auto bad = run_strand("machines check bad.json", dir);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_GE(std::count(bad.err.begin(), bad.err.end(), '\n'), 2) << bad.err;
  EXPECT_NE(bad.err.find("travel_lift_mm"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace strand::testing
