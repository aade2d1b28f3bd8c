// Forward/backward pass over straight blocks, as a firmware planner does, then trapezoid
// (or triangle) timing per block.
#include "postprocess/plan/motion_time.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "postprocess/plan/arc_segmentation.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Move;
using slicer::MoveKind;
using slicer::Vec3;

namespace {

struct Block {
  double length_mm = 0.0;
  double v_max = 0.0;       // nominal (cruise) speed, mm/s
  Vec3 unit = Vec3::Zero();
  bool stop_before = false;  // the machine is at rest when the block starts
  int layer = -1;
  double entry = 0.0;       // planned entry speed, mm/s
};

// Flow state a move leaves the machine in, for valve machines: 0 closed, 1 open.
int flow_state(const Move& mv) { return mv.kind == MoveKind::Deposit && !mv.coast ? 1 : 0; }

struct Collected {
  std::vector<Block> blocks;
  std::vector<double> dwell_by_layer;  // index layer + 1 (0 = before the first layer)
};

Collected collect(const slicer::MotionProgram& p, const TimeOptions& o) {
  Collected c;
  c.dwell_by_layer.assign(p.layers.size() + 1, 0.0);
  Vec3 at = p.start_mm;
  bool stop = true;
  int flow = 0;
  for (const auto& mv : p.moves) {
    const auto bucket = static_cast<std::size_t>(std::clamp(mv.layer + 1, 0, static_cast<int>(p.layers.size())));
    if (mv.kind == MoveKind::Dwell || mv.kind == MoveKind::Raw) {
      c.dwell_by_layer[bucket] += mv.kind == MoveKind::Dwell ? mv.dwell_s : 0.0;
      stop = true;
      continue;
    }
    if (o.stop_at_flow_change && flow_state(mv) != flow) stop = true;
    if (mv.kind == MoveKind::Deposit && !mv.coast && flow == 0) c.dwell_by_layer[bucket] += o.strand_start_dwell_s;
    flow = flow_state(mv);
    std::vector<Vec3> points;
    if (mv.is_arc) {
      const auto pts = segment_arc(at.head<2>(), mv.center_mm, mv.end_mm.head<2>(), mv.ccw, o.arc_tolerance_mm);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double t = static_cast<double>(i + 1) / static_cast<double>(pts.size());
        points.emplace_back(pts[i].x(), pts[i].y(), at.z() + t * (mv.end_mm.z() - at.z()));
      }
    } else {
      points.push_back(mv.end_mm);
    }
    const double v = slicer::mm_per_min_to_mm_per_s(std::min(mv.feed_mm_per_min, o.max_feed_mm_per_min));
    for (const Vec3& q : points) {
      const double len = (q - at).norm();
      if (len < 1e-9 || v <= 0) continue;
      c.blocks.push_back({len, v, (q - at) / len, stop, mv.layer});
      stop = false;
      at = q;
    }
  }
  return c;
}

void plan_speeds(std::vector<Block>& b, const TimeOptions& o) {
  const double a = o.acceleration_mm_per_s2;
  for (std::size_t i = 0; i < b.size(); ++i) {
    double limit = 0.0;
    if (i > 0 && !b[i].stop_before) {
      limit = std::min({b[i - 1].v_max, b[i].v_max,
                        junction_speed_mm_per_s(b[i - 1].unit, b[i].unit, a, o.junction_deviation_mm)});
    }
    b[i].entry = limit;
  }
  double exit = 0.0;  // the program ends at rest
  for (std::size_t k = b.size(); k-- > 0;) {
    b[k].entry = std::min(b[k].entry, std::sqrt(exit * exit + 2 * a * b[k].length_mm));
    exit = b[k].entry;
  }
  for (std::size_t i = 1; i < b.size(); ++i) {
    const double reach = std::sqrt(b[i - 1].entry * b[i - 1].entry + 2 * a * b[i - 1].length_mm);
    b[i].entry = std::min(b[i].entry, reach);
  }
}

}  // namespace

TimeOptions time_options_for(const machines::MachineProfile& m) {
  TimeOptions o;
  o.acceleration_mm_per_s2 = m.limits.acceleration_mm_per_s2;
  o.junction_deviation_mm = m.limits.junction_deviation_mm;
  o.max_feed_mm_per_min = m.limits.max_feed_mm_per_min;
  const bool valve = m.deposition.model == machines::DepositionModel::Valve;
  o.stop_at_flow_change = valve;
  o.strand_start_dwell_s = valve ? m.deposition.lead_s : 0.0;
  return o;
}

double junction_speed_mm_per_s(const Vec3& u1, const Vec3& u2, double a, double jd) {
  const double cos_theta = -u1.dot(u2);
  if (cos_theta > 0.999999) return 0.0;                                       // reversal
  if (cos_theta < -0.999999) return std::numeric_limits<double>::infinity();  // straight on
  const double sin_half = std::sqrt(0.5 * (1.0 - cos_theta));
  return std::sqrt(a * jd * sin_half / (1.0 - sin_half));
}

double block_time_s(double length_mm, double v_in, double v_max, double v_out, double a) {
  const double d_acc = (v_max * v_max - v_in * v_in) / (2 * a);
  const double d_dec = (v_max * v_max - v_out * v_out) / (2 * a);
  if (d_acc + d_dec <= length_mm) {
    return (v_max - v_in) / a + (v_max - v_out) / a + (length_mm - d_acc - d_dec) / v_max;
  }
  const double v_peak = std::sqrt((2 * a * length_mm + v_in * v_in + v_out * v_out) / 2);
  return std::max(0.0, (v_peak - v_in) / a) + std::max(0.0, (v_peak - v_out) / a);
}

MotionTime trapezoid_time(const slicer::MotionProgram& p, const TimeOptions& o) {
  Collected c = collect(p, o);
  plan_speeds(c.blocks, o);
  MotionTime t;
  t.layer_s.assign(p.layers.size(), 0.0);
  for (std::size_t i = 0; i < c.dwell_by_layer.size(); ++i) {
    t.total_s += c.dwell_by_layer[i];
    if (i > 0) t.layer_s[i - 1] += c.dwell_by_layer[i];
  }
  for (std::size_t i = 0; i < c.blocks.size(); ++i) {
    const Block& b = c.blocks[i];
    const double exit = i + 1 < c.blocks.size() ? c.blocks[i + 1].entry : 0.0;
    const double s = block_time_s(b.length_mm, b.entry, b.v_max, exit, o.acceleration_mm_per_s2);
    t.total_s += s;
    if (b.layer >= 0 && b.layer < static_cast<int>(t.layer_s.size())) t.layer_s[static_cast<std::size_t>(b.layer)] += s;
  }
  return t;
}

}  // namespace strand::post
