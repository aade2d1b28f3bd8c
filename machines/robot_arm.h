// Kinematics of the arm of a robot cell (KUKA LBR iiwa 14 R820 with 7 axes; Universal Robots
// UR10e and ABB IRB 1200-5/0.9 with 6): forward kinematics from the published
// Denavit-Hartenberg geometry, the geometric Jacobian, and a numeric inverse kinematics
// (damped least squares, redundancy resolved toward the previous solution and mid-range) so
// that every pose of a program can be checked against the joint limits. A 6-axis arm keeps
// its seventh joint at 0 (its Jacobian column is zero).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "machines/holder_profile.h"

namespace strand::machines {

using Joints = Eigen::Matrix<double, 7, 1>;  // A1..A7, rad (6-axis arms: A7 = 0)

// Standard DH row: T = Rz(q) Tz(d) Tx(a) Rx(alpha).
struct DhRow {
  double a_mm = 0.0;
  double alpha_rad = 0.0;
  double d_mm = 0.0;
};

struct ArmModel {
  std::string name;
  int axes = 7;  // 6 or 7; rows and joints past it are unused (held at 0)
  std::array<DhRow, 7> dh;
  Joints offset_rad = Joints::Zero();     // DH angle = joint value + offset
  Joints limit_rad = Joints::Zero();      // upper limit per joint
  Joints limit_min_rad = Joints::Zero();  // lower limit per joint (-limit_rad unless asymmetric)
  std::vector<Joints> seeds;              // postures the first pose is solved from
  Vec3 shoulder_mm = Vec3::Zero();        // A2 axis centre: the reach is measured from here
  double reach_mm = 0.0;                  // wrist centre (A6) within this distance of the shoulder
  double flange_mm = 0.0;                 // wrist centre to flange along the flange z axis
};

// The LBR iiwa 14 R820 (d1 360, d3 420, d5 400, d7 126 mm, twists -90/90/90/-90/-90/90/0 deg)
// with the cell's joint limits and reach.
ArmModel lbr_iiwa_14_r820(const RobotCell& cell);
// The UR10e (Universal Robots' published DH: d1 180.7, a2 -612.7, a3 -571.55, d4 174.15,
// d5 119.85, d6 116.55 mm, twists 90/0/0/90/-90/0 deg; joint values as the teach pendant
// shows them).
ArmModel ur10e(const RobotCell& cell);
// The ABB IRB 1200-5/0.9 (d1 399, a2 448, a3 42, d4 451, d6 82 mm; axis 2 at 0 with the
// upper arm vertical, axis 6 offset by 180 deg, so that joint values are ABB's).
ArmModel irb1200_5_09(const RobotCell& cell);
// The arm the cell names (robot.arm).
ArmModel arm_model(const RobotCell& cell);

// Flange pose in the robot base frame, mm.
Eigen::Isometry3d forward_kinematics(const ArmModel& arm, const Joints& q);
// True when every joint of q is within its limits (with `slack_rad`).
bool within_limits(const ArmModel& arm, const Joints& q, double slack_rad = 1e-9);
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
