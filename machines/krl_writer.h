// KUKA KRL program of a robot cell for a KR C4 (.src + .dat): the workpiece is carried by the
// robot and the nozzle is an external TCP ($IPO_MODE = #TCP, $TOOL = workpiece on the flange,
// $BASE = nozzle: the profile's frames in the .dat, or TOOL_DATA[n] / BASE_DATA[m] when the
// profile names the controller's, robot.krl.tool_data / base_data), so each LIN point is the nozzle's pose in the workpiece frame (X, Y, Z in mm,
// A, B, C in degrees) and $VEL.CP (m/s) is the speed of the contact over the workpiece. The
// program starts with a PTP to the first pose's axis values (from the arm's inverse
// kinematics). Each lap is a local sub-program, split further when longer than the profile's
// points per module. The module is named by krl_module_name, and KSS wants the files named
// after it (`<module>.src`, `<module>.dat`).
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"
#include "machines/robot_transit.h"
#include "slicer/pose_program.h"

namespace strand::machines {

struct KrlProgram {
  std::string src;
  std::string dat;
  int sub_programs = 0;
  int lin_points = 0;
};

// A KRL module name for an output base name: letters, digits and _ (at most 24 characters,
// not starting with a digit, not a KRL keyword).
std::string krl_module_name(const std::string& base_name);

// KUKA A, B, C angles (Z, Y', X'' rotations) of a rotation, degrees; exact at B = +-90 deg
// too (C = 0 there). kuka_abc_rotation is its inverse.
Vec3 kuka_abc_deg(const Eigen::Matrix3d& r);
Eigen::Matrix3d kuka_abc_rotation(const Vec3& abc_deg);

// The nozzle (external TCP) frame in the base frame: z along the flow, x = nozzle axis x
// cylinder axis, so the LIN angles stay clear of B = +-90 deg (A follows the turn).
Eigen::Matrix3d nozzle_frame_rotation(const RobotCell& cell);

// Precondition: m.robot.enabled.
KrlProgram write_krl(const slicer::PoseProgram& program, const MachineProfile& m,
                     const std::string& base_name, const std::vector<std::string>& header,
                     double blend_mm,
    const TransitPlan& transit);

}  // namespace strand::machines
