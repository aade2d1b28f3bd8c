// Draping: the flat program's moves re-targeted onto the surface, travels over the top.
#include "postprocess/plan/drape.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "postprocess/plan/idle_heads.h"
#include "postprocess/plan/placement.h"
#include "slicer/input_error.h"
#include "slicer/mesh.h"
#include "slicer/mesh_collision.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Move;
using slicer::MoveKind;
using slicer::Vec2;
using slicer::Vec3;

namespace {

std::string xyz(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.3f)", p.x(), p.y(), p.z());
  return buf;
}

class Draper {
 public:
  // `shape`: the substrate's triangles (its top is the travels' floor).
  Draper(const slicer::Surface& s, const slicer::TriangleMesh& shape, const machines::MachineProfile& m)
      : s_(s), m_(m), center_(m.volume.part_center_mm), top_z_(top_of(shape)) {
    for (int k = 0; k < machines::tool_count(m); ++k) lowest_tip_ = std::min(lowest_tip_, machines::tool_offset(m, k).z());
  }

  slicer::MotionProgram run(const slicer::MotionProgram& flat) {
    slicer::MotionProgram out;
    out.layers = flat.layers;
    Vec3 at_flat = flat.start_mm;
    std::size_t i = 0;
    while (i < flat.moves.size()) {
      const Move& mv = flat.moves[i];
      if (mv.kind == MoveKind::Travel) {
        std::size_t j = i;
        while (j < flat.moves.size() && flat.moves[j].kind == MoveKind::Travel) ++j;
        travel(flat.moves[j - 1], out);
        at_flat = flat.moves[j - 1].end_mm;
        i = j;
        continue;
      }
      if (mv.kind == MoveKind::Deposit) {
        deposit(at_flat, mv, out);
        at_flat = mv.end_mm;
      } else {
        out.moves.push_back(mv);
      }
      ++i;
    }
    out.start_mm = out.moves.empty() ? flat.start_mm : start_;
    return out;
  }

 private:
  static double top_of(const slicer::TriangleMesh& mesh) {
    double top = mesh.vertices_mm.empty() ? 0.0 : mesh.vertices_mm.front().z();
    for (const Vec3& v : mesh.vertices_mm) top = std::max(top, v.z());
    return top;
  }

  // The carriage at flat machine point c with head `tool` depositing: that head's tip
  // (c plus its offset) goes to the surface point under it raised by its flat z, slope-checked,
  // and the carriage follows it.
  Vec3 mapped(const Vec3& c, int tool) const {
    const Vec3 o = machines::tool_offset(m_, tool);
    const Vec3 q = c + o;
    const Vec2 uv = q.head<2>() - center_;
    if (!s_.in_domain(uv)) {
      const auto d = s_.domain();
      const auto mm = [](double v) { return slicer::short_number(std::round(v * 1000) / 1000); };
      throw InputError("onto: the pattern leaves the substrate at (u, v) = (" + mm(uv.x()) + ", " + mm(uv.y()) +
                       ") mm; the patch spans u in [" + mm(d.min_mm.x()) + ", " + mm(d.max_mm.x()) + "], v in [" +
                       mm(d.min_mm.y()) + ", " + mm(d.max_mm.y()) + "] (make the pattern smaller)");
    }
    const slicer::SurfaceFrame f = s_.frame_at(uv, 0.0);
    const double slope = slicer::rad_to_deg(std::acos(std::clamp(f.normal.z(), -1.0, 1.0)));
    if (slope > m_.max_surface_slope_deg) {
      throw InputError("onto: the substrate slopes " +
                       slicer::short_number(std::round(slope * 10) / 10) + " deg at " +
                       xyz(f.point_mm) + " under the path; " + m_.name +
                       " keeps its nozzle vertical and follows at most max_surface_slope_deg = " +
                       slicer::short_number(m_.max_surface_slope_deg) + " deg");
    }
    return Vec3(f.point_mm.x() + center_.x(), f.point_mm.y() + center_.y(), f.point_mm.z() + q.z()) - o;
  }

