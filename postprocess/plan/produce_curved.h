// One curved-substrate job end to end after generation: place the pattern on the cylinder,
// plan the timed pose program, check it against the machine (a robot cell's turning window,
// reach and joint limits; a rotary printer's envelope), and render every output from that one
// program: pose CSV, Sunrise Java, KRL .src/.dat and the extruder's E-only G-code for a robot
// cell, or 4-axis G-code for a rotary printer.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "machines/profile.h"
#include "slicer/pose_program.h"
#include "slicer/substrate_params.h"
#include "slicer/toolpath.h"

namespace strand::post {

struct CurvedProduced {
  std::vector<std::pair<std::string, std::string>> files;  // path -> content, written together
  nlohmann::json report;
  std::string summary;
  slicer::PoseProgram program;
};

// The files a curved job writes for `output` (robot cell: "part.csv" -> part.csv, part.java,
// part.src, part.dat, part.extruder.gcode; rotary: the G-code file itself). Throws InputError
// when the name does not fit the machine (a robot cell needs a .csv name).
std::vector<std::string> curved_output_paths(const machines::MachineProfile& m,
                                             const std::string& output);

// `t`: the generated pattern (flat, or periodic for wrap full) in its own frame. Throws
// InputError for a machine that cannot print on a cylinder, a pattern that does not fit, a
// lap over the turning window, an unreachable pose, a joint limit or the envelope.
CurvedProduced produce_curved(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                              const machines::MachineProfile& m, double arc_tolerance_mm,
                              const std::string& output);

}  // namespace strand::post
