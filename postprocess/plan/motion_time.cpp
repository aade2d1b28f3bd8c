// Forward/backward pass over straight blocks, as a firmware planner does, then trapezoid
// (or triangle) timing per block.
#include "postprocess/plan/motion_time.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "postprocess/plan/arc_segmentation.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Move;
using slicer::MoveKind;
using slicer::Vec3;

namespace {

struct Block {
  double length_mm = 0.0;
  double v_max = 0.0;  // nominal (cruise) speed, mm/s
  int layer = -1;
  double entry = 0.0;  // junction limit, then the planned entry speed, mm/s
};

// Flow state a move leaves the machine in, for valve machines: 0 closed, 1 open.
int flow_state(const Move& mv) { return mv.kind == MoveKind::Deposit && !mv.coast ? 1 : 0; }

// The firmware-style planner run as a stream: blocks wait in a queue until one is a cut,
// a block whose entry speed the backward pass can no longer lower (it can stop from its
// junction limit within its own length), so nothing after it changes anything before it.
// The queue is then planned backward and forward and timed, exactly as one pass over the
// whole program would, with memory bounded by the distance between cuts.
class StreamPlanner {
 public:
  StreamPlanner(double accel, MotionTime& t) : a_(accel), t_(t) {}

  void add(const Block& b) {
    q_.push_back(b);
    if (std::sqrt(2 * a_ * b.length_mm) >= b.entry) plan(false);
  }
  void finish() { plan(true); }  // the program ends at rest

 private:
  void plan(bool end) {
    if (q_.empty()) return;
    const std::size_t first = head_final_ ? 1 : 0;  // q_[0] may be final already
    double exit = 0.0;  // exact for a cut block too: its entry ignores what follows
    for (std::size_t k = q_.size(); k-- > first;) {
      q_[k].entry = std::min(q_[k].entry, std::sqrt(exit * exit + 2 * a_ * q_[k].length_mm));
      exit = q_[k].entry;
    }
    for (std::size_t i = std::max<std::size_t>(first, 1); i < q_.size(); ++i) {
      const double reach = std::sqrt(q_[i - 1].entry * q_[i - 1].entry + 2 * a_ * q_[i - 1].length_mm);
      q_[i].entry = std::min(q_[i].entry, reach);
    }
    const std::size_t timed = end ? q_.size() : q_.size() - 1;  // the last waits for its exit
    for (std::size_t i = 0; i < timed; ++i) {
      const Block& b = q_[i];
      const double exit_speed = i + 1 < q_.size() ? q_[i + 1].entry : 0.0;
      const double s = block_time_s(b.length_mm, b.entry, b.v_max, exit_speed, a_);
      t_.total_s += s;
      if (b.layer >= 0 && b.layer < static_cast<int>(t_.layer_s.size())) t_.layer_s[static_cast<std::size_t>(b.layer)] += s;
    }
    q_.erase(q_.begin(), q_.begin() + static_cast<std::ptrdiff_t>(timed));
    head_final_ = !q_.empty();
  }

  double a_;
  MotionTime& t_;
  std::vector<Block> q_;
  bool head_final_ = false;
};

}  // namespace

// Cuts the program into straight blocks (arcs as chords) with their junction limits and
// streams them through the planner; dwell time is counted per layer as it passes.
struct TrapezoidTimer::Impl {
  explicit Impl(const TimeOptions& options) : o(options), planner(options.acceleration_mm_per_s2, t) {}

  void add(const slicer::MotionProgram& p) {
    if (!started && !p.moves.empty()) {  // layers before the first move may be empty
      at = p.start_mm;
      started = true;
    }
    if (t.layer_s.size() < p.layers.size()) t.layer_s.resize(p.layers.size(), 0.0);
    add_dwells(p);
    for (const auto& mv : p.moves) add_move(mv);
  }

  // Dwell time per layer bucket (layer + 1; 0 = before the first layer): explicit dwells and
  // the lead dwell at every strand start, summed per bucket and then added bucket by bucket.
  void add_dwells(const slicer::MotionProgram& p) {
    std::map<int, double> dwell;
    const int layers = static_cast<int>(p.layers.size());
    for (const auto& mv : p.moves) {
      const int bucket = std::clamp(mv.layer + 1, 0, layers);
      if (mv.kind == MoveKind::Dwell || mv.kind == MoveKind::Raw) {
        dwell[bucket] += mv.kind == MoveKind::Dwell ? slicer::dwell_seconds(p, mv) : 0.0;
        continue;
      }
      if (mv.kind == MoveKind::Deposit && !mv.coast && dwell_flow == 0) dwell[bucket] += o.strand_start_dwell_s;
      dwell_flow = flow_state(mv);
    }
    for (const auto& [bucket, seconds] : dwell) {
      t.total_s += seconds;
      if (bucket > 0) t.layer_s[static_cast<std::size_t>(bucket - 1)] += seconds;
    }
  }

