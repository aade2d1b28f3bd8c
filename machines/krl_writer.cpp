// KRL text: one DEF per lap piece, inline LIN frames, speeds in m/s.
#include "machines/krl_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "machines/extruder_gcode.h"
#include "machines/gcode_format.h"
#include "machines/joint_analysis.h"
#include "machines/program_text.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

constexpr std::size_t kMaxKrlName = 24;  // KRL identifiers
// cos B below which A, B, C are taken as gimbal-locked (B = +-90 deg).
constexpr double kGimbalCosB = 1e-9;

std::string frame_text(const Vec3& p, const Vec3& abc) {
  return "{X " + fmt_fixed(p.x(), 4) + ", Y " + fmt_fixed(p.y(), 4) + ", Z " + fmt_fixed(p.z(), 4) +
         ", A " + fmt_fixed(abc.x(), 4) + ", B " + fmt_fixed(abc.y(), 4) + ", C " +
         fmt_fixed(abc.z(), 4) + "}";
}

// A sub-program: LIN to points [first, last], all of lap `lap`.
struct Piece {
  std::string name;
  std::size_t first, last;
  int lap;
  bool starts_lap;
};

// Laps own the points whose motion they execute (point 0 is the start, reached by PTP);
// laps longer than `per_module` points are cut into several sub-programs.
std::vector<Piece> pieces(const slicer::PoseProgram& p, int per_module) {
  std::vector<Piece> out;
  const auto& pts = p.points;
  for (std::size_t i = 1; i < pts.size();) {
    std::size_t j = i;
    while (j + 1 < pts.size() && pts[j + 1].lap == pts[i].lap) ++j;
    const std::size_t n = j - i + 1;
    const std::size_t parts = (n + per_module - 1) / per_module;
    for (std::size_t k = 0; k < parts; ++k) {
      // Local sub-programs: their names only need to be unique inside the module.
      out.push_back({"LAP" + std::to_string(pts[i].lap) + "_P" + std::to_string(k + 1),
                     i + n * k / parts, i + n * (k + 1) / parts - 1, pts[i].lap, k == 0});
    }
    i = j + 1;
  }
  return out;
}

}  // namespace

std::string krl_module_name(const std::string& base) {
  std::string out;
  for (char c : base) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "S" + out;
  out = out.substr(0, kMaxKrlName);
  if (is_krl_keyword(out)) out = ("S_" + out).substr(0, kMaxKrlName);
  return out;
}

Eigen::Matrix3d nozzle_frame_rotation(const RobotCell& c) {
  Eigen::Matrix3d r;
  r.col(0) = c.nozzle_axis.cross(c.substrate_axis);
  r.col(1) = -c.substrate_axis;
  r.col(2) = c.nozzle_axis;
  return r;
}

Vec3 kuka_abc_deg(const Eigen::Matrix3d& m) {
  // B from the first column; A from it too unless B = +-90 deg (gimbal lock, where only A -+ C
  // is defined: C = 0 and A from the second column). C is then solved from A, so the three
  // angles always give back m, even where A alone is ill-conditioned (two independent atan2
  // calls of near-zero pairs can disagree by 180 deg: a flipped target).
  const double cos_b = std::hypot(m(0, 0), m(1, 0));
  const double b = std::atan2(-m(2, 0), cos_b);
  double a = 0.0, c = 0.0;
  if (cos_b < kGimbalCosB) {
    a = std::atan2(-m(0, 1), m(1, 1));
  } else {
    a = std::atan2(m(1, 0), m(0, 0));
    const double sa = std::sin(a), ca = std::cos(a);
    c = std::atan2(sa * m(0, 2) - ca * m(1, 2), ca * m(1, 1) - sa * m(0, 1));
  }
  return Vec3(slicer::rad_to_deg(a), slicer::rad_to_deg(b), slicer::rad_to_deg(c));
}

Eigen::Matrix3d kuka_abc_rotation(const Vec3& abc_deg) {
  return (Eigen::AngleAxisd(slicer::deg_to_rad(abc_deg.x()), Vec3::UnitZ()) *
          Eigen::AngleAxisd(slicer::deg_to_rad(abc_deg.y()), Vec3::UnitY()) *
          Eigen::AngleAxisd(slicer::deg_to_rad(abc_deg.z()), Vec3::UnitX()))
      .toRotationMatrix();
}

