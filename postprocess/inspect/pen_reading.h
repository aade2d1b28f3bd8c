// Pen plotter files read back: which commands lift and lower the pen (M300 S, M280 S, M3/M5,
// Z) and at which values, from the machine profile when one is given, else from the common
// conventions, so a plotter that travels with G1 and the pen up is not read as all ink.
#pragma once

#include <optional>
#include <string>

#include "machines/profile.h"

namespace strand::post {

// Z-lift plotters without a profile: a drawing move more than this above the lowest drawing
// z is a pen-up travel (pen lifts are a millimetre or more; paper and bed flatness is well
// under this), mm.
inline constexpr double kPenLiftMinMm = 0.2;

struct PenReading {
  // Servo value (M280 S, M3 S, M300 S) of pen down and pen up; a value nearer down_value is
  // down. Unset: each command's common convention (pen_down_by_command).
  std::optional<double> down_value, up_value;
  int servo_index = -1;  // M280 P<index> of the pen servo; -1 = any servo
  // Z-lift plotters: a drawing move at or below this z has the pen down, mm. Unset: found
  // from the file (lowest drawing z + kPenLiftMinMm) when the check reads a drawing.
  std::optional<double> z_down_max_mm;
  std::string machine;  // profile the values come from, empty for the conventions
  // Valve outputs as LinuxCNC and Planet CNC switch them (M62/M64 on, M63/M65 off, P the
  // output): read only when a valve profile's on_gcode/off_gcode use them; then a G1 that
  // moves in XY deposits while the output is on.
  std::optional<int> valve_on_m, valve_off_m;
  std::optional<double> valve_p;
};

// The pen settings of a plotter profile (empty reading for printers and drum plotters), and
// the valve outputs of a valve printer whose commands are M62-M65.
PenReading pen_reading_from(const machines::MachineProfile& m);

// M-code `m` with its S and P words: true = pen down, false = pen up, nullopt = says nothing
// about the pen (a Marlin M300 beep with a duration P, another servo, another M-code).
std::optional<bool> pen_down_by_command(const PenReading& r, int m, std::optional<double> s,
                                        std::optional<double> p);

// One line for the report: which command and values were read as pen up and down.
std::string pen_convention(const PenReading& r, int m);

}  // namespace strand::post
