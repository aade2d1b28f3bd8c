// The contact point at the planned speed on every controller (issue 37, item 1), recomputed
// from the programs' own text: for KRL, URScript and RAPID on a coarse concave mesh and on a
// cylinder, each deposit move's contact speed (the contact chord the program's targets give,
// over the time its programmed speed takes for its frame's chord) within 2 % of the CSV row's,
// and each lap's time at the programmed speeds within 2 % of the extruder's time line (the
// CSV's t_s). Sunrise is run against recording stubs in sunrise_writer_test.cpp.
#include "machines/contact_speed.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>

#include "machines/pose_csv.h"
#include "machines/profile.h"
#include "machines/urscript_writer.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::machines {
namespace {

using slicer::Vec3;


// One motion of a program: where the contact point ends (workpiece frame), how long the
// motion takes at its programmed speed, and its lap.
struct Motion {
  Vec3 contact;
  double time_s;
  int lap;
};

Eigen::Isometry3d ur_pose(const std::smatch& g, int at) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Vec3(std::stod(g[at]), std::stod(g[at + 1]), std::stod(g[at + 2])) * 1000.0);
  t.rotate(
      rotation_of_vector(Vec3(std::stod(g[at + 3]), std::stod(g[at + 4]), std::stod(g[at + 5]))));
  return t;
}

// URScript: TCP poses in the base frame (set_tcp gives the TCP on the flange); the contact
// point is the nozzle tip in the workpiece frame the TCP pose implies.
std::vector<Motion> urscript_motions(const std::string& text, const MachineProfile& m) {
  const std::string num = R"((-?[0-9.]+))";
  const std::string pose =
      "p\\[" + num + ", " + num + ", " + num + ", " + num + ", " + num + ", " + num + "\\]";
  const std::regex tcp_re("set_tcp\\(" + pose + "\\)");
  const std::regex movel_re("movel\\(" + pose + ", a=[0-9.]+, v=" + num + ", r=[0-9.]+\\)(.*)");
  const std::regex lap_re(R"(^  # lap (\d+))");
  const Eigen::Isometry3d workpiece_on_flange = workpiece_in_flange(m.robot);
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity(), flange = tcp;
  bool started = false;
  int lap = -1;
  std::vector<Motion> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    if (std::regex_search(line, g, lap_re)) lap = std::stoi(g[1]);
    if (std::regex_search(line, g, tcp_re)) tcp = ur_pose(g, 1);
    if (!std::regex_search(line, g, movel_re)) continue;
    const Eigen::Isometry3d target = ur_pose(g, 1);
    const Eigen::Isometry3d new_flange = target * tcp.inverse();
    const Vec3 contact = (new_flange * workpiece_on_flange).inverse() * m.robot.nozzle_tip_mm;
    const std::string comment = g[8];
    if (comment.find("retract") != std::string::npos) break;
    if (comment.find("approach") != std::string::npos) continue;  // from the clearance pose
    if (started) {
      const double chord = (target.translation() - (flange * tcp).translation()).norm();
      out.push_back({contact, chord / (1000.0 * std::stod(g[7])), lap});
    } else {
      out.push_back({contact, 0.0, -1});
    }
    started = true;
    flange = new_flange;
  }
  return out;
}

// KRL: LIN frames are the nozzle in the workpiece frame, $VEL.CP its speed in m/s.
std::vector<Motion> krl_motions(const std::string& text) {
  const std::string num = R"((-?[0-9.]+))";
  const std::regex lin_re("LIN \\{X " + num + ", Y " + num + ", Z " + num);
  const std::regex vel_re("\\$VEL.CP = " + num);
  const std::regex def_re(R"(^DEF LAP(\d+)_)");
  std::vector<Motion> out;
  double v = 0.0;
  int lap = -1;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    if (std::regex_search(line, g, def_re)) lap = std::stoi(g[1]);
    if (std::regex_search(line, g, vel_re)) v = 1000.0 * std::stod(g[1]);
    if (!std::regex_search(line, g, lin_re)) continue;
    const Vec3 p(std::stod(g[1]), std::stod(g[2]), std::stod(g[3]));
    if (line.find("onto the first pose") != std::string::npos) {
      out.insert(out.begin(), {p, 0.0, -1});
    } else if (lap >= 0) {  // the retract is in the main program, before the laps' DEFs
      out.push_back({p, (p - out.back().contact).norm() / v, lap});
    }
  }
  return out;
}