namespace {

// Before lap 0 the lap output goes to the level before lap 0, which the extruder waits for
// (extruder_gcode.h: handshake_idle_level); handshake_end leaves both lines there.
std::string handshake_reset(const RobotCell& c) {
  const std::string idle = handshake_idle_level(c) == 1 ? "TRUE" : "FALSE";
  std::string s =
      "  ; handshake reset: the lap output and the extruder's ready to the level before lap 0\n";
  s += "  $OUT[" + std::to_string(c.programs.krl_lap_output) + "]=" + idle + " ; reset\n";
  return s;
}

// After the last lap: wait until the extruder has finished it and reset its ready, then reset
// the lap output, so the next run starts from the levels before lap 0 on both lines.
std::string handshake_end(const RobotCell& c) {
  const std::string idle = handshake_idle_level(c) == 1 ? "TRUE" : "FALSE";
  std::string s = "  ; handshake reset after the last lap: both lines to the level before lap 0\n";
  if (c.programs.krl_ready_input > 0) {
    s += "  WAIT FOR $IN[" + std::to_string(c.programs.krl_ready_input) + "] == " + idle +
         " ; the extruder has finished and reset\n";
  }
  return s + "  $OUT[" + std::to_string(c.programs.krl_lap_output) + "]=" + idle + " ; reset\n";
}

}  // namespace

