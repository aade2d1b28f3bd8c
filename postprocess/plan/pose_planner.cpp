// Pose planning: deposits sampled on the surface, travels backed off and turned, time by
// chord length over the planned contact speed.
#include "postprocess/plan/pose_planner.h"

#include <algorithm>
#include <cmath>

#include "postprocess/plan/laps.h"
#include "postprocess/plan/surface_sampling.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Feature;
using slicer::PosePoint;
using slicer::Vec2;
using slicer::Vec3;

namespace {

// A closed strand may start anywhere on its loop: start it at its lowest u (lowest turn), so
// the layer turns forward to its farthest point and returns to the start: one forward and
// one return lap, as the thesis printed its cylinder.
slicer::Stroke start_at_lowest_u(const slicer::Stroke& s) {
  if (s.segments.empty() || (s.end_mm() - s.start_mm).norm() > slicer::kSamePointMm) return s;
  std::size_t best = s.segments.size() - 1;  // the stroke's own start (= its end)
  for (std::size_t i = 0; i < s.segments.size(); ++i) {
    if (s.segments[i].end_mm.x() < s.segments[best].end_mm.x() - slicer::kSamePointMm) best = i;
  }
  slicer::Stroke out = s;
  out.start_mm = s.segments[best].end_mm;
  out.segments.clear();
  for (std::size_t k = 1; k <= s.segments.size(); ++k) {
    out.segments.push_back(s.segments[(best + k) % s.segments.size()]);
  }
  out.segments.back().end_mm = out.start_mm;  // exactly closed again
  return out;
}

class PosePlanner {
 public:
  PosePlanner(const slicer::CylinderSurface& s, const machines::Holder& h, const PosePlanOptions& o)
      : s_(s), h_(h), o_(o) {}

  slicer::PoseProgram run(const slicer::Toolpath& t) {
    p_.substrate = s_.describe();
    for (std::size_t k = 0; k < t.layers.size(); ++k) {
      const auto& layer = t.layers[k];
      p_.layers.push_back({layer.z_mm, layer.height_mm, s_.u_stretch(layer.z_mm)});
      layer_ = static_cast<int>(k);
      for (const auto& given : layer.strokes) {
        const slicer::Stroke stroke = start_at_lowest_u(given);
        travel_to(stroke.start_mm, layer.z_mm);
        deposit(stroke, layer.z_mm);
      }
    }
    if (!p_.points.empty())
      push(turn_, v_, off_ + o_.lift_mm, false, feature_, o_.lift_speed_mm_per_s);
    assign_laps(p_);
    return std::move(p_);
  }

 private:
  double speed_of(Feature f) const {
    const auto it = o_.deposit_speed_mm_per_s.find(f);
    return it == o_.deposit_speed_mm_per_s.end() ? o_.default_deposit_speed_mm_per_s : it->second;
  }

  void deposit(const slicer::Stroke& stroke, double offset) {
    Vec2 at = stroke.start_mm;
    for (const auto& seg : stroke.segments) {
      const double speed = speed_of(seg.feature);
      for (const Vec2& q : sample_on_surface(s_, at, seg, offset, o_.arc_tolerance_mm)) {
        push(s_.angle_rad(q.x(), offset), q.y(), offset, true, seg.feature, speed);
      }
      at = seg.end_mm;
    }
  }

  // Backs off to the higher of the two offsets plus the lift, turns and shifts there, and
  // approaches the target; the very first point starts backed off above the target.
  void travel_to(const Vec2& uv, double offset) {
    const double turn = s_.angle_rad(uv.x(), offset);
    measure_offset_ = offset;
    if (p_.points.empty()) {
      push(turn, uv.y(), offset + o_.lift_mm, false, feature_, 0.0);
      push(turn, uv.y(), offset, false, feature_, o_.lift_speed_mm_per_s);
      return;
    }
    const double r = s_.spec().radius_mm;
    if (std::abs(turn - turn_) * r < slicer::kSamePointMm &&
        std::abs(uv.y() - v_) < slicer::kSamePointMm &&
        std::abs(offset - off_) < slicer::kSamePointMm) {
      return;
    }
    const double safe = std::max(off_, offset) + o_.lift_mm;
    if (off_ < safe) push(turn_, v_, safe, false, feature_, o_.lift_speed_mm_per_s);
    cross(turn, uv.y(), safe);
    push(turn, uv.y(), offset, false, feature_, o_.lift_speed_mm_per_s);
  }

