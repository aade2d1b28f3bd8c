// G-code emitter: MotionProgram -> text for one machine profile (firmware flavour and
// deposition model). The only place that knows G-code words.
#pragma once

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "machines/gcode_format.h"
#include "machines/profile.h"
#include "slicer/motion.h"
#include "slicer/progress_listener.h"

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

// A file in two parts, for a program that is never whole (one layer at a time, planned by
// postprocess/plan's LayerPlanner): the head is options.header's comments (with the preview
// warning for viewer_e), known only once every layer has passed; the body is everything
// after it, written as the pieces come. gcode_head + body = emit_gcode of the whole program.
std::string gcode_head(const MachineProfile& machine, const EmitOptions& options);

class GcodeBodyWriter {
 public:
  // `options.header` is ignored (gcode_head writes it); `out` gets the text in blocks.
  GcodeBodyWriter(const MachineProfile& machine, const EmitOptions& options, std::ostream& out);
  ~GcodeBodyWriter();
  // The next piece (its moves index the layers it lists); the first also writes the start
  // G-code and preamble; the first with moves gives the start position (start_mm).
  void add(const slicer::MotionProgram& piece);
  // The end G-code; flushes.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};


}  // namespace strand::machines
