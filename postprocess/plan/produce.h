// One job end to end after generation: plan, estimate, emit G-code with its header, report.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "machines/profile.h"
#include "postprocess/plan/planner.h"
#include "slicer/motion.h"
#include "slicer/toolpath.h"

namespace strand::post {

struct Produced {
  std::string gcode;
  std::string viewer_gcode;  // preview-only copy with computed E; empty unless asked for
  nlohmann::json report;
  std::string summary;
  slicer::MotionProgram program;
};

// `gcode_path` is only recorded in the report. Throws InputError if the part does not fit.
// With `viewer_e`, also writes the preview-only variant (machines::EmitOptions::viewer_e).
Produced produce(const slicer::Toolpath& t, const machines::MachineProfile& m,
                 const PlanOptions& options, const std::string& gcode_path,
                 bool viewer_e = false);
// The same from an already planned program (conformal printing plans through a surface).
Produced produce_program(const slicer::Toolpath& t, slicer::MotionProgram program,
                         const machines::MachineProfile& m, const PlanOptions& options,
                         const std::string& gcode_path, bool viewer_e = false);

}  // namespace strand::post
