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

// The robot cell's vendor programs against the extruder's time line (machines/contact_speed.h):
// per program the worst contact speed / planned speed over deposit moves and the worst lap
// time difference, as written, and as a program moving its frame at the rows' own speeds would
// run. Stored as report["contact_speed"]; throws InputError naming the program when a written
// program's contact speed or lap time would differ by more than kContactSpeedTolerance.
constexpr double kContactSpeedTolerance = 0.02;
void add_contact_speed(nlohmann::json& report, const slicer::PoseProgram& p,
                       const machines::MachineProfile& m);
// The summary's "contact speed" line ("" without report["contact_speed"]).
std::string contact_speed_summary(const nlohmann::json& report);

}  // namespace strand::post
