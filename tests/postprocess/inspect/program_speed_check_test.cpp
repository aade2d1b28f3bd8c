// strand check reads the vendor programs beside a pose CSV back and reports their contact
// speed against the CSV's time line (issue 37, item 3).
#include "postprocess/inspect/program_speed_check.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"
#include "tests/support/sample_jobs.h"

namespace strand::post {
namespace {

using testing::run_strand;
using testing::slurp;

void overwrite(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A scaffold patch on the concave bowl held by `machine`: the written job and its folder.
std::string bowl_job(const std::string& machine) {
  const std::string dir = testing::fresh_dir("program-speed");
  const auto r = run_strand("scaffold --nozzle 0.8 --gap 1.5 --size 12x12 --layers 2 --substrate mesh "
                            "--substrate-mesh " + testing::write_concave_bowl_obj(dir) +
                                " --machine " + machine + " -o part.csv",
                            dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir;
}

TEST(ProgramSpeedCheck, TheUrScriptTheJobWroteKeepsTheTimeLineAndAHandEditDoesNot) {
  const std::string dir = bowl_job("ur10e-wasp-cylinder");
  const auto ok = run_strand("check part.csv --json", dir);
  ASSERT_EQ(ok.exit_code, 0) << ok.out << ok.err;
  const auto j = nlohmann::json::parse(ok.out);
  ASSERT_EQ(j.at("contact_speed").size(), 1u);
  const auto& ur = j.at("contact_speed")[0];
  EXPECT_EQ(ur.at("program"), "URScript");
  EXPECT_TRUE(ur.at("read").get<bool>());
  EXPECT_NEAR(ur.at("worst_contact_speed_ratio").get<double>(), 1.0, 0.02);
  EXPECT_LE(std::abs(ur.at("worst_lap_difference").get<double>()), 0.02);
  // The old program: every lap motion at the row's own speed (what the TCP did before the
  // fix), written by hand into the script: the check sees the contact point off its speed.
  const std::string csv = slurp(dir + "/part.csv");
  std::string script = slurp(dir + "/part.script");
  const std::regex v(R"(, v=[0-9.]+, r=([0-9.]+)\)$)");
  std::string edited;
  std::istringstream in(script);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("  movel(", 0) == 0 && line.find('#') == std::string::npos)
      line = std::regex_replace(line, v, ", v=0.006000, r=$1)");
    edited += line + "\n";
  }
  ASSERT_NE(edited, script);
  overwrite(dir + "/part.script", edited);
  const auto bad = run_strand("check part.csv", dir);
  EXPECT_EQ(bad.exit_code, 1) << bad.out;
  EXPECT_NE(bad.out.find("contact speed: URScript (part.script)"), std::string::npos) << bad.out;
  EXPECT_NE(bad.out.find("more than 2 % off: FAILED"), std::string::npos) << bad.out;
}

TEST(ProgramSpeedCheck, KukaProgramsAreReadBackAndASunriseWithoutScalingIsFound) {
  const std::string dir = bowl_job("kuka-iiwa14-wasp-cylinder");
  const auto ok = run_strand("check part.csv", dir);
  ASSERT_EQ(ok.exit_code, 0) << ok.out << ok.err;
  EXPECT_NE(ok.out.find("contact speed: KRL (part.src) 1.000 x"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("contact speed: Sunrise (Part.java) 1.000 x"), std::string::npos)
      << ok.out;
  // A Sunrise application that moves its frame at the rows' speeds (no frameSpeed).
  std::string java = slurp(dir + "/Part.java");
  java = std::regex_replace(java, std::regex(R"(frameSpeed\()"), "rowSpeed(");
  overwrite(dir + "/Part.java", java);
  const auto bad = run_strand("check part.csv", dir);
  EXPECT_EQ(bad.exit_code, 1) << bad.out;
  EXPECT_NE(bad.out.find("contact speed: Sunrise (Part.java)"), std::string::npos);
  EXPECT_NE(bad.out.find("FAILED"), std::string::npos);
  // A program whose numbers cannot be read is said so in one line, not a crash.
  overwrite(dir + "/part.src", std::regex_replace(slurp(dir + "/part.src"),
                                                  std::regex(R"(LIN \{X [0-9.-]+)"), "LIN {X 1e999"));
  const auto odd = run_strand("check part.csv", dir);
  EXPECT_NE(odd.out.find("contact speed: KRL (part.src) not read: a number in it cannot be read"),
            std::string::npos)
      << odd.out << odd.err;
  // Programs the user removed are said so, not judged.
  std::filesystem::remove(dir + "/Part.java");
  std::filesystem::remove(dir + "/part.src");
  const auto gone = run_strand("check part.csv", dir);
  EXPECT_EQ(gone.exit_code, 0) << gone.out;
  EXPECT_NE(gone.out.find("contact speed: KRL (part.src) not beside the CSV"), std::string::npos);
}

}  // namespace
}  // namespace strand::post
