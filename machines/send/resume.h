// Stopping and resuming a job: the modal state a file has set up before a given line
// (units, positioning, extrusion mode, position, feed, pen or tool state), the commands that
// restore it before resuming there, and the commands that leave the machine safe after a
// pause (pen up, valve closed, from the machine profile).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "machines/send/protocol.h"

namespace strand::machines {

struct ModalState {
  bool inches = false;              // G20
  bool relative = false;            // G91
  std::optional<bool> relative_e;   // M83 / M82, when the file says
  std::optional<double> x, y, z, e, f;  // machine position (file units) and feed
  std::vector<std::string> tool_state;  // last pen, spindle, fan, valve and tool commands
};

// The state after running every command before `file_line` (1-based); `m` names the
// valve commands.
ModalState modal_state_before(const std::vector<Command>& commands, int file_line,
                              const MachineProfile& m);

// Commands that make the machine safe mid-job: pen up (servo, Z or drum rest) for
// plotters, the valve's off commands for valve machines, nothing else.
std::vector<std::string> safe_state_gcode(const MachineProfile& m, const ModalState& s);

// Commands to send before resuming at the line `s` was taken at: units and positioning,
// the safe state, a travel to the position (lifted by the profile's travel lift first),
// down to z, E and feed, then the pen/tool state and relative modes as they were.
std::vector<std::string> resume_preamble(const MachineProfile& m, const ModalState& s);

}  // namespace strand::machines
