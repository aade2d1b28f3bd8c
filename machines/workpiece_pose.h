// Where the workpiece must be for one path point: the pose of the workpiece (cylinder) frame
// that puts contact point p under the nozzle tip with the surface normal against the nozzle
// axis. A robot cell keeps the tip fixed and moves the workpiece; a rotary axis keeps the
// workpiece origin on its axis, turns it, and moves the nozzle.
#pragma once

#include <Eigen/Geometry>

#include "machines/profile.h"

namespace strand::machines {

struct WorkpiecePose {
  Vec3 origin_mm = Vec3::Zero();                           // workpiece frame origin, machine frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // workpiece -> machine
  Vec3 tip_mm = Vec3::Zero();                              // nozzle tip, machine frame
};

// The line the workpiece turns about and the nozzle's direction, from a robot-holds-substrate
// or rotary profile.
struct Holder {
  bool fixed_tip = true;          // robot cell: the tip is fixed; rotary: the origin is fixed
  Vec3 anchor_mm = Vec3::Zero();  // robot: nozzle tip; rotary: axis point (the cylinder's v = 0)
  Vec3 nozzle_axis = -Vec3::UnitZ();  // unit, direction of flow
  Vec3 axis_dir = Vec3::UnitX();      // unit, the workpiece z axis in the machine frame
};

// Precondition: m.robot.enabled or m.rotary.enabled.
Holder holder_of(const MachineProfile& m);

// Pose for contact point p (workpiece frame, on a surface of revolution about the workpiece z
// axis) at workpiece turn `turn_rad` (the angle of p around the axis): R n = -nozzle_axis and
// R p + origin = tip.
WorkpiecePose workpiece_pose(const Holder& h, const Vec3& contact_mm, double turn_rad);

// The workpiece frame in the flange frame of a robot cell (mount along flange z).
Eigen::Isometry3d workpiece_in_flange(const RobotCell& cell);

// Unit quaternion (w, x, y, z) of a rotation, w >= 0 for a unique sign.
Eigen::Vector4d quaternion_wxyz(const Eigen::Matrix3d& r);
Eigen::Matrix3d rotation_of(const Eigen::Vector4d& wxyz);

}  // namespace strand::machines
