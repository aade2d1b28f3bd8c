// Parse + contacts + estimate: the interim check behind the manifest's `check` column.
#include "slicer/cli/sweep_check.h"

#include <algorithm>
#include <cmath>

#include "postprocess/crossings.h"
#include "postprocess/estimate.h"
#include "postprocess/gcode_parser.h"
#include "slicer/tolerances.h"

namespace strand::cli {

nlohmann::json sweep_check_summary(std::string_view gcode) {
  // Only proper crossings matter here, so touches use a negligible distance.
  constexpr double kTouchMm = 1e-6;
  const post::ParsedGcode parsed = post::parse_gcode(gcode);
  const post::ContactReport contacts =
      post::find_contacts(parsed.program, slicer::kDefaultArcToleranceMm, kTouchMm);
  const post::Estimate e = post::estimate(parsed.program);
  // Issues on lines that are not moves (e.g. the parser reading "M117 Open the valve" as
  // malformed numbers) do not change the toolpath, so only issues on move lines fail it.
  std::size_t move_issues = 0;
  for (const auto& issue : parsed.issues) {
    move_issues += std::binary_search(parsed.move_lines.begin(), parsed.move_lines.end(), issue.line);
  }
  const bool ok = move_issues == 0 && contacts.crossings.empty();
  return {{"ok", ok},
          {"parse_issues", parsed.issues.size()},
          {"move_issues", move_issues},
          {"crossings", contacts.crossings.size()},
          {"layers", parsed.program.layers.size()},
          {"deposit_length_mm", std::round(e.deposit_length_mm * 1000.0) / 1000.0}};
}

}  // namespace strand::cli
