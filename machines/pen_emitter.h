// Pen emitter: a plotting MotionProgram (paper frame) -> G-code for one plotter profile.
// Convention of plotting programs: z = 0 pen down, z = 1 pen up; a Travel that only changes
// z lifts or drops the pen; Deposit moves draw (G1), other Travels move with the pen up (G0);
// Move::tool is the 0-based pen. Paper points become axis values through the plotter's
// kinematics (cable lengths, R and theta screws), written with 3 decimals.
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"
#include "slicer/motion.h"

namespace strand::machines {

inline constexpr double kPenDownZ = 0.0;
inline constexpr double kPenUpZ = 1.0;
// Decimals of every axis word in pen G-code.
inline constexpr int kPenAxisDecimals = 3;

// Throws std::logic_error if the machine is not a plotter (the planner checks first).
std::string emit_pen_gcode(const slicer::MotionProgram& program, const MachineProfile& machine,
                           const std::vector<std::string>& header);

// The command that lifts (up) or drops the pen on a servo or Z-lift plotter, with its
// comment: "M280 P0 S90 ; pen up", "M3 S50 ; pen up" (GRBL), "G0 Z2.000 ; pen up".
// Throws std::logic_error for drum machines (their pen state depends on the marker).
std::string pen_lift_command(const MachineProfile& m, bool up);

// Drum angles of the 1-based marker k.
double drum_engage_deg(const PenSetup& pen, int k);
double drum_rest_deg(const PenSetup& pen, int k);
double drum_write_deg(const PenSetup& pen, int k);

}  // namespace strand::machines
