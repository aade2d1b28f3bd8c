// The slice job's thin-wall skip: strips of a sliced layer no bead reaches are taken out of
// the layer before it is filled, and said in the summary and report.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "patterns/region_pattern.h"
#include "slicer/region.h"

namespace strand::jobs {

// Strips of a layer no bead reaches (more than 4 nozzle^2, with the layers below and above
// covering them too: a wall, not a curved part's rim) are taken out of the layer; returns a
// note per run of layers and appends {"area_mm2", "near_mm", "z_mm"} to `skipped`. The layers'
// strips are found in parallel (oneTBB, the calling task arena), the result is one thread's.
std::vector<std::string> skip_thin_walls(std::vector<slicer::Region>& layers,
                                         const patterns::RegionPattern& p,
                                         nlohmann::json& skipped);

}  // namespace strand::jobs
