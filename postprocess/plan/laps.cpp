// Lap splitting at the farthest turn reached in each direction.
#include "postprocess/plan/laps.h"

#include <algorithm>

namespace strand::post {

using slicer::PoseLap;
using slicer::PosePoint;

namespace {

// A lap ends at the last point within this of its farthest turn: the small back-and-forth of
// a pass across a node or a U-turn does not start a new lap, rad (1 deg).
constexpr double kLapSlackRad = 0.017453292519943295;

// Index of the last point in [from, last] within the slack of the farthest turn in
// `direction`; `from` when nothing lies farther than the slack.
std::size_t farthest(const std::vector<PosePoint>& pts, std::size_t from, std::size_t last,
                     int direction) {
  double far = direction * pts[from].turn_rad;
  for (std::size_t i = from; i <= last; ++i) far = std::max(far, direction * pts[i].turn_rad);
  if (far - direction * pts[from].turn_rad <= kLapSlackRad) return from;
  std::size_t best = from;
  for (std::size_t i = from; i <= last; ++i) {
    if (direction * pts[i].turn_rad >= far - kLapSlackRad) best = i;
  }
  return best;
}

PoseLap make_lap(const std::vector<PosePoint>& pts, std::size_t first, std::size_t last, int layer,
                 int direction) {
  PoseLap lap{layer, direction, first, last, pts[first].turn_rad, pts[first].turn_rad};
  for (std::size_t i = first; i <= last; ++i) {
    lap.turn_min_rad = std::min(lap.turn_min_rad, pts[i].turn_rad);
    lap.turn_max_rad = std::max(lap.turn_max_rad, pts[i].turn_rad);
  }
  return lap;
}

}  // namespace

std::vector<PoseLap> split_laps(const std::vector<PosePoint>& pts, std::size_t first,
                                std::size_t last, int layer) {
  std::vector<PoseLap> laps;
  double lo = pts[first].turn_rad, hi = lo;
  for (std::size_t i = first; i <= last; ++i) {
    lo = std::min(lo, pts[i].turn_rad);
    hi = std::max(hi, pts[i].turn_rad);
  }
  int direction = hi - pts[first].turn_rad >= pts[first].turn_rad - lo ? 1 : -1;
  std::size_t start = first;
  int stalled = 0;  // direction flips without progress; two mean the rest holds its turn
  while (start < last) {
    const std::size_t end = farthest(pts, start, last, direction);
    if (end == start && ++stalled < 2) {
      direction = -direction;
      continue;
    }
    if (end == start) {  // the rest stays within the slack: it ends the previous lap
      if (laps.empty()) break;
      laps.back() = make_lap(pts, laps.back().first, last, layer, laps.back().direction);
      return laps;
    }
    laps.push_back(make_lap(pts, start, end, layer, direction));
    start = end;
    direction = -direction;
    stalled = 0;
  }
  if (laps.empty()) laps.push_back(make_lap(pts, first, last, layer, direction));
  return laps;
}

void assign_laps(slicer::PoseProgram& program) {
  auto& pts = program.points;
  program.laps.clear();
  std::size_t begin = 0;
  while (begin < pts.size()) {
    std::size_t end = begin;
    while (end + 1 < pts.size() && pts[end + 1].layer == pts[begin].layer) ++end;
    for (const PoseLap& lap : split_laps(pts, begin, end, pts[begin].layer)) {
      const int index = static_cast<int>(program.laps.size());
      // A lap owns its points after its first (the first closes the previous lap).
      for (std::size_t i = lap.first == begin ? lap.first : lap.first + 1; i <= lap.last; ++i) {
        pts[i].lap = index;
      }
      program.laps.push_back(lap);
    }
    begin = end + 1;
  }
}

std::pair<double, double> turn_range(const slicer::PoseProgram& program) {
  if (program.points.empty()) return {0.0, 0.0};
  double lo = program.points.front().turn_rad, hi = lo;
  for (const auto& p : program.points) {
    lo = std::min(lo, p.turn_rad);
    hi = std::max(hi, p.turn_rad);
  }
  return {lo, hi};
}

}  // namespace strand::post
