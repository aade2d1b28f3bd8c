// A job file's per-layer-range schedule for `scaffold`: "schedule": [{"layers": "0-4",
// "speed": 300, "flow": 1.1, "gap": 1.2, "angle": 45}, ...], read and checked.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "patterns/scaffold.h"

namespace strand::patterns {

// The entries sorted by layer; every problem (an entry not an object, unknown keys, values
// out of range, layers outside 0..layers-1, overlapping ranges) is added to `problems` as one
// line naming the entry by its layers and the key: "scaffold.schedule[0-4].speed = -5: must be
// in (0, 100000] (mm/min)".
std::vector<ScheduleEntry> schedule_from(const nlohmann::json& schedule, int layers,
                                         std::vector<std::string>& problems);

}  // namespace strand::patterns
