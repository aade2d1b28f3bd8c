// 4-axis G-code for a rotary-axis printer: the cylinder turns on the A axis under an XYZ
// nozzle. A is in degrees (the workpiece turns by +A about the axis direction); the feed is set
// so the SURFACE speed equals the planned speed on every move:
//  - Marlin (2.1, AXIS4_ROTATES): F applies to the XYZ distance when the move has XYZ
//    components (A only follows in the same time), and is degrees per minute when only A
//    moves; so F = XYZ distance / planned time, or |dA| / planned time for pure turns.
//  - RepRapFirmware 3.5+ with feed "inverse-time": G93, F = 1 / planned time in minutes.
// The header names the axis (;ROTARY_AXIS:, ;ROTARY_AXIS_DIR:, ;ROTARY_AXIS_POINT:) and the
// substrate (;SUBSTRATE:) so a reader can map every move back onto the workpiece.
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"
#include "slicer/pose_program.h"

namespace strand::machines {

struct RotaryGcodeInfo {
  std::vector<std::string> header;    // comment lines (without ';')
  std::vector<double> bead_area_mm2;  // per layer: deposit volume per mm of path
  std::vector<double> bead_width_mm;  // per layer, for ;WIDTH:
};

// The machine's A angle for a workpiece turn, degrees.
double rotary_a_deg(double turn_rad);

// Precondition: m.rotary.enabled.
std::string write_rotary_gcode(const slicer::PoseProgram& program, const MachineProfile& m,
                               const RotaryGcodeInfo& info);

}  // namespace strand::machines
