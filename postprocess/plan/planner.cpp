// Planner: placement, travels, arc handling, speeds and volumes.
#include "postprocess/plan/planner.h"

#include <algorithm>
#include <cmath>

#include "machines/flow_change.h"
#include "postprocess/plan/arc_segmentation.h"
#include "postprocess/plan/idle_heads.h"
#include "postprocess/plan/placement.h"
#include "postprocess/plan/valve_lag.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "slicer/tolerances.h"

namespace strand::post {

using slicer::Feature;
using slicer::Move;
using slicer::MoveKind;
using slicer::Vec2;
using slicer::Vec3;

namespace {

class Planner {
 public:
  Planner(const machines::MachineProfile& m, const PlanOptions& o, slicer::MotionProgram& out)
      : m_(m), o_(o), p_(out), offset_(m.volume.part_center_mm) {}

  void run(const slicer::Toolpath& t) {
    std::size_t bound = 1;  // the approach above the first point
    for (const auto& layer : t.layers) bound += move_bound(layer);
    p_.moves.reserve(bound);
    p_.layers.reserve(t.layers.size());
    for (const auto& layer : t.layers) add_layer(layer);
  }

  // The next layer's moves, appended to the program.
  void add_layer(const slicer::Layer& layer) {
    layer_ = static_cast<int>(p_.layers.size());
    p_.layers.push_back({layer.z_mm, layer.height_mm});
    if (o_.tools.empty()) {
      for (const auto& stroke : layer.strokes) add_stroke(stroke, layer.z_mm);
      return;
    }
    for (const auto& stroke : assign_tools(layer.strokes, o_.tools, layer_, tool_)) add_stroke(stroke, layer.z_mm);
  }

  const Vec3& position() const { return pos_; }
  bool started() const { return started_; }

  // Moves add_layer() can make at most for `layer` (travels skipped when already in place),
  // so the program is allocated once: a growing vector would briefly hold two or three times
  // its size.
  std::size_t move_bound(const slicer::Layer& layer) const {
    std::size_t n = 1;  // the approach above the first point
    {
      for (const auto& s : layer.strokes) {
        n += 3;  // lift, cross, lower
        if (!o_.stroke_flows.empty() || !o_.stroke_labels.empty() || o_.flow) n += 2;  // lift, text
        // A change of tool lifts once more; a stroke cut where its tool changes (by feature)
        // makes one more stroke per segment at most.
        if (!o_.tools.empty()) n += 4 * (1 + (o_.tools.by_feature.empty() ? 0 : s.segments.size()));
        Vec2 at = s.start_mm;
        for (const auto& seg : s.segments) {
          if (seg.kind == slicer::SegmentKind::Line || m_.arcs) {
            ++n;
          } else {
            const double r = (at - seg.center_mm).norm();
            // + 1: planning works on placed coordinates, whose rounding may add a chord.
            n += 1 + static_cast<std::size_t>(chords_needed(
                         r, slicer::arc_sweep(seg.center_mm, at, seg.end_mm, seg.ccw), o_.arc_tolerance_mm));
          }
          at = seg.end_mm;
        }
      }
    }
    return n;
  }

  void add_stroke(const slicer::Stroke& s, double layer_z) {
    // Each printhead's nozzle sits at its offset from the first: the carriage goes that much
    // the other way (issue 33; Strand moves by the offsets, as PrusaSlicer does).
    if (s.tool != tool_) {
      if (s.tool < 0 || s.tool >= machines::tool_count(m_)) {
        throw InputError("tools: tool " + std::to_string(s.tool) + " is not on machine " + m_.name + " (" +
                         std::to_string(machines::tool_count(m_)) + " tool(s): 0 to " + std::to_string(machines::tool_count(m_) - 1) + ")");
      }
      if (started_ && m_.travel_lift_mm > 0) {
        push_travel(Vec3(pos_.x(), pos_.y(), pos_.z() + m_.travel_lift_mm), m_.limits.z_feed_mm_per_min);
      }
      tool_ = s.tool;
      const Vec3 o = machines::tool_offset(m_, tool_);
      offset_ = m_.volume.part_center_mm - o.head<2>();
      z_offset_ = -o.z();
    }
    const double z = layer_z + z_offset_;
    const Vec3 start(s.start_mm.x() + offset_.x(), s.start_mm.y() + offset_.y(), z);
    const bool own_flow = stroke_ < o_.stroke_flows.size();
    if (own_flow) {
      set_flow(o_.stroke_flows[stroke_], "");
    } else if (o_.flow) {
      set_flow(*o_.flow, "this ink");
    }
    if (stroke_ < o_.stroke_labels.size() && !o_.stroke_labels[stroke_].empty()) {
      slicer::push_raw(p_, machines::comment_line(m_, o_.stroke_labels[stroke_]), layer_);
    }
    travel_to(start);
    double area = slicer::bead_area_mm2(s.width_mm, s.height_mm);
    if (o_.flow && !own_flow && m_.deposition.model == machines::DepositionModel::EVolumetric) area *= *o_.flow;
    const double speed = stroke_ < o_.stroke_speeds_mm_per_min.size() ? o_.stroke_speeds_mm_per_min[stroke_]
                                                                       : o_.speed_mm_per_min;
    ++stroke_;
    Vec2 at = s.start_mm + offset_;
    for (const auto& seg : s.segments) {
      const Vec2 end = seg.end_mm + offset_;
      const double feed = feed_for(seg.feature, area, speed);
      if (seg.kind == slicer::SegmentKind::Line) {
        deposit(at, end, z, feed, area, s.width_mm, seg.feature);
      } else if (m_.arcs) {
        Move mv = deposit_move(end, z, feed, s.width_mm, seg.feature);
        mv.is_arc = true;
        mv.center_mm = seg.center_mm + offset_;
        mv.ccw = seg.ccw;
        mv.volume_mm3 = area * slicer::segment_length(at, slicer::arc_to(end, mv.center_mm, seg.ccw, seg.feature));
        p_.moves.push_back(mv);
      } else {
        Vec2 from = at;
        for (const Vec2& q : segment_arc(at, seg.center_mm + offset_, end, seg.ccw, o_.arc_tolerance_mm)) {
          deposit(from, q, z, feed, area, s.width_mm, seg.feature);
          from = q;
        }
      }
      at = end;
    }
    pos_ = Vec3(at.x(), at.y(), z);
  }

