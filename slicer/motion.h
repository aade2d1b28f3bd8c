// MotionProgram: flat machine-level moves in the machine frame (mm, mm/min). Planners
// produce it from a Toolpath; the G-code parser produces it from any file, so checks,
// estimates and previews work on G-code that Strand did not write.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "slicer/geometry.h"
#include "slicer/large_allocator.h"
#include "slicer/toolpath.h"

namespace strand::slicer {

enum class MoveKind : std::uint8_t {
  Travel,   // no deposit (valve closed, pen up); G0
  Deposit,  // depositing ink or drawing; G1 (or G2/G3 when is_arc)
  Dwell,    // wait dwell_s seconds in place; G4
  Raw,      // verbatim machine text (start/end templates, valve commands)
};

// One machine move, kept compact (80 bytes) because large jobs hold millions: doubles first,
// small fields packed at the end, and the rare fields (a Raw move's text, a Dwell's seconds)
// out of line in MotionProgram, reached with raw_text() and dwell_seconds().
struct Move {
  Vec3 end_mm = Vec3::Zero();
  double feed_mm_per_min = 0.0;
  double volume_mm3 = 0.0;       // ink deposited by this move (Deposit only)
  double width_mm = 0.0;         // bead width, for ;WIDTH: and previews
  Vec2 center_mm = Vec2::Zero(); // arc centre (absolute)
  int layer = -1;                // index into MotionProgram::layers, -1 = before the first
  std::uint32_t side_index = 0;  // Raw: index into MotionProgram::texts; Dwell: into dwells_s
  std::int16_t tool = 0;         // extruder or pen index (plotting: which pen draws)
  MoveKind kind = MoveKind::Travel;
  Feature feature = Feature::Infill;
  bool is_arc = false;           // circular XY arc from the previous position
  bool ccw = true;               // arc direction
  bool coast = false;            // Deposit only: valve already closed (lag), the ink still
                                 // in the nozzle finishes the bead

  bool operator==(const Move&) const = default;
};
// Memory budget of large jobs (about 100 bytes per move end to end, issue 13).
static_assert(sizeof(Move) <= 80, "keep Move compact: move rare fields out of line");

struct LayerInfo {
  double z_mm = 0.0;
  double height_mm = 0.0;
  bool operator==(const LayerInfo&) const = default;
};

struct MotionProgram {
  LargeVector<Move> moves;  // millions in large jobs: huge pages (large_allocator.h)
  std::vector<LayerInfo> layers;
  std::vector<std::string> texts;  // Raw moves' text: one or more lines, no trailing newline
  std::vector<double> dwells_s;    // Dwell moves' waiting time, s
  Vec3 start_mm = Vec3::Zero();    // position before the first move
  bool operator==(const MotionProgram&) const = default;
};

// Appends a Raw move carrying `text` in `layer`.
inline void push_raw(MotionProgram& p, std::string text, int layer) {
  Move mv;
  mv.kind = MoveKind::Raw;
  mv.layer = layer;
  mv.side_index = static_cast<std::uint32_t>(p.texts.size());
  p.texts.push_back(std::move(text));
  p.moves.push_back(mv);
}
// Appends a Dwell move of `seconds` at `at_mm` in `layer`; returns it for further fields.
inline Move& push_dwell(MotionProgram& p, double seconds, const Vec3& at_mm, int layer) {
  Move mv;
  mv.kind = MoveKind::Dwell;
  mv.end_mm = at_mm;
  mv.layer = layer;
  mv.side_index = static_cast<std::uint32_t>(p.dwells_s.size());
  p.dwells_s.push_back(seconds);
  p.moves.push_back(mv);
  return p.moves.back();
}
// Appends `piece`, the next part of the same program (one layer from a planner): its moves
// with their texts and dwells, the layers it lists beyond those `whole` has, and its start if
// `whole` has no move yet.
inline void append_piece(MotionProgram& whole, const MotionProgram& piece) {
  if (whole.moves.empty()) whole.start_mm = piece.start_mm;
  for (std::size_t i = whole.layers.size(); i < piece.layers.size(); ++i) whole.layers.push_back(piece.layers[i]);
  for (Move mv : piece.moves) {
    if (mv.kind == MoveKind::Raw) {
      whole.texts.push_back(piece.texts.at(mv.side_index));
      mv.side_index = static_cast<std::uint32_t>(whole.texts.size() - 1);
    } else if (mv.kind == MoveKind::Dwell) {
      whole.dwells_s.push_back(piece.dwells_s.at(mv.side_index));
      mv.side_index = static_cast<std::uint32_t>(whole.dwells_s.size() - 1);
    }
    whole.moves.push_back(mv);
  }
}

// The text of a Raw move of `p`.
inline const std::string& raw_text(const MotionProgram& p, const Move& mv) {
  return p.texts.at(mv.side_index);
}
// The waiting time of a Dwell move of `p`, s.
inline double dwell_seconds(const MotionProgram& p, const Move& mv) {
  return p.dwells_s.at(mv.side_index);
}

}  // namespace strand::slicer