// RAPID: robtargets are the stationary tool (the nozzle) in the robot-held work object.
std::vector<Motion> rapid_motions(const std::string& text) {
  const std::string num = R"((-?[0-9.]+))";
  const std::regex speed_re("CONST speeddata (\\w+) := \\[" + num);
  const std::regex move_re("MoveL \\[\\[" + num + ", " + num + ", " + num + "\\].*\\], (\\w+), ");
  const std::regex proc_re(R"(PROC strandLap(\d+)_)");
  std::map<std::string, double> speeds;
  std::vector<Motion> out;
  int lap = -1;
  bool first = true;
  std::istringstream in(text);
  bool approach = false;  // the MoveL after "! approach" comes from the clearance pose
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    if (line.find("! approach") != std::string::npos) {
      approach = true;
      continue;
    }
    if (approach && std::regex_search(line, g, move_re)) {
      approach = false;
      continue;
    }
    if (std::regex_search(line, g, speed_re)) speeds[g[1]] = std::stod(g[2]);
    if (std::regex_search(line, g, proc_re)) lap = std::stoi(g[1]);
    if (!std::regex_search(line, g, move_re)) continue;
    const Vec3 p(std::stod(g[1]), std::stod(g[2]), std::stod(g[3]));
    if (first) {  // onto the first pose (main, before the retract)
      out.push_back({p, 0.0, -1});
      first = false;
    } else if (lap >= 0) {
      out.push_back({p, (p - out.back().contact).norm() / speeds.at(g[4]), lap});
    }
  }
  return out;
}

struct Figures {
  int deposit_moves = 0;
  double worst_ratio = 1.0;
  double worst_lap = 0.0;
};

// Matches each motion with its CSV row (rows repeating the previous target are not written)
// and compares speeds and lap times.
Figures compare(const std::vector<Motion>& motions, const std::vector<slicer::PosePoint>& rows) {
  Figures f;
  EXPECT_GT(motions.size(), 10u);
  std::size_t row = 0;
  std::map<int, double> program_s, csv_s;
  for (std::size_t k = 1; k < motions.size(); ++k) {
    const Motion& mo = motions[k];
    std::size_t j = row + 1;
    while (j < rows.size() && (rows[j].contact_mm - mo.contact).norm() > 2e-3) ++j;
    EXPECT_LT(j, rows.size()) << "motion " << k << " is no CSV row";
    if (j >= rows.size()) return f;
    const double contact = (mo.contact - motions[k - 1].contact).norm();
    if (contact > 1e-3) {  // a turn in place is off the time line by design
      program_s[mo.lap] += mo.time_s;
      for (std::size_t i = row + 1; i <= j; ++i)
        csv_s[rows[i].lap] += rows[i].t_s - rows[i - 1].t_s;
    }
    if (j == row + 1 && rows[j].extrude && contact >= kContactSpeedMinChordMm) {
      const double ratio = contact / mo.time_s / rows[j].speed_mm_per_s;
      ++f.deposit_moves;
      if (std::abs(ratio - 1.0) > std::abs(f.worst_ratio - 1.0)) f.worst_ratio = ratio;
    }
    row = j;
  }
  for (const auto& [lap, s] : csv_s) {
    const double d = (program_s[lap] - s) / s;
    if (std::abs(d) > std::abs(f.worst_lap)) f.worst_lap = d;
  }
  return f;
}

