// The thesis cylinder specimen end to end, and a rotary sleeve: the properties every output
// of a pose program must have (issue 11's tests).
#include "postprocess/plan/produce_curved.h"

#include <gtest/gtest.h>

#include <regex>

#include "machines/extruder_gcode.h"
#include "postprocess/plan/lap_timing.h"
#include "machines/joint_analysis.h"
#include "machines/krl_writer.h"
#include "machines/pose_csv.h"
#include "machines/rotary_gcode.h"
#include "machines/workpiece_pose.h"
#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"

namespace strand::post {
namespace {

using slicer::Vec3;

struct Job {
  slicer::Toolpath toolpath;
  slicer::SubstrateSpec substrate;
  machines::MachineProfile machine;
};

Job sample_job(const std::string& file) {
  const auto j = nlohmann::json::parse(testing::slurp(testing::samples_dir() + "/" + file));
  const auto* g = patterns::find_generator(j.at("generator"));
  Job job{g->generate(slicer::resolve_params(g->table(), j.at("params"))),
          *slicer::substrate_from(j.at("substrate")), machines::load_profile(j.at("machine"))};
  return job;
}

const CurvedProduced& thesis() {
  static const CurvedProduced p = [] {
    const Job j = sample_job("missing-rib-cylinder.json");
    return produce_curved(j.toolpath, j.substrate, j.machine, 0.01, "part.csv");
  }();
  return p;
}

const std::string& file(const CurvedProduced& p, const std::string& path) {
  for (const auto& [name, content] : p.files) {
    if (name == path) return content;
  }
  static const std::string none;
  ADD_FAILURE() << "no " << path;
  return none;
}

TEST(ProduceCurved, RobotCellWritesTheFiveFilesFromOnePoseProgram) {
  std::vector<std::string> names;
  for (const auto& f : thesis().files) names.push_back(f.first);
  EXPECT_EQ(names, (std::vector<std::string>{"part.csv", "Part.java", "part.src", "part.dat",
                                             "part.extruder.gcode"}))
      << "Sunrise and KSS load programs from files named after their class and module";
  EXPECT_EQ(file(thesis(), "part.csv").substr(0, std::string(machines::kPoseCsvHeader).size() + 1),
            std::string(machines::kPoseCsvHeader) + "\n");
}

TEST(ProduceCurved, EveryCsvRowPutsTheContactOnTheTipWithTheNormalAgainstTheNozzle) {
  const auto m = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  const auto rows = machines::read_pose_csv(file(thesis(), "part.csv"), "part.csv");
  ASSERT_EQ(rows.size(), thesis().program.points.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Eigen::Matrix3d r = machines::rotation_of(rows[i].workpiece_wxyz);
    EXPECT_LT((r * rows[i].contact_mm + rows[i].workpiece_origin_mm - m.robot.nozzle_tip_mm).norm(),
              0.01)
        << i;
    const double angle =
        std::acos(std::clamp((r * rows[i].normal).dot(-m.robot.nozzle_axis), -1.0, 1.0));
    EXPECT_LT(slicer::rad_to_deg(angle), 0.1) << i;
  }
}

TEST(ProduceCurved, ThreeLayersOfForwardAndReturnLapsAsInTheThesis) {
  const auto& p = thesis().program;
  ASSERT_EQ(p.layers.size(), 3u);
  ASSERT_EQ(p.laps.size(), 6u);
  for (std::size_t k = 0; k < p.laps.size(); ++k) {
    EXPECT_EQ(p.laps[k].layer, static_cast<int>(k / 2));
    EXPECT_EQ(p.laps[k].direction, k % 2 == 0 ? 1 : -1);
  }
  // Deposits run at v_cart; the time line is chord length over speed.
  for (std::size_t i = 1; i < p.points.size(); ++i) {
    const auto& a = p.points[i - 1];
    const auto& b = p.points[i];
    if (b.extrude) {
      EXPECT_DOUBLE_EQ(b.speed_mm_per_s, 6.0);
    }
    EXPECT_NEAR(b.t_s - a.t_s, (b.contact_mm - a.contact_mm).norm() / b.speed_mm_per_s, 1e-9);
  }
}

TEST(ProduceCurved, LapsNeverTakeA7PastItsLimit) {
  const auto m = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  const auto arm = machines::lbr_iiwa_14_r820(m.robot);
  const auto r = machines::analyse_joints(arm, m.robot, thesis().program.points);
  ASSERT_TRUE(r.ok());
  EXPECT_LE(std::abs(slicer::rad_to_deg(r.min_rad[6])), 175.0);
  EXPECT_LE(std::abs(slicer::rad_to_deg(r.max_rad[6])), 175.0);
}

double deposited_mm(const slicer::PoseProgram& p) {
  double len = 0.0;
  for (std::size_t i = 1; i < p.points.size(); ++i) {
    if (p.points[i].extrude) len += (p.points[i].contact_mm - p.points[i - 1].contact_mm).norm();
  }
  return len;
}

// E and seconds of the extruder's program per lap (";LAP:k" starts lap k).
struct ExtruderLaps {
  std::vector<double> e, seconds;
};

ExtruderLaps extruder_laps(const std::string& g) {
  ExtruderLaps out;
  const std::regex move(R"(^G1 E([0-9.]+) F([0-9.]+)$)"), dwell(R"(^G4 P([0-9]+))"),
      lap(R"(^;LAP:([0-9]+))");
  std::istringstream in(g.substr(g.find("\nM400")));  // after parking, E only
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, lap)) {
      EXPECT_EQ(std::stoul(m[1]), out.e.size());
      out.e.push_back(0.0), out.seconds.push_back(0.0);
    }
    if (std::regex_search(line, m, move))
      out.e.back() += std::stod(m[1]), out.seconds.back() += std::stod(m[1]) / std::stod(m[2]) * 60.0;
    if (std::regex_search(line, m, dwell)) out.seconds.back() += std::stod(m[1]) / 1000.0;
    if (line.rfind("G1", 0) == 0) {
      EXPECT_EQ(line.find(" X"), std::string::npos) << line;
    }
  }
  return out;
}

