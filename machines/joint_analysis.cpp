// Reach, inverse kinematics and joint limits over a pose program.
#include "machines/joint_analysis.h"

#include <cmath>

#include "machines/gcode_format.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

// A solution counts when its flange is this close to the target (mm); the pose checks
// ask for 0.01 mm at the contact.
constexpr double kSolvedMm = 1e-3;
constexpr double kSolvedRad = 1e-6;
// Turn step when following the workpiece from turn 0 to the first pose, rad.
constexpr double kFollowStepRad = 0.05;

bool solved(const IkResult& r) {
  return r.position_error_mm < kSolvedMm && r.orientation_error_rad < kSolvedRad;
}

// Mid-range cost of a solution: smaller is farther from the limits.
double limit_cost(const ArmModel& arm, const Joints& q) {
  const Joints mid = (arm.limit_rad + arm.limit_min_rad) / 2.0;
  const Joints half = (arm.limit_rad - arm.limit_min_rad) / 2.0;
  return (q - mid).cwiseQuotient(half).squaredNorm();
}

// The first pose has no predecessor: solve the same workpiece position turned back to turn 0
// (u = 0 facing the nozzle) from a few fixed elbow postures, keep the solution nearest
// mid-range, then follow the turn to the first pose in small steps. The last joint's winding
// is then centred on turn 0, as patterns are centred on u = 0.
IkResult first_solution(const ArmModel& arm, const RobotCell& cell, const slicer::PosePoint& p) {
  IkResult best;
  bool found = false;
  double best_cost = 0.0;
  const Eigen::Matrix3d r_first = rotation_of(p.workpiece_wxyz);
  auto turned = [&](double turn) {
    const Eigen::Matrix3d r =
        r_first * Eigen::AngleAxisd(p.turn_rad - turn, Vec3::UnitZ()).toRotationMatrix();
    return flange_pose(cell, p.workpiece_origin_mm, quaternion_wxyz(r));
  };
  for (const Joints& seed : arm.seeds) {
    const IkResult r = solve_ik(arm, turned(0.0), seed, 400);
    const double cost = limit_cost(arm, r.q);
    if (solved(r) && within_limits(arm, r.q) && (!found || cost < best_cost))
      best = r, best_cost = cost, found = true;
  }
  if (!found) {
    // No posture within the limits: the best outside them (reported as such).
    for (const Joints& seed : arm.seeds) {
      const IkResult r = solve_ik(arm, turned(0.0), seed, 400);
      const double cost = limit_cost(arm, r.q);
      if (solved(r) && (!found || cost < best_cost)) best = r, best_cost = cost, found = true;
    }
  }
  if (!found) return best;
  const int steps = static_cast<int>(std::ceil(std::abs(p.turn_rad) / kFollowStepRad));
  for (int k = 1; k <= steps; ++k) best = solve_ik(arm, turned(p.turn_rad * k / steps), best.q);
  return best;
}

std::string limit_text(const ArmModel& arm, const Joints& q, int i) {
  const std::string range = arm.limit_min_rad[i] == -arm.limit_rad[i]
                                ? "+-" + fmt_fixed(slicer::rad_to_deg(arm.limit_rad[i]), 0)
                                : fmt_fixed(slicer::rad_to_deg(arm.limit_min_rad[i]), 0) + ".." +
                                      fmt_fixed(slicer::rad_to_deg(arm.limit_rad[i]), 0);
  return "A" + std::to_string(i + 1) + " = " + fmt_fixed(slicer::rad_to_deg(q[i]), 1) +
         " deg, limit " + range + " deg";
}

void record_limits(const ArmModel& arm, const Joints& q, std::size_t index, JointReport& out) {
  for (int i = 0; i < arm.axes; ++i) {
    if (q[i] > arm.limit_rad[i] + 1e-9 || q[i] < arm.limit_min_rad[i] - 1e-9) {
      if (out.outside_limits++ == 0) {
        out.first_outside = index;
        out.first_outside_what = limit_text(arm, q, i);
      }
      return;
    }
  }
}

}  // namespace

Eigen::Isometry3d flange_pose(const RobotCell& cell, const Vec3& origin,
                              const Eigen::Vector4d& wxyz) {
  Eigen::Isometry3d w = Eigen::Isometry3d::Identity();
  w.translate(origin);
  w.rotate(rotation_of(wxyz));
  return w * workpiece_in_flange(cell).inverse();
}

JointReport analyse_joints(const ArmModel& arm, const RobotCell& cell,
                           const std::vector<slicer::PosePoint>& points, bool keep_solutions,
                           std::size_t max_problems) {
  JointReport out;
  out.poses = points.size();
  out.axes = arm.axes;
  std::optional<Joints> seed;
  bool first_range = true;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (out.unreachable + out.outside_limits >= max_problems) {
      out.unchecked = points.size() - i;
      break;
    }
    const auto& p = points[i];
    const Eigen::Isometry3d target = flange_pose(cell, p.workpiece_origin_mm, p.workpiece_wxyz);
    const double reach = (wrist_centre(arm, target) - arm.shoulder_mm).norm();
    out.max_reach_mm = std::max(out.max_reach_mm, reach);
    IkResult r;
    if (reach <= arm.reach_mm)
      r = seed ? solve_ik(arm, target, *seed) : first_solution(arm, cell, p);
    if (reach > arm.reach_mm || !solved(r)) {
      if (out.unreachable++ == 0) {
        out.first_unreachable = i;
        out.first_unreachable_what =
            reach > arm.reach_mm
                ? "wrist " + fmt_fixed(reach, 1) + " mm from the shoulder > reach " +
                      fmt_fixed(arm.reach_mm, 0) + " mm"
                : "no joint solution (position error " + fmt_fixed(r.position_error_mm, 3) + " mm)";
      }
      if (keep_solutions) out.solutions.push_back(seed.value_or(Joints::Zero()));
      continue;
    }
    seed = r.q;
    out.max_ik_error_mm = std::max(out.max_ik_error_mm, r.position_error_mm);
    out.min_rad = first_range ? r.q : out.min_rad.cwiseMin(r.q);
    out.max_rad = first_range ? r.q : out.max_rad.cwiseMax(r.q);
    first_range = false;
    record_limits(arm, r.q, i, out);
    if (keep_solutions) out.solutions.push_back(r.q);
  }
  return out;
}

Joints start_joints(const RobotCell& cell, const slicer::PosePoint& first) {
  const JointReport j = analyse_joints(arm_model(cell), cell, {first}, true);
  return j.ok() && !j.solutions.empty() ? j.solutions.front() : Joints::Zero();
}

slicer::PosePoint moved_along_nozzle(const RobotCell& cell, const slicer::PosePoint& p,
                                     double away_mm) {
  slicer::PosePoint out = p;
  out.workpiece_origin_mm += away_mm * cell.nozzle_axis;
  out.contact_mm -= away_mm * (rotation_of(p.workpiece_wxyz).transpose() * cell.nozzle_axis);
  return out;
}

}  // namespace strand::machines