  // A new flow on a pneumatic machine: lifted clear of the bead (a pause may follow), the
  // machine's commands. Nothing when the flow is unchanged or set by E.
  void set_flow(double flow, const std::string& what) {
    if (!machines::flow_is_pressure(m_) || (flow_ && *flow_ == flow)) return;
    flow_ = flow;
    if (started_ && m_.travel_lift_mm > 0) {
      push_travel(Vec3(pos_.x(), pos_.y(), pos_.z() + m_.travel_lift_mm), m_.limits.z_feed_mm_per_min);
    }
    slicer::push_raw(p_, machines::flow_change_gcode(m_, flow, what), layer_);
  }

  void deposit(const Vec2& from, const Vec2& to, double z, double feed, double area, double width,
               Feature f) {
    if ((to - from).norm() < slicer::kSamePointMm) return;
    Move mv = deposit_move(to, z, feed, width, f);
    mv.volume_mm3 = area * (to - from).norm();
    p_.moves.push_back(mv);
  }

  Move deposit_move(const Vec2& end, double z, double feed, double width, Feature f) const {
    Move mv;
    mv.kind = MoveKind::Deposit;
    mv.tool = static_cast<std::int16_t>(tool_);
    mv.end_mm = Vec3(end.x(), end.y(), z);
    mv.feed_mm_per_min = feed;
    mv.width_mm = width;
    mv.feature = f;
    mv.layer = layer_;
    return mv;
  }

  // Base speed x feature factor (job first, then profile), capped by the machine's feed
  // and, on E-driven machines, by its volumetric flow over the bead section.
  double feed_for(Feature f, double area_mm2, double speed_mm_per_min) {
    // Consecutive segments nearly always share feature and bead: skip the table lookups.
    if (cached_ && f == cached_feature_ && area_mm2 == cached_area_ && speed_mm_per_min == cached_speed_) {
      return cached_feed_;
    }
    cached_ = true;
    cached_feature_ = f;
    cached_area_ = area_mm2;
    cached_speed_ = speed_mm_per_min;
    cached_feed_ = feed_uncached(f, area_mm2, speed_mm_per_min);
    return cached_feed_;
  }

  double feed_uncached(Feature f, double area_mm2, double speed_mm_per_min) const {
    double factor = 1.0;
    if (auto it = o_.speed_factors.find(f); it != o_.speed_factors.end()) {
      factor = it->second;
    } else if (auto pt = m_.speed_factors.find(f); pt != m_.speed_factors.end()) {
      factor = pt->second;
    }
    double feed = std::min(speed_mm_per_min * factor, m_.limits.max_feed_mm_per_min);
    const double q_max = m_.limits.max_volumetric_flow_mm3_per_s;
    if (m_.deposition.model == machines::DepositionModel::EVolumetric && q_max > 0 && area_mm2 > 0) {
      feed = std::min(feed, slicer::mm_per_s_to_mm_per_min(q_max / area_mm2));
    }
    return feed;
  }

  // Travels to `target`: straight down or up when only z changes, else lift, cross, lower.
  void travel_to(const Vec3& target) {
    if (!started_) {
      started_ = true;
      // Arrive above the first point, then go straight down: never swoop in from home.
      const Vec3 above(target.x(), target.y(), target.z() + std::max(m_.travel_lift_mm, 1.0));
      p_.start_mm = above;
      push_travel(above, m_.limits.travel_feed_mm_per_min);
    }
    if ((target - pos_).norm() < slicer::kSamePointMm) return;
    const bool same_xy = (target.head<2>() - pos_.head<2>()).norm() < slicer::kSamePointMm;
    if (same_xy) {
      push_travel(target, m_.limits.z_feed_mm_per_min);
      return;
    }
    const double safe_z = std::max(pos_.z(), target.z()) + m_.travel_lift_mm;
    if (m_.travel_lift_mm > 0 && pos_.z() < safe_z) push_travel(Vec3(pos_.x(), pos_.y(), safe_z), m_.limits.z_feed_mm_per_min);
    push_travel(Vec3(target.x(), target.y(), m_.travel_lift_mm > 0 ? safe_z : target.z()), m_.limits.travel_feed_mm_per_min);
    if (m_.travel_lift_mm > 0) push_travel(target, m_.limits.z_feed_mm_per_min);
  }

