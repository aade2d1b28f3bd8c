// Build-volume check over every move of a planned program.
#include "postprocess/plan/placement.h"

#include "machines/kinematics.h"
#include "machines/gcode_format.h"
#include "postprocess/plan/arc_segmentation.h"
#include "slicer/input_error.h"

namespace strand::post {

namespace {

void fail(const machines::MachineProfile& m, const std::string& reason, const slicer::Vec3& p) {
  throw InputError("part does not fit machine " + m.name + ": " + reason + " at (" +
                   machines::fmt_xyz(p.x()) + ", " + machines::fmt_xyz(p.y()) + ", " +
                   machines::fmt_xyz(p.z()) + ") mm; make the part smaller or choose another --machine");
}

}  // namespace

void check_fits(const slicer::MotionProgram& program, const machines::MachineProfile& machine) {
  slicer::Vec3 at = program.start_mm;
  for (const auto& mv : program.moves) {
    if (mv.kind != slicer::MoveKind::Travel && mv.kind != slicer::MoveKind::Deposit) continue;
    if (auto why = machines::outside_reason(machine.volume, mv.end_mm)) fail(machine, *why, mv.end_mm);
    if (mv.is_arc) {
      // Sample the arc finely: a chord tolerance of 1 um bounds the miss.
      const slicer::Vec2 from(at.x(), at.y());
      for (const auto& q : segment_arc(from, mv.center_mm, mv.end_mm.head<2>(), mv.ccw, 1e-3)) {
        const slicer::Vec3 p(q.x(), q.y(), mv.end_mm.z());
        if (auto why = machines::outside_reason(machine.volume, p)) fail(machine, *why, p);
      }
    }
    at = mv.end_mm;
  }
}

}  // namespace strand::post
