// A change of ink flow inside a job (issue 32: the line-width matrix prints each row at its
// own flow; an ink profile's flow is set once at the start) in the machine's terms. On
// E-driven machines the planner scales the deposited volume, so no command is needed; on
// pneumatic machines flow is the pressure: the profile's deposition.pressure_command
// template, or a pause asking the operator to set it by hand.
#pragma once

#include <string>

#include "machines/profile.h"

namespace strand::machines {

// True when the machine sets flow by pressure (valve or manual valve), so a flow change
// needs commands; false for E-driven machines and those without deposition.
bool flow_is_pressure(const MachineProfile& m);

// The G-code lines (joined by '\n', no trailing newline) that set `flow` on a pneumatic
// machine: pressure_command with {flow} replaced, else an LCD message and a pause in the
// firmware's words (Marlin M117 + M0, Klipper M117 + PAUSE, RepRapFirmware a blocking M291,
// GRBL M0 with a comment). `what` says what the flow is for ("this ink"; empty: nothing).
// Empty when !flow_is_pressure(m).
std::string flow_change_gcode(const MachineProfile& m, double flow, const std::string& what);

// One comment line in the firmware's syntax, the text made safe (gcode_format.h).
std::string comment_line(const MachineProfile& m, const std::string& text);

}  // namespace strand::machines
