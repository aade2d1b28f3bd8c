// Kinematics of the 7-axis arm of a robot cell (KUKA LBR iiwa 14 R820): forward kinematics
// from its published Denavit-Hartenberg geometry, the geometric Jacobian, and a numeric
// inverse kinematics (damped least squares, redundancy resolved toward the previous solution
// and mid-range) so that every pose of a program can be checked against the joint limits.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>

#include "machines/holder_profile.h"

namespace strand::machines {

using Joints = Eigen::Matrix<double, 7, 1>;  // A1..A7, rad

// Standard DH row: T = Rz(q) Tz(d) Tx(a) Rx(alpha).
struct DhRow {
  double a_mm = 0.0;
  double alpha_rad = 0.0;
  double d_mm = 0.0;
};

struct ArmModel {
  std::string name;
  std::array<DhRow, 7> dh;
  Joints limit_rad = Joints::Zero();  // symmetric limits +-limit per joint
  Vec3 shoulder_mm = Vec3::Zero();    // A2 axis centre: the reach is measured from here
  double reach_mm = 0.0;              // wrist centre (A6) within this distance of the shoulder
  double flange_mm = 0.0;             // wrist centre to flange along the flange z axis
};

// The LBR iiwa 14 R820 (d1 360, d3 420, d5 400, d7 126 mm, twists -90/90/90/-90/-90/90/0 deg)
// with the cell's joint limits and reach.
ArmModel lbr_iiwa_14_r820(const RobotCell& cell);

// Flange pose in the robot base frame, mm.
Eigen::Isometry3d forward_kinematics(const ArmModel& arm, const Joints& q);
// 6 x 7 geometric Jacobian at q: rows 0-2 linear (mm/rad), rows 3-5 angular, base frame.
Eigen::Matrix<double, 6, 7> jacobian(const ArmModel& arm, const Joints& q);
// Wrist centre of a flange pose (flange origin minus flange_mm along its z axis).
Vec3 wrist_centre(const ArmModel& arm, const Eigen::Isometry3d& flange);

struct IkResult {
  Joints q = Joints::Zero();
  bool converged = false;
  double position_error_mm = 0.0;
  double orientation_error_rad = 0.0;
  int iterations = 0;
};

// Solves for a flange pose from `seed` (the previous pose's solution along a path): damped
// least squares on the 6D error, with the null space pulled toward the seed and the joints'
// mid-range so the redundant elbow stays continuous and away from its limits.
IkResult solve_ik(const ArmModel& arm, const Eigen::Isometry3d& target, const Joints& seed,
                  int max_iterations = 100);

}  // namespace strand::machines
