// The manifest's `check` column from post::check_gcode.
#include "jobs/sweep_check.h"

#include <algorithm>

#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "slicer/tolerances.h"

namespace strand::jobs {

nlohmann::json sweep_check_summary(std::string_view gcode, const std::string& machine) {
  const machines::MachineProfile m = machines::load_profile(machine);
  post::CheckOptions o;
  o.arc_tolerance_mm = slicer::kDefaultArcToleranceMm;
  o.machine = &m;
  const post::CheckReport r = post::check_gcode(gcode, o);
  int max_strands = 0;
  for (const auto& l : r.layers) max_strands = std::max(max_strands, l.strands);
  return {{"ok", r.ok()},
          {"parse_issues", r.parse_issues.size()},
          {"crossings", r.crossing_count()},
          {"touches", r.touch_count()},
          {"arcs_forbidden", r.arcs_forbidden_total},
          {"outside_volume", r.outside_volume_total},
          {"layers", r.layers.size()},
          {"max_strands_per_layer", max_strands}};
}

}  // namespace strand::jobs