KrlProgram write_krl(const slicer::PoseProgram& p, const MachineProfile& m, const std::string& base,
                     const std::vector<std::string>& header, double blend_mm,
                     const TransitPlan& transit) {
  const RobotCell& c = m.robot;
  const std::string module = krl_module_name(base);
  const Eigen::Matrix3d nozzle = nozzle_frame_rotation(c);
  KrlProgram out;
  const auto subs = pieces(p, c.programs.krl_points_per_module);
  out.sub_programs = static_cast<int>(subs.size());
  std::string& s = out.src;
  s = "&ACCESS RVP\nDEF " + module + "()\n";
  for (const auto& h : header) s += "; " + program_comment_text(h) + "\n";
  const RobotMotionSetup& mo = c.motion;
  s += "  BAS(#INITMOV, 0)\n  BAS(#VEL_PTP, " + std::to_string(mo.ptp_velocity_percent) +
       ")\n  BAS(#ACC_PTP, " + std::to_string(mo.ptp_velocity_percent) + ")\n";
  const RobotPrograms& pr = c.programs;
  const std::string tool_n = std::to_string(pr.krl_tool_data);
  // Tool and base from the controller's calibrated data when the profile names them (plain
  // assignments: BAS(#TOOL) would also need the KSS data lists of the inline forms).
  s += pr.krl_tool_data > 0 ? "  $TOOL = TOOL_DATA[" + tool_n +
                                  "] ; the workpiece on the flange, calibrated on the controller\n"
                            : std::string("  $TOOL = workpiece_on_flange\n");
  s += pr.krl_base_data > 0 ? "  $BASE = BASE_DATA[" + std::to_string(pr.krl_base_data) +
                                  "] ; the nozzle (external TCP), calibrated on the controller\n"
                            : std::string("  $BASE = nozzle_in_world\n");
  if (pr.krl_tool_data > 0) {
    s += "  $LOAD = LOAD_DATA[" + tool_n + "] ; the load determined with tool " + tool_n + "\n";
  } else if (mo.load_mass_kg > 0.0) {
    const Vec3& g = mo.load_cog_mm;
    s += "  $LOAD = {M " + fmt_fixed(mo.load_mass_kg, 3) + ", CM {X " + fmt_fixed(g.x(), 3) +
         ", Y " + fmt_fixed(g.y(), 3) + ", Z " + fmt_fixed(g.z(), 3) +
         ", A 0.0, B 0.0, C 0.0}, J {X 0.0, Y 0.0, Z 0.0}} ; the workpiece on the flange\n";
  }
  s += "  $IPO_MODE = #TCP ; external TCP: the nozzle is fixed, the robot carries the workpiece; "
       "LIN frames are the nozzle in the workpiece frame\n";
  s += "  $APO.CDIS = " + fmt_fixed(blend_mm, 3) + "\n  $ADVANCE = 3\n";
  if (mo.path_acceleration_mm_per_s2) {
    s += "  $ACC.CP = " + fmt_fixed(*mo.path_acceleration_mm_per_s2 / 1000.0, 6) +
         " ; m/s^2, the path acceleration the lap timing assumes\n";
  }
  const auto axes = [](const Joints& q, const std::string& what) {
    std::string t = "  PTP {E6AXIS: A1 " + fmt_fixed(slicer::rad_to_deg(q[0]), 4);
    for (int i = 1; i < 6; ++i)
      t += ", A" + std::to_string(i + 1) + " " + fmt_fixed(slicer::rad_to_deg(q[i]), 4);
    return t + ", E1 " + fmt_fixed(slicer::rad_to_deg(q[6]), 4) + "} ; " + what + "\n";
  };
  Joints home = Joints::Zero();
  if (mo.home_joints_deg) {
    for (int i = 0; i < 7; ++i) home[i] = slicer::deg_to_rad((*mo.home_joints_deg)[i]);
    s += axes(home, "home (E1 = A7 of the LBR)");
  }
  // The start: axis values of the approach pose (approach_mm from the first pose along the
  // nozzle axis), so neither Status/Turn nor the redundant elbow (E1 = A7 of the LBR) is left
  // to the controller; then straight onto the first pose.
  const auto& first = p.points.front();
  const auto frame_of = [&](const slicer::PosePoint& pt) {
    return frame_text(pt.contact_mm,
                      kuka_abc_deg(rotation_of(pt.workpiece_wxyz).transpose() * nozzle));
  };
  s += axes(transit.start_clearance_joints,
            "clearance pose: " + fmt_fixed(transit.start_clearance_mm, 1) +
                " mm from the first pose along the nozzle axis (the joint move checked clear of "
                "the nozzle)");
  s += "  $VEL.CP = " + fmt_fixed(c.travel_speed_mm_per_s / 1000.0, 6) + " ; m/s\n";
  s += "  LIN " + frame_of(transit.start_approach) + " ; approach: " + fmt_fixed(mo.approach_mm, 1) +
       " mm from the first pose along the nozzle axis\n";
  s += "  LIN " + frame_of(first) + " ; onto the first pose\n";
  for (const auto& sub : subs) s += "  " + sub.name + "()\n";
  s += "  $VEL.CP = " + fmt_fixed(c.travel_speed_mm_per_s / 1000.0, 6) + " ; m/s\n";
  s += "  LIN " + frame_of(moved_along_nozzle(c, p.points.back(), mo.retract_mm)) +
       " ; retract along the nozzle axis\n";
  s += "  LIN " + frame_of(transit.end_clearance) + " ; clearance pose: " +
       fmt_fixed(transit.end_clearance_mm, 1) + " mm from the last pose\n";
  if (mo.home_joints_deg) s += axes(home, "home");
  s += "END\n";
  std::string previous_frame = frame_of(first);
  for (const auto& sub : subs) {
    s += "\nDEF " + sub.name + "()\n";
    if (&sub == &subs.front()) s += handshake_reset(c);
    if (sub.starts_lap && c.programs.krl_ready_input > 0) {
      // Two-way handshake: the extruder is parked and ready with this lap's level.
      s += "  WAIT FOR $IN[" + std::to_string(c.programs.krl_ready_input) +
           "] == " + (lap_signal_level(c, sub.lap) == 1 ? "TRUE" : "FALSE") +
           " ; the extruder is ready for lap " + std::to_string(sub.lap) + "\n";
    }
    if (sub.starts_lap) {
      // Switched on the path (not in the advance run) as the lap's first motion starts.
      s += "  TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[" +
           std::to_string(c.programs.krl_lap_output) +
           "]=" + (lap_signal_level(c, sub.lap) == 1 ? "TRUE" : "FALSE") + " ; lap " +
           std::to_string(sub.lap) + " starts\n";
    }
    double speed = -1.0;
    for (std::size_t i = sub.first; i <= sub.last; ++i) {
      const auto& pt = p.points[i];
      const Eigen::Matrix3d r = rotation_of(pt.workpiece_wxyz).transpose() * nozzle;
      std::string frame = frame_text(pt.contact_mm, kuka_abc_deg(r));
      if (frame == previous_frame) continue;  // a zero-length motion: nothing to move
      previous_frame = frame;
      if (pt.speed_mm_per_s != speed) {
        speed = pt.speed_mm_per_s;
        s += "  $VEL.CP = " + fmt_fixed(speed / 1000.0, 6) + " ; m/s\n";
      }
      s += "  LIN " + frame + " C_DIS\n";
      ++out.lin_points;
    }
    if (&sub == &subs.back()) s += handshake_end(c);
    s += "END\n";
  }
  out.dat = "&ACCESS RVP\nDEFDAT " + module + "\n";
  if (pr.krl_tool_data > 0 || pr.krl_base_data > 0) {
    out.dat += "; the program uses" +
               (pr.krl_tool_data > 0 ? " TOOL_DATA[" + tool_n + "]" : std::string()) +
               (pr.krl_tool_data > 0 && pr.krl_base_data > 0 ? " and" : "") +
               (pr.krl_base_data > 0 ? " BASE_DATA[" + std::to_string(pr.krl_base_data) + "]"
                                     : std::string()) +
               " of the controller; the profile's values are below for comparison\n";
  }
  out.dat +=
      "; $TOOL: the workpiece (cylinder) frame on the flange; $BASE: the nozzle tip (external TCP) "
      "in the world\n";
  const Eigen::Isometry3d wf = workpiece_in_flange(c);
  out.dat += "DECL FRAME workpiece_on_flange = " +
             frame_text(wf.translation(), kuka_abc_deg(wf.linear())) + "\n";
  out.dat += "DECL FRAME nozzle_in_world = " + frame_text(c.nozzle_tip_mm, kuka_abc_deg(nozzle)) +
             " ; calibration value of the profile\n";
  out.dat += "DECL REAL v_cart_m_s = " + fmt_fixed(c.v_cart_mm_per_s / 1000.0, 6) + "\nENDDAT\n";
  return out;
}

}  // namespace strand::machines
