// Report of a curved-substrate job: laps per layer and each lap's turning range, path length
// on the surface, time, ink, the u stretch per layer; the caller adds the machine part (robot
// programs and joint ranges, or the rotary file). And the few lines printed on the terminal.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "machines/profile.h"
#include "slicer/pose_program.h"
#include "slicer/substrate_params.h"
#include "slicer/toolpath.h"

namespace strand::post {

// Deposit volume per mm of path of each layer's beads (bead area), mm^2.
std::vector<double> bead_areas_mm2(const slicer::Toolpath& t);
std::vector<double> bead_widths_mm(const slicer::Toolpath& t);

nlohmann::json pose_report(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                           const machines::MachineProfile& m, const slicer::PoseProgram& p);

// Size, laps, turning, length, time, ink, programs, joints (when present in the report).
std::string pose_summary(const nlohmann::json& report);

}  // namespace strand::post