  void push_travel(const Vec3& to, double feed) {
    Move mv;
    mv.kind = MoveKind::Travel;
    mv.tool = static_cast<std::int16_t>(tool_);
    mv.end_mm = to;
    mv.feed_mm_per_min = feed;
    mv.layer = layer_;
    p_.moves.push_back(mv);
    pos_ = to;
  }

  const machines::MachineProfile& m_;
  const PlanOptions& o_;
  slicer::MotionProgram& p_;
  Vec2 offset_ = Vec2::Zero();  // part frame to machine frame for the current tool
  double z_offset_ = 0.0;
  int tool_ = 0;                // the printhead the strokes are planned for
  Vec3 pos_ = Vec3::Zero();
  bool started_ = false;
  int layer_ = -1;
  bool cached_ = false;
  Feature cached_feature_ = Feature::Infill;
  double cached_area_ = 0.0;
  double cached_speed_ = 0.0;
  double cached_feed_ = 0.0;
  std::size_t stroke_ = 0;  // strokes planned so far, for stroke_speeds_mm_per_min
  std::optional<double> flow_;  // the flow last set on a pneumatic machine
};

}  // namespace

PlanOptions plan_options_from(const slicer::Toolpath& t, double arc_tolerance_mm) {
  PlanOptions o;
  o.arc_tolerance_mm = arc_tolerance_mm;
  o.speed_mm_per_min = t.parameters.value("speed", o.speed_mm_per_min);
  for (Feature f : {Feature::Infill, Feature::Wall, Feature::Ligament, Feature::Node,
                    Feature::Grip, Feature::Frame, Feature::Link, Feature::Pen}) {
    const std::string key = slicer::to_string(f) + "-speed-factor";
    if (t.parameters.contains(key)) o.speed_factors[f] = t.parameters.at(key).get<double>();
  }
  if (t.derived.is_object() && t.derived.contains("stroke_speeds_mm_per_min")) {
    o.stroke_speeds_mm_per_min = t.derived.at("stroke_speeds_mm_per_min").get<std::vector<double>>();
  }
  if (t.derived.is_object() && t.derived.contains("stroke_flows")) {
    o.stroke_flows = t.derived.at("stroke_flows").get<std::vector<double>>();
  }
  if (t.derived.is_object() && t.derived.contains("stroke_labels")) {
    o.stroke_labels = t.derived.at("stroke_labels").get<std::vector<std::string>>();
  }
  return o;
}

namespace {

// What the machine asks of planned moves: the valve closed its lag early, every move inside
// the build volume (InputError otherwise).
void finish_for_machine(slicer::MotionProgram& p, const machines::MachineProfile& machine) {
  if (machine.deposition.model == machines::DepositionModel::Valve && machine.deposition.lag_s > 0) {
    apply_valve_lag(p, machine.deposition.lag_s);
  }
  check_fits(p, machine);
}

}  // namespace

slicer::MotionProgram plan(const slicer::Toolpath& t, const machines::MachineProfile& machine,
                           const PlanOptions& options) {
  slicer::MotionProgram p;
  Planner(machine, options, p).run(t);
  finish_for_machine(p, machine);
  if (options.check_idle_heads) {
    IdleHeadCheck idle(machine);
    throw_if_idle_head_drags(idle, p, machine, options.arc_tolerance_mm);
  }
  return p;
}

struct LayerPlanner::State {
  State(const machines::MachineProfile& m, const PlanOptions& o) : machine(m), options(o), planner(m, options, chunk), idle(m) {}
  const machines::MachineProfile& machine;
  PlanOptions options;
  slicer::MotionProgram chunk;
  Planner planner;
  IdleHeadCheck idle;  // the beads of the layers so far, under the idle heads
};

LayerPlanner::LayerPlanner(const machines::MachineProfile& machine, const PlanOptions& options)
    : s_(std::make_unique<State>(machine, options)) {}

LayerPlanner::~LayerPlanner() = default;

const slicer::MotionProgram& LayerPlanner::plan(const slicer::Layer& layer) {
  slicer::MotionProgram& p = s_->chunk;
  p.moves.clear();
  p.texts.clear();
  p.dwells_s.clear();
  const bool first = !s_->planner.started();
  const Vec3 before = s_->planner.position();
  p.moves.reserve(s_->planner.move_bound(layer));
  s_->planner.add_layer(layer);
  if (!first) p.start_mm = before;  // the first layer's start is its approach point
  finish_for_machine(p, s_->machine);  // per layer: a strand never spans two
  throw_if_idle_head_drags(s_->idle, p, s_->machine, s_->options.arc_tolerance_mm);
  return p;
}

}  // namespace strand::post
