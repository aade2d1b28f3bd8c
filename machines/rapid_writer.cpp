// RAPID text: inline robtargets, one procedure per lap, stationary tool and moving work object.
#include "machines/rapid_writer.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "machines/extruder_gcode.h"
#include "machines/gcode_format.h"
#include "machines/joint_analysis.h"
#include "machines/krl_writer.h"
#include "machines/program_text.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

const char* const kExtax = "[9E9, 9E9, 9E9, 9E9, 9E9, 9E9]";
// How long a lap waits for the extruder's ready input, s.
constexpr double kReadyTimeoutS = 600.0;

std::string quaternion_text(const Eigen::Matrix3d& r) {
  const Eigen::Vector4d q = quaternion_wxyz(r);
  return "[" + fmt_fixed(q[0], 9) + ", " + fmt_fixed(q[1], 9) + ", " + fmt_fixed(q[2], 9) + ", " +
         fmt_fixed(q[3], 9) + "]";
}

std::string pos_text(const Vec3& p) {
  return "[" + fmt_fixed(p.x(), 4) + ", " + fmt_fixed(p.y(), 4) + ", " + fmt_fixed(p.z(), 4) + "]";
}

std::string joints_text(const Joints& q) {
  std::string t = "[";
  for (int i = 0; i < 6; ++i) t += (i ? ", " : "") + fmt_fixed(slicer::rad_to_deg(q[i]), 4);
  return t + "]";
}

// Before lap 0 the lap output goes to the level before lap 0, which the extruder waits for
// (extruder_gcode.h: handshake_idle_level); handshake_end leaves both lines there.
std::string handshake_reset(const RobotCell& c) {
  const RobotPrograms& pr = c.programs;
  const std::string idle = handshake_idle_level(c) == 1 ? "1" : "0";
  std::string s =
      "    ! handshake reset: the lap output and the extruder's ready to the level before lap 0\n";
  return s + "    SetDO " + pr.rapid_lap_signal + ", " + idle + ";\n";
}

// After the last lap: wait until the extruder has finished it and reset its ready, then reset
// the lap output, so the next run starts from the levels before lap 0 on both lines.
std::string handshake_end(const RobotCell& c) {
  const RobotPrograms& pr = c.programs;
  const std::string idle = handshake_idle_level(c) == 1 ? "1" : "0";
  std::string s;
  if (!pr.rapid_ready_signal.empty()) {
    s += "    ! the extruder has finished and reset\n    WaitDI " + pr.rapid_ready_signal + ", " +
         idle + "\\MaxTime:=" + fmt_fixed(kReadyTimeoutS, 0) + ";\n";
  }
  s += "    ! handshake reset after the last lap: the lap output to the level before lap 0\n";
  return s + "    SetDO " + pr.rapid_lap_signal + ", " + idle + ";\n";
}

int quadrant(double rad) { return static_cast<int>(std::floor(rad / (slicer::kPi / 2.0) + 1e-12)); }

}  // namespace

std::array<int, 4> abb_confdata(const ArmModel& arm, const Joints& q) {
  // Frames of the chain up to the wrist centre.
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  std::array<Vec3, 7> origin;
  origin[0] = Vec3::Zero();
  for (int i = 0; i < arm.axes; ++i) {
    Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
    step.rotate(Eigen::AngleAxisd(q[i] + arm.offset_rad[i], Vec3::UnitZ()));
    step.translate(Vec3(arm.dh[i].a_mm, 0.0, arm.dh[i].d_mm));
    step.rotate(Eigen::AngleAxisd(arm.dh[i].alpha_rad, Vec3::UnitX()));
    t = t * step;
    origin[static_cast<std::size_t>(i + 1)] = t.translation();
  }
  const Vec3 wrist = origin[4];  // axes 4, 5 and 6 meet here
  // In the arm's plane: radial along axis 1's direction, up along base z.
  const Vec3 radial(std::cos(q[0]), std::sin(q[0]), 0.0);
  const bool behind = wrist.dot(radial) < 0.0;
  const Vec3 a2 = origin[1], a3 = origin[2];
  const double ux = (a3 - a2).dot(radial), uz = (a3 - a2).z();
  const double wx = (wrist - a2).dot(radial), wz = (wrist - a2).z();
  // At the zero posture (lower arm up, forearm forward) the wrist is "above" the lower arm.
  const bool below = ux * wz - uz * wx > 0.0;
  const bool a5_negative = q[4] < 0.0;
  const int cfx = (behind ? 4 : 0) + (below ? 2 : 0) + (a5_negative ? 1 : 0);
  return {quadrant(q[0]), quadrant(q[3]), quadrant(q[5]), cfx};
}

