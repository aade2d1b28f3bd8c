// Machine profiles: kinematics, firmware flavour, deposition model, limits and start/end
// templates, loaded from JSON (shipped ones by name, user ones by path).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "machines/holder_profile.h"
#include "machines/plotter_profile.h"
#include "slicer/geometry.h"
#include "slicer/toolpath.h"

namespace strand::machines {

using slicer::Vec2;
using slicer::Vec3;

enum class KinematicsKind {
  Delta,                // cylindrical build volume centred on (0, 0)
  Cartesian,            // box from min_mm to max_mm
  RobotHoldsSubstrate,  // a robot holds a curved substrate under a fixed nozzle (robot cell)
  Rotary,               // XYZ box plus a rotary axis that turns a cylinder under the nozzle
};

enum class Firmware { Marlin, RepRap, Klipper, Grbl };

enum class DepositionModel {
  ManualValve,  // operator opens the air valve by hand: flow never stops, no E words
  Valve,        // controllable valve: on/off commands around each strand
  EVolumetric,  // screw or piston extruder driven by the E axis
  None,         // no flow words at all (the thesis' E0 files)
};

struct BuildVolume {
  KinematicsKind kind = KinematicsKind::Cartesian;
  double radius_mm = 0.0;         // delta: printable radius
  double height_mm = 0.0;         // usable z
  Vec3 min_mm = Vec3::Zero();     // cartesian box
  Vec3 max_mm = Vec3::Zero();
  Vec2 part_center_mm = Vec2::Zero();  // where parts are centred
};

struct Deposition {
  DepositionModel model = DepositionModel::None;
  double lead_s = 0.0;            // valve: open this long before moving; manual: wait at start
  double lag_s = 0.0;             // valve: close this long before the strand ends
  std::string message;            // manual valve: LCD message (M117)
  std::vector<std::string> on_gcode;   // valve: commands that open it
  std::vector<std::string> off_gcode;  // valve: commands that close it
  // valve, manual valve: commands that set the pressure, {flow} replaced by the value of a
  // line-width matrix row or an ink profile (machines/flow_change.h); empty: ask by hand.
  std::vector<std::string> pressure_command;
  double mm3_per_e = 1.0;         // e-volumetric: ink volume pushed by one E unit
  bool relative_e = false;        // e-volumetric: M83 when true, M82 otherwise
  double prime_e = 0.0;           // e-volumetric: E pushed once at start
  double retract_e = 0.0;         // e-volumetric: suck-back at strand ends (0 = none)
  double reservoir_ml = 30.0;     // syringe or tank volume, for refill estimates
  // e-volumetric: Marlin's EXTRUDE_MAXLENGTH; a move pushing more E units than this is
  // silently dropped by the firmware, so longer moves are split.
  double extrude_max_length = 200.0;
};

// One printhead of a machine with several (issue 33): where its nozzle sits relative to the
// first one, and how it deposits (the machine's deposition unless it has its own).
struct Tool {
  std::string name;
  Vec3 offset_mm = Vec3::Zero();  // nozzle position minus tool 0's, mm (Strand moves by it)
  double nozzle_mm = 0.0;         // 0: not given
  // How high the head is held above its printing height while another head deposits (its
  // own Z axis or a retracting mount), mm; 0: it rides at its offset (post/plan/idle_heads.h).
  double idle_lift_mm = 0.0;
  Deposition deposition;
  double temperature_c = 0.0;     // a heated or cooled head's set point; 0: none
  std::vector<std::string> select_gcode;    // after a change to this head (prime, purge, wipe)
  std::vector<std::string> deselect_gcode;  // before a change away from it (idle retract, pressure off)
};

struct Limits {
  double max_feed_mm_per_min = 6000.0;
  double travel_feed_mm_per_min = 3000.0;
  double z_feed_mm_per_min = 600.0;
  double acceleration_mm_per_s2 = 500.0;
  double junction_deviation_mm = 0.05;
  // e-volumetric: highest ink flow the extruder sustains; deposit feeds are capped so that
  // feed x bead area stays below it. 0 = no cap.
  double max_volumetric_flow_mm3_per_s = 0.0;
};

struct MachineProfile {
  std::string name;
  std::string description;
  BuildVolume volume;
  Firmware firmware = Firmware::Marlin;
  bool arcs = false;                 // firmware accepts G2/G3
  Deposition deposition;
  Limits limits;
  // Per-feature deposit speed factors (node 1.1 = 10 % faster); a job's
  // "<feature>-speed-factor" overrides the profile's value for that feature.
  std::map<slicer::Feature, double> speed_factors;
  double travel_lift_mm = 1.0;       // z hop for travels between strands
  // Conformal printing with the nozzle vertical (strand slice --onto): the steepest substrate
  // slope, normal from vertical, the nozzle follows before its side touches the substrate;
  // 30 deg suits a plain syringe needle over a gently curved part, deg.
  double max_surface_slope_deg = 30.0;
  // Printheads (empty: one, tool 0, with `deposition`). Strand applies each tool's offset
  // to the coordinates it writes (as PrusaSlicer does), so firmware offsets must be zero.
  std::vector<Tool> tools;
  // A tool change: template lines with {tool} (index) and {name}; default "T{tool}".
  std::vector<std::string> tool_change_gcode;
  std::vector<std::string> start_gcode;  // templates; {lead_s}, {lead_ms}, {message}
  std::vector<std::string> end_gcode;
  nlohmann::json source;             // the profile as loaded, for reports
  // --- plotting (issue 5) ---
  Plotter plotter;                   // pen and plotter kinematics; enabled for plotters
  // --- curved substrates (issue 11) ---
  RobotCell robot;                   // enabled for robot-holds-substrate
  RotaryAxis rotary;                 // enabled for rotary
};

// Loads a profile by name — the user's own (user_profile_dir()/NAME.json) before a shipped
// one — or from a path ending in .json. Throws InputError naming the key path of every problem.
MachineProfile load_profile(const std::string& name_or_path);

// A lab's own profiles: $XDG_CONFIG_HOME/strand/machines, else ~/.config/strand/machines
// ("" when neither variable is set).
std::string user_profile_dir();

// One profile `--machine NAME` can name: shipped, or a user file (which wins over a shipped
// profile of the same name: `shadows_shipped`).
struct ProfileEntry {
  std::string name;
  std::string description;
  std::string origin;  // "shipped" or the user file's path
  bool shadows_shipped = false;
  std::string json_text;  // the profile as written
};
// Every name, sorted; a user file that cannot be read is listed with its problem as the
// description. At most 1000 user files are read.
std::vector<ProfileEntry> profile_catalog();
// Parses and validates profile JSON; `origin` names the file in messages.
MachineProfile profile_from_json(const nlohmann::json& j, const std::string& origin);
// Names and one-line descriptions of the shipped profiles, sorted by name.
std::vector<std::pair<std::string, std::string>> list_profiles();

std::string to_string(Firmware f);
std::string to_string(KinematicsKind k);
std::string to_string(DepositionModel m);

// How many tools the machine has (1 without a "tools" list) and tool k's deposition (the
// machine's when it has no tools list).
int tool_count(const MachineProfile& m);
const Deposition& tool_deposition(const MachineProfile& m, int tool);
Vec3 tool_offset(const MachineProfile& m, int tool);

}  // namespace strand::machines
