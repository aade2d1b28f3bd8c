// The `check` column of a sweep manifest, computed from the G-code text alone. Kept in one
// function so it can become post::check_gcode when `strand check` lands.
#pragma once

#include <nlohmann/json.hpp>
#include <string_view>

namespace strand::cli {

// {"ok", "parse_issues", "move_issues", "crossings", "layers", "deposit_length_mm"}.
// ok = no parse issue on a move line and no filament crossing itself within a layer.
nlohmann::json sweep_check_summary(std::string_view gcode);

}  // namespace strand::cli
