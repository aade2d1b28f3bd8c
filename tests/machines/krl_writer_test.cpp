// KRL as KSS would read it: every line one of the forms the writer means to write, the module
// named as its file, external-TCP interpolation, a start by axis values, and every LIN frame
// converted back equal to its pose CSV row (issue 20), gimbal-locked poses included.
#include "machines/krl_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <tuple>
#include <regex>
#include <sstream>

#include "machines/joint_analysis.h"
#include "machines/pose_csv.h"
#include "machines/robot_arm.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"

namespace strand::machines {
namespace {

using slicer::Vec3;

double angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

TEST(KukaAbc, GivesBackEveryRotationIncludingGimbalLock) {
  std::vector<Eigen::Matrix3d> rotations;
  std::mt19937 rng(20);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 2000; ++i) {
    rotations.push_back(Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
                            .normalized()
                            .toRotationMatrix());
  }
  // B = +-90 deg exactly and within rounding of it, for several A and C.
  for (double b : {90.0, -90.0}) {
    for (double a : {0.0, 30.0, 90.0, 180.0, -135.0}) {
      for (double c : {0.0, 45.0, -90.0, 180.0}) {
        for (double tiny : {0.0, 1e-13, -1e-13, 1e-8}) {
          rotations.push_back(kuka_abc_rotation(Vec3(a, b + tiny, c)));
        }
      }
    }
  }
  // Issue 20's row 21: quaternion (0, -0.7071, 0, -0.7071), the turn-0 pose of a scaffold.
  rotations.push_back(
      rotation_of(Eigen::Vector4d(0.0, -std::sqrt(0.5), 0.0, -std::sqrt(0.5)).normalized()));
  rotations.push_back(Eigen::Matrix3d::Identity());
  for (const auto& r : rotations) {
    const Vec3 abc = kuka_abc_deg(r);
    EXPECT_LT(angle_between(kuka_abc_rotation(abc), r), 1e-9) << abc.transpose();
    EXPECT_LE(std::abs(abc.y()), 90.0 + 1e-9);
  }
}

TEST(KrlModuleName, IsAKrlIdentifierOfAtMost24Characters) {
  EXPECT_EQ(krl_module_name("missing-rib-cylinder"), "missing_rib_cylinder");
  EXPECT_EQ(krl_module_name("3d"), "S3d");
  EXPECT_EQ(krl_module_name("end"), "S_end");
  EXPECT_EQ(krl_module_name("LIN"), "S_LIN");
  EXPECT_EQ(krl_module_name("a\";DEF x()\nEND"), "a__DEF_x___END");
  EXPECT_EQ(krl_module_name(std::string(40, 'p')).size(), 24u);
}

// The forms a program line may take; anything else is a defect (or an injection).
bool known_line(const std::string& line) {
  static const std::vector<std::regex> kForms = {
      std::regex(R"(&ACCESS RVP)"),
      std::regex(R"(DEF [A-Za-z_][A-Za-z0-9_]{0,23}\(\))"),
      std::regex(R"(END)"),
      std::regex(R"(; [ -~]*)"),
      std::regex(R"(  BAS\(#(INITMOV, 0|VEL_PTP, [0-9]+|ACC_PTP, [0-9]+)\))"),
      std::regex(R"(  \$TOOL = workpiece_on_flange)"),
      std::regex(R"(  \$BASE = nozzle_in_world)"),
      std::regex(R"(  \$TOOL = TOOL_DATA\[[0-9]+\] ; [ -~]*)"),
      std::regex(R"(  \$BASE = BASE_DATA\[[0-9]+\] ; [ -~]*)"),
      std::regex(R"(  \$LOAD = LOAD_DATA\[[0-9]+\] ; [ -~]*)"),
      std::regex(R"(  \$ACC\.CP = [0-9.]+ ; m/s\^2[ -~]*)"),
      std::regex(R"(  \$IPO_MODE = #TCP ; [ -~]*)"),
      std::regex(R"(  \$APO\.CDIS = [0-9.]+)"),
      std::regex(R"(  \$ADVANCE = 3)"),
      std::regex(
          R"(  PTP \{E6AXIS: A1 -?[0-9.]+, A2 -?[0-9.]+, A3 -?[0-9.]+, A4 -?[0-9.]+, A5 -?[0-9.]+, A6 -?[0-9.]+, E1 -?[0-9.]+\} ; [ -~]*)"),
      std::regex(R"(  LAP[0-9]+_P[0-9]+\(\))"),
      std::regex(
          R"(  TRIGGER WHEN DISTANCE=0 DELAY=0 DO \$OUT\[[0-9]+\]=(TRUE|FALSE) ; lap [0-9]+ starts)"),
      std::regex(R"(  \$VEL\.CP = [0-9.]+ ; m/s)"),
      std::regex(
          R"(  LIN \{X -?[0-9.]+, Y -?[0-9.]+, Z -?[0-9.]+, A -?[0-9.]+, B -?[0-9.]+, C -?[0-9.]+\}( C_DIS| ; onto the first pose| ; retract along the nozzle axis| ; approach: [0-9.]+ mm from the first pose along the nozzle axis| ; clearance pose: [0-9.]+ mm from the last pose))"),
      std::regex(
          R"(  \$LOAD = \{M [0-9.]+, CM \{X -?[0-9.]+, Y -?[0-9.]+, Z -?[0-9.]+, A 0.0, B 0.0, C 0.0\}, J \{X 0.0, Y 0.0, Z 0.0\}\} ; [ -~]*)"),
      std::regex(
          R"(  WAIT FOR \$IN\[[0-9]+\] == (TRUE|FALSE) ; the extruder is ready for lap [0-9]+)"),
      // Issue 29: the handshake reset before lap 0.
      std::regex(R"(  ; handshake reset[ -~]*)"),
      std::regex(R"(  \$OUT\[[0-9]+\]=(TRUE|FALSE) ; reset)"),
      std::regex(R"(  WAIT FOR \$IN\[[0-9]+\] == (TRUE|FALSE) ; the extruder has finished and reset)"),
      std::regex(R"()"),
  };
  for (const auto& f : kForms)
    if (std::regex_match(line, f)) return true;
  return false;
}

void expect_krl_follows_the_csv(const std::string& job_args,
                                const std::string& dir = testing::fresh_dir("krl")) {
  const auto r = testing::run_strand(job_args + " -o my-part.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(testing::exists(dir + "/my_part.src")) << "KSS loads DEF my_part from my_part.src";
  ASSERT_TRUE(testing::exists(dir + "/my_part.dat"));
  const std::string src = testing::slurp(dir + "/my_part.src");
  EXPECT_EQ(src.rfind("&ACCESS RVP\nDEF my_part()\n", 0), 0u);
  EXPECT_EQ(testing::slurp(dir + "/my_part.dat").rfind("&ACCESS RVP\nDEFDAT my_part\n", 0), 0u);
  EXPECT_NE(src.find("\n  $IPO_MODE = #TCP"), std::string::npos) << "external TCP";
  EXPECT_EQ(src.find("#BASE"), std::string::npos);

  const MachineProfile m = load_profile("kuka-iiwa14-wasp-cylinder");
  const Eigen::Matrix3d nozzle = nozzle_frame_rotation(m.robot);
  const auto rows = read_pose_csv(testing::slurp(dir + "/my-part.csv"), "my-part.csv");
  EXPECT_NE(src.find("\n  $ACC.CP = 0.100000 ; m/s^2"), std::string::npos)
      << "the profile's path acceleration, as the lap timing assumes";
  const std::regex lin(
      R"(  LIN \{X (-?[0-9.]+), Y (-?[0-9.]+), Z (-?[0-9.]+), A (-?[0-9.]+), B (-?[0-9.]+), C (-?[0-9.]+)\}(.*))");
  const std::regex ptp(
      R"(  PTP \{E6AXIS: A1 (-?[0-9.]+), A2 (-?[0-9.]+), A3 (-?[0-9.]+), A4 (-?[0-9.]+), A5 (-?[0-9.]+), A6 (-?[0-9.]+), E1 (-?[0-9.]+)\} ; (.*))");
  const std::regex wait(R"(  WAIT FOR \$IN\[([0-9]+)\] == (TRUE|FALSE) ; .*)");
  const std::regex trigger(R"(  TRIGGER .*\$OUT\[[0-9]+\]=(TRUE|FALSE) ; lap ([0-9]+) starts)");
  const ArmModel arm = lbr_iiwa_14_r820(m.robot);
  // In the module's order: the main program, then the sub-programs it calls in turn.
  std::istringstream in(src);
  std::size_t row = 0, ptps = 0, lins = 0, waits = 0;
  double worst_mm = 0.0, worst_rad = 0.0;
  Vec3 previous_p = rows[0].contact_mm;
  Eigen::Matrix3d previous_r = rotation_of(rows[0].workpiece_wxyz).transpose() * nozzle;
  const auto expect_frame = [&](const std::smatch& g, const slicer::PosePoint& pose) {
    const Vec3 p(std::stod(g[1]), std::stod(g[2]), std::stod(g[3]));
    const Eigen::Matrix3d r =
        kuka_abc_rotation(Vec3(std::stod(g[4]), std::stod(g[5]), std::stod(g[6])));
    const Eigen::Matrix3d want = rotation_of(pose.workpiece_wxyz).transpose() * nozzle;
    worst_mm = std::max(worst_mm, (p - pose.contact_mm).norm());
    worst_rad = std::max(worst_rad, angle_between(r, want));
  };
  std::string retract_line, pending_wait;
  for (std::string line; std::getline(in, line);) {
    EXPECT_TRUE(known_line(line)) << line;
    std::smatch g;
    if (std::regex_match(line, g, ptp)) {
      Joints q;
      for (int i = 0; i < 7; ++i) q[i] = slicer::deg_to_rad(std::stod(g[i + 1]));
      if (g[8].str().rfind("clearance pose", 0) == 0) {
        const Eigen::Isometry3d f = forward_kinematics(arm, q);
        const auto a = moved_along_nozzle(m.robot, rows[0], m.robot.motion.clearance_mm);
        const Eigen::Isometry3d want =
            flange_pose(m.robot, a.workpiece_origin_mm, a.workpiece_wxyz);
        EXPECT_LT((f.translation() - want.translation()).norm(), 0.01);
        EXPECT_LT(angle_between(f.linear(), want.linear()), 1.75e-4);
      } else {
        EXPECT_EQ(g[8].str().rfind("home", 0), 0u) << line;
        for (int i = 0; i < 7; ++i)
          EXPECT_NEAR(q[i], slicer::deg_to_rad((*m.robot.motion.home_joints_deg)[i]), 1e-6);
      }
      ++ptps;
    } else if (line.find("reset") != std::string::npos) {
      // Issue 29: before lap 0, both lines to the level before lap 0 (robot_handshake_test).
      EXPECT_TRUE(pending_wait.empty()) << "the handshake resets come outside the laps' waits";
    } else if (std::regex_match(line, g, wait)) {
      pending_wait = g[2];
      ++waits;
    } else if (std::regex_match(line, g, trigger)) {
      EXPECT_EQ(pending_wait, g[1].str())
          << "the robot waits for the extruder's ready level of the lap it starts";
      pending_wait.clear();
    } else if (std::regex_match(line, g, lin)) {
      if (g[7] == " ; onto the first pose") {
        expect_frame(g, rows[0]);
        continue;
      }
      if (g[7].str().rfind(" ; approach", 0) == 0) {
        expect_frame(g, moved_along_nozzle(m.robot, rows[0], m.robot.motion.approach_mm));
        continue;
      }
      if (g[7].str().rfind(" ; clearance pose", 0) == 0) {
        expect_frame(g, moved_along_nozzle(m.robot, rows.back(), m.robot.motion.clearance_mm));
        continue;
      }
      if (g[7] == " ; retract along the nozzle axis") {
        expect_frame(g, moved_along_nozzle(m.robot, rows.back(), m.robot.motion.retract_mm));
        retract_line = line;
        continue;
      }
      // The next CSV row that moves: rows that repeat the previous pose are not written.
      for (++row; row < rows.size(); ++row) {
        const Eigen::Matrix3d want = rotation_of(rows[row].workpiece_wxyz).transpose() * nozzle;
        if ((rows[row].contact_mm - previous_p).norm() > 1e-4 ||
            angle_between(want, previous_r) > 1e-6)
          break;
      }
      ASSERT_LT(row, rows.size());
      expect_frame(g, rows[row]);
      previous_p = rows[row].contact_mm;
      previous_r = rotation_of(rows[row].workpiece_wxyz).transpose() * nozzle;
      ++lins;
    }
  }
  EXPECT_EQ(ptps, 3u) << "home, clearance pose, home";
  EXPECT_FALSE(retract_line.empty());
  EXPECT_GE(waits, 2u);
  EXPECT_GT(lins, rows.size() / 2);
  EXPECT_LT(worst_mm, 0.01);
  EXPECT_LT(worst_rad, 1.75e-4);
}

TEST(KrlWriter, TheThesisCylinderLoadsAndMatchesTheCsv) {
  expect_krl_follows_the_csv("job " + std::string(STRAND_SOURCE_DIR) +
                             "/samples/missing-rib-cylinder.json");
}

TEST(KrlWriter, TheScaffoldWithTurnZeroPosesMatchesTheCsv) {
  expect_krl_follows_the_csv(
      "scaffold --nozzle 0.8 --gap 1.5 --size 40x30 --layers 4 --substrate cylinder "
      "--substrate-radius 25 --substrate-length 60 --machine kuka-iiwa14-wasp-cylinder");
}

// A copy of the shipped KUKA profile with robot.krl values changed (null removes a key).
std::string kuka_profile_with(const std::string& dir, const nlohmann::json& krl,
                              const nlohmann::json& robot = nlohmann::json::object()) {
  nlohmann::json j = nlohmann::json::parse(testing::slurp(
      std::string(STRAND_SOURCE_DIR) + "/machines/profiles/kuka-iiwa14-wasp-cylinder.json"));
  j["name"] = "kuka-test-cell";
  for (const auto& [k, v] : krl.items()) j["robot"]["krl"][k] = v;
  for (const auto& [k, v] : robot.items()) {
    if (v.is_null()) {
      j["robot"].erase(k);
    } else {
      j["robot"][k] = v;
    }
  }
  const std::string path = dir + "/cell.json";
  std::ofstream(path) << j.dump(2);
  return path;
}

const char* const kKrlScaffold =
    "scaffold --nozzle 0.8 --gap 1.5 --size 40x30 --layers 4 --substrate cylinder "
    "--substrate-radius 25 --substrate-length 60";

TEST(KrlWriter, ToolAndBaseFromControllerDataChangeOnlyTheirLines) {
  const std::string cal = testing::fresh_dir("krl-cal"), plain = testing::fresh_dir("krl-plain");
  const std::string machine = kuka_profile_with(cal, {{"tool_data", 3}, {"base_data", 5}});
  expect_krl_follows_the_csv(std::string(kKrlScaffold) + " --machine " + machine, cal);
  const auto r = testing::run_strand(std::string(kKrlScaffold) +
                                         " --machine kuka-iiwa14-wasp-cylinder -o my-part.csv",
                                     plain);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string src = testing::slurp(cal + "/my_part.src");
  EXPECT_NE(src.find("\n  $TOOL = TOOL_DATA[3] ;"), std::string::npos);
  EXPECT_NE(src.find("\n  $BASE = BASE_DATA[5] ;"), std::string::npos);
  EXPECT_NE(src.find("\n  $LOAD = LOAD_DATA[3] ;"), std::string::npos) << "the tool's own load";
  EXPECT_EQ(src.find("BAS(#TOOL"), std::string::npos) << "plain assignments";
  EXPECT_EQ(src.find("workpiece_on_flange"), std::string::npos);
  // Everything else as with the profile's frames: the same targets, the same .dat frames.
  const auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);)
      if (l.find("$TOOL") == std::string::npos && l.find("$BASE") == std::string::npos &&
          l.find("$LOAD") == std::string::npos && l.rfind("; the program uses", 0) != 0 &&
          l.rfind("; machine:", 0) != 0)
        out.push_back(l);
    return out;
  };
  EXPECT_EQ(lines(src), lines(testing::slurp(plain + "/my_part.src")));
  EXPECT_EQ(lines(testing::slurp(cal + "/my_part.dat")),
            lines(testing::slurp(plain + "/my_part.dat")));
  EXPECT_NE(testing::slurp(cal + "/my_part.dat").find("TOOL_DATA[3] and BASE_DATA[5]"),
            std::string::npos);
}

