// The job report (JSON for --report) and the short summary printed on stdout.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "machines/profile.h"
#include "postprocess/plan/estimate.h"
#include "slicer/toolpath.h"

namespace strand::post {

nlohmann::json make_report(const slicer::Toolpath& t, const machines::MachineProfile& m,
                           const Estimate& e, const std::string& gcode_path);
// A few lines for a terminal: size, layers, strands, length, ink, time.
std::string summary_text(const nlohmann::json& report);

// Shared by the reports: `v` rounded to `decimals` places, and seconds as "1h 2m 3s".
double round_to(double v, int decimals);
std::string clock_text(double seconds);

}  // namespace strand::post
