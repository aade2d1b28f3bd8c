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
  // When the robot reaches each point, one per point (post::time_laps: each lap's real
  // duration with its corner slowdowns); empty: the pose program's distance / speed t_s.
  std::vector<double> t_s = {};
};

// E per mm of path at contact speed `speed_mm_per_s` over a bead of `bead_area_mm2`:
// v_ext / v for a time-based extruder, bead area / mm3 per E for a volumetric one.
double e_per_mm(const MachineProfile& m, double speed_mm_per_s, double bead_area_mm2);

// E of a deposit of `length_mm` that the robot runs in `duration_s`: v_ext x duration for a
// time-based extruder (the screw runs at its fixed feed while the robot deposits, as in the
// thesis), the bead volume / mm3 per E for a volumetric one (the profile's calibration).
double deposit_e(const MachineProfile& m, double length_mm, double duration_s,
                 double bead_area_mm2);

struct ExtruderProgram {
  std::string gcode;
  std::vector<double> lap_e;  // E pushed in each lap (index = PosePoint::lap)
  double e_total = 0.0;
};

// Precondition: m.robot.enabled. Every E move is at most the profile's extrude_max_length.
// Runs of deposits share one E move while their E feeds stay within 1 % of the run's first
// (the move's feed is the run's E over its time, so the time line is kept exactly).
ExtruderProgram extruder_program(const slicer::PoseProgram& program, const MachineProfile& m,
                                 const ExtruderGcodeInfo& info);
std::string write_extruder_gcode(const slicer::PoseProgram& program, const MachineProfile& m,
                                 const ExtruderGcodeInfo& info);

// The pin level the robot sets, and the printer waits for, at the start of lap `lap`:
// levels alternate so a late printer never waits for a signal it already missed.
int lap_signal_level(const RobotCell& cell, int lap);

// The level both handshake lines rest at between runs (the level of "lap -1"). Each program
// drives its output there at start (the extruder then waits for the robot's) and after the
// last lap (the robot after the extruder's), so a finished run, whatever its number of laps,
// leaves both lines where the next run's lap 0 cannot be taken from them.
int handshake_idle_level(const RobotCell& cell);

}  // namespace strand::machines
