// URScript as a UR controller would read it (issue 20 item 4): every line one of the forms the
// writer means to write, rotation vectors exact near pi, every movel converted back equal to
// its pose CSV row (turn-0 poses included, where the rotation is a half turn), the start by
// joint values, the lap handshake in order; hostile names and profile strings stay text
// (issue 24).
#include "machines/urscript_writer.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
#include <sstream>

#include "machines/builtin_profiles.h"
#include "machines/joint_analysis.h"
#include "machines/pose_csv.h"
#include "machines/profile.h"
#include "machines/program_text.h"
#include "machines/robot_arm.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"

namespace strand::machines {
namespace {

using slicer::Vec3;

double ur_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

std::string ur_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

const char* const kUrScaffold =
    "scaffold --nozzle 0.8 --gap 1.5 --size 40x30 --layers 4 --substrate cylinder "
    "--substrate-radius 25 --substrate-length 60";

TEST(UrRotationVector, GivesBackEveryRotationIncludingHalfTurns) {
  std::vector<Eigen::Matrix3d> rotations;
  std::mt19937 rng(24);
  std::normal_distribution<double> normal;
  for (int i = 0; i < 2000; ++i) {
    rotations.push_back(Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
                            .normalized()
                            .toRotationMatrix());
  }
  // Half turns and within rounding of them, about several axes; none and almost none.
  for (double tiny : {0.0, 1e-13, -1e-13, 1e-9, -1e-7}) {
    for (const Vec3& axis : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 0, 1),
                             Vec3(-1, 2, 3), Vec3(0, -1, -1)}) {
      rotations.push_back(
          Eigen::AngleAxisd(slicer::kPi + tiny, axis.normalized()).toRotationMatrix());
      rotations.push_back(Eigen::AngleAxisd(tiny, axis.normalized()).toRotationMatrix());
    }
  }
  // Issue 20's row 21: quaternion (0, -0.7071, 0, -0.7071), a turn-0 pose: a half turn.
  rotations.push_back(
      rotation_of(Eigen::Vector4d(0.0, -std::sqrt(0.5), 0.0, -std::sqrt(0.5)).normalized()));
  for (const auto& r : rotations) {
    const Vec3 rv = rotation_vector(r);
    EXPECT_LT(ur_angle_between(rotation_of_vector(rv), r), 1e-9) << rv.transpose();
    EXPECT_LE(rv.norm(), slicer::kPi + 1e-12);
  }
}

TEST(UrFunctionName, IsAUrScriptIdentifier) {
  EXPECT_EQ(urscript_function_name("my-part"), "my_part");
  EXPECT_EQ(urscript_function_name("3d"), "p3d");
  EXPECT_EQ(urscript_function_name("end"), "strand_end");
  EXPECT_EQ(urscript_function_name("movel"), "strand_movel");
  EXPECT_EQ(urscript_function_name("a\"):\nend\xe2\x80\xa8"), "a____end___");
  EXPECT_EQ(urscript_function_name(std::string(100, 'p')).size(), 63u);
}

const std::string kUrNum = R"(-?[0-9]+\.[0-9]+)";

std::string ur_pose_re() {
  std::string p = "p\\[(" + kUrNum + ")";
  for (int i = 0; i < 5; ++i) p += ", (" + kUrNum + ")";
  return p + "\\]";
}

