// Pen motion planning with the kinematic error budget, and estimates from the plan.
#include "postprocess/plot/pen_planner.h"

#include <algorithm>
#include <cmath>

#include "machines/pen_emitter.h"
#include "machines/plotter_kinematics.h"
#include "postprocess/plot/plot_layout.h"
#include "slicer/input_error.h"
#include "slicer/memory.h"
#include "slicer/params.h"

namespace strand::post {

namespace {

using slicer::Move;
using slicer::MoveKind;
using slicer::Vec2;
using slicer::Vec3;

// Below this share of the tolerance left for the bow, the machine cannot meet --tolerance.
constexpr double kMinBowShare = 0.05;

double worst_rounding(const slicer::Toolpath& t, const machines::MachineProfile& m) {
  double worst = 0.0;
  for (const auto& s : t.layers[0].strokes) {
    worst = std::max(worst, machines::rounding_error_mm(m.plotter.setup, s.start_mm, machines::kPenAxisDecimals));
    for (const auto& seg : s.segments) {
      worst = std::max(worst, machines::rounding_error_mm(m.plotter.setup, seg.end_mm, machines::kPenAxisDecimals));
    }
  }
  return worst;
}

class PenProgram {
 public:
  PenProgram(const machines::MachineProfile& m, double bow_mm) : m_(m), bow_mm_(bow_mm) {}

  slicer::MotionProgram& program() { return p_; }

  // Room for the moves of `strokes` when no draw move needs splitting (travel, pen down and
  // dwell, one move per segment, pen up and dwell; the way home), so the program is allocated
  // once instead of growing past twice its size.
  void reserve(const std::vector<slicer::Stroke>& strokes) {
    std::size_t n = 1;
    for (const auto& s : strokes) n += 5 + s.segments.size();
    p_.moves.reserve(n);
    p_.dwells_s.reserve(2 * strokes.size());
  }

  void start(const Vec2& home) {
    p_.layers.push_back({0.0, 0.0});
    p_.start_mm = Vec3(home.x(), home.y(), machines::kPenUpZ);
    at_ = p_.start_mm;
  }
  void travel(const Vec2& to, int tool) {
    if ((to - at_.head<2>()).norm() == 0.0) return;
    push(MoveKind::Travel, Vec3(to.x(), to.y(), machines::kPenUpZ), m_.limits.travel_feed_mm_per_min, tool);
  }
  void pen(bool down, int tool) {
    push(MoveKind::Travel, Vec3(at_.x(), at_.y(), down ? machines::kPenDownZ : machines::kPenUpZ),
         m_.limits.z_feed_mm_per_min, tool);
    if (m_.plotter.pen.lift == machines::PenLift::Servo && m_.plotter.pen.dwell_s > 0) {
      slicer::push_dwell(p_, m_.plotter.pen.dwell_s, at_, 0).tool = static_cast<std::int16_t>(tool);
    }
  }
  void draw(const Vec2& to, int tool, double width_mm) {
    const Vec2 from = at_.head<2>();
    for (const Vec2& q : machines::split_for_axes(m_.plotter.setup, from, to, bow_mm_)) {
      if (const auto why = machines::unreachable_reason(m_.plotter, q)) {
        throw InputError("plot: point (" + slicer::short_number(q.x()) + ", " + slicer::short_number(q.y()) +
                         ") mm cannot be drawn: " + *why);
      }
      push(MoveKind::Deposit, Vec3(q.x(), q.y(), machines::kPenDownZ), m_.plotter.pen.draw_feed_mm_per_min, tool);
      p_.moves.back().width_mm = width_mm;
    }
  }

 private:
  void push(MoveKind kind, const Vec3& to, double feed, int tool) {
    Move mv;
    mv.kind = kind;
    mv.end_mm = to;
    mv.feed_mm_per_min = feed;
    mv.feature = slicer::Feature::Pen;
    mv.layer = 0;
    mv.tool = tool;
    p_.moves.push_back(mv);
    at_ = to;
  }