RapidProgram write_rapid(const slicer::PoseProgram& p, const MachineProfile& m,
                         const std::string& module, const std::string& csv_name,
                         const std::vector<std::string>& header, double blend_mm,
                         const TransitPlan& transit) {
  const RobotCell& c = m.robot;
  const RobotMotionSetup& mo = c.motion;
  const RobotPrograms& pr = c.programs;
  const ArmModel arm = arm_model(c);
  const Eigen::Matrix3d nozzle = nozzle_frame_rotation(c);
  const auto& pts = p.points;
  // Joint solutions along the path: the configuration of every robtarget.
  const JointReport joints = analyse_joints(arm, c, pts, true);
  const std::string tool = pr.rapid_tool, wobj = pr.rapid_wobj;
  const std::string tw = ", " + tool + "\\WObj:=" + wobj + ";";
  RapidProgram out;
  std::string& s = out.mod;
  s = "MODULE " + module + "\n";
  for (const auto& h : header) s += "  ! " + program_comment_text(h) + "\n";
  // The stationary tool: the nozzle tip in the world (= robot base) frame, z along the flow.
  const bool tool_there = pr.rapid_tool_on_controller, wobj_there = pr.rapid_wobj_on_controller;
  if (!tool_there || !wobj_there) {
    s += "  ! " + tool + ": the nozzle (stationary tool); " + wobj +
         ": the workpiece on the flange (robot-held work object). Calibration values of the "
         "profile.\n";
  }
  // Data calibrated on the controller (a PERS in a system module) is used, not declared.
  if (tool_there || wobj_there) {
    s += "  ! " + std::string(tool_there ? tool : "") + (tool_there && wobj_there ? " and " : "") +
         (wobj_there ? wobj : "") +
         ": PERS data calibrated on the controller (declared in a system module, not here).\n";
  }
  const Vec3 cog = mo.load_cog_mm;
  if (!tool_there) {
    s += "  PERS tooldata " + tool + " := [FALSE, [" + pos_text(c.nozzle_tip_mm) + ", " +
         quaternion_text(nozzle) + "], [" + fmt_fixed(std::max(mo.load_mass_kg, 0.001), 3) +
         ", " + pos_text(cog) + ", [1, 0, 0, 0], 0, 0, 0]];\n";
  }
  const Eigen::Isometry3d wf = workpiece_in_flange(c);
  if (!wobj_there) {
    s += "  PERS wobjdata " + wobj + " := [TRUE, TRUE, \"\", [" + pos_text(wf.translation()) +
         ", " + quaternion_text(wf.linear()) + "], [[0, 0, 0], [1, 0, 0, 0]]];\n";
  }
  const double zb = std::max(blend_mm, 0.001);
  s += "  CONST zonedata strandZone := [FALSE, " + fmt_fixed(zb, 3) + ", " +
       fmt_fixed(1.5 * zb, 3) + ", " + fmt_fixed(1.5 * zb, 3) + ", 0.15, " +
       fmt_fixed(1.5 * zb, 3) + ", 0.15];\n";
  // One speeddata per distinct contact speed (mm/s); joint moves at the PTP percentage.
  std::map<long, std::string> speeds;
  const auto speed_name = [&](double mm_s) {
    const long key = std::lround(mm_s * 1000.0);
    auto it = speeds.find(key);
    if (it == speeds.end())
      it = speeds.emplace(key, "strandV" + std::to_string(speeds.size() + 1)).first;
    return it->second;
  };
  s += "  ! Contact speeds (mm/s) of the moves; joint moves at the profile's PTP percentage.\n";
  const std::string travel = speed_name(c.travel_speed_mm_per_s);
  for (std::size_t i = 1; i < pts.size(); ++i) speed_name(pts[i].speed_mm_per_s);
  for (const auto& [key, name] : speeds) {
    s += "  CONST speeddata " + name + " := [" + fmt_fixed(key / 1000.0, 3) +
         ", 500, 5000, 1000];\n";
  }
  s += "  CONST speeddata strandPtp := [" + fmt_fixed(10.0 * mo.ptp_velocity_percent, 1) + ", " +
       fmt_fixed(5.0 * mo.ptp_velocity_percent, 1) + ", 5000, 1000];\n";
  const Joints start = transit.start_clearance_joints;
  s += "  ! The clearance pose, " + fmt_fixed(transit.start_clearance_mm, 1) +
       " mm from the first pose along the nozzle axis, by axis values (deg) from IK.\n";
  s += "  CONST jointtarget strandStart := [" + joints_text(start) + ", " + kExtax + "];\n";
  if (mo.home_joints_deg) {
    Joints home = Joints::Zero();
    for (int i = 0; i < 6; ++i) home[i] = slicer::deg_to_rad((*mo.home_joints_deg)[i]);
    s += "  CONST jointtarget strandHome := [" + joints_text(home) + ", " + kExtax + "];\n";
  }
  const auto robtarget = [&](const slicer::PosePoint& pt, const Joints& q) {
    const std::array<int, 4> cf = abb_confdata(arm, q);
    return "[" + pos_text(pt.contact_mm) + ", " +
           quaternion_text(rotation_of(pt.workpiece_wxyz).transpose() * nozzle) + ", [" +
           std::to_string(cf[0]) + ", " + std::to_string(cf[1]) + ", " + std::to_string(cf[2]) +
           ", " + std::to_string(cf[3]) + "], " + kExtax + "]";
  };
  const auto solution = [&](std::size_t i) {
    return i < joints.solutions.size() ? joints.solutions[i] : start;
  };
  // Laps: procedures strandLap<k>_<part>, at most 2000 motions each.
  struct Proc {
    std::string name;
    std::size_t first, last;
    int lap;
    bool starts_lap;
  };
  std::vector<Proc> procs;
  constexpr std::size_t kPerProc = 2000;
  for (std::size_t i = 1; i < pts.size();) {
    std::size_t j = i;
    while (j + 1 < pts.size() && pts[j + 1].lap == pts[i].lap) ++j;
    const std::size_t n = j - i + 1, parts = (n + kPerProc - 1) / kPerProc;
    for (std::size_t k = 0; k < parts; ++k) {
      procs.push_back({"strandLap" + std::to_string(pts[i].lap) + "_" + std::to_string(k + 1),
                       i + n * k / parts, i + n * (k + 1) / parts - 1, pts[i].lap, k == 0});
    }
    i = j + 1;
  }
  out.procedures = static_cast<int>(procs.size());
  s += "\n  PROC main()\n";
  s += "    TPWrite " + rapid_string_literal("Strand pose program " + csv_name) + ";\n";
  s += "    ConfL\\On;\n";
  if (mo.path_acceleration_mm_per_s2) {
    const std::string a = fmt_fixed(*mo.path_acceleration_mm_per_s2 / 1000.0, 3);
    s += "    ! the path acceleration the lap timing assumes (m/s^2)\n    PathAccLim TRUE\\AccMax:=" +
         a + ", TRUE\\DecelMax:=" + a + ";\n";
  }
  if (mo.home_joints_deg) s += "    ! home\n    MoveAbsJ strandHome, strandPtp, fine" + tw + "\n";
  s += "    ! clearance pose (the joint move checked clear of the nozzle)\n    MoveAbsJ strandStart, "
       "strandPtp, fine" + tw + "\n";
  s += "    ! approach\n    MoveL " + robtarget(transit.start_approach, start) + ", " + travel +
       ", fine" + tw + "\n";
  s += "    ! onto the first pose\n    MoveL " + robtarget(pts.front(), solution(0)) + ", " +
       travel + ", fine" + tw + "\n";
  for (const auto& pc : procs) s += "    " + pc.name + ";\n";
  const slicer::PosePoint retract = moved_along_nozzle(c, pts.back(), mo.retract_mm);
  s += "    ! retract along the nozzle axis\n    MoveL " +
       robtarget(retract, solution(pts.size() - 1)) + ", " + travel + ", fine" + tw + "\n";
  s += "    ! clearance pose\n    MoveL " + robtarget(transit.end_clearance, transit.end_clearance_joints) +
       ", " + travel + ", fine" + tw + "\n";
  if (mo.home_joints_deg) s += "    ! home\n    MoveAbsJ strandHome, strandPtp, fine" + tw + "\n";
  s += "  ENDPROC\n";
  std::string previous = robtarget(pts.front(), solution(0));
  for (const auto& pc : procs) {
    s += "\n  PROC " + pc.name + "()\n";
    if (&pc == &procs.front()) s += handshake_reset(c);
    if (pc.starts_lap) {
      const std::string level = lap_signal_level(c, pc.lap) == 1 ? "1" : "0";
      if (!pr.rapid_ready_signal.empty()) {
        s += "    ! the extruder is ready for lap " + std::to_string(pc.lap) + "\n    WaitDI " +
             pr.rapid_ready_signal + ", " + level + "\\MaxTime:=" + fmt_fixed(kReadyTimeoutS, 0) +
             ";\n";
      }
      s += "    ! lap " + std::to_string(pc.lap) + " starts\n    SetDO " + pr.rapid_lap_signal +
           ", " + level + ";\n";
    }
    for (std::size_t i = pc.first; i <= pc.last; ++i) {
      const std::string target = robtarget(pts[i], solution(i));
      if (target == previous) continue;  // a zero-length motion: nothing to move
      previous = target;
      const bool lap_end = i + 1 == pts.size() || pts[i + 1].lap != pts[i].lap;
      s += "    MoveL " + target + ", " + speed_name(pts[i].speed_mm_per_s) + ", " +
           (lap_end ? "fine" : "strandZone") + tw + "\n";
      ++out.move_l;
    }
    if (&pc == &procs.back()) s += handshake_end(c);
    s += "  ENDPROC\n";
  }
  s += "ENDMODULE\n";
  return out;
}

}  // namespace strand::machines
