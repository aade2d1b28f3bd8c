// Distance, volume, strand and naive time sums over a MotionProgram.
#include "postprocess/plan/estimate.h"

#include <cmath>

#include "postprocess/plan/motion_time.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::MoveKind;

double move_length(const slicer::Vec3& from, const slicer::Move& mv) {
  if (!mv.is_arc) return (mv.end_mm - from).norm();
  const slicer::Vec2 a = from.head<2>();
  const double r = (a - mv.center_mm).norm();
  const double xy = r * std::abs(slicer::arc_sweep(mv.center_mm, a, mv.end_mm.head<2>(), mv.ccw));
  return std::hypot(xy, mv.end_mm.z() - from.z());
}

Estimate estimate(const slicer::MotionProgram& p) {
  Estimate e;
  for (std::size_t i = 0; i < p.layers.size(); ++i) {
    e.layers.push_back({static_cast<int>(i), p.layers[i].z_mm});
  }
  slicer::Vec3 at = p.start_mm;
  bool depositing = false;
  int last_layer = -2;
  for (const auto& mv : p.moves) {
    LayerEstimate* le = mv.layer >= 0 && mv.layer < static_cast<int>(e.layers.size())
                            ? &e.layers[static_cast<std::size_t>(mv.layer)]
                            : nullptr;
    if (mv.layer != last_layer) depositing = false;  // a new layer starts a new strand
    last_layer = mv.layer;
    if (mv.kind == MoveKind::Dwell) {
      e.time_naive_s += slicer::dwell_seconds(p, mv);
      if (le) le->time_naive_s += slicer::dwell_seconds(p, mv);
      continue;
    }
    if (mv.kind == MoveKind::Raw) continue;
    const double len = move_length(at, mv);
    const double t = mv.feed_mm_per_min > 0 ? len / slicer::mm_per_min_to_mm_per_s(mv.feed_mm_per_min) : 0.0;
    e.time_naive_s += t;
    if (mv.kind == MoveKind::Deposit) {
      e.deposit_length_mm += len;
      e.volume_mm3 += mv.volume_mm3;
      if (le) {
        if (!depositing) ++le->strands;
        le->deposit_length_mm += len;
        le->volume_mm3 += mv.volume_mm3;
        le->time_naive_s += t;
      }
      depositing = true;
    } else {
      if (len > 0) depositing = false;
      e.travel_length_mm += len;
      if (le) {
        le->travel_length_mm += len;
        le->time_naive_s += t;
      }
    }
    at = mv.end_mm;
  }
  return e;
}

Estimate estimate(const slicer::MotionProgram& p, const machines::MachineProfile& m) {
  Estimate e = estimate(p);
  const TimeOptions o = time_options_for(m);
  const MotionTime t = trapezoid_time(p, o);
  e.time_trapezoid_s = t.total_s;
  for (std::size_t i = 0; i < e.layers.size(); ++i) {
    auto& l = e.layers[i];
    l.time_trapezoid_s = t.layer_s[i];
    l.time_naive_s += l.strands * o.strand_start_dwell_s;
    e.time_naive_s += l.strands * o.strand_start_dwell_s;
  }
  return e;
}

}  // namespace strand::post