  const machines::MachineProfile& m_;
  double bow_mm_;
  slicer::MotionProgram p_;
  Vec3 at_ = Vec3::Zero();
};

}  // namespace

slicer::MotionProgram plan_pen(const slicer::Toolpath& t, const machines::MachineProfile& m,
                               double tolerance_mm) {
  const double rounding = worst_rounding(t, m);
  const double bow = tolerance_mm * (1.0 - kFlattenShare) - rounding;
  if (bow < kMinBowShare * tolerance_mm) {
    throw InputError("plot.tolerance = " + slicer::short_number(tolerance_mm) + ": must be >= " +
                     slicer::short_number(std::ceil((rounding / (1.0 - kFlattenShare - kMinBowShare)) * 1e4) / 1e4) +
                     " (mm) on " + m.name + " (its step size and 3-decimal axes already cost " +
                     slicer::short_number(std::round(rounding * 1e5) / 1e5) + " mm)");
  }
  // Stroke copies freed by merging and ordering go back to the OS before the program grows.
  slicer::release_free_memory();
  PenProgram p(m, bow);
  p.reserve(t.layers[0].strokes);
  const Vec2 home = m.plotter.setup.home_mm;
  p.start(home);
  const auto& pen = m.plotter.pen;
  std::vector<double> drawn(static_cast<std::size_t>(pen.count), 0.0);
  for (const auto& s : t.layers[0].strokes) {
    p.travel(s.start_mm, s.tool);
    const double len = slicer::stroke_length(s);
    double& used = drawn[static_cast<std::size_t>(s.tool)];
    if (pen.capacity_mm > 0 && pen.pause_on_empty && !pen.change_gcode.empty() &&
        std::floor((used + len) / pen.capacity_mm) > std::floor(used / pen.capacity_mm)) {
      std::string change;
      for (std::string line : pen.change_gcode) {
        const auto at = line.find("{pen}");
        if (at != std::string::npos) line.replace(at, 5, std::to_string(s.tool + 1));
        change += (change.empty() ? "" : "\n") + line + " ; pen ran dry";
      }
      slicer::push_raw(p.program(), std::move(change), 0);
    }
    used += len;
    p.pen(true, s.tool);
    for (const auto& seg : s.segments) p.draw(seg.end_mm, s.tool, s.width_mm);
    p.pen(false, s.tool);
  }
  p.travel(home, t.layers[0].strokes.empty() ? 0 : t.layers[0].strokes.back().tool);
  return std::move(p.program());
}

PenEstimate estimate_pen(const slicer::MotionProgram& prog, const machines::MachineProfile& m) {
  PenEstimate e;
  const auto& pen = m.plotter.pen;
  e.draw_mm_per_pen.assign(static_cast<std::size_t>(pen.count), 0.0);
  Vec3 at = prog.start_mm;
  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& mv : prog.moves) {
    if (mv.kind == MoveKind::Dwell) e.time_s += slicer::dwell_seconds(prog, mv);
    if (mv.kind != MoveKind::Travel && mv.kind != MoveKind::Deposit) continue;
    const double paper = (mv.end_mm.head<2>() - at.head<2>()).norm();
    const double axes = (machines::to_axes(m.plotter.setup, mv.end_mm.head<2>()) -
                         machines::to_axes(m.plotter.setup, at.head<2>())).norm();
    const double t = axes / (mv.feed_mm_per_min / 60.0);
    if (mv.kind == MoveKind::Deposit) {
      e.draw_mm += paper;
      e.draw_mm_per_pen[static_cast<std::size_t>(mv.tool)] += paper;
      lo = lo.cwiseMin(mv.end_mm.head<2>()).cwiseMin(at.head<2>());
      hi = hi.cwiseMax(mv.end_mm.head<2>()).cwiseMax(at.head<2>());
      e.time_s += t;
    } else if (paper > 0.0) {
      e.pen_up_mm += paper;
      e.pen_up_time_s += t;
      e.time_s += t;
    } else if (mv.end_mm.z() != at.z()) {
      if (mv.end_mm.z() == machines::kPenUpZ) ++e.pen_lifts;
      const double stroke = pen.lift == machines::PenLift::Z ? std::abs(pen.z_up_mm - pen.z_down_mm)
                            : pen.lift == machines::PenLift::Drum ? pen.drum.write_offset_deg : 0.0;
      e.time_s += stroke / (m.limits.z_feed_mm_per_min / 60.0);
    }
    at = mv.end_mm;
  }
  if (e.draw_mm > 0) e.size_mm = hi - lo;
  for (std::size_t i = 0; i < e.draw_mm_per_pen.size(); ++i) {
    if (pen.capacity_mm > 0 && e.draw_mm_per_pen[i] > pen.capacity_mm) {
      e.warnings.push_back("pen " + std::to_string(i + 1) + " draws " + slicer::short_number(std::round(e.draw_mm_per_pen[i])) +
                           " mm, past its capacity of " + slicer::short_number(pen.capacity_mm) + " mm" +
                           (pen.pause_on_empty && !pen.change_gcode.empty() ? " (a pen change is inserted)" : " (change it midway)"));
    }
  }
  return e;
}

}  // namespace strand::post