  void deposit(const Vec3& from, const Move& mv, slicer::MotionProgram& out) {
    const double len = (mv.end_mm - from).head<2>().norm();
    const int n = std::max(1, static_cast<int>(std::ceil(len / kDrapeStepMm)));
    const double area = len > 0 ? mv.volume_mm3 / len : 0.0;  // bead section of the flat move
    for (int k = 1; k <= n; ++k) {
      Move piece = mv;
      piece.end_mm = mapped(from + (mv.end_mm - from) * (static_cast<double>(k) / n), mv.tool);
      piece.volume_mm3 = area * (piece.end_mm - last_).norm();
      out.moves.push_back(piece);
      last_ = piece.end_mm;
    }
  }

  // A run of flat travels becomes: up to the clearance, across, down onto the target.
  void travel(const Move& last_flat, slicer::MotionProgram& out) {
    const Vec3 target = mapped(last_flat.end_mm, last_flat.tool);
    // Every head's tip above the substrate's top, the lowest one included.
    const double clear =
        top_z_ + std::max(layer_z(last_flat, out), 0.0) + std::max(m_.travel_lift_mm, 1.0) - lowest_tip_;
    auto push = [&](const Vec3& p, double feed) {
      Move t = last_flat;
      t.end_mm = p;
      t.feed_mm_per_min = feed;
      out.moves.push_back(t);
    };
    if (out.moves.empty()) {
      start_ = Vec3(target.x(), target.y(), clear);
    } else {
      push(Vec3(last_.x(), last_.y(), clear), m_.limits.z_feed_mm_per_min);
    }
    push(Vec3(target.x(), target.y(), clear), m_.limits.travel_feed_mm_per_min);
    push(target, m_.limits.z_feed_mm_per_min);
    last_ = target;
  }

  static double layer_z(const Move& mv, const slicer::MotionProgram& p) {
    return mv.layer >= 0 && mv.layer < static_cast<int>(p.layers.size()) ? p.layers[mv.layer].z_mm
                                                                         : 0.0;
  }

  const slicer::Surface& s_;
  const machines::MachineProfile& m_;
  Vec2 center_;
  double top_z_;
  double lowest_tip_ = 0.0;  // the lowest head's z offset (0 or below)
  Vec3 last_ = Vec3::Zero();
  Vec3 start_ = Vec3::Zero();
};

}  // namespace

slicer::MotionProgram plan_draped(const slicer::Toolpath& t, const slicer::Surface& s,
                                  const machines::MachineProfile& machine,
                                  const PlanOptions& options) {
  machines::MachineProfile chords = machine;
  chords.arcs = false;  // arcs become chords before mapping: a draped arc is not planar
  PlanOptions flat_options = options;
  flat_options.check_idle_heads = false;  // the draped moves are checked, against the substrate too
  const slicer::MotionProgram flat = plan(t, chords, flat_options);
  const slicer::TriangleMesh shape = s.preview_mesh(0.1);
  slicer::MotionProgram draped = Draper(s, shape, machine).run(flat);
  check_fits(draped, machine);
  IdleHeadCheck idle(machine);
  if (!idle.active() || shape.triangles.empty()) return draped;
  // The idle tips against the beads and the substrate: its top under a bed point is where a
  // vertical line there first meets its triangles (CGAL's AABB tree, slicer/mesh_collision.h).
  const slicer::Mesh substrate{shape.vertices_mm, shape.triangles, {}};
  const slicer::Box3 box = slicer::bounds(substrate);
  const slicer::MeshProximity proximity(substrate);
  const Vec2 centre = machine.volume.part_center_mm;
  idle.set_ground([&](const Vec2& xy) {
    const Vec2 w = xy - centre;
    const auto hit = proximity.first_hit(Vec3(w.x(), w.y(), box.max_mm.z() + 1.0), Vec3(w.x(), w.y(), box.min_mm.z() - 1.0));
    return hit ? hit->point_mm.z() : -std::numeric_limits<double>::infinity();
  });
  throw_if_idle_head_drags(idle, draped, machine, options.arc_tolerance_mm);
  return draped;
}

}  // namespace strand::post
