// G-code emitter: MotionProgram -> text for one machine profile (firmware flavour and
// deposition model). The only place that knows G-code words.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "slicer/motion.h"
#include "slicer/progress.h"

namespace strand::machines {

struct EmitOptions {
  std::vector<std::string> header;  // comment lines (without ';') written first
  // Preview-only copy: write computed relative E even where the machine takes none, so
  // viewers that colour by extrusion show deposits. Never for printing.
  bool viewer_e = false;
  // Told how many of the program's moves are written (a step every few thousand), for the
  // progress bar's time left; may be null.
  slicer::Progress* progress = nullptr;
};

std::string emit_gcode(const slicer::MotionProgram& program, const MachineProfile& machine,
                       const EmitOptions& options);
// The same text written to `out` in blocks as it is formatted: the whole file never sits in
// memory (large jobs stream into the temporary output file).
void emit_gcode(const slicer::MotionProgram& program, const MachineProfile& machine,
                const EmitOptions& options, std::ostream& out);

// PrusaSlicer's viewer knows only its own role names in ;TYPE:; this maps ours onto them.
std::string viewer_role(slicer::Feature f);

}  // namespace strand::machines
