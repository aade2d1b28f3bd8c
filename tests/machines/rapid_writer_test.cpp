// RAPID as an ABB controller would read it (issue 20 item 4): every line one of the forms the
// writer means to write, the module named as its file, a stationary tool and a robot-held work
// object, every robtarget converted back equal to its pose CSV row (turn-0 poses included),
// configuration data from the inverse kinematics, the lap handshake in order; hostile names and
// profile strings refused or kept as text (issue 24).
#include "machines/rapid_writer.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "machines/builtin_profiles.h"
#include "machines/joint_analysis.h"
#include "machines/pose_csv.h"
#include "machines/profile.h"
#include "machines/program_text.h"
#include "machines/robot_arm.h"
#include "machines/workpiece_pose.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"

namespace strand::machines {
namespace {

using slicer::Vec3;

double abb_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

std::string abb_quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

const char* const kAbbScaffold =
    "scaffold --nozzle 0.8 --gap 1.5 --size 40x30 --layers 4 --substrate cylinder "
    "--substrate-radius 25 --substrate-length 60";

Eigen::Matrix3d abb_rotation(double w, double x, double y, double z) {
  return Eigen::Quaterniond(w, x, y, z).toRotationMatrix();
}

Joints abb_deg(std::initializer_list<double> deg) {
  Joints q = Joints::Zero();
  int i = 0;
  for (double d : deg) q[i++] = slicer::deg_to_rad(d);
  return q;
}

TEST(AbbConfdata, QuadrantsAndTheWristCentreCase) {
  const MachineProfile m = load_profile("abb-irb1200-wasp-cylinder");
  const ArmModel arm = arm_model(m.robot);
  // The calibration posture: wrist in front of axis 1 and above the lower arm, axis 5 >= 0.
  EXPECT_EQ(abb_confdata(arm, abb_deg({0, 0, 0, 0, 0, 0})), (std::array<int, 4>{0, 0, 0, 0}));
  EXPECT_EQ(abb_confdata(arm, abb_deg({100, 0, 0, -10, -30, 200})),
            (std::array<int, 4>{1, -1, 2, 1}));
  EXPECT_EQ(abb_confdata(arm, abb_deg({-30, 0, 0, 0, 30, -95})),
            (std::array<int, 4>{-1, 0, -2, 0}));
  // Leaning back with the forearm up: the wrist centre behind axis 1.
  EXPECT_EQ(abb_confdata(arm, abb_deg({0, -90, 0, 0, 10, 0}))[3], 4);
  // The forearm folded back past the lower arm: the wrist centre below it.
  EXPECT_EQ(abb_confdata(arm, abb_deg({0, 40, -180, 0, 10, 0}))[3] & 2, 2);
}

TEST(AbbKinematics, TheCalibrationPostureMatchesTheDataSheet) {
  // IRB 1200-5/0.9 at all axes 0: wrist centre 448 + 399 mm above the base... along the
  // forearm: x = 451, z = 399 + 448 + 42; flange 82 mm further forward, pointing forward.
  const MachineProfile m = load_profile("abb-irb1200-wasp-cylinder");
  const ArmModel arm = arm_model(m.robot);
  const Eigen::Isometry3d f = forward_kinematics(arm, Joints::Zero());
  EXPECT_LT((f.translation() - Vec3(451.0 + 82.0, 0.0, 399.0 + 448.0 + 42.0)).norm(), 1e-9)
      << f.translation().transpose();
  EXPECT_LT((f.linear().col(2) - Vec3::UnitX()).norm(), 1e-9);
  // tool0 at the calibration posture: ABB's quaternion [0.707107, 0, 0.707107, 0].
  EXPECT_LT(abb_angle_between(f.linear(), abb_rotation(std::sqrt(0.5), 0, std::sqrt(0.5), 0)),
            1e-9);
  // Axis 2 positive tilts the upper arm forward, axis 3 positive the forearm down.
  EXPECT_GT(forward_kinematics(arm, abb_deg({0, 30, 0, 0, 0, 0})).translation().x(), 533.0);
  EXPECT_LT(forward_kinematics(arm, abb_deg({0, 0, 30, 0, 0, 0})).translation().z(), 889.0);
  // UR10e at all joints 0: stretched out along -x (a2 + a3), d4 along -y, d5 down... as UR's
  // published zero posture: flange at (-1184.25, -290.7, 60.85) mm.
  const MachineProfile u = load_profile("ur10e-wasp-cylinder");
  const Eigen::Isometry3d g = forward_kinematics(arm_model(u.robot), Joints::Zero());
  EXPECT_LT((g.translation() - Vec3(-1184.25, -290.7, 60.85)).norm(), 1e-9)
      << g.translation().transpose();
}

TEST(RapidNames, ModuleNamesAndIdentifiers) {
  EXPECT_EQ(rapid_module_name("my-part"), "my_part");
  EXPECT_EQ(rapid_module_name("3d"), "M3d");
  EXPECT_EQ(rapid_module_name("_x"), "M_x");
  EXPECT_EQ(rapid_module_name("MODULE"), "M_MODULE");
  EXPECT_EQ(rapid_module_name("endproc"), "M_endproc");
  EXPECT_EQ(rapid_module_name(std::string(50, 'p')).size(), 32u);
  EXPECT_TRUE(is_rapid_identifier(rapid_module_name("a\";ENDMODULE\n\xe2\x80\xa8")));
  EXPECT_NO_THROW(require_rapid_identifier("k", "doLapStart"));
  for (const std::string bad : {"", "_a", "9a", "a b", "a;b", "PROC", "endmodule", "caf\xc3\xa9",
                                "abcdefghijklmnopqrstuvwxyz0123456"}) {
    EXPECT_THROW(require_rapid_identifier("robot.rapid.lap_signal", bad), InputError) << bad;
  }
}

const std::regex& rapid_string_re() {
  static const std::regex r(R"re("([ !#-\[\]-~]|""|\\\\|\\[0-9A-F]{2})*")re");
  return r;
}

TEST(RapidStringLiteral, EscapesQuotesBackslashesAndEveryOtherByte) {
  EXPECT_EQ(rapid_string_literal("a\"b\\c"), "\"a\"\"b\\\\c\"");
  EXPECT_EQ(rapid_string_literal("a\nb\xe2\x80\xa8"), "\"a\\0Ab\\E2\\80\\A8\"");
  for (const std::string& s :
       std::vector<std::string>{"x\";ENDMODULE", "\\", "\r\n", std::string(300, '"')}) {
    const std::string lit = rapid_string_literal(s);
    EXPECT_TRUE(std::regex_match(lit, rapid_string_re())) << lit;
  }
  EXPECT_LE(rapid_string_literal(std::string(300, 'x')).size(), 82u);
}

const std::string kAbbNum = R"(-?[0-9]+(\.[0-9]+)?)";

std::string abb_list(int n) {
  std::string t = "\\[" + kAbbNum;
  for (int i = 1; i < n; ++i) t += ", " + kAbbNum;
  return t + "\\]";
}

std::string robtarget_re() {
  return "\\[" + abb_list(3) + ", " + abb_list(4) +
         ", \\[-?[0-9]+, -?[0-9]+, -?[0-9]+, [0-7]\\], \\[9E9, 9E9, 9E9, 9E9, 9E9, 9E9\\]\\]";
}

// The forms a module line may take; anything else is a defect (or an injection).
bool rapid_known_line(const std::string& line) {
  const std::string id = "[A-Za-z][A-Za-z0-9_]{0,31}";
  const std::string tw = ", " + id + "\\\\WObj:=" + id + ";";
  static const std::vector<std::regex> kForms = {
      std::regex("MODULE " + id),
      std::regex("ENDMODULE"),
      std::regex(R"(  ! [ -~]*)"),
      std::regex(R"(    ! [ -~]*)"),
      std::regex(""),
      std::regex("  PERS tooldata " + id + " := \\[FALSE, \\[" + abb_list(3) + ", " + abb_list(4) +
                 "\\], \\[" + kAbbNum + ", " + abb_list(3) + ", \\[1, 0, 0, 0\\], 0, 0, 0\\]\\];"),
      std::regex("  PERS wobjdata " + id + " := \\[TRUE, TRUE, \"\", \\[" + abb_list(3) + ", " +
                 abb_list(4) + "\\], \\[\\[0, 0, 0\\], \\[1, 0, 0, 0\\]\\]\\];"),
      std::regex("  CONST zonedata strandZone := \\[FALSE, " + kAbbNum + ", " + kAbbNum + ", " +
                 kAbbNum + ", 0.15, " + kAbbNum + ", 0.15\\];"),
      std::regex("  CONST speeddata strandV[0-9]+ := \\[" + kAbbNum + ", 500, 5000, 1000\\];"),
      std::regex("  CONST speeddata strandPtp := \\[" + kAbbNum + ", " + kAbbNum +
                 ", 5000, 1000\\];"),
      std::regex("  CONST jointtarget strand(Start|Home) := \\[" + abb_list(6) +
                 ", \\[9E9, 9E9, 9E9, 9E9, 9E9, 9E9\\]\\];"),
      std::regex("  PROC (main|strandLap[0-9]+_[0-9]+)\\(\\)"),
      std::regex("  ENDPROC"),
      std::regex(R"re(    TPWrite "([ !#-\[\]-~]|""|\\\\|\\[0-9A-F]{2})*";)re"),
      std::regex(R"(    ConfL\\On;)"),
      std::regex("    PathAccLim TRUE\\\\AccMax:=" + kAbbNum + ", TRUE\\\\DecelMax:=" + kAbbNum + ";"),
      std::regex("    MoveAbsJ strand(Home|Start), strandPtp, fine" + tw),
      std::regex("    MoveL " + robtarget_re() + ", strandV[0-9]+, (fine|strandZone)" + tw),
      std::regex("    WaitDI " + id + ", [01]\\\\MaxTime:=600;"),
      std::regex("    SetDO " + id + ", [01];"),
      std::regex("    strandLap[0-9]+_[0-9]+;"),
  };
  for (const auto& f : kForms)
    if (std::regex_match(line, f)) return true;
  return false;
}

void expect_rapid_follows_the_csv(const std::string& job_args) {
  const std::string dir = testing::fresh_dir("rapid");
  const auto r = testing::run_strand(job_args + " -o my-part.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(testing::exists(dir + "/my_part.mod")) << "the module is named as its file";
  EXPECT_TRUE(testing::exists(dir + "/my-part.extruder.gcode"));
  const std::string mod = testing::slurp(dir + "/my_part.mod");
  EXPECT_EQ(mod.rfind("MODULE my_part\n", 0), 0u);

  const MachineProfile m = load_profile("abb-irb1200-wasp-cylinder");
  const ArmModel arm = arm_model(m.robot);
  const auto rows = read_pose_csv(testing::slurp(dir + "/my-part.csv"), "my-part.csv");
  const std::string n = "(-?[0-9]+(?:\\.[0-9]+)?)";
  const std::regex tool("  PERS tooldata (\\w+) := \\[FALSE, \\[\\[" + n + ", " + n + ", " + n +
                        "\\], \\[" + n + ", " + n + ", " + n + ", " + n + "\\]\\].*");
  const std::regex wobj("  PERS wobjdata (\\w+) := \\[TRUE, TRUE, \"\", \\[\\[" + n + ", " + n +
                        ", " + n + "\\], \\[" + n + ", " + n + ", " + n + ", " + n + "\\]\\].*");
  const std::regex move(
      "    MoveL \\[\\[" + n + ", " + n + ", " + n + "\\], \\[" + n + ", " + n + ", " + n + ", " +
      n +
      "\\], \\[(-?[0-9]+), (-?[0-9]+), (-?[0-9]+), ([0-7])\\].*, (strandV[0-9]+), "
      "(fine|strandZone), (\\w+)\\\\WObj:=(\\w+);");
  const std::regex speed("  CONST speeddata (strandV[0-9]+) := \\[" + n + ", .*");
  const std::regex start("  CONST jointtarget strandStart := \\[\\[" + n + ", " + n + ", " + n +
                         ", " + n + ", " + n + ", " + n + "\\].*");
  const std::regex wait(R"(    WaitDI (\w+), ([01])\\MaxTime:=600;)");
  const std::regex setdo(R"(    SetDO (\w+), ([01]);)");
  std::map<std::string, double> speeds;
  Eigen::Matrix3d nozzle = Eigen::Matrix3d::Identity();
  std::string tool_name, wobj_name, pending_wait, comment;
  std::size_t row = 0, moves = 0, waits = 0, laps = 0;
  double worst_mm = 0.0, worst_rad = 0.0, worst_speed = 0.0;
  bool first = true, retracted = false;
  Vec3 previous_p = Vec3::Zero();
  Eigen::Matrix3d previous_r = Eigen::Matrix3d::Identity();
  const auto want_rotation = [&](const slicer::PosePoint& p) {
    return Eigen::Matrix3d(rotation_of(p.workpiece_wxyz).transpose() * nozzle);
  };
  std::istringstream in(mod);
  for (std::string line; std::getline(in, line);) {
    EXPECT_TRUE(rapid_known_line(line)) << line;
    std::smatch g;
    if (std::regex_match(line, g, tool)) {
      tool_name = g[1];
      const Vec3 tip(std::stod(g[2]), std::stod(g[3]), std::stod(g[4]));
      EXPECT_LT((tip - m.robot.nozzle_tip_mm).norm(), 1e-3);
      nozzle = abb_rotation(std::stod(g[5]), std::stod(g[6]), std::stod(g[7]), std::stod(g[8]));
      EXPECT_LT((nozzle.col(2) - m.robot.nozzle_axis).norm(), 1e-6) << "tool z along the flow";
    } else if (std::regex_match(line, g, wobj)) {
      wobj_name = g[1];
      const Eigen::Isometry3d wf = workpiece_in_flange(m.robot);
      EXPECT_LT((Vec3(std::stod(g[2]), std::stod(g[3]), std::stod(g[4])) - wf.translation()).norm(),
                1e-3);
      EXPECT_LT(abb_angle_between(abb_rotation(std::stod(g[5]), std::stod(g[6]), std::stod(g[7]),
                                               std::stod(g[8])),
                                  wf.linear()),
                1e-7);
    } else if (std::regex_match(line, g, speed)) {
      speeds[g[1]] = std::stod(g[2]);
    } else if (std::regex_match(line, g, start)) {
      Joints q = Joints::Zero();
      for (int i = 0; i < 6; ++i) q[i] = slicer::deg_to_rad(std::stod(g[i + 1]));
      const Eigen::Isometry3d f = forward_kinematics(arm, q);
      const auto a = moved_along_nozzle(m.robot, rows[0], m.robot.motion.clearance_mm);
      const Eigen::Isometry3d want = flange_pose(m.robot, a.workpiece_origin_mm, a.workpiece_wxyz);
      EXPECT_LT((f.translation() - want.translation()).norm(), 0.01);
      EXPECT_LT(abb_angle_between(f.linear(), want.linear()), 1.75e-4);
      EXPECT_TRUE(within_limits(arm, q));
    } else if (comment.find("reset") != std::string::npos) {
      // Issue 29: before lap 0 and after the last lap, the lines to the level before lap 0
      // (robot_handshake_test).
    } else if (std::regex_match(line, g, wait)) {
      EXPECT_EQ(g[1].str(), m.robot.programs.rapid_ready_signal);
      pending_wait = g[2];
      ++waits;
    } else if (std::regex_match(line, g, setdo)) {
      EXPECT_EQ(g[1].str(), m.robot.programs.rapid_lap_signal);
      EXPECT_EQ(pending_wait, g[2].str()) << "the robot waits for the level of the lap it starts";
      pending_wait.clear();
      ++laps;
    } else if (std::regex_match(line, g, move)) {
      EXPECT_EQ(g[14].str(), tool_name);
      EXPECT_EQ(g[15].str(), wobj_name);
      const Vec3 p(std::stod(g[1]), std::stod(g[2]), std::stod(g[3]));
      const Eigen::Matrix3d rot =
          abb_rotation(std::stod(g[4]), std::stod(g[5]), std::stod(g[6]), std::stod(g[7]));
      const Eigen::Vector4d q(std::stod(g[4]), std::stod(g[5]), std::stod(g[6]), std::stod(g[7]));
      EXPECT_NEAR(q.norm(), 1.0, 1e-6) << "RAPID wants normalised quaternions";
      const auto expect_pose = [&](const slicer::PosePoint& pose) {
        worst_mm = std::max(worst_mm, (p - pose.contact_mm).norm());
        worst_rad = std::max(worst_rad, abb_angle_between(rot, want_rotation(pose)));
      };
      if (comment == "approach") {  // from the clearance pose
        expect_pose(moved_along_nozzle(m.robot, rows[0], m.robot.motion.approach_mm));
        continue;
      }
      if (comment == "clearance pose") {
        expect_pose(moved_along_nozzle(m.robot, rows.back(), m.robot.motion.clearance_mm));
        continue;
      }
      if (first) {
        EXPECT_EQ(comment, "onto the first pose");
        expect_pose(rows[0]);
        previous_p = rows[0].contact_mm, previous_r = want_rotation(rows[0]);
        first = false;
        continue;
      }
      if (comment == "retract along the nozzle axis") {
        expect_pose(moved_along_nozzle(m.robot, rows.back(), m.robot.motion.retract_mm));
        retracted = true;
        continue;
      }
      for (++row; row < rows.size(); ++row) {
        if ((rows[row].contact_mm - previous_p).norm() > 1e-4 ||
            abb_angle_between(want_rotation(rows[row]), previous_r) > 1e-6)
          break;
      }
      ASSERT_LT(row, rows.size());
      expect_pose(rows[row]);
      ASSERT_TRUE(speeds.count(g[12]));
      worst_speed = std::max(worst_speed, std::abs(speeds[g[12]] - rows[row].speed_mm_per_s));
      previous_p = rows[row].contact_mm, previous_r = want_rotation(rows[row]);
      ++moves;
    }
    comment = line.rfind("    ! ", 0) == 0 ? line.substr(6) : "";
  }
  EXPECT_TRUE(retracted);
  EXPECT_GE(laps, 2u);
  EXPECT_EQ(waits, laps);
  EXPECT_GT(moves, rows.size() / 2);
  EXPECT_LT(worst_mm, 0.01);
  EXPECT_LT(worst_rad, 1.75e-4);
  EXPECT_LT(worst_speed, 1e-3);
}

TEST(RapidWriter, TheScaffoldWithTurnZeroPosesMatchesTheCsv) {
  expect_rapid_follows_the_csv(std::string(kAbbScaffold) + " --machine abb-irb1200-wasp-cylinder");
}

TEST(RapidWriter, TheThesisPatternMatchesTheCsv) {
  expect_rapid_follows_the_csv(
      "missing-rib --nozzle 1.2 --rib 6 --rows 4 --cols 8 --layers 3 --substrate cylinder "
      "--substrate-radius 20 --substrate-length 80 --machine abb-irb1200-wasp-cylinder");
}

std::string abb_profile_with(const std::string& dir, const nlohmann::json& rapid,
                             const std::string& name = "abb-test-cell") {
  nlohmann::json j;
  for (const auto& b : builtin_profiles())
    if (std::string(b.name) == "abb-irb1200-wasp-cylinder") j = nlohmann::json::parse(b.json);
  j["name"] = name;
  for (const auto& [k, v] : rapid.items()) j["robot"]["rapid"][k] = v;
  const std::string path = dir + "/cell.json";
  std::ofstream(path) << j.dump(2);
  return path;
}

TEST(RapidWriter, HostileNamesStayTextAndTheModuleStillParses) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"a\";ENDMODULE\nMODULE x\n!.csv", "cell"},
      {"a\xe2\x80\xa8"
       "ENDPROC\xc2\x85.csv",
       "cell\xe2\x80\xa8"
       "ENDMODULE"},
      {"proc.csv", "cell ! \" \\ ENDMODULE"},
      {std::string(60, 'q') + ".csv", "cell"},
  };
  for (const auto& [output, name] : cases) {
    const std::string dir = testing::fresh_dir("rapid-inject");
    const std::string machine = abb_profile_with(dir, nlohmann::json::object(), name);
    const auto r = testing::run_strand(std::string(kAbbScaffold) + " --machine " +
                                           abb_quoted(machine) + " -o " + abb_quoted(output),
                                       dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string module = rapid_module_name(output.substr(0, output.size() - 4));
    ASSERT_TRUE(is_rapid_identifier(module)) << module;
    const std::string mod = testing::slurp(dir + "/" + module + ".mod");
    ASSERT_FALSE(mod.empty()) << module;
    std::istringstream in(mod);
    int modules = 0, ends = 0;
    for (std::string line; std::getline(in, line);) {
      EXPECT_TRUE(rapid_known_line(line)) << line;
      modules += line.rfind("MODULE ", 0) == 0;
      ends += line == "ENDMODULE";
    }
    EXPECT_EQ(modules, 1);
    EXPECT_EQ(ends, 1);
  }
}

TEST(RapidWriter, ToolAndWorkObjectFromTheControllerAreUsedNotDeclared) {
  const std::string dir = testing::fresh_dir("rapid-controller");
  const std::string plain = testing::fresh_dir("rapid-plain");
  const std::string machine =
      abb_profile_with(dir, {{"tool", "tCalNozzle"}, {"tool_on_controller", true},
                             {"wobj", "wobjCal"}, {"wobj_on_controller", true}});
  const std::string base = abb_profile_with(plain, {{"tool", "tCalNozzle"}, {"wobj", "wobjCal"}});
  for (const auto& [d, m] : {std::pair{dir, machine}, std::pair{plain, base}}) {
    const auto r = testing::run_strand(
        std::string(kAbbScaffold) + " --machine " + abb_quoted(m) + " -o p.csv", d);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string mod = testing::slurp(dir + "/p.mod");
  EXPECT_EQ(mod.find("PERS tooldata"), std::string::npos) << "declared on the controller";
  EXPECT_EQ(mod.find("PERS wobjdata"), std::string::npos);
  EXPECT_NE(mod.find(", tCalNozzle\\WObj:=wobjCal;"), std::string::npos);
  EXPECT_NE(mod.find("PathAccLim TRUE\\AccMax:=0.500, TRUE\\DecelMax:=0.500;"), std::string::npos)
      << "the profile's path acceleration, as the lap timing assumes";
  std::istringstream in(mod);
  for (std::string line; std::getline(in, line);) EXPECT_TRUE(rapid_known_line(line)) << line;
  // Apart from the declarations (and their comment) the modules are the same.
  std::string without = testing::slurp(plain + "/p.mod");
  for (const char* decl : {"  PERS tooldata", "  PERS wobjdata", "  ! tCalNozzle"}) {
    const std::size_t at = without.find(decl);
    ASSERT_NE(at, std::string::npos) << decl;
    without.erase(at, without.find('\n', at) + 1 - at);
  }
  std::string with = mod;
  const std::size_t at = with.find("  ! tCalNozzle and wobjCal: PERS data");
  ASSERT_NE(at, std::string::npos);
  with.erase(at, with.find('\n', at) + 1 - at);
  EXPECT_EQ(with, without);
}

TEST(RapidWriter, ProfileNamesMustBeRapidIdentifiers) {
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"tool", "t;ENDMODULE"},
                                                        {"wobj", "PROC"},
                                                        {"lap_signal", "do\nLap"},
                                                        {"ready_signal", "_ready"},
                                                        {"tool", std::string(33, 't')}}) {
    const std::string dir = testing::fresh_dir("rapid-ident");
    const std::string machine = abb_profile_with(dir, {{key, value}});
    const auto r = testing::run_strand(
        std::string(kAbbScaffold) + " --machine " + abb_quoted(machine) + " -o p.csv", dir);
    testing::expect_input_error(r, "robot.rapid." + key);
    EXPECT_FALSE(testing::exists(dir + "/p.csv"));
    EXPECT_FALSE(testing::exists(dir + "/p.mod"));
  }
}

}  // namespace
}  // namespace strand::machines
