// Mesh pose planning, the path: strokes cut into pieces no longer than kMeshStepMm and sampled
// on their layer's offset surface, travels lifted above it, every point placed by the row rule
// (slicer/mesh_row_rule.h) and its nozzle cone checked against the mesh.
#include "postprocess/plan/mesh_path_targets.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "machines/gcode_format.h"
#include "postprocess/plan/surface_sampling.h"
#include "slicer/input_error.h"
#include "slicer/mesh_row_rule.h"
#include "slicer/params.h"
#include "slicer/tolerances.h"

namespace strand::post::mesh_detail {

using slicer::Feature;
using slicer::Vec2;

namespace {

// Deposit segments are cut into pieces no longer than this before sampling, so the samples
// follow the mesh from triangle to triangle, mm.
constexpr double kMeshStepMm = 2.0;

std::string mm(double v) { return machines::fmt_fixed(v, 3); }

// Segments cut into pieces of at most kMeshStepMm (lines and arcs stay exact).
std::vector<slicer::Segment> pieces_of(const Vec2& from, const slicer::Segment& s) {
  const double len = slicer::segment_length(from, s);
  const int n = std::max(1, static_cast<int>(std::ceil(len / kMeshStepMm)));
  if (n == 1) return {s};
  std::vector<slicer::Segment> out;
  if (s.kind == slicer::SegmentKind::Line) {
    for (int i = 1; i <= n; ++i) {
      slicer::Segment p = s;
      p.end_mm = i == n ? s.end_mm : Vec2(from + (s.end_mm - from) * (double(i) / n));
      out.push_back(p);
    }
    return out;
  }
  const double r = (from - s.center_mm).norm();
  const double a0 = slicer::angle_of(s.center_mm, from);
  const double sweep = slicer::arc_sweep(s.center_mm, from, s.end_mm, s.ccw);
  for (int i = 1; i <= n; ++i) {
    slicer::Segment p = s;
    p.end_mm = i == n ? s.end_mm : slicer::on_circle(s.center_mm, r, a0 + sweep * i / n);
    out.push_back(p);
  }
  return out;
}

}  // namespace

std::string where(const Target& t) {
  return "pattern point (u, v) = (" + mm(t.uv.x()) + ", " + mm(t.uv.y()) +
         ") mm, nozzle tip at (x, y, z) = (" + mm(t.frame.point_mm.x()) + ", " +
         mm(t.frame.point_mm.y()) + ", " + mm(t.frame.point_mm.z()) +
         ") mm in the mesh's frame, layer " + std::to_string(t.layer);
}

std::vector<Target> PathBuilder::run(const slicer::Toolpath& t) {
  for (std::size_t k = 0; k < t.layers.size(); ++k) {
    layer_ = static_cast<int>(k);
    layer_offset_ = t.layers[k].z_mm;
    for (const auto& stroke : t.layers[k].strokes) {
      if (stroke.segments.empty()) continue;
      travel_to(stroke.start_mm, layer_offset_);
      Vec2 at = stroke.start_mm;
      for (const auto& seg : stroke.segments) {
        const double speed = speed_of(seg.feature);
        for (const auto& piece : pieces_of(at, seg)) {
          for (const Vec2& q : sample_on_surface(s_, at, piece, layer_offset_, o_.arc_tolerance_mm))
            push(q, layer_offset_, true, seg.feature, speed);
          at = piece.end_mm;
        }
      }
    }
  }
  if (!out_.empty()) push(uv_, off_ + o_.lift_mm, false, feature_, o_.lift_speed_mm_per_s);
  return std::move(out_);
}

Target PathBuilder::lifted(const Target& t, double by) const {
  Target l = t;
  l.offset = t.offset + by;
  l.lifted = true;
  l.extrude = false;
  l.speed = o_.lift_speed_mm_per_s;
  l.frame = slicer::mesh_row_frame(s_, t.uv, l.offset);  // same foot and normal
  check_cone(l);
  return l;
}

double PathBuilder::speed_of(Feature f) const {
  const auto it = o_.deposit_speed_mm_per_s.find(f);
  return it == o_.deposit_speed_mm_per_s.end() ? o_.default_deposit_speed_mm_per_s : it->second;
}

void PathBuilder::travel_to(const Vec2& uv, double offset) {
  if (out_.empty()) {
    push(uv, offset + o_.lift_mm, false, feature_, 0.0);
    push(uv, offset, false, feature_, o_.lift_speed_mm_per_s);
    return;
  }
  if ((uv - uv_).norm() < slicer::kSamePointMm && std::abs(offset - off_) < slicer::kSamePointMm)
    return;
  const double safe = std::max(off_, offset) + o_.lift_mm;
  if (off_ < safe) push(uv_, safe, false, feature_, o_.lift_speed_mm_per_s);
  if ((uv - uv_).norm() >= slicer::kSamePointMm) {
    Vec2 at = uv_;
    for (const auto& piece : pieces_of(uv_, slicer::line_to(uv, feature_))) {
      for (const Vec2& q : sample_on_surface(s_, at, piece, safe, o_.arc_tolerance_mm))
        push(q, safe, false, feature_, o_.travel_speed_mm_per_s);
      at = piece.end_mm;
    }
  }
  push(uv, offset, false, feature_, o_.lift_speed_mm_per_s);
}

void PathBuilder::check_cone(const Target& t) const {
  if (auto hit = s_.cone_hit(c_.nozzle_cone, t.frame.point_mm, t.frame.normal)) {
    const auto& cone = c_.nozzle_cone;
    throw InputError(
        "substrate.mesh = " + s_.source() + ": the nozzle would touch the mesh at (" +
        mm(hit->x()) + ", " + mm(hit->y()) + ", " + mm(hit->z()) + ") mm with its tip at " +
        where(t) + " (robot.nozzle_cone: " + slicer::short_number(cone.half_angle_deg) +
        " deg half-angle, " + slicer::short_number(cone.length_mm) + " mm long, tip radius " +
        slicer::short_number(cone.tip_radius_mm) + " mm); the surface rises into the nozzle there");
  }
}

void PathBuilder::push(const Vec2& uv, double offset, bool extrude, Feature f, double speed) {
  if (!s_.in_domain(uv)) {
    const slicer::UvBox b = s_.domain();
    throw InputError("substrate.mesh = " + s_.source() + ": the pattern leaves the mesh at " +
                     "pattern point (u, v) = (" + mm(uv.x()) + ", " + mm(uv.y()) + ") mm, layer " +
                     std::to_string(layer_) + "; the mesh's (u, v) spans " + mm(b.min_mm.x()) +
                     ".." + mm(b.max_mm.x()) + " x " + mm(b.min_mm.y()) + ".." + mm(b.max_mm.y()) +
                     " mm: use a smaller pattern or a larger mesh");
  }
  if (out_.size() >= kMaxPosePoints) {
    throw InputError("arc-tolerance = " + slicer::short_number(o_.arc_tolerance_mm) +
                     ": the program would need more than " + std::to_string(kMaxPosePoints) +
                     " poses; raise it (mm) or print fewer layers");
  }
  Target t;
  t.uv = uv;
  t.offset = offset;
  t.extrude = extrude;
  t.lifted = offset > layer_offset_ + 1e-9;
  t.feature = f;
  t.speed = speed;
  t.layer = layer_;
  t.frame = slicer::mesh_row_frame(s_, uv, offset);
  check_cone(t);
  out_.push_back(t);
  uv_ = uv, off_ = offset, feature_ = f;
}

}  // namespace strand::post::mesh_detail
