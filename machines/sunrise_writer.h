// KUKA Sunrise (LBR iiwa) program of a robot cell: a RoboticsAPIApplication that reads the
// pose CSV on the controller and moves a frame of the workpiece through it lap by lap with
// lin motions at setCartVelocity(v_cart), setting an I/O output at each lap start for the
// extruder's handshake. The moved frame sits on the layer's contact radius, so its speed is
// the contact speed (a turn about the cylinder axis moves every point of one radius alike).
// With robot.sunrise.tool_template / tool_frame the cylinder is the project's calibrated tool
// template, with robot.sunrise.nozzle_frame the targets are relative to the project's nozzle
// frame; otherwise both come from the profile.
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"
#include "machines/robot_transit.h"
#include "slicer/pose_program.h"

namespace strand::machines {

// A Java class name for an output base name: "missing-rib-cylinder" -> "MissingRibCylinder".
std::string java_class_name(const std::string& base_name);

// `csv_name`: the CSV's file name as copied to the controller. Precondition: m.robot.enabled.
std::string write_sunrise_java(const slicer::PoseProgram& program, const MachineProfile& m,
                               const std::string& base_name, const std::string& csv_name,
                               const std::vector<std::string>& header,
    const TransitPlan& transit);

}  // namespace strand::machines