TEST(KrlWriter, WithoutControllerDataOrAccelerationTheProgramIsAsBefore) {
  const std::string dir = testing::fresh_dir("krl-none");
  const std::string machine =
      kuka_profile_with(dir, nlohmann::json::object(), {{"acceleration_mm_per_s2", nullptr}});
  const auto r = testing::run_strand(
      std::string(kKrlScaffold) + " --machine " + machine + " -o p.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string src = testing::slurp(dir + "/p.src");
  EXPECT_NE(src.find("\n  $TOOL = workpiece_on_flange\n  $BASE = nozzle_in_world\n  $LOAD = {M "),
            std::string::npos);
  EXPECT_EQ(src.find("$ACC.CP"), std::string::npos);
  EXPECT_EQ(src.find("_DATA["), std::string::npos);
  EXPECT_EQ(testing::slurp(dir + "/P.java").find("setCartAcceleration"), std::string::npos);
}

TEST(KrlWriter, ControllerDataIndicesAreWholeNumbersInRange) {
  for (const auto& [key, value, says] :
       std::vector<std::tuple<std::string, nlohmann::json, std::string>>{
           {"tool_data", 2.5, "robot.krl.tool_data"},
           {"base_data", 0, "robot.krl.base_data"},
           {"tool_data", 17, "robot.krl.tool_data"},
           {"tool_index", 1, "robot.krl.tool_index"}}) {
    const std::string dir = testing::fresh_dir("krl-index");
    const std::string machine = kuka_profile_with(dir, {{key, value}});
    const auto r = testing::run_strand(
        std::string(kKrlScaffold) + " --machine " + machine + " -o p.csv", dir);
    testing::expect_input_error(r, says);
    EXPECT_FALSE(testing::exists(dir + "/p.csv"));
    EXPECT_FALSE(testing::exists(dir + "/p.src"));
  }
}

}  // namespace
}  // namespace strand::machines