TEST(ProduceCurved, ExtruderEPerLapIsVextTimesTheLapsPlannedDepositTime) {
  const auto m = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  const auto& p = thesis().program;
  const LapTiming timing = time_laps(p, corner_model_for(m, 0.01));
  // The robot's deposit time per lap, corner slowdowns included.
  std::vector<double> deposit_s(p.laps.size(), 0.0);
  for (std::size_t i = 1; i < p.points.size(); ++i)
    if (p.points[i].extrude)
      deposit_s[static_cast<std::size_t>(p.points[i].lap)] += timing.t_s[i] - timing.t_s[i - 1];
  const ExtruderLaps x = extruder_laps(file(thesis(), "part.extruder.gcode"));
  ASSERT_EQ(x.e.size(), p.laps.size());
  double e = 0.0;
  for (std::size_t k = 0; k < p.laps.size(); ++k) {
    const double expected = 100.0 / 60.0 * deposit_s[k];  // v_ext = 100 mm/min
    EXPECT_NEAR(x.e[k], expected, expected * 0.005) << "lap " << k;
    // The lap takes as long in the extruder as the robot needs for it.
    EXPECT_NEAR(x.seconds[k], timing.planned_s[k], 0.002 * timing.planned_s[k] + 0.002) << k;
    EXPECT_GT(timing.planned_s[k], timing.nominal_s[k]) << "the corners slow every lap";
    EXPECT_NEAR(thesis().report.at("laps")[k].at("e").get<double>(), x.e[k], 0.01);
    EXPECT_NEAR(thesis().report.at("laps")[k].at("planned_time_s").get<double>(),
                timing.planned_s[k], 0.01);
    e += x.e[k];
  }
  // More than v_ext / v_cart x the deposited length: the corners take longer.
  EXPECT_GT(e, 1.02 * 100.0 / (6.0 * 60.0) * deposited_mm(p));
  EXPECT_NEAR(thesis().report.at("ink").at("e_total").get<double>(), e, 0.01);
  EXPECT_NE(thesis().summary.find("\n  lap timing     laps timed with corner slowdowns: +4.8 % "
                                  "over distance/speed"),
            std::string::npos)
      << thesis().summary;
}

