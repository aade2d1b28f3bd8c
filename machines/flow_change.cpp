// Flow changes on pneumatic machines: the profile's pressure template or a pause.
#include "machines/flow_change.h"

#include "machines/gcode_format.h"
#include "slicer/params.h"

namespace strand::machines {

bool flow_is_pressure(const MachineProfile& m) {
  return m.deposition.model == DepositionModel::Valve || m.deposition.model == DepositionModel::ManualValve;
}

std::string comment_line(const MachineProfile& m, const std::string& text) {
  if (m.firmware == Firmware::Grbl) return "(" + comment_text(text, false) + ")";
  return "; " + comment_text(text);
}

std::string flow_change_gcode(const MachineProfile& m, double flow, const std::string& what) {
  if (!flow_is_pressure(m)) return {};
  const std::string value = slicer::short_number(flow);
  std::string out;
  if (!m.deposition.pressure_command.empty()) {
    for (const std::string& line : m.deposition.pressure_command) {
      out += (out.empty() ? "" : "\n") + replace_all(line, "{flow}", value);
    }
    return out + "\n" + comment_line(m, "flow " + value + (what.empty() ? "" : " for " + what));
  }
  // By hand: the message names the value and what it is for; the pause waits for the operator.
  std::string message = comment_text("Set flow " + value + (what.empty() ? "" : " for " + what) + ", then resume", false);
  for (char& c : message) {
    if (c == '"' || c == ';') c = '\'';  // M291 P"..." and comments end there
  }
  switch (m.firmware) {
    case Firmware::Marlin: return "M117 " + message + "\nM0 " + message;
    case Firmware::Klipper: return "M117 " + message + "\nPAUSE";
    case Firmware::RepRap: return "M291 P\"" + message + "\" S2";
    case Firmware::Grbl: return "M0 (" + message + ")";
  }
  return {};
}

}  // namespace strand::machines
