// ABB RAPID module of a robot cell (IRC5 / OmniCore, IRB 1200): the nozzle is a stationary
// tool (tooldata robhold FALSE, its frame in the world = robot base frame) and the workpiece a
// robot-held work object (wobjdata robhold TRUE, its user frame on the flange), so each
// robtarget is the nozzle's pose in the workpiece frame (mm and a quaternion) with the
// configuration (cf1, cf4, cf6, cfx) of the arm's inverse kinematics, and the speeddata of a
// MoveL is the contact speed over the workpiece. The module starts with MoveAbsJ to home and
// to the approach pose's joint values; each lap is a procedure that waits for the extruder's
// ready input (when the profile names one) and sets the lap output. The module is named by
// rapid_module_name and the file after it (`<module>.mod`).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "machines/robot_arm.h"
#include "machines/robot_transit.h"
#include "slicer/pose_program.h"

namespace strand::machines {

struct RapidProgram {
  std::string mod;
  int procedures = 0;
  int move_l = 0;
};

// ABB configuration data of a solution of the IRB 1200: quadrants of axes 1, 4 and 6 and the
// cfx number (wrist centre in front of / behind axis 1, above / below the lower arm, axis 5
// positive / negative).
std::array<int, 4> abb_confdata(const ArmModel& arm, const Joints& q);

// Precondition: m.robot.enabled. `module` is rapid_module_name of the output stem.
RapidProgram write_rapid(const slicer::PoseProgram& program, const MachineProfile& m,
                         const std::string& module, const std::string& csv_name,
                         const std::vector<std::string>& header, double blend_mm,
    const TransitPlan& transit);

}  // namespace strand::machines
