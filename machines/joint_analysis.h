// Joint-space view of a robot cell's pose program: every workpiece pose turned into a flange
// pose, checked against the arm's reach and solved by inverse kinematics along the path, with
// each joint's range over the program and the poses outside the joint limits.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "machines/robot_arm.h"
#include "slicer/pose_program.h"

namespace strand::machines {

struct JointReport {
  std::size_t poses = 0;
  int axes = 7;                     // the arm's joints (the rest of min/max stay 0)
  Joints min_rad = Joints::Zero();  // over the solved poses
  Joints max_rad = Joints::Zero();
  double max_reach_mm = 0.0;       // farthest wrist centre from the shoulder
  double max_ik_error_mm = 0.0;    // worst flange position error of a solution
  std::size_t unreachable = 0;     // wrist beyond reach, or no solution found
  std::size_t outside_limits = 0;  // a solved pose with a joint beyond its limit
  std::optional<std::size_t> first_unreachable, first_outside;
  std::string first_unreachable_what;  // "wrist 851.2 mm from the shoulder > reach 820 mm"
  std::string first_outside_what;      // "A7 = 181.2 deg, limit +-175 deg"
  std::vector<Joints> solutions;       // per pose (only when asked for)
  std::size_t unchecked = 0;           // poses left after max_problems problems

  bool ok() const { return unreachable == 0 && outside_limits == 0; }
};

// Flange pose of a workpiece pose (origin, quaternion w-first) in a robot cell.
Eigen::Isometry3d flange_pose(const RobotCell& cell, const Vec3& workpiece_origin_mm,
                              const Eigen::Vector4d& workpiece_wxyz);

// Solves every point of `points` in order, each seeded by the previous solution; stops after
// `max_problems` unreachable or out-of-limit poses (bounding the work on a hopeless program).
JointReport analyse_joints(const ArmModel& arm, const RobotCell& cell,
                           const std::vector<slicer::PosePoint>& points,
                           bool keep_solutions = false, std::size_t max_problems = 1000);

// Joint values (A1..A7, rad) of the first pose of a program, as analyse_joints finds them, so
// that robot programs can start by axis values (no Status/Turn or elbow left to the
// controller). Zero when the pose has no solution (produce_curved refuses such programs).
Joints start_joints(const RobotCell& cell, const slicer::PosePoint& first);

// `p` with the workpiece moved `away_mm` along the nozzle axis (the flow), away from the fixed
// tip: the approach and retract poses. The contact point (the tip in the workpiece frame)
// moves back against the flow by the same distance.
slicer::PosePoint moved_along_nozzle(const RobotCell& cell, const slicer::PosePoint& p,
                                     double away_mm);

}  // namespace strand::machines