  void add_move(const Move& mv) {
    if (mv.kind == MoveKind::Dwell || mv.kind == MoveKind::Raw) {
      stop = true;
      return;
    }
    if (o.stop_at_flow_change && flow_state(mv) != flow) stop = true;
    flow = flow_state(mv);
    points.clear();
    if (mv.is_arc) {
      const auto pts = segment_arc(at.head<2>(), mv.center_mm, mv.end_mm.head<2>(), mv.ccw, o.arc_tolerance_mm);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double f = static_cast<double>(i + 1) / static_cast<double>(pts.size());
        points.emplace_back(pts[i].x(), pts[i].y(), at.z() + f * (mv.end_mm.z() - at.z()));
      }
    } else {
      points.push_back(mv.end_mm);
    }
    const double v = slicer::mm_per_min_to_mm_per_s(std::min(mv.feed_mm_per_min, o.max_feed_mm_per_min));
    for (const Vec3& q : points) {
      const double len = (q - at).norm();
      if (len < 1e-9 || v <= 0) continue;
      const Vec3 unit = (q - at) / len;
      double limit = 0.0;
      if (any && !stop) {
        limit = std::min({prev_v, v, junction_speed_mm_per_s(prev_unit, unit, o.acceleration_mm_per_s2,
                                                             o.junction_deviation_mm)});
      }
      planner.add({len, v, mv.layer, limit});
      any = true;
      stop = false;
      prev_unit = unit;
      prev_v = v;
      at = q;
    }
  }

  TimeOptions o;
  MotionTime t;
  StreamPlanner planner;
  bool started = false;
  Vec3 at = Vec3::Zero();
  bool stop = true;
  bool any = false;  // a block was made (the first one starts at rest)
  Vec3 prev_unit = Vec3::Zero();
  double prev_v = 0.0;
  int flow = 0;
  int dwell_flow = 0;
  std::vector<Vec3> points;
};

TrapezoidTimer::TrapezoidTimer(const TimeOptions& o) : impl_(std::make_unique<Impl>(o)) {}
TrapezoidTimer::~TrapezoidTimer() = default;
void TrapezoidTimer::add(const slicer::MotionProgram& piece) { impl_->add(piece); }
MotionTime TrapezoidTimer::finish() {
  impl_->planner.finish();
  return std::move(impl_->t);
}

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

double blended_corner_speed_mm_per_s(const Vec3& u1, const Vec3& u2, double a, double blend_mm) {
  const double cos_turn = u1.dot(u2);
  if (cos_turn > 0.999999999999) return std::numeric_limits<double>::infinity();  // straight on
  if (cos_turn < -0.999999 || blend_mm <= 0.0) return 0.0;  // a reversal, or an exact stop
  const double half = 0.5 * std::acos(std::clamp(cos_turn, -1.0, 1.0));
  return std::sqrt(a * blend_mm / std::tan(half));
}

std::vector<double> rest_to_rest_times_s(const std::vector<PathBlock>& blocks, double a) {
  const std::size_t n = blocks.size();
  std::vector<double> entry(n, 0.0), times(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    entry[i] = std::min({blocks[i].corner_limit, blocks[i - 1].v_max, blocks[i].v_max});
  double exit = 0.0;
  for (std::size_t k = n; k-- > 0;) {
    entry[k] = std::min(entry[k], std::sqrt(exit * exit + 2 * a * blocks[k].length_mm));
    exit = entry[k];
  }
  for (std::size_t i = 1; i < n; ++i) {
    entry[i] = std::min(entry[i], std::sqrt(entry[i - 1] * entry[i - 1] +
                                            2 * a * blocks[i - 1].length_mm));
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (blocks[i].length_mm <= 0.0 || blocks[i].v_max <= 0.0) continue;
    times[i] = block_time_s(blocks[i].length_mm, entry[i], blocks[i].v_max,
                            i + 1 < n ? entry[i + 1] : 0.0, a);
  }
  return times;
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
  TrapezoidTimer timer(o);
  timer.add(p);
  return timer.finish();
}

}  // namespace strand::post
