// Time left of a file being sent (see send_estimate.h).
#include "jobs/send_estimate.h"

#include <iterator>

#include "postprocess/inspect/gcode_parser.h"
#include "slicer/motion.h"

namespace strand::jobs {

std::map<int, double> time_left_after(const std::string& gcode_text) {
  const post::ParsedGcode parsed = post::parse_gcode(gcode_text);
  std::map<int, double> per_line;
  slicer::Vec3 at = parsed.program.start_mm;
  double total = 0.0;
  for (std::size_t i = 0; i < parsed.program.moves.size(); ++i) {
    const auto& mv = parsed.program.moves[i];
    double t = 0.0;
    if (mv.kind == slicer::MoveKind::Dwell) t = slicer::dwell_seconds(parsed.program, mv);
    if (mv.kind == slicer::MoveKind::Travel || mv.kind == slicer::MoveKind::Deposit) {
      if (mv.feed_mm_per_min > 0) t = (mv.end_mm - at).norm() / (mv.feed_mm_per_min / 60.0);
      at = mv.end_mm;
    }
    per_line[parsed.move_lines[i]] += t;
    total += t;
  }
  std::map<int, double> left;
  for (const auto& [line, t] : per_line) left[line] = (total -= t);
  return left;
}

double time_left_at(const std::map<int, double>& left, int line) {
  if (left.empty()) return 0.0;
  const auto it = left.upper_bound(line);
  return it == left.begin() ? left.begin()->second : std::prev(it)->second;
}

}  // namespace strand::jobs
