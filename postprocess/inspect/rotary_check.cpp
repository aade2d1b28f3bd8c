// Rotary G-code mapped back onto its cylinder through the header's axis and substrate lines.
#include <algorithm>
#include <cmath>

#include "machines/gcode_format.h"
#include "machines/kinematics.h"
#include "postprocess/inspect/pose_check.h"
#include "slicer/input_error.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Vec3;

PoseCheckReport check_rotary_gcode(std::string_view text, const std::string& file,
                                   const machines::MachineProfile* machine) {
  const RotaryHeader h = read_rotary_header(text, file);
  const ParsedGcode parsed = parse_gcode(text);
  PoseCheckReport r;
  r.kind = "rotary G-code";
  r.machine = machine ? machine->name : "";
  r.rows = parsed.program.moves.size();
  for (const auto& issue : parsed.issues)
    r.parse.add(static_cast<std::size_t>(issue.line), issue.what);
  const std::vector<CylinderSample> samples = rotary_samples(parsed, h);
  for (std::size_t i = 0; i < parsed.program.moves.size(); ++i) {
    const auto& mv = parsed.program.moves[i];
    const std::size_t line = static_cast<std::size_t>(parsed.move_lines[i]);
    if (mv.kind == slicer::MoveKind::Deposit) {
      // The nozzle points straight down: a deposit must be on top of the cylinder.
      const Vec3 rel = mv.end_mm - h.axis_point_mm;
      const Vec3 radial = rel - rel.dot(h.axis_dir) * h.axis_dir;
      const double angle = slicer::rad_to_deg(
          std::acos(std::clamp(radial.normalized().dot(Vec3::UnitZ()), -1.0, 1.0)));
      if (angle > slicer::kPoseNormalDeg)
        r.normals.add(line, "the nozzle is " + machines::fmt_fixed(angle, 3) +
                                " deg off the top of the cylinder");
    }
    if (machine && (mv.kind == slicer::MoveKind::Deposit || mv.kind == slicer::MoveKind::Travel)) {
      if (auto why = machines::outside_reason(machine->volume, mv.end_mm))
        r.outside.add(line, *why);
    }
  }
  check_on_cylinder(samples, slicer::kGcodeResolutionMm, r);
  return r;
}

}  // namespace strand::post
