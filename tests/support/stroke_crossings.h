// Crossings among one layer's strokes, as `strand check` finds them in a file: the strokes
// become a motion program (a travel to each start, deposits along it) for post::find_contacts.
#pragma once

#include <cstddef>
#include <vector>

#include "postprocess/inspect/crossings.h"
#include "slicer/motion.h"
#include "slicer/toolpath.h"

namespace strand::testing {

inline std::size_t layer_crossings(const std::vector<slicer::Stroke>& strokes) {
  slicer::MotionProgram program;
  program.layers.push_back({0.5, 0.5});
  for (const slicer::Stroke& s : strokes) {
    slicer::Move travel;
    travel.end_mm = slicer::Vec3(s.start_mm.x(), s.start_mm.y(), 0.5);
    program.moves.push_back(travel);
    for (const auto& seg : s.segments) {
      slicer::Move mv = travel;
      mv.kind = slicer::MoveKind::Deposit;
      mv.end_mm = slicer::Vec3(seg.end_mm.x(), seg.end_mm.y(), 0.5);
      mv.width_mm = s.width_mm;
      program.moves.push_back(mv);
    }
  }
  return post::find_contacts(program, 0.01, 1e-3).crossings.size();
}

}  // namespace strand::testing
