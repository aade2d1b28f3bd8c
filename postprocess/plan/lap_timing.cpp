// Each lap planned from rest to rest with the blended-corner speed limit.
#include "postprocess/plan/lap_timing.h"

#include <algorithm>
#include <cmath>

#include "machines/gcode_format.h"
#include "postprocess/plan/motion_time.h"
#include "postprocess/plan/report.h"

namespace strand::post {

using slicer::Vec3;

namespace {

// Motions shorter than this are repeats of the previous pose (the programs skip them), mm.
constexpr double kZeroLengthMm = 1e-9;

// Times the blocks ending at points [first, last] (one lap) into `t`; returns the lap's
// nominal and planned durations and the corners slowed.
struct LapSums {
  double nominal = 0.0, planned = 0.0;
  int slowed = 0;
};

LapSums time_lap(const slicer::PoseProgram& p, std::size_t first, std::size_t last,
                 const CornerModel& model, std::vector<double>& t) {
  const auto& pts = p.points;
  std::vector<PathBlock> blocks;
  std::vector<std::size_t> ends;  // the point each block ends at
  std::vector<Vec3> units;
  LapSums sums;
  for (std::size_t i = first; i <= last; ++i) {
    const Vec3 d = pts[i].contact_mm - pts[i - 1].contact_mm;
    const double len = d.norm();
    if (len < kZeroLengthMm || !(pts[i].speed_mm_per_s > 0.0)) continue;
    PathBlock b{len, pts[i].speed_mm_per_s, 0.0};
    const Vec3 unit = d / len;
    if (!blocks.empty()) {
      const double blend = std::min({model.blend_mm, 0.5 * blocks.back().length_mm, 0.5 * len});
      b.corner_limit = blended_corner_speed_mm_per_s(units.back(), unit,
                                                     model.acceleration_mm_per_s2, blend);
      if (b.corner_limit < std::min(blocks.back().v_max, b.v_max) - 1e-9) ++sums.slowed;
    }
    sums.nominal += len / b.v_max;
    blocks.push_back(b);
    ends.push_back(i);
    units.push_back(unit);
  }
  const std::vector<double> times = rest_to_rest_times_s(blocks, model.acceleration_mm_per_s2);
  std::vector<double> dt(last - first + 1, 0.0);
  for (std::size_t k = 0; k < blocks.size(); ++k) dt[ends[k] - first] = times[k];
  for (std::size_t i = first; i <= last; ++i) {
    t[i] = t[i - 1] + dt[i - first];
    sums.planned += dt[i - first];
  }
  return sums;
}

}  // namespace

CornerModel corner_model_for(const machines::MachineProfile& m, double blend_mm) {
  return {machines::corner_acceleration_mm_per_s2(m.robot), blend_mm};
}

LapTiming time_laps(const slicer::PoseProgram& p, const CornerModel& model) {
  LapTiming out;
  out.model = model;
  const auto& pts = p.points;
  out.t_s.assign(pts.size(), 0.0);
  const std::size_t laps = std::max<std::size_t>(p.laps.size(), 1);
  out.nominal_s.assign(laps, 0.0);
  out.planned_s.assign(laps, 0.0);
  out.slowed_corners.assign(laps, 0);
  for (std::size_t i = 1; i < pts.size();) {
    std::size_t j = i;
    while (j + 1 < pts.size() && pts[j + 1].lap == pts[i].lap) ++j;
    const LapSums s = time_lap(p, i, j, model, out.t_s);
    const auto lap = static_cast<std::size_t>(std::clamp(pts[i].lap, 0, static_cast<int>(laps) - 1));
    out.nominal_s[lap] += s.nominal;
    out.planned_s[lap] += s.planned;
    out.slowed_corners[lap] += s.slowed;
    out.nominal_total_s += s.nominal;
    out.planned_total_s += s.planned;
    i = j + 1;
  }
  return out;
}

nlohmann::json lap_timing_json(const LapTiming& t) {
  using machines::fmt_fixed;
  const double percent =
      t.nominal_total_s > 0.0 ? 100.0 * (t.planned_total_s / t.nominal_total_s - 1.0) : 0.0;
  int slowed = 0;
  for (int s : t.slowed_corners) slowed += s;
  const std::string sign = percent < 0.0 ? "-" : "+";
  return {{"acceleration_mm_per_s2", t.model.acceleration_mm_per_s2},
          {"blend_mm", t.model.blend_mm},
          {"nominal_s", round_to(t.nominal_total_s, 2)},
          {"planned_s", round_to(t.planned_total_s, 2)},
          {"increase_percent", round_to(percent, 2)},
          {"slowed_corners", slowed},
          {"text", "laps timed with corner slowdowns: " + sign + fmt_fixed(std::abs(percent), 1) +
                       " % over distance/speed (" + std::to_string(slowed) + " corners at " +
                       fmt_fixed(t.model.acceleration_mm_per_s2, 0) + " mm/s2 through " +
                       fmt_fixed(t.model.blend_mm, 3) + " mm blends; the extruder follows)"}};
}

}  // namespace strand::post
