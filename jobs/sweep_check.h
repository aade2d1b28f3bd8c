// The `check` column of a sweep manifest: `strand check` run on each point's G-code
// against the point's machine.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace strand::jobs {

// {"ok", "parse_issues", "crossings", "touches", "arcs_forbidden", "outside_volume", "layers",
// "max_strands_per_layer"}; ok is post::CheckReport::ok().
nlohmann::json sweep_check_summary(std::string_view gcode, const std::string& machine);

}  // namespace strand::jobs