TEST(ProduceCurved, ExtrusionTimeOrVolumetricChoosesWhatDrivesE) {
  Job j = sample_job("missing-rib-cylinder.json");
  const auto& l = j.toolpath.layers.front().strokes.front();
  for (const std::string mode : {"time", "volumetric"}) {
    j.substrate.extrusion = mode;
    j.machine.robot.extruder.time_based = mode != "time";  // the flag wins over the profile
    const auto out = produce_curved(j.toolpath, j.substrate, j.machine, 0.01, "x.csv");
    const ExtruderLaps x = extruder_laps(file(out, "x.extruder.gcode"));
    double e = 0.0;
    for (double v : x.e) e += v;
    const double ratio = out.report.at("ink").at("extruder_to_bead_ratio").get<double>();
    EXPECT_EQ(out.report.at("ink").at("extrusion"), mode);
    // Extruder and bead volumes are printed in both modes.
    EXPECT_NE(out.summary.find(" mL from the extruder, beads 3.53 mL)"), std::string::npos)
        << out.summary;
    const bool warned = out.summary.find("warning        the extruder delivers") != std::string::npos;
    if (mode == "volumetric") {
      const double expected = slicer::bead_area_mm2(l.width_mm, l.height_mm) *
                              deposited_mm(out.program) / j.machine.deposition.mm3_per_e;
      EXPECT_NEAR(e, expected, expected * 0.005);
      EXPECT_NEAR(ratio, 1.0, 0.01) << "balanced";
      EXPECT_FALSE(warned) << out.summary;
    } else {
      EXPECT_NEAR(ratio, 0.34, 0.01);
      EXPECT_TRUE(warned) << out.summary;
      EXPECT_NE(out.summary.find("or use --extrusion volumetric"), std::string::npos);
    }
  }
  // A rotary printer has no separate extruder to choose for.
  Job r = sample_job("scaffold-cylinder-rotary.json");
  r.substrate.extrusion = "time";
  EXPECT_THROW(produce_curved(r.toolpath, r.substrate, r.machine, 0.01, "r.gcode"), InputError);
}

TEST(ProduceCurved, AVolumetricExtruderPushesTheBeadVolume) {
  Job j = sample_job("missing-rib-cylinder.json");
  j.machine.robot.extruder.time_based = false;
  j.machine.robot.extruder.handshake_pin = -1;
  const auto out = produce_curved(j.toolpath, j.substrate, j.machine, 0.01, "v.csv");
  const std::string g = file(out, "v.extruder.gcode");
  double e = 0.0;
  std::istringstream in(g);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("G1 E", 0) == 0) e += std::stod(line.substr(4));
  }
  const auto& l = j.toolpath.layers.front().strokes.front();
  const double expected = slicer::bead_area_mm2(l.width_mm, l.height_mm) * deposited_mm(out.program) / j.machine.deposition.mm3_per_e;
  EXPECT_NEAR(e, expected, expected * 0.005);
  EXPECT_EQ(g.find("M226"), std::string::npos) << "no handshake without a pin";
}

TEST(ProduceCurved, EveryEMoveIsWithinTheFirmwaresLimitAndLapsWaitForTheRobot) {
  const std::string g = file(thesis(), "part.extruder.gcode");
  std::istringstream in(g);
  int waits = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("G1 E", 0) == 0) {
      EXPECT_LE(std::stod(line.substr(4)), 200.0) << line;
    }
    if (line.rfind("M226 P3 S", 0) == 0 && line.find("reset") == std::string::npos) ++waits;
  }
  EXPECT_EQ(waits, 6);
  EXPECT_NE(g.find("M226 P3 S0 ; reset: wait for the robot's reset"), std::string::npos)
      << "issue 29: the robot's reset before lap 0";
  EXPECT_NE(g.find("M83"), std::string::npos);
  EXPECT_NE(g.find("M302 S0"), std::string::npos);
  EXPECT_NE(g.find("G1 X0.000 Y-90.000 Z244.000"), std::string::npos)
      << "parks where the thesis touched the cylinder";
}