struct Job {
  std::string dir;
  std::vector<slicer::PosePoint> rows;
  MachineProfile machine;
};

Job run_job(const std::string& machine, bool mesh) {
  Job j{testing::fresh_dir("contact-speed"), {}, load_profile(machine)};
  const std::string substrate =
      mesh ? "--substrate mesh --substrate-mesh " + testing::write_concave_bowl_obj(j.dir)
           : std::string("--substrate cylinder --substrate-radius 25 --substrate-length 60");
  const auto r =
      testing::run_strand("scaffold --nozzle 0.8 --gap 1.5 --size 20x20 --layers 2 " + substrate +
                              " --machine " + machine + " -o p.csv --report p.json",
                          j.dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("contact speed"), std::string::npos) << r.out;
  j.rows = read_pose_csv(testing::slurp(j.dir + "/p.csv"), "p.csv");
  return j;
}

void expect_planned_speed(const Figures& f, const std::string& what) {
  EXPECT_GT(f.deposit_moves, 20) << what;
  EXPECT_NEAR(f.worst_ratio, 1.0, 0.02) << what << ": worst contact / planned speed";
  EXPECT_NEAR(f.worst_lap, 0.0, 0.02) << what << ": worst lap against the extruder";
  std::cout << "  " << what << ": " << f.deposit_moves << " deposit moves, worst ratio "
            << f.worst_ratio << ", worst lap " << 100.0 * f.worst_lap << " %\n";
}

TEST(ContactSpeed, UrScriptMovesTheContactPointAtThePlannedSpeed) {
  for (bool mesh : {true, false}) {
    const Job j = run_job("ur10e-wasp-cylinder", mesh);
    expect_planned_speed(
        compare(urscript_motions(testing::slurp(j.dir + "/p.script"), j.machine), j.rows),
        mesh ? "URScript on a concave mesh" : "URScript on a cylinder");
  }
}

TEST(ContactSpeed, KrlMovesTheContactPointAtThePlannedSpeed) {
  for (bool mesh : {true, false}) {
    const Job j = run_job("kuka-iiwa14-wasp-cylinder", mesh);
    expect_planned_speed(compare(krl_motions(testing::slurp(j.dir + "/p.src")), j.rows),
                         mesh ? "KRL on a concave mesh" : "KRL on a cylinder");
  }
}

TEST(ContactSpeed, RapidMovesTheContactPointAtThePlannedSpeed) {
  for (bool mesh : {true, false}) {
    const Job j = run_job("abb-irb1200-wasp-cylinder", mesh);
    expect_planned_speed(compare(rapid_motions(testing::slurp(j.dir + "/p.mod")), j.rows),
                         mesh ? "RAPID on a concave mesh" : "RAPID on a cylinder");
  }
}

TEST(ContactSpeed, TheSummaryReportsEveryProgramAndAScaledFrameKeepsTheTimeLine) {
  const Job j = run_job("kuka-iiwa14-wasp-cylinder", true);
  const auto report = nlohmann::json::parse(testing::slurp(j.dir + "/p.json"));
  const auto& programs = report.at("contact_speed").at("programs");
  ASSERT_EQ(programs.size(), 2u);
  for (const auto& p : programs) {
    EXPECT_NEAR(p.at("worst_ratio").get<double>(), 1.0, 0.02) << p.dump();
    EXPECT_LE(std::abs(p.at("worst_lap_time_difference_pct").get<double>()), 2.0) << p.dump();
  }
  // The moved frame at each row's own speed (the programs before issue 37) misses it.
  const auto& sunrise = programs.at(1);
  EXPECT_EQ(sunrise.at("program"), "Sunrise");
  EXPECT_GT(std::abs(sunrise.at("at_row_speed").at("worst_ratio").get<double>() - 1.0), 0.02);
}

}  // namespace
}  // namespace strand::machines
