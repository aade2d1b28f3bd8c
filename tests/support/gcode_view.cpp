// Deposit segment extraction for tests.
#include "tests/support/gcode_view.h"

namespace strand::testing {

std::vector<DepositSeg> deposit_segments(const slicer::MotionProgram& p) {
  std::vector<DepositSeg> out;
  slicer::Vec3 at = p.start_mm;
  for (const auto& mv : p.moves) {
    if (mv.kind == slicer::MoveKind::Deposit && !mv.is_arc) out.push_back({at, mv.end_mm, mv.feature, mv.layer});
    if (mv.kind == slicer::MoveKind::Deposit || mv.kind == slicer::MoveKind::Travel) at = mv.end_mm;
  }
  return out;
}

}  // namespace strand::testing
