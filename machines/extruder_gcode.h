// The fixed printer's own program in a robot cell: E-only G-code on the pose program's time
// line. The printer parks its nozzle on the cylinder, then for each lap (optionally after a
// handshake on a pin the robot sets) pushes E while the robot deposits and dwells while it
// travels, so both machines run the same schedule.
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"
#include "slicer/pose_program.h"

namespace strand::machines {

struct ExtruderGcodeInfo {
  std::vector<std::string> header;    // comment lines (without ';')
  std::vector<double> bead_area_mm2;  // per layer, for a volumetric extruder
};

// E per mm of path at contact speed `speed_mm_per_s` over a bead of `bead_area_mm2`:
// v_ext / v for a time-based extruder, bead area / mm3 per E for a volumetric one.
double e_per_mm(const MachineProfile& m, double speed_mm_per_s, double bead_area_mm2);

// Precondition: m.robot.enabled. Every E move is at most the profile's extrude_max_length.
std::string write_extruder_gcode(const slicer::PoseProgram& program, const MachineProfile& m,
                                 const ExtruderGcodeInfo& info);

// The pin level the robot sets, and the printer waits for, at the start of lap `lap`:
// levels alternate so a late printer never waits for a signal it already missed.
int lap_signal_level(const RobotCell& cell, int lap);

}  // namespace strand::machines
