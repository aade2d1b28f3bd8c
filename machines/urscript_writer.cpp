// URScript text: movel per pose in metres and rotation vectors, set_tcp per layer.
#include "machines/urscript_writer.h"

#include <algorithm>
#include <cmath>

#include "machines/contact_speed.h"
#include "machines/extruder_gcode.h"
#include "machines/gcode_format.h"
#include "machines/joint_analysis.h"
#include "machines/program_text.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

// Joint speed of movej at 100 %, rad/s (the UR10e's base and shoulder joints: 120 deg/s).
constexpr double kMaxJointSpeedRadS = 2.0944;
// Blend radii below this are written as 0 (a stop), m.
constexpr double kMinBlendM = 1e-6;

std::string pose_text(const Eigen::Isometry3d& t) {
  const Vec3 p = t.translation() / 1000.0;
  const Vec3 rv = rotation_vector(t.linear());
  return "p[" + fmt_fixed(p.x(), 7) + ", " + fmt_fixed(p.y(), 7) + ", " + fmt_fixed(p.z(), 7) +
         ", " + fmt_fixed(rv.x(), 7) + ", " + fmt_fixed(rv.y(), 7) + ", " + fmt_fixed(rv.z(), 7) +
         "]";
}

std::string joints_text(const Joints& q) {
  std::string t = "[";
  for (int i = 0; i < 6; ++i) t += (i ? ", " : "") + fmt_fixed(q[i], 6);
  return t + "]";
}

// The TCP (contact frame of the layer) in the base frame for a pose.
Eigen::Isometry3d tcp_target(const slicer::PosePoint& pt, double radius_mm) {
  Eigen::Isometry3d w = Eigen::Isometry3d::Identity();
  w.translate(pt.workpiece_origin_mm);
  w.rotate(rotation_of(pt.workpiece_wxyz));
  return w * Eigen::Translation3d(radius_mm, 0.0, 0.0);
}

// v of movel in m/s: 0.001 mm/s steps, finer below 1 mm/s so a slow TCP keeps its time.
std::string speed_text(double mm_per_s) {
  return fmt_fixed(mm_per_s / 1000.0, mm_per_s < 1.0 ? 9 : 6);
}

// Before lap 0 the lap output goes to the level of "lap -1", which the extruder waits for:
// levels an aborted run left are not taken for this run's lap 0 (handshake_end: a finished
// run leaves both lines there).
std::string handshake_reset(const RobotCell& c) {
  const RobotPrograms& pr = c.programs;
  const std::string idle = handshake_idle_level(c) == 1 ? "True" : "False";
  std::string s =
      "  # handshake reset: the lap output and the extruder's ready to the level before lap 0\n";
  s += "  set_standard_digital_out(" + std::to_string(pr.ur_lap_output) + ", " + idle +
       ")  # reset\n";
  return s;
}

// After the last lap: wait until the extruder has finished it and reset its ready, then reset
// the lap output, so the next run starts from the levels before lap 0 on both lines.
std::string handshake_end(const RobotCell& c) {
  const RobotPrograms& pr = c.programs;
  const std::string idle = handshake_idle_level(c) == 1 ? "True" : "False";
  std::string s = "  # handshake reset after the last lap: both lines to the level before lap 0\n";
  if (pr.ur_ready_input >= 0) {
    s += "  while (get_standard_digital_in(" + std::to_string(pr.ur_ready_input) + ") != " + idle +
         "):  # the extruder has finished and reset\n";
    s += "    sync()\n  end\n";
  }
  return s + "  set_standard_digital_out(" + std::to_string(pr.ur_lap_output) + ", " + idle +
         ")  # reset\n";
}

}  // namespace

Vec3 rotation_vector(const Eigen::Matrix3d& r) {
  Eigen::Quaterniond q(r);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  const double s = q.vec().norm();
  if (s < 1e-15) return Vec3::Zero();
  const double angle = 2.0 * std::atan2(s, q.w());  // in [0, pi]
  return q.vec() / s * angle;
}

Eigen::Matrix3d rotation_of_vector(const Vec3& rv) {
  const double angle = rv.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rv / angle).toRotationMatrix();
}

Eigen::Isometry3d contact_tcp_in_flange(const RobotCell& cell, double radius_mm) {
  return workpiece_in_flange(cell) * Eigen::Translation3d(radius_mm, 0.0, 0.0);
}