TEST(ProduceCurved, EveryKrlLinParsesAndSpeedsAreInMetresPerSecond) {
  const auto m = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  const std::string src = file(thesis(), "part.src");
  const std::regex lin(
      R"(^  LIN \{X (-?[0-9.]+), Y (-?[0-9.]+), Z (-?[0-9.]+), A (-?[0-9.]+), B (-?[0-9.]+), C (-?[0-9.]+)\} C_DIS$)");
  const std::regex vel(R"(^  \$VEL\.CP = ([0-9.]+) ; m/s$)");
  std::istringstream in(src);
  std::size_t lins = 0, i = 1;
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    // The LINs of the lap sub-programs (not the approach onto the first pose or the retract).
    if (line.find("LIN ") != std::string::npos && line.find(" C_DIS") != std::string::npos) {
      ASSERT_TRUE(std::regex_match(line, g, lin)) << line;
      // The nozzle frame in the workpiece frame: rebuild the base-frame tip from the CSV pose.
      // Points that repeat the previous pose are not written.
      const auto& pts = thesis().program.points;
      while (i + 1 < pts.size() && (pts[i].contact_mm - pts[i - 1].contact_mm).norm() < 1e-5 &&
             (pts[i].workpiece_wxyz - pts[i - 1].workpiece_wxyz).norm() < 1e-9)
        ++i;
      const auto& pt = pts[i++];
      const Vec3 p(std::stod(g[1]), std::stod(g[2]), std::stod(g[3]));
      const Eigen::Matrix3d r = machines::rotation_of(pt.workpiece_wxyz);
      EXPECT_LT((r * p + pt.workpiece_origin_mm - m.robot.nozzle_tip_mm).norm(), 1e-3);
      const Eigen::Matrix3d abc =
          (Eigen::AngleAxisd(slicer::deg_to_rad(std::stod(g[4])), Vec3::UnitZ()) *
           Eigen::AngleAxisd(slicer::deg_to_rad(std::stod(g[5])), Vec3::UnitY()) *
           Eigen::AngleAxisd(slicer::deg_to_rad(std::stod(g[6])), Vec3::UnitX()))
              .toRotationMatrix();
      EXPECT_LT(((r * abc).col(2) - m.robot.nozzle_axis).norm(), 1e-4)
          << "the nozzle's z is its flow";
      EXPECT_LT(Eigen::AngleAxisd((r * abc).transpose() * machines::nozzle_frame_rotation(m.robot))
                    .angle(),
                1.75e-4)
          << "the whole nozzle frame, not only its axis";
      ++lins;
    }
    if (line.find("$VEL.CP") != std::string::npos) {
      ASSERT_TRUE(std::regex_match(line, g, vel)) << line;
      EXPECT_TRUE(std::stod(g[1]) == 0.006 || std::stod(g[1]) == 0.02)
          << "v_cart 6 mm/s or travel 20 mm/s, in m/s: " << line;
    }
  }
  EXPECT_LE(lins, thesis().program.points.size() - 1) << "zero-length motions are left out";
  EXPECT_GT(lins, thesis().program.points.size() * 9 / 10);
  EXPECT_NE(src.find("$IPO_MODE = #TCP"), std::string::npos) << "the nozzle is an external TCP";
}

TEST(ProduceCurved, LongLapsAreSplitIntoSubPrograms) {
  Job j = sample_job("missing-rib-cylinder.json");
  j.machine.robot.programs.krl_points_per_module = 100;
  const auto out = produce_curved(j.toolpath, j.substrate, j.machine, 0.01, "p.csv");
  const std::string src = file(out, "p.src");
  int defs = 0;
  for (std::size_t at = src.find("\nDEF "); at != std::string::npos;
       at = src.find("\nDEF ", at + 1))
    ++defs;
  EXPECT_GE(defs, static_cast<int>(out.program.points.size() / 100));
  EXPECT_EQ(out.report["programs"]["krl_sub_programs"].get<int>(), defs - 1)
      << "the main program calls them";
}

TEST(ProduceCurved, SunriseReadsTheCsvAndMovesAtVcart) {
  const std::string java = file(thesis(), "Part.java");
  for (const char* want :
       {"extends RoboticsAPIApplication", "CSV_NAME = \"part.csv\"", "setCartVelocity(speed)",
        "frameSpeed(rows.get(i - 1), r)",
        "lin(target(r, 0.0))", "V_CART_MM_S = 6.000", "extruder.setLapStart(",
        "extruder.getExtruderReady()", "RETRACT_MM = 20.000",
        "CONTACT_RADIUS_MM = {20.9600, 21.9200, 22.8800}"}) {
    EXPECT_NE(java.find(want), std::string::npos) << want;
  }
}

TEST(ProduceCurved, SameInputSameBytes) {
  const Job j = sample_job("missing-rib-cylinder.json");
  const auto again = produce_curved(j.toolpath, j.substrate, j.machine, 0.01, "part.csv");
  EXPECT_EQ(again.files, thesis().files);
}

TEST(ProduceCurved, ChordsStayWithinTheToleranceOnTheSurface) {
  // Deposits between consecutive poses are chords of the mapped pattern; every chord's
  // midpoint lies within the arc tolerance of the cylinder surface at the layer's offset.
  const auto& p = thesis().program;
  for (std::size_t i = 1; i < p.points.size(); ++i) {
    if (!p.points[i].extrude) continue;
    const Vec3 mid = (p.points[i].contact_mm + p.points[i - 1].contact_mm) / 2.0;
    EXPECT_LT(20.0 + p.points[i].offset_mm - mid.head<2>().norm(), 0.01 + 1e-9) << i;
  }
}

