// One job end to end after generation: plan, estimate, emit G-code with its header, report.
#pragma once

#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "machines/profile.h"
#include "postprocess/plan/planner.h"
#include "slicer/motion.h"
#include "slicer/progress.h"
#include "slicer/toolpath.h"

namespace strand::post {

struct Produced {
  std::string gcode;         // empty when streamed (GcodeStreams)
  std::string viewer_gcode;  // preview-only copy with computed E; empty unless asked for
  nlohmann::json report;
  std::string summary;
  slicer::MotionProgram program;
};

// Where the G-code goes instead of Produced's strings: written in blocks as it is formatted,
// so a large job never holds its whole file in memory.
struct GcodeStreams {
  std::ostream* gcode = nullptr;
  std::ostream* viewer_gcode = nullptr;  // used with viewer_e
};

// `gcode_path` is only recorded in the report. Throws InputError if the part does not fit.
// With `viewer_e`, also writes the preview-only variant (machines::EmitOptions::viewer_e).
// `progress` (may be null) is told the phases: planning, writing G-code.
// The toolpath is taken by value and released layer by layer as it is planned (pass it with
// std::move so a large job does not hold toolpath and program at once).
Produced produce(slicer::Toolpath t, const machines::MachineProfile& m,
                 const PlanOptions& options, const std::string& gcode_path,
                 bool viewer_e = false, const GcodeStreams& streams = {},
                 slicer::Progress* progress = nullptr);
// The same from an already planned program (conformal printing plans through a surface).
Produced produce_program(const slicer::Toolpath& t, slicer::MotionProgram program,
                         const machines::MachineProfile& m, const PlanOptions& options,
                         const std::string& gcode_path, bool viewer_e = false,
                         const GcodeStreams& streams = {}, slicer::Progress* progress = nullptr);

}  // namespace strand::post