std::string write_urscript(const slicer::PoseProgram& p, const MachineProfile& m,
                           const std::string& name, const std::string& csv_name,
                           const std::vector<std::string>& header, double blend_mm,
                           const TransitPlan& transit) {
  const RobotCell& c = m.robot;
  const RobotMotionSetup& mo = c.motion;
  const RobotPrograms& pr = c.programs;
  const double radius = p.substrate.value("radius_mm", 0.0);
  const auto layer_radius = [&](int layer) {
    return radius + p.layers[static_cast<std::size_t>(layer)].offset_mm;
  };
  std::string s;
  for (const auto& h : header) s += "# " + program_comment_text(h) + "\n";
  s += "def " + name + "():\n";
  s += "  textmsg(" + urscript_string_literal("Strand pose program " + csv_name) + ")\n";
  const Vec3 cog = mo.load_cog_mm / 1000.0;
  s += "  set_payload(" + fmt_fixed(mo.load_mass_kg, 3) + ", [" + fmt_fixed(cog.x(), 4) + ", " +
       fmt_fixed(cog.y(), 4) + ", " + fmt_fixed(cog.z(), 4) + "])  # the workpiece on the flange\n";
  const double vj = kMaxJointSpeedRadS * mo.ptp_velocity_percent / 100.0;
  const std::string joint_speed = ", a=" + fmt_fixed(2.0 * vj, 4) + ", v=" + fmt_fixed(vj, 4) + ")";
  const std::string accel = ", a=" + fmt_fixed(pr.ur_acceleration_mm_per_s2 / 1000.0, 4);
  if (mo.home_joints_deg) {
    Joints home = Joints::Zero();
    for (int i = 0; i < 6; ++i) home[i] = slicer::deg_to_rad((*mo.home_joints_deg)[i]);
    s += "  movej(" + joints_text(home) + joint_speed + "  # home\n";
  }
  const auto& first = p.points.front();
  s += "  movej(" + joints_text(transit.start_clearance_joints) + joint_speed +
       "  # clearance pose: " + fmt_fixed(transit.start_clearance_mm, 1) +
       " mm from the first pose along the nozzle axis (the joint move checked clear of the "
       "nozzle)\n";
  int tcp_layer = first.layer;
  s += "  set_tcp(" + pose_text(contact_tcp_in_flange(c, layer_radius(tcp_layer))) + ")  # layer " +
       std::to_string(tcp_layer) + " contact frame\n";
  const std::string travel = ", v=" + fmt_fixed(c.travel_speed_mm_per_s / 1000.0, 6);
  s += "  movel(" + pose_text(tcp_target(transit.start_approach, layer_radius(tcp_layer))) + accel +
       travel + ", r=0)  # approach: " + fmt_fixed(mo.approach_mm, 1) +
       " mm from the first pose along the nozzle axis\n";
  s += "  movel(" + pose_text(tcp_target(first, layer_radius(tcp_layer))) + accel + travel +
       ", r=0)  # onto the first pose\n";
  std::string previous = pose_text(tcp_target(first, layer_radius(tcp_layer)));
  Vec3 previous_contact = first.contact_mm;
  const auto& pts = p.points;
  // The TCP is a point of the workpiece, not the contact point: each movel's v is the row's
  // contact speed scaled by TCP chord / contact chord, so the row takes its planned time.
  const std::vector<ProgrammedMotion> timed = timed_motions(p, MovedFrame::WorkpieceFrame);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const auto& pt = pts[i];
    const bool lap_start = pt.lap != pts[i - 1].lap || i == 1;
    if (i == 1) s += handshake_reset(c);
    if (lap_start) {
      const bool level = lap_signal_level(c, pt.lap) == 1;
      const std::string lv = level ? "True" : "False";
      s += "  # lap " + std::to_string(pt.lap) + "\n";
      if (pr.ur_ready_input >= 0) {
        s += "  while (get_standard_digital_in(" + std::to_string(pr.ur_ready_input) +
             ") != " + lv + "):  # the extruder is ready for lap " + std::to_string(pt.lap) + "\n";
        s += "    sync()\n  end\n";
      }
      s += "  set_standard_digital_out(" + std::to_string(pr.ur_lap_output) + ", " + lv +
           ")  # lap " + std::to_string(pt.lap) + " starts\n";
    }
    if (pt.layer != tcp_layer) {
      tcp_layer = pt.layer;
      s += "  set_tcp(" + pose_text(contact_tcp_in_flange(c, layer_radius(tcp_layer))) +
           ")  # layer " + std::to_string(tcp_layer) + " contact frame\n";
      previous.clear();
    }
    const std::string target = pose_text(tcp_target(pt, layer_radius(tcp_layer)));
    if (target == previous) continue;  // a zero-length motion: nothing to move
    previous = target;
    // Blend within the lap, at most half the shorter neighbouring motion; stop at a lap's end
    // so the lap signal follows the motion.
    double r_m = 0.0;
    const bool lap_end = i + 1 == pts.size() || pts[i + 1].lap != pt.lap;
    if (!lap_end) {
      const double in = (pt.contact_mm - previous_contact).norm();
      const double out = (pts[i + 1].contact_mm - pt.contact_mm).norm();
      r_m = std::min(blend_mm, 0.4 * std::min(in, out)) / 1000.0;
      r_m = std::floor(r_m * 1e6) / 1e6;
      if (r_m < kMinBlendM) r_m = 0.0;
    }
    previous_contact = pt.contact_mm;
    s += "  movel(" + target + accel + ", v=" + speed_text(timed[i].speed_mm_per_s) +
         ", r=" + fmt_fixed(r_m, 6) + ")\n";
  }
  s += handshake_end(c);
  s += "  movel(" +
       pose_text(
           tcp_target(moved_along_nozzle(c, pts.back(), mo.retract_mm), layer_radius(tcp_layer))) +
       accel + travel + ", r=0)  # retract along the nozzle axis\n";
  s += "  movel(" + pose_text(tcp_target(transit.end_clearance, layer_radius(tcp_layer))) + accel +
       travel + ", r=0)  # clearance pose: " + fmt_fixed(transit.end_clearance_mm, 1) +
       " mm from the last pose (the joint move home checked clear of the nozzle)\n";
  if (mo.home_joints_deg) {
    Joints home = Joints::Zero();
    for (int i = 0; i < 6; ++i) home[i] = slicer::deg_to_rad((*mo.home_joints_deg)[i]);
    s += "  movej(" + joints_text(home) + joint_speed + "  # home\n";
  }
  s += "end\n";
  return s;
}

}  // namespace strand::machines
