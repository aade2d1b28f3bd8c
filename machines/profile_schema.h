// The profile schema: which keys exist, their types and ranges. Unknown keys are errors.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace strand::machines {

// Every problem in `j` as "<origin>: <key.path> = value: rule".
std::vector<std::string> check_profile_schema(const nlohmann::json& j, const std::string& origin);

}  // namespace strand::machines