  // Turns and shifts at a constant offset, in steps whose sagitta stays within tolerance.
  void cross(double turn, double v, double offset) {
    const double r = s_.spec().radius_mm + offset;
    const double tol = std::min(o_.arc_tolerance_mm, r);
    const double step = std::max(2.0 * std::acos(1.0 - tol / r), 1e-6);
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(turn - turn_) / step)));
    const double t0 = turn_, v0 = v_;
    for (int i = 1; i <= n; ++i) {
      const double f = double(i) / n;
      push(t0 + f * (turn - t0), v0 + f * (v - v0), offset, false, feature_,
           o_.travel_speed_mm_per_s);
    }
  }

  void push(double turn, double v, double offset, bool extrude, Feature f, double speed) {
    const slicer::SurfaceFrame fr = s_.frame_at_turn(turn, v, offset);
    const machines::WorkpiecePose w = machines::workpiece_pose(h_, fr.point_mm, turn);
    PosePoint p;
    p.contact_mm = fr.point_mm;
    p.normal = fr.normal;
    p.workpiece_origin_mm = w.origin_mm;
    p.workpiece_wxyz = machines::quaternion_wxyz(w.rotation);
    p.tip_mm = w.tip_mm;
    p.uv_mm = Vec2(turn * s_.u_radius_mm(measure_offset_), v);
    p.offset_mm = offset;
    p.turn_rad = turn;
    p.extrude = extrude;
    p.layer = layer_;
    p.feature = f;
    if (!p_.points.empty()) {
      const PosePoint& prev = p_.points.back();
      if (p.workpiece_wxyz.dot(prev.workpiece_wxyz) < 0) p.workpiece_wxyz = -p.workpiece_wxyz;
      p.speed_mm_per_s = speed;
      p.t_s = prev.t_s + (p.contact_mm - prev.contact_mm).norm() / speed;
    }
    p_.points.push_back(p);
    turn_ = turn, v_ = v, off_ = offset, feature_ = f;
  }

  const slicer::CylinderSurface& s_;
  const machines::Holder& h_;
  const PosePlanOptions& o_;
  slicer::PoseProgram p_;
  double turn_ = 0.0, v_ = 0.0, off_ = 0.0, measure_offset_ = 0.0;
  Feature feature_ = Feature::Infill;
  int layer_ = 0;
};

// Refuses programs that would need more poses than kMaxPosePoints, before planning them.
void check_work(const slicer::Toolpath& t, const slicer::CylinderSurface& s, double tol) {
  const double r = s.spec().radius_mm;
  // Travel steps per mm of u at the substrate radius (the tightest, at the smallest radius).
  const double travel_steps_per_mm = 1.0 / (r * 2.0 * std::acos(1.0 - std::min(tol, r) / r));
  double bound = 0.0;
  Vec2 prev_end = Vec2::Zero();
  for (const auto& layer : t.layers) {
    for (const auto& stroke : layer.strokes) {
      Vec2 at = stroke.start_mm;
      bound += 4.0 + std::abs(at.x() - prev_end.x()) * travel_steps_per_mm;
      for (const auto& seg : stroke.segments) {
        bound += static_cast<double>(sample_bound(s, at, seg, layer.z_mm, tol));
        at = seg.end_mm;
      }
      prev_end = at;
      if (bound > static_cast<double>(kMaxPosePoints)) {
        throw InputError("arc-tolerance = " + slicer::short_number(tol) +
                         ": the program would need more than " + std::to_string(kMaxPosePoints) +
                         " poses; raise it (mm) or print fewer layers");
      }
    }
  }
}

}  // namespace

slicer::PoseProgram plan_poses(const slicer::Toolpath& t, const slicer::CylinderSurface& s,
                               const machines::Holder& holder, const PosePlanOptions& options) {
  check_work(t, s, options.arc_tolerance_mm);
  return PosePlanner(s, holder, options).run(t);
}

}  // namespace strand::post
