// Room postprocess/inspect (library strand_inspect; links plan): reading any G-code, ours or a
// slicer's, back into a MotionProgram (gcode_parser.h) and judging it: strands per layer,
// self-crossings and touches (crossings.h), forbidden arcs, build volume, units. It writes
// no G-code and draws nothing; previews of what it finds live in preview/.
//
// `strand check`: reads any G-code and reports, per layer, strands, self-crossings and
// touches, plus forbidden arcs, moves outside the build volume and parse problems.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "machines/profile.h"
#include "postprocess/inspect/crossings.h"
#include "postprocess/inspect/gcode_parser.h"

namespace strand::post {

struct CheckOptions {
  double arc_tolerance_mm = 0.01;  // chord error when arcs are flattened for the contact search
  double touch_mm = 1e-3;          // segments closer than this touch (G-code resolution)
  const machines::MachineProfile* machine = nullptr;  // bounds and arcs are checked when set
};

struct LayerCheck {
  int layer = 0;  // index as in ;LAYER:n; -1 for deposits before the first layer
  double z_mm = 0.0;
  int strands = 0;  // uninterrupted deposit runs
  std::vector<Contact> crossings, touches;
};

// One problem tied to a move: where it is and why.
struct Finding {
  int line = 0;          // 1-based line in the G-code
  std::size_t move = 0;  // index into the parsed MotionProgram::moves
  slicer::Vec3 at_mm = slicer::Vec3::Zero();
  std::string what;
};

struct CheckReport {
  std::vector<LayerCheck> layers;
  std::vector<ParseIssue> parse_issues;  // non-finite or malformed numbers, inch units, ...
  std::vector<Finding> arcs_forbidden;   // G2/G3 on a machine with arcs == false
  std::vector<Finding> outside_volume;   // move end (or arc bulge) outside the build volume
  std::size_t arcs_forbidden_total = 0;  // the vectors keep the first kMaxFindings only
  std::size_t outside_volume_total = 0;
  std::size_t moves = 0;
  std::string machine;          // profile name, empty when none was given
  std::vector<int> move_lines;  // G-code line of each parsed move
  // Checked as a pen drawing (the machine is a plotter): coordinates are read back to the
  // paper through the machine's kinematics, and strokes crossing is drawing content, not a
  // defect, so crossings are listed but do not fail the check.
  bool pen_drawing = false;

  static constexpr std::size_t kMaxFindings = 1000;
  // False on crossings (DIW only), forbidden arcs, outside moves and parse issues; touches
  // are fine.
  bool ok() const;
  std::size_t crossing_count() const;
  std::size_t touch_count() const;
  int line_of(std::size_t move) const;  // 0 when unknown
};

CheckReport check_gcode(std::string_view gcode_text, const CheckOptions& options);
// Same, on an already parsed file (the SVG preview reuses the parsed program).
CheckReport check_parsed(const ParsedGcode& parsed, const CheckOptions& options);

nlohmann::json to_json(const CheckReport& report);
// A short per-layer table (equal consecutive layers grouped) and the problems with
// coordinates and line numbers.
std::string to_text(const CheckReport& report);

}  // namespace strand::post
