// URScript program of a robot cell for a Universal Robots e-Series arm (UR10e): the robot
// holds the workpiece under the fixed nozzle, so the TCP is set (set_tcp) to a frame of the
// workpiece on the contact radius of the current layer, and every movel target is that
// frame's pose in the base frame (p[x, y, z, rx, ry, rz]: metres and a rotation vector) with
// v the contact speed in m/s. The program starts with movej to the home and to the approach
// pose's joint values (from the arm's inverse kinematics), sets the lap output at each lap
// start after waiting for the extruder's ready input when the profile names one, and ends
// with a retract along the nozzle axis and home.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "machines/robot_transit.h"
#include "slicer/pose_program.h"

namespace strand::machines {

// The rotation vector (axis times angle, rad, angle in [0, pi]) of a rotation; robust near pi
// (from the rotation's quaternion, not from its trace).
Vec3 rotation_vector(const Eigen::Matrix3d& r);
Eigen::Matrix3d rotation_of_vector(const Vec3& rv);

// The TCP of layer k: the workpiece frame moved `radius_mm` along its x axis (the u = 0
// line), in the flange frame.
Eigen::Isometry3d contact_tcp_in_flange(const RobotCell& cell, double radius_mm);

// Precondition: m.robot.enabled. `name` is the script's function name (urscript_function_name
// of the output stem); `csv_name` is shown on the teach pendant; blend_mm the largest blend
// radius of movel.
std::string write_urscript(const slicer::PoseProgram& program, const MachineProfile& m,
                           const std::string& name, const std::string& csv_name,
                           const std::vector<std::string>& header, double blend_mm,
    const TransitPlan& transit);

}  // namespace strand::machines