// The forms a script line may take; anything else is a defect (or an injection).
bool ur_known_line(const std::string& line) {
  const std::string n = kUrNum;
  const std::string joints =
      "\\[" + n + ", " + n + ", " + n + ", " + n + ", " + n + ", " + n + "\\]";
  static const std::vector<std::regex> kForms = {
      std::regex(R"(# [ -~]*)"),
      std::regex(R"(def [A-Za-z_][A-Za-z0-9_]{0,62}\(\):)"),
      std::regex(R"(  textmsg\("[ !#-\[\]-~]*"\))"),
      std::regex("  set_payload\\(" + n + ", \\[" + n + ", " + n + ", " + n + "\\]\\)  # [ -~]*"),
      std::regex("  movej\\(" + joints + ", a=" + n + ", v=" + n +
                 "\\)  # (home|clearance pose: [ -~]*)"),
      std::regex("  set_tcp\\(" + ur_pose_re() + "\\)  # layer [0-9]+ contact frame"),
      std::regex("  movel\\(" + ur_pose_re() + ", a=" + n + ", v=" + n + ", r=(0|" + n +
                 ")\\)(  # onto the first pose|  # retract along the nozzle axis|  # approach: [ -~]*|  # clearance pose: [ -~]*)?"),
      std::regex(R"(  # lap [0-9]+)"),
      std::regex(
          R"(  while \(get_standard_digital_in\([0-7]\) != (True|False)\):  # the extruder is ready for lap [0-9]+)"),
      std::regex(R"(    sync\(\))"),
      std::regex(R"(  end)"),
      std::regex(R"(  set_standard_digital_out\([0-7], (True|False)\)  # lap [0-9]+ starts)"),
      // Issue 29: the handshake reset before lap 0.
      std::regex(R"(  # handshake reset[ -~]*)"),
      std::regex(R"(  set_standard_digital_out\([0-7], (True|False)\)  # reset)"),
      std::regex(
          R"(  while \(get_standard_digital_in\([0-7]\) != (True|False)\):  # the extruder has finished and reset)"),
      std::regex(R"(end)"),
  };
  for (const auto& f : kForms)
    if (std::regex_match(line, f)) return true;
  return false;
}

Eigen::Isometry3d ur_pose_of(const std::smatch& g, int first) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() =
      1000.0 * Vec3(std::stod(g[first]), std::stod(g[first + 1]), std::stod(g[first + 2]));
  t.linear() = rotation_of_vector(
      Vec3(std::stod(g[first + 3]), std::stod(g[first + 4]), std::stod(g[first + 5])));
  return t;
}

void expect_urscript_follows_the_csv(const std::string& job_args) {
  const std::string dir = testing::fresh_dir("urscript");
  const auto r = testing::run_strand(job_args + " -o my-part.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(testing::exists(dir + "/my-part.script"));
  EXPECT_TRUE(testing::exists(dir + "/my-part.extruder.gcode"));
  EXPECT_FALSE(testing::exists(dir + "/my_part.src")) << "no KUKA programs for a UR cell";
  const std::string script = testing::slurp(dir + "/my-part.script");
  EXPECT_NE(script.find("\ndef my_part():\n"), std::string::npos);

  const MachineProfile m = load_profile("ur10e-wasp-cylinder");
  const auto rows = read_pose_csv(testing::slurp(dir + "/my-part.csv"), "my-part.csv");
  const ArmModel arm = arm_model(m.robot);
  const std::regex movel("  movel\\(" + ur_pose_re() +
                         ", a=[0-9.]+, v=([0-9.]+), r=[0-9.]+\\)(.*)");
  const std::regex set_tcp("  set_tcp\\(" + ur_pose_re() + "\\)  # .*");
  const std::regex movej("  movej\\(\\[(" + kUrNum + "), (" + kUrNum + "), (" + kUrNum + "), (" +
                         kUrNum + "), (" + kUrNum + "), (" + kUrNum + ")\\], .*  # (.*)");
  const std::regex wait(R"(  while \(get_standard_digital_in\(([0-7])\) != (True|False)\):.*)");
  const std::regex out(
      R"(  set_standard_digital_out\(([0-7]), (True|False)\)  # lap ([0-9]+) starts)");
  std::istringstream in(script);
  std::size_t row = 0, movejs = 0, movels = 0, waits = 0, laps = 0, resets = 0;
  double worst_mm = 0.0, worst_rad = 0.0, worst_speed = 0.0;
  Eigen::Isometry3d tcp_in_workpiece = Eigen::Isometry3d::Identity();
  bool have_tcp = false, retracted = false;
  std::string pending_wait;
  Eigen::Isometry3d previous = Eigen::Isometry3d::Identity();
  const auto workpiece = [](const slicer::PosePoint& p) {
    Eigen::Isometry3d w = Eigen::Isometry3d::Identity();
    w.translate(p.workpiece_origin_mm);
    w.rotate(rotation_of(p.workpiece_wxyz));
    return w;
  };
  const auto expect_pose = [&](const Eigen::Isometry3d& target, const slicer::PosePoint& pose) {
    const Eigen::Isometry3d w = target * tcp_in_workpiece.inverse();
    const Eigen::Isometry3d want = workpiece(pose);
    worst_mm = std::max(worst_mm, (w.translation() - want.translation()).norm());
    worst_rad = std::max(worst_rad, ur_angle_between(w.linear(), want.linear()));
  };
  for (std::string line; std::getline(in, line);) {
    EXPECT_TRUE(ur_known_line(line)) << line;
    std::smatch g;
    if (std::regex_match(line, g, movej)) {
      Joints q = Joints::Zero();
      for (int i = 0; i < 6; ++i) q[i] = std::stod(g[i + 1]);
      if (g[7].str().rfind("clearance pose", 0) == 0) {
        const Eigen::Isometry3d f = forward_kinematics(arm, q);
        const auto a = moved_along_nozzle(m.robot, rows[0], m.robot.motion.clearance_mm);
        const Eigen::Isometry3d want =
            flange_pose(m.robot, a.workpiece_origin_mm, a.workpiece_wxyz);
        EXPECT_LT((f.translation() - want.translation()).norm(), 0.01);
        EXPECT_LT(ur_angle_between(f.linear(), want.linear()), 1.75e-4);
        EXPECT_TRUE(within_limits(arm, q));
      } else {
        EXPECT_EQ(g[7].str(), "home");
        for (int i = 0; i < 6; ++i)
          EXPECT_NEAR(q[i], slicer::deg_to_rad((*m.robot.motion.home_joints_deg)[i]), 1e-6);
      }
      ++movejs;
    } else if (std::regex_match(line, g, set_tcp)) {
      // The TCP in the flange, back into the workpiece frame: the contact frame of the layer.
      tcp_in_workpiece = workpiece_in_flange(m.robot).inverse() * ur_pose_of(g, 1);
      EXPECT_TRUE(tcp_in_workpiece.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-6));
      EXPECT_LT(std::abs(tcp_in_workpiece.translation().y()), 1e-3);
      have_tcp = true;
    } else if (line.find("reset") != std::string::npos) {
      // Issue 29: before lap 0, both lines to the level before lap 0 (robot_handshake_test).
      ++resets;
    } else if (std::regex_match(line, g, wait)) {
      pending_wait = g[2];
      EXPECT_EQ(std::stoi(g[1]), m.robot.programs.ur_ready_input);
      ++waits;
    } else if (std::regex_match(line, g, out)) {
      EXPECT_EQ(pending_wait, g[2].str()) << "the robot waits for the level of the lap it starts";
      pending_wait.clear();
      ++laps;
    } else if (std::regex_match(line, g, movel)) {
      ASSERT_TRUE(have_tcp) << "set_tcp before the first movel";
      const Eigen::Isometry3d target = ur_pose_of(g, 1);
      if (g[8] == "  # onto the first pose") {
        expect_pose(target, rows[0]);
        previous = target;
        continue;
      }
      if (g[8].str().rfind("  # approach", 0) == 0) {
        expect_pose(target, moved_along_nozzle(m.robot, rows[0], m.robot.motion.approach_mm));
        continue;
      }
      if (g[8].str().rfind("  # clearance pose", 0) == 0) {
        expect_pose(target, moved_along_nozzle(m.robot, rows.back(), m.robot.motion.clearance_mm));
        continue;
      }
      if (g[8] == "  # retract along the nozzle axis") {
        expect_pose(target, moved_along_nozzle(m.robot, rows.back(), m.robot.motion.retract_mm));
        retracted = true;
        continue;
      }
      // The next CSV row that moves the TCP: zero-length motions are not written.
      for (++row; row < rows.size(); ++row) {
        const Eigen::Isometry3d t = workpiece(rows[row]) * tcp_in_workpiece;
        if ((t.translation() - previous.translation()).norm() > 1e-4 ||
            ur_angle_between(t.linear(), previous.linear()) > 1e-6)
          break;
      }
      ASSERT_LT(row, rows.size());
      expect_pose(target, rows[row]);
      worst_speed =
          std::max(worst_speed, std::abs(1000.0 * std::stod(g[7]) - rows[row].speed_mm_per_s));
      previous = target;
      ++movels;
    }
  }
  EXPECT_EQ(movejs, 3u) << "home, clearance pose, home";
  EXPECT_TRUE(retracted);
  EXPECT_GE(laps, 2u);
  EXPECT_EQ(waits, laps);
  EXPECT_EQ(resets, 5u) << "before lap 0 comment and output, after the last comment, wait, output";
  EXPECT_GT(movels, rows.size() / 2);
  EXPECT_LT(worst_mm, 0.01);
  EXPECT_LT(worst_rad, 1.75e-4);
  EXPECT_LT(worst_speed, 1e-3);
}

TEST(UrScriptWriter, TheScaffoldWithTurnZeroPosesMatchesTheCsv) {
  expect_urscript_follows_the_csv(std::string(kUrScaffold) + " --machine ur10e-wasp-cylinder");
}

TEST(UrScriptWriter, TheThesisPatternMatchesTheCsv) {
  expect_urscript_follows_the_csv(
      "missing-rib --nozzle 1.2 --rib 6 --rows 4 --cols 8 --layers 3 --substrate cylinder "
      "--substrate-radius 20 --substrate-length 80 --machine ur10e-wasp-cylinder");
}

// A copy of the shipped UR profile with some values changed, written into `dir`.
std::string ur_profile_with(const std::string& dir, const std::string& name) {
  nlohmann::json j;
  for (const auto& b : builtin_profiles())
    if (std::string(b.name) == "ur10e-wasp-cylinder") j = nlohmann::json::parse(b.json);
  j["name"] = name;
  const std::string path = dir + "/cell.json";
  std::ofstream(path) << j.dump(2);
  return path;
}

TEST(UrScriptWriter, HostileNamesStayTextAndTheScriptStillParses) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"a\"):\nend\nmovej([0,0,0,0,0,0])\n#.csv", "cell"},
      {"a\xe2\x80\xa8movej(x)\xc2\x85.csv", "cell\xe2\x80\xa8movej(x)"},
      {"a\\\"); halt()#.csv", "cell\r\nhalt()"},
      {"end.csv", "cell # ) \" \\ \\u000a"},
  };
  for (const auto& [output, name] : cases) {
    const std::string dir = testing::fresh_dir("ur-inject");
    const std::string machine = ur_profile_with(dir, name);
    const auto r = testing::run_strand(
        std::string(kUrScaffold) + " --machine " + ur_quoted(machine) + " -o " + ur_quoted(output),
        dir);
    if (name.find('\r') != std::string::npos) {
      testing::expect_input_error(r, "name");
      continue;
    }
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string script =
        testing::slurp(dir + "/" + output.substr(0, output.size() - 4) + ".script");
    ASSERT_FALSE(script.empty()) << output;
    std::istringstream in(script);
    int defs = 0;
    for (std::string line; std::getline(in, line);) {
      EXPECT_TRUE(ur_known_line(line)) << line;
      defs += line.rfind("def ", 0) == 0;
    }
    EXPECT_EQ(defs, 1);
    EXPECT_EQ(script.find("\nmovej(x"), std::string::npos);
    EXPECT_EQ(script.find("halt()\n"), std::string::npos);
  }
}

}  // namespace
}  // namespace strand::machines
