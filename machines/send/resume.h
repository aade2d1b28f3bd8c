// Stopping and resuming a job: the modal state a file has set up before a given line
// (units, positioning, plane, feed mode, work offset, extrusion mode, position including
// rotary axes, feed, pen, valve, output pin, spindle, coolant, fan, heater and tool state),
// the commands that restore it before resuming there, and the commands that leave the
// machine safe after a pause (pen up, valve closed, from the machine profile).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "machines/send/protocol.h"

namespace strand::machines {

struct ModalState {
  bool inches = false;                  // G20
  bool relative = false;                // G91
  std::optional<bool> relative_e;       // M83 / M82 (G90 / G91 set it too once it is known)
  std::optional<bool> inverse_time;     // G93 / G94, when the file says
  std::vector<std::string> modes;       // plane (G17-G19) and work offset (G54-G59.3) set
  std::optional<double> x, y, z, e, f;  // position (file units; unknown after G28) and feed
  std::map<char, double> rotary;        // A, B, C positions the file moved to or set
  std::vector<std::string> tool_state;  // last pen, valve, pin, spindle, coolant, fan, heater
                                        // and tool commands, in order of first use
};

// The state after running every command before `file_line` (1-based); `m` names the
// valve commands.
ModalState modal_state_before(const std::vector<Command>& commands, int file_line,
                              const MachineProfile& m);

// Commands that make the machine safe mid-job: pen up (servo, Z or drum rest) for
// plotters, the valve's off commands for valve machines, nothing else.
std::vector<std::string> safe_state_gcode(const MachineProfile& m, const ModalState& s);

// Commands to send before resuming at the line `s` was taken at: units, positioning, plane
// and work offset, E mode, the safe state, a travel to the position (lifted by the profile's
// travel lift first; in mm/min, so under G94), down to z, E and rotary positions (G92: a
// rotary axis has no home, and telling it the position it had is right whether or not the
// controller restarted), the feed, then the pen/tool/output state, G93 and G91 as they were.
std::vector<std::string> resume_preamble(const MachineProfile& m, const ModalState& s);

}  // namespace strand::machines