// Turning span of each layer's deposits, rad.
std::vector<double> layer_spans(const slicer::PoseProgram& p) {
  std::vector<double> lo(p.layers.size(), 1e9), hi(p.layers.size(), -1e9);
  for (const auto& pt : p.points) {
    if (!pt.extrude) continue;
    lo[pt.layer] = std::min(lo[pt.layer], pt.turn_rad);
    hi[pt.layer] = std::max(hi[pt.layer], pt.turn_rad);
  }
  std::vector<double> span;
  for (std::size_t k = 0; k < lo.size(); ++k) span.push_back(hi[k] - lo[k]);
  return span;
}

TEST(ProduceCurved, DepositionArcLengthKeepsThePitchOnOuterLayers) {
  Job j = sample_job("missing-rib-cylinder.json");
  j.machine = machines::load_profile("marlin-rotary-a");
  j.substrate.radius_mm = 25.0;
  const double h = j.toolpath.layers.front().height_mm, r = 25.0;
  const auto surface = produce_curved(j.toolpath, j.substrate, j.machine, 0.01, "s.gcode").program;
  j.substrate.arc_length_at = slicer::ArcLengthAt::Deposition;
  const auto deposition =
      produce_curved(j.toolpath, j.substrate, j.machine, 0.01, "d.gcode").program;
  const auto s = layer_spans(surface), d = layer_spans(deposition);
  for (std::size_t k = 0; k < 3; ++k) {
    // Surface: every layer spans the same angle; its length grows by the stretch.
    EXPECT_NEAR(s[k], s[0], 1e-9);
    EXPECT_NEAR(surface.layers[k].u_stretch, (r + (k + 1) * h) / r, 1e-12);
    // Deposition: the span at each layer's bead centre is the pattern's width.
    EXPECT_NEAR(d[k] * (r + (k + 0.5) * h), s[0] * r, 1e-6);
    EXPECT_NEAR(deposition.layers[k].u_stretch, (r + (k + 1) * h) / (r + (k + 0.5) * h), 1e-12);
  }
}

// One layer around the whole cylinder: a strand along u over exactly one period, as a
// periodic design hands it over (x beyond the period wraps).
slicer::Toolpath ring(double period_mm, double v_mm) {
  slicer::Toolpath t;
  t.generator = "ring";
  t.parameters = {{"speed", 300.0}};
  slicer::Stroke s;
  s.start_mm = slicer::Vec2(-period_mm / 2, v_mm);
  s.segments = {slicer::line_to(slicer::Vec2(0.1, v_mm + 2.0), slicer::Feature::Infill),
                slicer::line_to(slicer::Vec2(period_mm / 2, v_mm), slicer::Feature::Infill)};
  s.width_mm = 0.6;
  s.height_mm = 0.5;
  t.layers.push_back({0.5, 0.5, {s}});
  return t;
}

TEST(ProduceCurved, FullWrapClosesAcrossTheSeam) {
  const slicer::SubstrateSpec s{"cylinder", 15.0, 40.0, slicer::Wrap::Full,
                                slicer::ArcLengthAt::Surface};
  const auto p = produce_curved(ring(slicer::kTwoPi * 15.0, 0.0), s,
                                machines::load_profile("marlin-rotary-a"), 0.01, "w.gcode")
                     .program;
  const slicer::PosePoint* first = nullptr;
  const slicer::PosePoint* last = nullptr;
  for (std::size_t i = 1; i < p.points.size(); ++i) {
    if (p.points[i].extrude) last = &p.points[i], first = first ? first : &p.points[i - 1];
  }
  ASSERT_TRUE(first && last);
  EXPECT_LT((first->contact_mm - last->contact_mm).norm(), 1e-6)
      << "the strand meets itself on the cylinder";
  EXPECT_NEAR(last->turn_rad - first->turn_rad, slicer::kTwoPi, 1e-9);
  // The robot cell cannot turn the cylinder a full circle: refused, named.
  try {
    produce_curved(ring(slicer::kTwoPi * 15.0, 0.0), s,
                   machines::load_profile("kuka-iiwa14-wasp-cylinder"), 0.01, "w.csv");
    ADD_FAILURE() << "a full turn on A7";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("A7 allows 340.0 deg"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strand::post
