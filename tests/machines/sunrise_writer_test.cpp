// The Sunrise application as a controller would run it: written by `strand`, compiled with
// javac against stand-in RoboticsAPI classes (tests/data/sunrise_stubs) and run; every motion
// it commands is compared with the pose CSV it reads (issue 20: the 180 deg flip at turn 0).
// Hostile names and profile strings: sunrise_hostile_test.cpp.
#include "machines/sunrise_writer.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "machines/builtin_profiles.h"
#include "machines/contact_speed.h"
#include "machines/extruder_gcode.h"
#include "machines/joint_analysis.h"
#include "machines/krl_writer.h"
#include "machines/pose_csv.h"
#include "machines/profile.h"
#include "machines/robot_arm.h"
#include "machines/workpiece_pose.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/machines/sunrise_harness.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::machines {
namespace {

using slicer::Vec3;

using namespace sunrise_test;

Eigen::Isometry3d frame(double x, double y, double z, double a, double b, double c) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Vec3(x, y, z));
  t.rotate(Eigen::AngleAxisd(a, Vec3::UnitZ()) * Eigen::AngleAxisd(b, Vec3::UnitY()) *
           Eigen::AngleAxisd(c, Vec3::UnitX()));
  return t;
}

double angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

// Runs a robot job into a fresh directory with its csv_dir pointing there, compiles and runs
// the application, and checks every commanded motion against the CSV it read.
// `sunrise`: further robot.sunrise values. A tool template's frames and the nozzle frame of the
// application data are taken as calibrated where the profile says (the stand-ins log names).
void expect_application_follows_the_csv(const std::string& job_args,
                                        nlohmann::json sunrise = nlohmann::json::object()) {
  const std::string dir = testing::fresh_dir("sunrise");
  sunrise["csv_dir"] = dir;
  const bool from_template = sunrise.contains("tool_template");
  const std::string nozzle_frame = sunrise.value("nozzle_frame", "");
  const std::string machine = profile_with(dir, sunrise);
  // A job file names its machine inside ("MACHINE" is replaced); flags take --machine.
  std::string args = job_args;
  if (args.rfind("job ", 0) == 0) {
    const std::string job_file = args.substr(5, args.size() - 6);
    std::string text = testing::slurp(job_file);
    text.replace(text.find("\"MACHINE\""), 9, nlohmann::json(machine).dump());
    std::ofstream(job_file) << text;
  } else {
    args += " --machine " + quoted(machine);
  }
  const auto r = testing::run_strand(args + " -o p.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(testing::exists(dir + "/P.java")) << "the file is named after its class";
  ASSERT_EQ(compile(dir, "P.java"), "");
  const Shell run = run_java(dir, "P", "run");
  ASSERT_EQ(run.exit_code, 0) << run.out.substr(0, 2000);

  const MachineProfile m = load_profile(machine);
  const auto rows = read_pose_csv(testing::slurp(dir + "/p.csv"), "p.csv");
  const ArmModel arm = lbr_iiwa_14_r820(m.robot);
  std::map<std::string, Eigen::Isometry3d> contact_in_flange;
  // The flange pose the controller would take for a target of `moved` vs the one of a pose.
  double worst_mm = 0.0, worst_rad = 0.0;
  std::size_t worst_row = 0;
  const auto expect_flange = [&](const Eigen::Isometry3d& flange, const slicer::PosePoint& pose,
                                 std::size_t row) {
    const Eigen::Isometry3d want =
        flange_pose(m.robot, pose.workpiece_origin_mm, pose.workpiece_wxyz);
    const double mm = (flange.translation() - want.translation()).norm();
    const double rad = angle_between(flange.linear(), want.linear());
    if (mm > worst_mm || rad > worst_rad) worst_row = row;
    worst_mm = std::max(worst_mm, mm);
    worst_rad = std::max(worst_rad, rad);
  };
  std::vector<std::string> kinds;
  std::istringstream in(run.out);
  std::size_t next_row = 0, lins = 0, ptps = 0, accelerated = 0;
  bool approached = false;
  int signals = 0, lap = -1, resets = 0;
  std::string last_ready;
  const std::string idle = handshake_idle_level(m.robot) == 1 ? "true" : "false";
  // The contact point's speed at the commanded speeds (issue 37), from the targets alone.
  Eigen::Isometry3d previous_flange = Eigen::Isometry3d::Identity();
  double worst_ratio = 1.0;
  int deposit_moves = 0;
  std::map<int, double> lap_program_s, lap_csv_s;
  for (std::string line; std::getline(in, line);) {
    std::istringstream w(line);
    std::string kind, name;
    w >> kind >> name;
    if (kind != "READY" && (kinds.empty() || kinds.back() != kind)) kinds.push_back(kind);
    if (kind == "FRAME") {
      double v[6];
      for (double& x : v) w >> x;
      std::string parent;
      w >> parent;  // a frame of the template: the cylinder's, calibrated as in the profile
      EXPECT_EQ(parent, from_template ? sunrise.at("tool_frame").get<std::string>() : "");
      contact_in_flange[name] = (from_template ? workpiece_in_flange(m.robot)
                                               : Eigen::Isometry3d::Identity()) *
                                frame(v[0], v[1], v[2], v[3], v[4], v[5]);
    } else if (kind == "TEMPLATE") {
      EXPECT_EQ(name, sunrise.value("tool_template", ""));
    } else if (kind == "APP_FRAME") {
      EXPECT_EQ(name, nozzle_frame);
    } else if (kind == "LOAD_MASS") {
      EXPECT_FALSE(from_template) << "a template carries its own load data";
      EXPECT_EQ(std::stod(name), m.robot.motion.load_mass_kg);
    } else if (kind == "PTP_JOINTS") {
      double rel;
      Joints q;
      w >> rel;
      for (int i = 0; i < 7; ++i) w >> q[i];
      EXPECT_NEAR(rel, m.robot.motion.ptp_velocity_percent / 100.0, 1e-12);
      ++ptps;
      if (ptps == 2) {  // the clearance pose: clearance_mm off the first pose, by axis values
        const Eigen::Isometry3d f = forward_kinematics(arm, q);
        expect_flange(f, moved_along_nozzle(m.robot, rows[0], m.robot.motion.clearance_mm), 0);
      } else {  // home, first and last
        for (int i = 0; i < 7; ++i)
          EXPECT_NEAR(q[i], slicer::deg_to_rad((*m.robot.motion.home_joints_deg)[i]), 1e-6);
      }
    } else if (kind == "READY") {
      last_ready = name;
    } else if (kind == "SIGNAL" && resets == 0) {
      // Issue 29: before lap 0 the lap signal goes to the level before lap 0 (the extruder
      // waits for it).
      EXPECT_EQ(name, idle) << "the handshake reset comes first";
      EXPECT_EQ(next_row, 1u) << "the reset is right before lap 0";
      ++resets;
      last_ready.clear();
    } else if (kind == "SIGNAL" && next_row == rows.size()) {
      // After the last lap: back to the level before lap 0 once the extruder has reset.
      EXPECT_EQ(name, idle);
      EXPECT_EQ(last_ready, idle) << "the robot waited for the extruder's reset";
      ++resets;
    } else if (kind == "SIGNAL") {
      // The extruder waits for the level of the lap that starts next: it must come before
      // that lap's first motion, and after the extruder said it was ready with that level.
      ASSERT_LT(next_row, rows.size());
      EXPECT_NE(rows[next_row].lap, lap) << "one signal per lap, before its motions";
      lap = rows[next_row].lap;
      const std::string level = lap_signal_level(m.robot, lap) == 1 ? "true" : "false";
      EXPECT_EQ(name, level);
      EXPECT_EQ(last_ready, level) << "the robot waited for the extruder's ready level";
      last_ready.clear();
      ++signals;
    } else if (kind == "LIN") {
      std::string parent;
      double v[6], speed, blend;
      w >> parent;
      for (double& x : v) w >> x;
      w >> speed >> blend;
      // Relative to the nozzle frame: that frame calibrated where the profile puts the nozzle.
      Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
      EXPECT_EQ(parent, nozzle_frame.empty() ? "World" : nozzle_frame);
      if (!nozzle_frame.empty()) {
        base.translate(m.robot.nozzle_tip_mm);
        base.rotate(nozzle_frame_rotation(m.robot));
      }
      const Eigen::Isometry3d flange =
          base * frame(v[0], v[1], v[2], v[3], v[4], v[5]) * contact_in_flange.at(name).inverse();
      double acceleration = -1.0;
      if (w >> acceleration) {
        EXPECT_EQ(acceleration, *m.robot.motion.path_acceleration_mm_per_s2);
        ++accelerated;
      }
      ++lins;
      if (next_row == 0 && !approached) {  // from the clearance pose to the approach
        expect_flange(flange, moved_along_nozzle(m.robot, rows[0], m.robot.motion.approach_mm), 0);
        approached = true;
        previous_flange = flange;
        continue;
      }
      if (next_row >= rows.size()) {  // the retract, then the clearance pose
        const double away = next_row == rows.size() ? m.robot.motion.retract_mm
                                                    : m.robot.motion.clearance_mm;
        expect_flange(flange, moved_along_nozzle(m.robot, rows.back(), away), next_row);
        EXPECT_NEAR(speed, m.robot.travel_speed_mm_per_s, 1e-9);
        ++next_row;
        continue;
      }
      ASSERT_LT(next_row, rows.size());
      const auto& row = rows[next_row];
      EXPECT_EQ(name, "Contact" + std::to_string(row.layer));
      if (next_row > 0) {
        EXPECT_EQ(row.lap, lap) << "row " << next_row << " moves before its lap's signal";
        // The moved frame's chord from where the last motion left the arm, in the time the
        // commanded speed takes; the contact point (the nozzle tip in the workpiece) in it.
        const Eigen::Isometry3d& moved = contact_in_flange.at(name);
        const double frame_chord =
            ((flange * moved).translation() - (previous_flange * moved).translation()).norm();
        const auto contact_of = [&](const Eigen::Isometry3d& f) {
          return Vec3((f * workpiece_in_flange(m.robot)).inverse() * m.robot.nozzle_tip_mm);
        };
        const double contact_chord = (contact_of(flange) - contact_of(previous_flange)).norm();
        if (contact_chord > 1e-3) {  // a turn in place is off the time line by design
          lap_program_s[row.lap] += frame_chord / speed;
          lap_csv_s[row.lap] += row.t_s - rows[next_row - 1].t_s;
        }
        if (row.extrude && contact_chord >= kContactSpeedMinChordMm) {
          const double ratio = contact_chord / (frame_chord / speed) / row.speed_mm_per_s;
          if (std::abs(ratio - 1.0) > std::abs(worst_ratio - 1.0)) worst_ratio = ratio;
          ++deposit_moves;
        }
      }
      expect_flange(flange, row, next_row);
      previous_flange = flange;
      ++next_row;
    }
  }
  EXPECT_EQ(kinds.front(), from_template ? "TEMPLATE" : "LOAD_MASS");
  EXPECT_EQ(accelerated, rows.size() - 1) << "every lap motion at the profile's acceleration";
  EXPECT_EQ(kinds.back(), "PTP_JOINTS") << "home last";
  EXPECT_EQ(ptps, 3u) << "home, approach, home";
  EXPECT_EQ(lins, rows.size() + 3)
      << "to the approach, onto the first pose, one lin per later row, the retract and the "
         "clearance pose";
  EXPECT_GE(signals, 2);
  EXPECT_EQ(resets, 2) << "before lap 0 and after the last lap";
  EXPECT_GT(deposit_moves, 20);
  EXPECT_NEAR(worst_ratio, 1.0, 0.02) << "the contact point at the planned speed";
  for (const auto& [k, s] : lap_csv_s) {
    EXPECT_NEAR(lap_program_s[k] / s, 1.0, 0.02) << "lap " << k << " against the extruder's";
  }
  std::cout << "  Sunrise: " << deposit_moves << " deposit moves, worst contact / planned speed "
            << worst_ratio << "\n";
  EXPECT_LT(worst_mm, 0.01) << "worst at CSV row " << worst_row;
  EXPECT_LT(worst_rad, 1.75e-4) << "0.01 deg; worst at CSV row " << worst_row;
}

TEST(SunriseWriter, TheThesisCylinderRunsAsTheCsvSays) {
  // The sample job, on the test's copy of its machine.
  const std::string dir = testing::fresh_dir("thesis-job");
  auto job = nlohmann::json::parse(
      testing::slurp(std::string(STRAND_SOURCE_DIR) + "/samples/missing-rib-cylinder.json"));
  job["machine"] = "MACHINE";
  std::ofstream(dir + "/job.json") << job.dump();
  expect_application_follows_the_csv("job " + quoted(dir + "/job.json"));
}

TEST(SunriseWriter, TheScaffoldWithTurnZeroPosesDoesNotFlip) {
  // Issue 20's reproducer: row 21 is the quaternion (0, -0.7071, 0, -0.7071), B = -90 deg.
  expect_application_follows_the_csv(
      "scaffold --nozzle 0.8 --gap 1.5 --size 40x30 --layers 4 --substrate cylinder "
      "--substrate-radius 25 --substrate-length 60");
}

TEST(SunriseWriter, ToolTemplateAndNozzleFrameFromTheProjectRunAsTheCsvSays) {
  expect_application_follows_the_csv(
      "scaffold --nozzle 0.8 --gap 1.5 --size 40x30 --layers 4 --substrate cylinder "
      "--substrate-radius 25 --substrate-length 60",
      {{"tool_template", "StrandCylinder"}, {"tool_frame", "/Cylinder"},
       {"nozzle_frame", "/Cell/NozzleTip"}});
  // Each alone, too.
  expect_application_follows_the_csv(
      "scaffold --nozzle 0.8 --gap 1.5 --size 20x20 --layers 2 --substrate cylinder "
      "--substrate-radius 25 --substrate-length 60",
      {{"nozzle_frame", "/Nozzle"}});
  expect_application_follows_the_csv(
      "scaffold --nozzle 0.8 --gap 1.5 --size 20x20 --layers 2 --substrate cylinder "
      "--substrate-radius 25 --substrate-length 60",
      {{"tool_template", "Cyl_40"}, {"tool_frame", "/Cylinder"}});
}


TEST(SunriseWriter, OnAConcaveMeshTheContactPointMovesAtThePlannedSpeed) {
  // Issue 37: the moved frame is a point of the workpiece; where the workpiece tilts its
  // speed is scaled so the contact point keeps the row's speed (ratios 0.07-1.84 before).
  const std::string dir = testing::fresh_dir("bowl");
  expect_application_follows_the_csv(
      "scaffold --nozzle 0.8 --gap 1.5 --size 20x20 --layers 2 --substrate mesh "
      "--substrate-mesh " + quoted(testing::write_concave_bowl_obj(dir)));
}

}  // namespace
}  // namespace strand::machines
