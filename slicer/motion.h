// MotionProgram: flat machine-level moves in the machine frame (mm, mm/min). Planners
// produce it from a Toolpath; the G-code parser produces it from any file, so checks,
// estimates and previews work on G-code that Strand did not write.
#pragma once

#include <string>
#include <vector>

#include "slicer/geometry.h"
#include "slicer/toolpath.h"

namespace strand::slicer {

enum class MoveKind {
  Travel,   // no deposit (valve closed, pen up); G0
  Deposit,  // depositing ink or drawing; G1 (or G2/G3 when is_arc)
  Dwell,    // wait dwell_s seconds in place; G4
  Raw,      // verbatim machine text (start/end templates, valve commands)
};

struct Move {
  MoveKind kind = MoveKind::Travel;
  Vec3 end_mm = Vec3::Zero();
  double feed_mm_per_min = 0.0;
  bool is_arc = false;           // circular XY arc from the previous position
  Vec2 center_mm = Vec2::Zero(); // arc centre (absolute)
  bool ccw = true;               // arc direction
  double volume_mm3 = 0.0;       // ink deposited by this move (Deposit only)
  bool coast = false;            // Deposit only: valve already closed (lag), the ink still
                                 // in the nozzle finishes the bead
  double width_mm = 0.0;         // bead width, for ;WIDTH: and previews
  Feature feature = Feature::Infill;
  int layer = -1;                // index into MotionProgram::layers, -1 = before the first
  double dwell_s = 0.0;          // Dwell only
  std::string text;              // Raw only: one or more lines without trailing newline
  int tool = 0;                  // extruder or pen index (plotting: which pen draws)

  bool operator==(const Move&) const = default;
};

struct LayerInfo {
  double z_mm = 0.0;
  double height_mm = 0.0;
  bool operator==(const LayerInfo&) const = default;
};

struct MotionProgram {
  std::vector<Move> moves;
  std::vector<LayerInfo> layers;
  Vec3 start_mm = Vec3::Zero();  // position before the first move
  bool operator==(const MotionProgram&) const = default;
};

}  // namespace strand::slicer
